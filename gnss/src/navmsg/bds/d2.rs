//! D2 message (GEO, 500 bit/s, no secondary code): frame of 5 subframes of 300 bits
//! (0.6 s each, 3 s per frame), superframe of 120 frames (6 min)
//! (BDS-SIS-ICD-B1I-3.0 §5.3.1, §5.3.2).
//!
//! - SOW is the BDT seconds of week at the start of the frame: the same in the five
//!   subframes of a frame, +3 s per frame (as C01 broadcasts, and as receivers that take
//!   the time from subframe 1 expect).
//! - Subframe 1: 10 pages (Pnum 4 bits) carrying the clock, ionosphere and ephemeris
//!   split as in the ICD figures; page k is sent in frames k, k + 10, ... of the
//!   superframe (one page per frame, the whole set every 30 s).
//! - Subframe 2 (integrity and differential corrections): Rev and the page number
//!   (Pnum 4 bits, 1-6, one per frame), all other bits zero. Subframes 3 and 4: header
//!   only, all other bits zero. SkyForge broadcasts no integrity or differential
//!   corrections; the zero content of these subframes is a documented placeholder whose
//!   meaning to a receiver that decodes them could not be confirmed.
//! - Subframe 5 (120 pages, Pnum 7 bits): pages 1-13 and 61-73 ionospheric grid (13 grid
//!   points per page, 4 on pages 13 and 73), sent with no data (all ones: not available);
//!   35, 36 health; 37-60 almanac of PRNs 1-24; 95-100 almanac of PRNs 25-30; 101 time
//!   offsets (zero); 102 UTC; the others reserved (zero; no expanded almanac).

use super::d1;
use super::info::InfoBits;
use super::pages::{self, Content};
use super::quant::{EphFields, IonoFields, width as w};

/// Subframe duration (ms).
pub(super) const SUBFRAME_MS: u64 = 600;
/// Frame duration (s).
pub(super) const FRAME_S: u64 = 3;
/// Pages of subframe 1.
pub(super) const SF1_PAGES: u64 = 10;
/// Pages of subframe 2.
const SF2_PAGES: u64 = 6;
/// Pages of subframe 5 (frames per superframe).
const SF5_PAGES: u64 = 120;
/// Width of the subframe 1 and 2 page numbers.
const PNUM_BITS: usize = 4;

/// Information bits of D2 subframe `index` (counted from the start of the week; `wn` and
/// `sow` are the week number and the SOW of its frame).
pub(super) fn subframe(c: &Content<'_>, index: u64, wn: u32, sow: u32) -> InfoBits {
    let fra_id = (index % 5) as u32 + 1;
    let frame = index / 5;
    let mut s = InfoBits::with_header(fra_id, sow);
    match fra_id {
        1 => {
            let page = (frame % SF1_PAGES) as u32 + 1;
            s.put(PNUM_BITS, u64::from(page));
            subframe1_page(&mut s, c.eph, c.iono, wn, page);
        }
        2 => {
            s.skip(1);
            s.put(PNUM_BITS, frame % SF2_PAGES + 1);
        }
        3 | 4 => {}
        _ => subframe5(&mut s, c, (frame % SF5_PAGES) as u32 + 1),
    }
    s
}

/// Subframe 1 page `page` (after Pnum), BDS-SIS-ICD-B1I-3.0 §5.3.2 (subframe 1 figures).
/// Fields split across pages: the MSBs end one page, the LSBs start the next.
fn subframe1_page(s: &mut InfoBits, e: &EphFields, iono: &IonoFields, wn: u32, page: u32) {
    // Upper `len` bits of a `width`-bit field.
    let msb = |v: i64, width: usize, len: usize| (v as u64) >> (width - len);
    match page {
        1 => d1::clock_head(s, e, wn),
        2 => {
            for &a in &iono.alpha {
                s.put_signed(w::KLOBUCHAR, a);
            }
            for &b in &iono.beta {
                s.put_signed(w::KLOBUCHAR, b);
            }
        }
        3 => {
            s.skip(38);
            s.put_signed(w::A0, e.a0);
            s.put(4, msb(e.a1, w::A1, 4));
        }
        4 => {
            s.put(w::A1 - 4, e.a1 as u64);
            s.put_signed(w::A2, e.a2);
            s.put(w::AODE, e.aode as u64);
            s.put_signed(w::DELTA_N, e.delta_n);
            s.put(14, msb(e.cuc, w::HARMONIC, 14));
        }
        5 => {
            s.put(w::HARMONIC - 14, e.cuc as u64);
            s.put_signed(w::WORD32, e.m0);
            s.put_signed(w::HARMONIC, e.cus);
            s.put(10, msb(e.e, w::WORD32, 10));
        }
        6 => {
            s.put(w::WORD32 - 10, e.e as u64);
            s.put(w::WORD32, e.sqrt_a as u64);
            s.put(10, msb(e.cic, w::HARMONIC, 10));
        }
        7 => {
            s.put(w::HARMONIC - 10, e.cic as u64);
            s.put_signed(w::HARMONIC, e.cis);
            s.put(w::TOE, e.toe as u64);
            s.put(21, msb(e.i0, w::WORD32, 21));
        }
        8 => {
            s.put(w::WORD32 - 21, e.i0 as u64);
            s.put_signed(w::HARMONIC, e.crc);
            s.put_signed(w::HARMONIC, e.crs);
            s.put(19, msb(e.omega_dot, w::OMEGA_DOT, 19));
        }
        9 => {
            s.put(w::OMEGA_DOT - 19, e.omega_dot as u64);
            s.put_signed(w::WORD32, e.omega0);
            s.put(27, msb(e.omega, w::WORD32, 27));
        }
        _ => {
            s.put(w::WORD32 - 27, e.omega as u64);
            s.put_signed(w::IDOT, e.idot);
        }
    }
}

/// Subframe 5 page `page`.
fn subframe5(s: &mut InfoBits, c: &Content<'_>, page: u32) {
    let a = c.almanac;
    match page {
        13 | 73 => pages::empty_iono_grid(s, page, 4),
        1..=12 | 61..=72 => pages::empty_iono_grid(s, page, 13),
        35 => pages::health1(s, page, a),
        36 => pages::health2(s, page, a),
        37..=60 => {
            let sat = a.sats[page as usize - 37];
            pages::almanac(s, page, sat.as_ref(), a);
        }
        95..=100 => {
            let sat = a.sats[24 + page as usize - 95];
            pages::almanac(s, page, sat.as_ref(), a);
        }
        101 => pages::time_offsets(s, page),
        102 => pages::utc(s, page, c.utc),
        _ => pages::reserved(s, page),
    }
}
