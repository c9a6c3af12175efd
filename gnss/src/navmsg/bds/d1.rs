//! D1 message (MEO/IGSO, 50 bit/s): frame of 5 subframes of 300 bits (6 s each),
//! superframe of 24 frames (12 min) (BDS-SIS-ICD-B1I-3.0 §5.2.2, §5.2.3).
//!
//! - Subframes 1-3: clock, ionosphere and ephemeris (every frame).
//! - Subframe 4 pages 1-24: almanac of PRNs 1-24.
//! - Subframe 5 pages 1-6: almanac of PRNs 25-30; page 7: health of PRNs 1-19; page 8:
//!   health of PRNs 20-30, WNa, toa; page 9: time offsets to GPS/Galileo/GLONASS (zero);
//!   page 10: UTC parameters; pages 11-24: reserved (zero; AmID = 00, no extended
//!   almanac).
//! - SOW is the BDT seconds of week at the start of the subframe (+6 s per subframe).
//!   Page k of subframes 4/5 is sent in frame k of the superframe; superframes start at
//!   the start of the week (604800 s is a whole number of superframes).

use super::info::{InfoBits, SUBFRAME_INFO};
use super::pages::{self, Content};
use super::quant::{EphFields, IonoFields, width as w};

/// Subframe duration (ms).
pub(super) const SUBFRAME_MS: u64 = 6000;
/// Frames per superframe (pages of subframes 4 and 5).
const PAGES: u64 = 24;
/// Almanac pages of subframe 5 (PRNs 25-30).
const SF5_ALMANAC_PAGES: u32 = 6;

/// Information bits of D1 subframe `index` (counted from the start of the week; `wn`
/// and `sow` are the week number and seconds of week at its start).
pub(super) fn subframe(c: &Content<'_>, index: u64, wn: u32, sow: u32) -> InfoBits {
    let fra_id = (index % 5) as u32 + 1;
    let page = ((index / 5) % PAGES) as u32 + 1;
    let mut s = InfoBits::with_header(fra_id, sow);
    match fra_id {
        1 => subframe1(&mut s, c.eph, c.iono, wn),
        2 => subframe2(&mut s, c.eph),
        3 => subframe3(&mut s, c.eph),
        4 => {
            let sat = c.almanac.sats[page as usize - 1];
            pages::almanac(&mut s, page, sat.as_ref(), c.almanac);
        }
        _ => subframe5(&mut s, c, page),
    }
    s
}

/// Subframe 5, page `page`.
fn subframe5(s: &mut InfoBits, c: &Content<'_>, page: u32) {
    let a = c.almanac;
    match page {
        1..=SF5_ALMANAC_PAGES => {
            let sat = a.sats[24 + page as usize - 1];
            pages::almanac(s, page, sat.as_ref(), a);
        }
        7 => pages::health1(s, page, a),
        8 => pages::health2(s, page, a),
        9 => pages::time_offsets(s, page),
        10 => pages::utc(s, page, c.utc),
        _ => pages::reserved(s, page),
    }
}

/// SatH1, AODC, URAI, WN, toc, TGD1, TGD2: the start of D1 subframe 1 and of D2
/// subframe 1 page 1.
pub(super) fn clock_head(s: &mut InfoBits, e: &EphFields, wn: u32) {
    s.put(w::SAT_H1, e.sat_h1 as u64);
    s.put(w::AODC, e.aodc as u64);
    s.put(w::URAI, e.urai as u64);
    s.put(w::WN, u64::from(wn));
    s.put(w::TOC, e.toc as u64);
    s.put_signed(w::TGD, e.tgd1);
    s.put_signed(w::TGD, e.tgd2);
}

/// Subframe 1: SatH1, AODC, URAI, WN, toc, TGD1, TGD2, alpha0-3, beta0-3, a2, a0, a1,
/// AODE (fills the subframe exactly).
fn subframe1(s: &mut InfoBits, e: &EphFields, iono: &IonoFields, wn: u32) {
    clock_head(s, e, wn);
    for &a in &iono.alpha {
        s.put_signed(w::KLOBUCHAR, a);
    }
    for &b in &iono.beta {
        s.put_signed(w::KLOBUCHAR, b);
    }
    s.put_signed(w::A2, e.a2);
    s.put_signed(w::A0, e.a0);
    s.put_signed(w::A1, e.a1);
    s.put(w::AODE, e.aode as u64);
    debug_assert_eq!(s.len(), SUBFRAME_INFO);
}

/// Subframe 2: Delta n, Cuc, M0, e, Cus, Crc, Crs, sqrt(A), toe (2 MSBs).
fn subframe2(s: &mut InfoBits, e: &EphFields) {
    s.put_signed(w::DELTA_N, e.delta_n);
    s.put_signed(w::HARMONIC, e.cuc);
    s.put_signed(w::WORD32, e.m0);
    s.put(w::WORD32, e.e as u64);
    s.put_signed(w::HARMONIC, e.cus);
    s.put_signed(w::HARMONIC, e.crc);
    s.put_signed(w::HARMONIC, e.crs);
    s.put(w::WORD32, e.sqrt_a as u64);
    s.put(2, (e.toe as u64) >> (w::TOE - 2));
    debug_assert_eq!(s.len(), SUBFRAME_INFO);
}

/// Subframe 3: toe (15 LSBs), i0, Cic, Omega dot, Cis, IDOT, Omega0, omega, Rev (1).
fn subframe3(s: &mut InfoBits, e: &EphFields) {
    s.put(w::TOE - 2, e.toe as u64);
    s.put_signed(w::WORD32, e.i0);
    s.put_signed(w::HARMONIC, e.cic);
    s.put_signed(w::OMEGA_DOT, e.omega_dot);
    s.put_signed(w::HARMONIC, e.cis);
    s.put_signed(w::IDOT, e.idot);
    s.put_signed(w::WORD32, e.omega0);
    s.put_signed(w::WORD32, e.omega);
    debug_assert_eq!(s.len(), SUBFRAME_INFO - 1);
}
