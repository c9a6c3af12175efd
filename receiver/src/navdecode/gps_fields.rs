//! LNAV field extraction from parity-checked source words (IS-GPS-200 figure 20-1;
//! bit layout tables 20-I and 20-II, scale factors tables 20-I, 20-III and 20-X).
//!
//! Source words: 24 bits each, word 1 first, d1 at bit 23. Fields are named by the ICD's
//! word number (1-10) and first bit (1-24).

use super::{DecodedEphemeris, WEEK_S, sign_extend, week_of_reference};
use skyforge_gnss::navmsg::gps_lnav::GPS_PI;
use skyforge_gnss::navmsg::gps_lnav::IonoParams;
use skyforge_gnss::navmsg::gps_lnav::UtcParams;
use skyforge_orbits::ephemeris::{
    BroadcastEphemeris, ClockParams, HarmonicCorrections, KeplerElements, OrbitClass, SatId,
};
use skyforge_orbits::time::epoch_from_gpst;

/// Fit interval for fit interval flag 0 (IS-GPS-200 20.3.3.4.3.1: 4 hours).
const FIT_FLAG0_S: f64 = 4.0 * 3600.0;
/// Fit interval used for fit interval flag 1, which the ICD only defines as "greater than
/// 4 hours": 6 h is assumed (an assumption, not an ICD value).
const FIT_FLAG1_S: f64 = 6.0 * 3600.0;

/// 2^n.
fn p2(n: i32) -> f64 {
    2f64.powi(n)
}

/// Unsigned field of `len` bits at ICD word `word` (1-10), bit `first` (1-24).
fn field(src: &[u32; 10], word: usize, first: u32, len: u32) -> u64 {
    let w = u64::from(src[word - 1]);
    (w >> (24 - (first - 1 + len))) & ((1u64 << len) - 1)
}

/// Two's-complement field.
fn signed(src: &[u32; 10], word: usize, first: u32, len: u32) -> i64 {
    sign_extend(field(src, word, first, len), len)
}

/// A 32-bit field: 8 MSBs at bits 17-24 of `word`, 24 LSBs in `word + 1` (the layout of
/// M0, e, sqrt A, OMEGA0, i0, omega in table 20-II).
fn split32(src: &[u32; 10], word: usize) -> u64 {
    (field(src, word, 17, 8) << 24) | field(src, word + 1, 1, 24)
}

/// TLM and HOW (IS-GPS-200 20.3.3.1-2).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Header {
    /// The 8-bit preamble (10001011 when the word is right).
    pub preamble: u32,
    /// HOW TOW count: 6-s units, the start of the next subframe.
    pub tow_count: u32,
    /// Subframe ID (1-5 for a valid subframe).
    pub id: u8,
}

impl Header {
    pub fn new(src: &[u32; 10]) -> Self {
        Self {
            preamble: field(src, 1, 1, 8) as u32,
            tow_count: field(src, 2, 1, 17) as u32,
            id: field(src, 2, 20, 3) as u8,
        }
    }

    /// Time of week (s) of the start of this subframe: one subframe before the HOW count.
    pub fn start_tow_s(&self) -> f64 {
        (f64::from(self.tow_count) * 6.0 - 6.0).rem_euclid(WEEK_S)
    }
}

/// SV ID of a subframe 4 or 5 page (word 3 bits 3-8, after the 2-bit data ID).
pub(crate) fn page_sv_id(src: &[u32; 10]) -> u8 {
    field(src, 3, 3, 6) as u8
}

/// Subframe 1: week, URA, health, clock (table 20-I).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Subframe1 {
    /// The 10 LSBs of the week of transmission.
    pub wn10: u32,
    pub ura_index: u8,
    pub health: u32,
    pub iodc: u32,
    pub tgd_s: f64,
    pub toc_sow: f64,
    pub af2: f64,
    pub af1: f64,
    pub af0: f64,
}

impl Subframe1 {
    pub fn new(src: &[u32; 10]) -> Self {
        Self {
            wn10: field(src, 3, 1, 10) as u32,
            ura_index: field(src, 3, 13, 4) as u8,
            health: field(src, 3, 17, 6) as u32,
            iodc: ((field(src, 3, 23, 2) << 8) | field(src, 8, 1, 8)) as u32,
            tgd_s: p2(-31) * signed(src, 7, 17, 8) as f64,
            toc_sow: p2(4) * field(src, 8, 9, 16) as f64,
            af2: p2(-55) * signed(src, 9, 1, 8) as f64,
            af1: p2(-43) * signed(src, 9, 9, 16) as f64,
            af0: p2(-31) * signed(src, 10, 1, 22) as f64,
        }
    }
}

/// Subframe 2: first half of the ephemeris (table 20-II), angles in rad.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Subframe2 {
    pub iode: u32,
    pub crs: f64,
    pub delta_n: f64,
    pub m0: f64,
    pub cuc: f64,
    pub e: f64,
    pub cus: f64,
    pub sqrt_a: f64,
    pub toe_sow: f64,
    pub fit_flag: bool,
}

impl Subframe2 {
    pub fn new(src: &[u32; 10]) -> Self {
        Self {
            iode: field(src, 3, 1, 8) as u32,
            crs: p2(-5) * signed(src, 3, 9, 16) as f64,
            delta_n: GPS_PI * p2(-43) * signed(src, 4, 1, 16) as f64,
            m0: GPS_PI * p2(-31) * sign_extend(split32(src, 4), 32) as f64,
            cuc: p2(-29) * signed(src, 6, 1, 16) as f64,
            e: p2(-33) * split32(src, 6) as f64,
            cus: p2(-29) * signed(src, 8, 1, 16) as f64,
            sqrt_a: p2(-19) * split32(src, 8) as f64,
            toe_sow: p2(4) * field(src, 10, 1, 16) as f64,
            fit_flag: field(src, 10, 17, 1) == 1,
        }
    }
}

/// Subframe 3: second half of the ephemeris (table 20-II), angles in rad.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Subframe3 {
    pub cic: f64,
    pub omega0: f64,
    pub cis: f64,
    pub i0: f64,
    pub crc: f64,
    pub omega: f64,
    pub omega_dot: f64,
    pub iode: u32,
    pub idot: f64,
}

impl Subframe3 {
    pub fn new(src: &[u32; 10]) -> Self {
        let angle = |word| GPS_PI * p2(-31) * sign_extend(split32(src, word), 32) as f64;
        Self {
            cic: p2(-29) * signed(src, 3, 1, 16) as f64,
            omega0: angle(3),
            cis: p2(-29) * signed(src, 5, 1, 16) as f64,
            i0: angle(5),
            crc: p2(-5) * signed(src, 7, 1, 16) as f64,
            omega: angle(7),
            omega_dot: GPS_PI * p2(-43) * signed(src, 9, 1, 24) as f64,
            iode: field(src, 10, 1, 8) as u32,
            idot: GPS_PI * p2(-43) * signed(src, 10, 9, 14) as f64,
        }
    }
}

/// Subframe 4 page 18 (SV ID 56): Klobuchar and UTC parameters (figure 20-1 sheet 8,
/// table 20-X). Weeks are the broadcast 8 LSBs.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Page18 {
    pub iono: IonoParams,
    pub a0: f64,
    pub a1: f64,
    pub tot: u32,
    pub wnt8: u32,
    pub dt_ls: i32,
    pub wn_lsf8: u32,
    pub dn: u8,
    pub dt_lsf: i32,
}

/// SV ID of subframe 4 page 18 (IS-GPS-200 table 20-V).
pub(crate) const PAGE18_SV_ID: u8 = 56;

/// Scale exponents of alpha0..3 and beta0..3 (table 20-X).
const ALPHA_LOG2: [i32; 4] = [-30, -27, -24, -24];
const BETA_LOG2: [i32; 4] = [11, 14, 16, 16];

impl Page18 {
    pub fn new(src: &[u32; 10]) -> Self {
        // alpha0 alpha1 | alpha2 alpha3 beta0 | beta1 beta2 beta3: 8-bit fields from word 3
        // bit 9 on.
        let positions = [
            (3, 9),
            (3, 17),
            (4, 1),
            (4, 9),
            (4, 17),
            (5, 1),
            (5, 9),
            (5, 17),
        ];
        let v = |k: usize| signed(src, positions[k].0, positions[k].1, 8) as f64;
        Self {
            iono: IonoParams {
                alpha: std::array::from_fn(|n| p2(ALPHA_LOG2[n]) * v(n)),
                beta: std::array::from_fn(|n| p2(BETA_LOG2[n]) * v(n + 4)),
            },
            a1: p2(-50) * signed(src, 6, 1, 24) as f64,
            a0: p2(-30) * sign_extend((field(src, 7, 1, 24) << 8) | field(src, 8, 1, 8), 32) as f64,
            tot: (field(src, 8, 9, 8) as u32) << 12,
            wnt8: field(src, 8, 17, 8) as u32,
            dt_ls: signed(src, 9, 1, 8) as i32,
            wn_lsf8: field(src, 9, 9, 8) as u32,
            dn: field(src, 9, 17, 8) as u8,
            dt_lsf: signed(src, 10, 1, 8) as i32,
        }
    }

    /// The UTC parameters with full weeks: each 8-bit week is taken within +-128 weeks of
    /// `week` (IS-GPS-200 20.3.3.5.2.4 keeps a scheduled leap-second week within 127
    /// weeks of the current one). A past event older than that (WN_LSF stays at the last
    /// event when none is scheduled) is only known modulo 256 weeks.
    pub fn utc(&self, week: u32) -> UtcParams {
        UtcParams {
            a0: self.a0,
            a1: self.a1,
            tot: self.tot,
            wnt: nearest_week(self.wnt8, 8, week),
            dt_ls: self.dt_ls,
            wn_lsf: nearest_week(self.wn_lsf8, 8, week),
            dn: self.dn,
            dt_lsf: self.dt_lsf,
        }
    }
}

/// The full week whose `bits` LSBs are `lsbs`, nearest to `reference`.
pub(crate) fn nearest_week(lsbs: u32, bits: u32, reference: u32) -> u32 {
    let modulus = 1i64 << bits;
    let r = i64::from(reference);
    let d = (i64::from(lsbs) - r).rem_euclid(modulus);
    let d = if d >= modulus / 2 { d - modulus } else { d };
    u32::try_from(r + d).unwrap_or(lsbs)
}

/// The ephemeris of subframes 1-3 sent in GPS week `week` at time of week `tx_sow`
/// (toe and toc placed in the week that puts them within half a week of `tx_sow`).
pub(crate) fn ephemeris(
    sat: SatId,
    week: u32,
    tx_sow: f64,
    s1: &Subframe1,
    s2: &Subframe2,
    s3: &Subframe3,
) -> DecodedEphemeris {
    let epoch = |sow| epoch_from_gpst(week_of_reference(week, tx_sow, sow), sow);
    let orbit = KeplerElements {
        sqrt_a: s2.sqrt_a,
        e: s2.e,
        i0: s3.i0,
        omega0: s3.omega0,
        omega: s3.omega,
        m0: s2.m0,
        delta_n: s2.delta_n,
        idot: s3.idot,
        omega_dot: s3.omega_dot,
    };
    let harmonics = HarmonicCorrections {
        cuc: s2.cuc,
        cus: s2.cus,
        crc: s3.crc,
        crs: s2.crs,
        cic: s3.cic,
        cis: s3.cis,
    };
    let clock = ClockParams {
        af0: s1.af0,
        af1: s1.af1,
        af2: s1.af2,
        tgd_s: s1.tgd_s,
        tgd2_s: 0.0,
    };
    let fit_interval_s = if s2.fit_flag {
        FIT_FLAG1_S
    } else {
        FIT_FLAG0_S
    };
    DecodedEphemeris {
        eph: BroadcastEphemeris {
            toc: epoch(s1.toc_sow),
            iode: s2.iode,
            iodc: s1.iodc,
            health: s1.health,
            ..BroadcastEphemeris::from_elements(
                sat,
                OrbitClass::Standard,
                epoch(s2.toe_sow),
                orbit,
                harmonics,
                clock,
                fit_interval_s,
            )
        },
        ura_index: s1.ura_index,
        tgd2_s: None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fields_use_icd_word_and_bit_numbers() {
        let mut src = [0u32; 10];
        src[2] = 0b1000000001 << 14; // word 3: WN = 513
        src[3] = 0x00_00FF; // word 4: M0 MSBs = 0xFF (bits 17-24)
        src[4] = 0xFF_FFFF; // word 5: M0 LSBs
        assert_eq!(field(&src, 3, 1, 10), 513);
        assert_eq!(sign_extend(split32(&src, 4), 32), -1);
        assert_eq!(Subframe1::new(&src).wn10, 513);
    }

    #[test]
    fn eight_bit_weeks_resolve_near_the_reference() {
        // 2111 = 8 x 256 + 63.
        assert_eq!(nearest_week(63, 8, 2111), 2111);
        assert_eq!(nearest_week(250, 8, 2111), 2042);
        assert_eq!(nearest_week(100, 8, 2111), 2148);
        // An event 182 weeks back (1929 seen from 2111) is out of reach of 8 bits.
        assert_eq!(nearest_week(1929 % 256, 8, 2111), 2185);
        assert_eq!(nearest_week(1929 % 256, 8, 2000), 1929);
        assert_eq!(nearest_week(2111 % 1024, 10, 2560), 2111);
    }

    #[test]
    fn start_of_subframe_is_one_count_before_the_how() {
        let h = |tow_count| Header {
            preamble: 0x8B,
            tow_count,
            id: 1,
        };
        assert_eq!(h(1).start_tow_s(), 0.0);
        assert_eq!(h(0).start_tow_s(), 604_794.0);
        assert_eq!(h(100).start_tow_s(), 594.0);
    }
}
