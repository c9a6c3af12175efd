//! Page bodies shared by D1 subframes 4/5 and D2 subframe 5: after the header, Rev (1 bit)
//! and Pnum (7 bits), the same field sequences (BDS-SIS-ICD-B1I-3.0 §5.2.3 figures for
//! D1 subframe 4, subframe 5 pages 1-10; §5.3.2 figures for D2 subframe 5 pages 35-36,
//! 37-60, 95-100, 101, 102).

use super::almanac::{Almanac, AlmanacFields, alm};
use super::info::{InfoBits, SUBFRAME_INFO};
use super::quant::{EphFields, IonoFields};

/// Everything a D1 or D2 subframe is built from.
#[derive(Debug, Clone, Copy)]
pub(super) struct Content<'a> {
    pub eph: &'a EphFields,
    pub iono: &'a IonoFields,
    pub almanac: &'a Almanac,
    pub utc: &'a UtcFields,
}

/// Bits of a health word Hea_i.
const HEA_BITS: usize = 9;
/// PRNs whose health is on the first health page (D1 subframe 5 page 7, D2 subframe 5
/// page 35); the second page carries PRNs 20-30, WNa and toa.
pub(super) const HEALTH_PAGE1_PRNS: usize = 19;

/// UTC parameters (D1 subframe 5 page 10, D2 subframe 5 page 102), integers.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct UtcFields {
    /// Delta t_LS: BDT - UTC before the pending leap second (s).
    pub dt_ls: i64,
    /// Delta t_LSF: BDT - UTC after it (s).
    pub dt_lsf: i64,
    /// WN_LSF (week mod 256).
    pub wn_lsf: i64,
    /// DN: day of week of the leap second.
    pub dn: i64,
}

/// Rev (1 bit) and Pnum (7 bits), which start every page of D1 subframes 4/5 and D2
/// subframe 5.
fn page_number(s: &mut InfoBits, pnum: u32) {
    s.skip(1);
    s.put(7, u64::from(pnum));
}

/// An almanac page: sqrt(A), a1, a0, Omega0, e, delta_i, toa, Omega dot, omega, M0,
/// AmEpID (00). Without almanac every field is zero.
pub(super) fn almanac(s: &mut InfoBits, pnum: u32, fields: Option<&AlmanacFields>, a: &Almanac) {
    page_number(s, pnum);
    match fields {
        Some(f) => {
            s.put(alm::SQRT_A.0, f.sqrt_a as u64);
            s.put_signed(alm::A1.0, f.a1);
            s.put_signed(alm::A0.0, f.a0);
            s.put_signed(alm::ANGLE_BITS, f.omega0);
            s.put(alm::E.0, f.e as u64);
            s.put_signed(alm::DELTA_I.0, f.delta_i);
            s.put(8, a.toa as u64);
            s.put_signed(alm::OMEGA_DOT.0, f.omega_dot);
            s.put_signed(alm::ANGLE_BITS, f.omega);
            s.put_signed(alm::ANGLE_BITS, f.m0);
        }
        None => s.skip(SUBFRAME_INFO - 2 - s.len()),
    }
    s.skip(2); // AmEpID = 00
    debug_assert_eq!(s.len(), SUBFRAME_INFO);
}

/// First health page: Hea1..Hea19.
pub(super) fn health1(s: &mut InfoBits, pnum: u32, a: &Almanac) {
    page_number(s, pnum);
    for &h in &a.health[..HEALTH_PAGE1_PRNS] {
        s.put(HEA_BITS, h as u64);
    }
}

/// Second health page: Hea20..Hea30, WNa, toa.
pub(super) fn health2(s: &mut InfoBits, pnum: u32, a: &Almanac) {
    page_number(s, pnum);
    for &h in &a.health[HEALTH_PAGE1_PRNS..] {
        s.put(HEA_BITS, h as u64);
    }
    s.put(8, a.wna as u64);
    s.put(8, a.toa as u64);
}

/// Time offsets to GPS, Galileo and GLONASS: A0/A1 for each, all zero (SkyForge's time
/// scales differ by whole seconds only, BDT = GPST - 14 s).
pub(super) fn time_offsets(s: &mut InfoBits, pnum: u32) {
    page_number(s, pnum);
    // Rev 30, A0GPS 14, A1GPS 16, A0Gal 14, A1Gal 16, A0GLO 14, A1GLO 16: all zero.
}

/// UTC parameters: Delta t_LS, Delta t_LSF, WN_LSF, A0UTC (= 0), A1UTC (= 0), DN.
pub(super) fn utc(s: &mut InfoBits, pnum: u32, u: &UtcFields) {
    page_number(s, pnum);
    s.put_signed(8, u.dt_ls);
    s.put_signed(8, u.dt_lsf);
    s.put(8, u.wn_lsf as u64);
    s.skip(32 + 24); // A0UTC, A1UTC
    s.put(8, u.dn as u64);
}

/// A reserved page: only the page number.
pub(super) fn reserved(s: &mut InfoBits, pnum: u32) {
    page_number(s, pnum);
}

/// A D2 ionospheric grid page (subframe 5 pages 1-13 and 61-73) with no data: `points`
/// grid points (13, or 4 on pages 13 and 73) of (d tau 9 bits, GIVEI 4 bits) all ones
/// (d tau = 511: not available), as C01 broadcasts for points without data; the rest of
/// the page reserved (zero).
pub(super) fn empty_iono_grid(s: &mut InfoBits, pnum: u32, points: usize) {
    page_number(s, pnum);
    s.ones(13 * points);
}
