//! D1/D2 field extraction from the information bits of a subframe
//! (BDS-SIS-ICD-B1I-3.0 §5.2.3-5.2.4 for D1, §5.3.2-5.3.3 for D2).
//!
//! Counting information bits only (the BCH parity bits removed), every subframe is a
//! plain sequence of fields: header (preamble 11, Rev 4, FraID 3, SOW 20), then the
//! subframe's fields in the order of the ICD's bit-allocation figures. D2 subframe 1
//! splits fields across pages: the MSBs end page n, the LSBs start page n + 1.

use super::{DecodedEphemeris, sign_extend, week_of_reference};
use skyforge_gnss::navmsg::Klobuchar;
use skyforge_orbits::ephemeris::{
    BroadcastEphemeris, ClockParams, HarmonicCorrections, KeplerElements, OrbitClass, SatId,
};
use skyforge_orbits::time::epoch_from_bdt;
use std::f64::consts::PI;

/// Validity interval given to a decoded BeiDou ephemeris (s): the 6 h around toe that the
/// orbits crate's RINEX reader also assumes (the message carries no fit interval).
const BDS_FIT_S: f64 = 6.0 * 3600.0;
/// Information bits of the header.
pub(crate) const HEADER_BITS: usize = 38;

/// 2^n.
fn p2(n: i32) -> f64 {
    2f64.powi(n)
}

/// Sequential reader over information bits; reads past the end give zeros.
#[derive(Debug, Clone)]
pub(crate) struct Reader<'a> {
    bits: &'a [u8],
    pos: usize,
}

impl<'a> Reader<'a> {
    /// A reader at information bit `pos`.
    pub fn at(bits: &'a [u8], pos: usize) -> Self {
        Self { bits, pos }
    }

    /// Next `len` bits, unsigned.
    pub fn u(&mut self, len: usize) -> u64 {
        let v = (self.pos..self.pos + len).fold(0u64, |a, k| {
            (a << 1) | u64::from(self.bits.get(k).copied().unwrap_or(0) & 1)
        });
        self.pos += len;
        v
    }

    /// Next `len` bits, two's complement.
    pub fn s(&mut self, len: usize) -> i64 {
        sign_extend(self.u(len), len as u32)
    }

    /// Skip `len` bits.
    pub fn skip(&mut self, len: usize) {
        self.pos += len;
    }

    /// The LSB part of a field whose `msb` (`msb_len` bits) came from the previous page:
    /// reads `len - msb_len` bits and returns the whole `len`-bit field, two's complement
    /// if `signed`.
    pub fn rest(&mut self, msb: u64, len: usize, msb_len: usize, signed: bool) -> i64 {
        let v = (msb << (len - msb_len)) | self.u(len - msb_len);
        if signed {
            sign_extend(v, len as u32)
        } else {
            v as i64
        }
    }
}

/// Subframe header.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Header {
    pub fra_id: u8,
    /// Seconds of BDT week (D1: at the subframe start; D2: at the frame start).
    pub sow: u32,
}

impl Header {
    pub fn new(info: &[u8]) -> Self {
        // Preamble (11 bits) and Rev (4 bits) are checked by the framer.
        let mut r = Reader::at(info, 15);
        let fra_id = r.u(3) as u8;
        let sow = r.u(20) as u32;
        Self { fra_id, sow }
    }
}

/// Page number right after the header: `rev` reserved bits, then `len` bits.
pub(crate) fn page_number(info: &[u8], rev: usize, len: usize) -> u8 {
    let mut r = Reader::at(info, HEADER_BITS + rev);
    r.u(len) as u8
}

/// Clock, group delays, week and issue numbers (D1 subframe 1; D2 subframe 1 pages 1, 3,
/// 4), SI units.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(crate) struct Clock {
    pub sat_h1: u32,
    pub aodc: u32,
    pub urai: u8,
    pub wn: u32,
    pub toc_sow: f64,
    pub tgd1_s: f64,
    pub tgd2_s: f64,
    pub a0: f64,
    pub a1: f64,
    pub a2: f64,
    pub aode: u32,
}

/// Orbit parameters (D1 subframes 2-3; D2 subframe 1 pages 4-10), angles in rad.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(crate) struct Orbit {
    pub delta_n: f64,
    pub cuc: f64,
    pub m0: f64,
    pub e: f64,
    pub cus: f64,
    pub crc: f64,
    pub crs: f64,
    pub sqrt_a: f64,
    pub toe_sow: f64,
    pub i0: f64,
    pub cic: f64,
    pub omega_dot: f64,
    pub cis: f64,
    pub idot: f64,
    pub omega0: f64,
    pub omega: f64,
}

/// Scale factors (§5.2.4 tables; the same in D2, §5.3.3). Angles are broadcast in
/// semicircles; SkyForge's encoder converts with `std::f64::consts::PI`, used here too
/// (it differs from the ICD's 3.1415926535898 by 2e-15 relative, 1e-5 of an LSB).
mod lsb {
    use super::{PI, p2};
    /// toc, toe (s).
    pub const T_REF: f64 = 8.0;
    /// TGD1, TGD2: 0.1 ns.
    pub const TGD: f64 = 0.1e-9;
    /// Delta n, Omega dot, IDOT: 2^-43 semicircles/s.
    pub fn rate() -> f64 {
        PI * p2(-43)
    }
    /// M0, i0, Omega0, omega: 2^-31 semicircles.
    pub fn angle() -> f64 {
        PI * p2(-31)
    }
    /// Exponents of alpha0..3 and beta0..3 (Klobuchar, same as GPS).
    pub const ALPHA_LOG2: [i32; 4] = [-30, -27, -24, -24];
    pub const BETA_LOG2: [i32; 4] = [11, 14, 16, 16];
}

/// Eight Klobuchar bytes alpha0..3, beta0..3.
fn klobuchar(r: &mut Reader<'_>) -> Klobuchar {
    let alpha = std::array::from_fn(|n| p2(lsb::ALPHA_LOG2[n]) * r.s(8) as f64);
    let beta = std::array::from_fn(|n| p2(lsb::BETA_LOG2[n]) * r.s(8) as f64);
    Klobuchar { alpha, beta }
}

/// SatH1, AODC, URAI, WN, toc, TGD1, TGD2 (start of D1 subframe 1 and D2 page 1).
fn clock_head(r: &mut Reader<'_>, c: &mut Clock) {
    c.sat_h1 = r.u(1) as u32;
    c.aodc = r.u(5) as u32;
    c.urai = r.u(4) as u8;
    c.wn = r.u(13) as u32;
    c.toc_sow = lsb::T_REF * r.u(17) as f64;
    c.tgd1_s = lsb::TGD * r.s(10) as f64;
    c.tgd2_s = lsb::TGD * r.s(10) as f64;
}

/// D1 subframe 1: clock and Klobuchar.
pub(crate) fn d1_subframe1(info: &[u8]) -> (Clock, Klobuchar) {
    let mut r = Reader::at(info, HEADER_BITS);
    let mut c = Clock::default();
    clock_head(&mut r, &mut c);
    let iono = klobuchar(&mut r);
    c.a2 = p2(-66) * r.s(11) as f64;
    c.a0 = p2(-33) * r.s(24) as f64;
    c.a1 = p2(-50) * r.s(22) as f64;
    c.aode = r.u(5) as u32;
    (c, iono)
}

/// D1 subframes 2 and 3: the orbit (toe split: 2 MSBs end subframe 2).
pub(crate) fn d1_orbit(sf2: &[u8], sf3: &[u8]) -> Orbit {
    let mut r = Reader::at(sf2, HEADER_BITS);
    let mut o = Orbit {
        delta_n: lsb::rate() * r.s(16) as f64,
        cuc: p2(-31) * r.s(18) as f64,
        m0: lsb::angle() * r.s(32) as f64,
        e: p2(-33) * r.u(32) as f64,
        cus: p2(-31) * r.s(18) as f64,
        crc: p2(-6) * r.s(18) as f64,
        crs: p2(-6) * r.s(18) as f64,
        sqrt_a: p2(-19) * r.u(32) as f64,
        ..Orbit::default()
    };
    let toe_msb = r.u(2);
    let mut r = Reader::at(sf3, HEADER_BITS);
    o.toe_sow = lsb::T_REF * r.rest(toe_msb, 17, 2, false) as f64;
    o.i0 = lsb::angle() * r.s(32) as f64;
    o.cic = p2(-31) * r.s(18) as f64;
    o.omega_dot = lsb::rate() * r.s(24) as f64;
    o.cis = p2(-31) * r.s(18) as f64;
    o.idot = lsb::rate() * r.s(14) as f64;
    o.omega0 = lsb::angle() * r.s(32) as f64;
    o.omega = lsb::angle() * r.s(32) as f64;
    o
}

/// Information bits where D2 subframe 1 page content starts (after the 4-bit Pnum).
const D2_PAGE_BODY: usize = HEADER_BITS + 4;

/// D2 subframe 1 page 1: the clock head (week, toc, TGDs, issue of clock).
pub(crate) fn d2_page1(info: &[u8]) -> Clock {
    let mut c = Clock::default();
    clock_head(&mut Reader::at(info, D2_PAGE_BODY), &mut c);
    c
}

/// D2 subframe 1 page 2: Klobuchar.
pub(crate) fn d2_page2(info: &[u8]) -> Klobuchar {
    klobuchar(&mut Reader::at(info, D2_PAGE_BODY))
}

/// D2 subframe 1 pages 1-10 (index 0 = page 1): clock, and orbit.
pub(crate) fn d2_pages(p: &[&[u8]; 10]) -> (Clock, Orbit) {
    let mut c = d2_page1(p[0]);
    let page = |n: usize| Reader::at(p[n - 1], D2_PAGE_BODY);
    let mut r = page(3);
    r.skip(38);
    c.a0 = p2(-33) * r.s(24) as f64;
    let a1_msb = r.u(4);
    let mut r = page(4);
    c.a1 = p2(-50) * r.rest(a1_msb, 22, 4, true) as f64;
    c.a2 = p2(-66) * r.s(11) as f64;
    c.aode = r.u(5) as u32;
    let mut o = Orbit {
        delta_n: lsb::rate() * r.s(16) as f64,
        ..Orbit::default()
    };
    let cuc_msb = r.u(14);
    let mut r = page(5);
    o.cuc = p2(-31) * r.rest(cuc_msb, 18, 14, true) as f64;
    o.m0 = lsb::angle() * r.s(32) as f64;
    o.cus = p2(-31) * r.s(18) as f64;
    let e_msb = r.u(10);
    let mut r = page(6);
    o.e = p2(-33) * r.rest(e_msb, 32, 10, false) as f64;
    o.sqrt_a = p2(-19) * r.u(32) as f64;
    let cic_msb = r.u(10);
    let mut r = page(7);
    o.cic = p2(-31) * r.rest(cic_msb, 18, 10, true) as f64;
    o.cis = p2(-31) * r.s(18) as f64;
    o.toe_sow = lsb::T_REF * r.u(17) as f64;
    let i0_msb = r.u(21);
    let mut r = page(8);
    o.i0 = lsb::angle() * r.rest(i0_msb, 32, 21, true) as f64;
    o.crc = p2(-6) * r.s(18) as f64;
    o.crs = p2(-6) * r.s(18) as f64;
    let omega_dot_msb = r.u(19);
    let mut r = page(9);
    o.omega_dot = lsb::rate() * r.rest(omega_dot_msb, 24, 19, true) as f64;
    o.omega0 = lsb::angle() * r.s(32) as f64;
    let omega_msb = r.u(27);
    let mut r = page(10);
    o.omega = lsb::angle() * r.rest(omega_msb, 32, 27, true) as f64;
    o.idot = lsb::rate() * r.s(14) as f64;
    (c, o)
}

/// The ephemeris of `sat` from `clock` and `orbit`, sent in BDT week `clock.wn` at
/// seconds of week `tx_sow` (toe and toc placed within half a week of it).
pub(crate) fn ephemeris(
    sat: SatId,
    class: OrbitClass,
    tx_sow: f64,
    c: &Clock,
    o: &Orbit,
) -> DecodedEphemeris {
    let epoch = |sow| epoch_from_bdt(week_of_reference(c.wn, tx_sow, sow), sow);
    let orbit = KeplerElements {
        sqrt_a: o.sqrt_a,
        e: o.e,
        i0: o.i0,
        omega0: o.omega0,
        omega: o.omega,
        m0: o.m0,
        delta_n: o.delta_n,
        idot: o.idot,
        omega_dot: o.omega_dot,
    };
    let harmonics = HarmonicCorrections {
        cuc: o.cuc,
        cus: o.cus,
        crc: o.crc,
        crs: o.crs,
        cic: o.cic,
        cis: o.cis,
    };
    let clock = ClockParams {
        af0: c.a0,
        af1: c.a1,
        af2: c.a2,
        tgd_s: c.tgd1_s,
        tgd2_s: 0.0,
    };
    DecodedEphemeris {
        eph: BroadcastEphemeris {
            toc: epoch(c.toc_sow),
            iode: c.aode,
            iodc: c.aodc,
            health: c.sat_h1,
            ..BroadcastEphemeris::from_elements(
                sat,
                class,
                epoch(o.toe_sow),
                orbit,
                harmonics,
                clock,
                BDS_FIT_S,
            )
        },
        ura_index: c.urai,
        tgd2_s: Some(c.tgd2_s),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reader_reads_fields_in_sequence() {
        let bits = [1, 0, 1, 1, 1, 1, 1, 1, 0, 0, 1];
        let mut r = Reader::at(&bits, 0);
        assert_eq!(r.u(3), 0b101);
        assert_eq!(r.s(5), -1);
        r.skip(2);
        assert_eq!(r.u(1), 1);
        assert_eq!(r.u(4), 0); // past the end
        let mut r = Reader::at(&bits, 8);
        assert_eq!(r.rest(0b1, 4, 1, true), -7); // 1001
        let mut r = Reader::at(&bits, 8);
        assert_eq!(r.rest(0b1, 4, 1, false), 9);
    }

    #[test]
    fn header_positions() {
        // preamble 11100010010, Rev 0000, FraID 011, SOW 345606 on 20 bits.
        let mut bits = Vec::new();
        let push = |bits: &mut Vec<u8>, v: u64, n: usize| {
            bits.extend((0..n).rev().map(|k| ((v >> k) & 1) as u8));
        };
        push(&mut bits, 0b111_0001_0010, 11);
        push(&mut bits, 0, 4);
        push(&mut bits, 3, 3);
        push(&mut bits, 345_606, 20);
        let h = Header::new(&bits);
        assert_eq!((h.fra_id, h.sow), (3, 345_606));
    }
}
