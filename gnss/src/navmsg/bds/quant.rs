//! Quantisation of the clock, ephemeris and ionosphere parameters to the integers the D1/D2
//! messages carry, and back to SI units.
//!
//! Bit widths and scale factors: BDS-SIS-ICD-B1I-3.0 §5.2.4 (D1; the D2 message carries
//! the same parameters with the same scale factors, §5.3.3). Angles are carried in
//! semicircles (1 semicircle = pi rad) and angular rates in semicircles/s.
//! Signed fields are two's complement. A value outside the field's range is an error,
//! not a silent saturation.

use super::{BdsExtraFields, BdsNavError, Klobuchar};
use hifitime::Epoch;
use skyforge_orbits::ephemeris::{
    BroadcastEphemeris, ClockParams, HarmonicCorrections, KeplerElements,
};
use skyforge_orbits::time::bdt_week_sow;
use std::f64::consts::PI;

/// Bit widths of the D1/D2 fields (BDS-SIS-ICD-B1I-3.0 §5.2.3 figures, §5.2.4 tables).
pub(super) mod width {
    pub const SAT_H1: usize = 1;
    pub const AODC: usize = 5;
    pub const URAI: usize = 4;
    pub const WN: usize = 13;
    pub const TOC: usize = 17;
    pub const TGD: usize = 10;
    pub const KLOBUCHAR: usize = 8;
    pub const A0: usize = 24;
    pub const A1: usize = 22;
    pub const A2: usize = 11;
    pub const AODE: usize = 5;
    pub const DELTA_N: usize = 16;
    /// Cuc, Cus, Cic, Cis, Crc, Crs.
    pub const HARMONIC: usize = 18;
    /// M0, e, sqrt(A), i0, Omega0, omega.
    pub const WORD32: usize = 32;
    pub const TOE: usize = 17;
    pub const OMEGA_DOT: usize = 24;
    pub const IDOT: usize = 14;
}

/// Smallest AODE broadcast: an AODE of 0 is sent as 1. GNSS-SDR (the 2019-2022
/// sources, e.g. release 0.0.17) accepts a BeiDou ephemeris only when its AODE differs
/// from the previous one, initialised to 0, so a message with AODE = 0 never yields an
/// ephemeris there. 1 is what BeiDou satellites broadcast most of the time (933 of the
/// 1061 sets of BRD400DLR 2023-03-12).
const AODE_MIN: u32 = 1;

/// 2^n.
pub(super) fn p2(n: i32) -> f64 {
    2f64.powi(n)
}

/// Scale factors (LSB values) in SI units; angles in radians.
pub(super) mod lsb {
    use super::p2;
    use std::f64::consts::PI;
    /// toc, toe: 2^3 s.
    pub fn t_ref() -> f64 {
        8.0
    }
    /// TGD1, TGD2: 0.1 ns.
    pub const TGD_S: f64 = 0.1e-9;
    pub fn a0() -> f64 {
        p2(-33)
    }
    pub fn a1() -> f64 {
        p2(-50)
    }
    pub fn a2() -> f64 {
        p2(-66)
    }
    /// Delta n, Omega dot, IDOT: 2^-43 semicircles/s.
    pub fn rate() -> f64 {
        PI * p2(-43)
    }
    /// M0, i0, Omega0, omega: 2^-31 semicircles.
    pub fn angle() -> f64 {
        PI * p2(-31)
    }
    /// Cuc, Cus, Cic, Cis: 2^-31 rad.
    pub fn c_angle() -> f64 {
        p2(-31)
    }
    /// Crc, Crs: 2^-6 m.
    pub fn c_radius() -> f64 {
        p2(-6)
    }
    pub fn e() -> f64 {
        p2(-33)
    }
    pub fn sqrt_a() -> f64 {
        p2(-19)
    }
    /// alpha0..alpha3: 2^-30, 2^-27, 2^-24, 2^-24 s/semicircle^n.
    pub fn alpha(n: usize) -> f64 {
        p2([-30, -27, -24, -24][n])
    }
    /// beta0..beta3: 2^11, 2^14, 2^16, 2^16 s/semicircle^n.
    pub fn beta(n: usize) -> f64 {
        p2([11, 14, 16, 16][n])
    }
}

/// Rounds SI values to field integers, checking the range; errors name the satellite.
#[derive(Debug, Clone, Copy)]
pub(super) struct Quantiser<'a> {
    pub sat: &'a str,
}

impl Quantiser<'_> {
    /// round(value / lsb) on `bits` bits, signed (two's complement) or unsigned.
    pub(super) fn q(
        &self,
        field: &'static str,
        value: f64,
        lsb: f64,
        bits: usize,
        signed: bool,
    ) -> Result<i64, BdsNavError> {
        let (min, max) = if signed {
            (-(1i64 << (bits - 1)), (1i64 << (bits - 1)) - 1)
        } else {
            (0, (1i64 << bits) - 1)
        };
        let n = (value / lsb).round();
        if n.is_finite() && n >= min as f64 && n <= max as f64 {
            Ok(n as i64)
        } else {
            Err(BdsNavError::FieldOutOfRange {
                sat: self.sat.to_string(),
                field,
                value,
                min: min as f64 * lsb,
                max: max as f64 * lsb,
            })
        }
    }

    /// An angle (rad) on `bits` bits of 2^-(bits-1) semicircles (the full circle), after
    /// wrapping to [-pi, pi).
    pub(super) fn angle(
        &self,
        field: &'static str,
        rad: f64,
        bits: usize,
    ) -> Result<i64, BdsNavError> {
        let half = 1i64 << (bits - 1);
        let n = self.q(field, wrap_pi(rad), PI / half as f64, bits + 1, true)?;
        // +pi rounds to +2^(bits-1), the same angle as -2^(bits-1).
        Ok(if n >= half { n - 2 * half } else { n })
    }
}

pub(super) use skyforge_orbits::angles::wrap_pi;

/// The clock and ephemeris fields of subframes 1-3 (D1) or subframe 1 pages 1-10 (D2), as
/// integers in units of their LSB.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct EphFields {
    pub sat_h1: i64,
    pub aodc: i64,
    pub urai: i64,
    pub toc: i64,
    pub tgd1: i64,
    pub tgd2: i64,
    pub a0: i64,
    pub a1: i64,
    pub a2: i64,
    pub aode: i64,
    pub toe: i64,
    pub sqrt_a: i64,
    pub e: i64,
    pub i0: i64,
    pub omega0: i64,
    pub omega: i64,
    pub m0: i64,
    pub delta_n: i64,
    pub idot: i64,
    pub omega_dot: i64,
    pub cuc: i64,
    pub cus: i64,
    pub cic: i64,
    pub cis: i64,
    pub crc: i64,
    pub crs: i64,
}

impl EphFields {
    /// Quantise an ephemeris whose toe and toc are already multiples of 8 s.
    pub(super) fn quantise(
        eph: &BroadcastEphemeris,
        extra: &BdsExtraFields,
        q: Quantiser<'_>,
    ) -> Result<Self, BdsNavError> {
        use width as w;
        let sow = |t: Epoch| bdt_week_sow(t).1;
        Ok(Self {
            sat_h1: i64::from(eph.health != 0),
            aodc: q.q("AODC", f64::from(eph.iodc), 1.0, w::AODC, false)?,
            urai: q.q("URAI", f64::from(extra.urai), 1.0, w::URAI, false)?,
            toc: q.q("toc", sow(eph.toc), lsb::t_ref(), w::TOC, false)?,
            tgd1: q.q("TGD1", eph.clock.tgd_s, lsb::TGD_S, w::TGD, true)?,
            tgd2: q.q("TGD2", extra.tgd2_s, lsb::TGD_S, w::TGD, true)?,
            a0: q.q("a0", eph.clock.af0, lsb::a0(), w::A0, true)?,
            a1: q.q("a1", eph.clock.af1, lsb::a1(), w::A1, true)?,
            a2: q.q("a2", eph.clock.af2, lsb::a2(), w::A2, true)?,
            aode: q.q(
                "AODE",
                f64::from(eph.iode.max(AODE_MIN)),
                1.0,
                w::AODE,
                false,
            )?,
            toe: q.q("toe", sow(eph.toe), lsb::t_ref(), w::TOE, false)?,
            sqrt_a: q.q("sqrt(A)", eph.orbit.sqrt_a, lsb::sqrt_a(), w::WORD32, false)?,
            e: q.q("e", eph.orbit.e, lsb::e(), w::WORD32, false)?,
            i0: q.angle("i0", eph.orbit.i0, w::WORD32)?,
            omega0: q.angle("Omega0", eph.orbit.omega0, w::WORD32)?,
            omega: q.angle("omega", eph.orbit.omega, w::WORD32)?,
            m0: q.angle("M0", eph.orbit.m0, w::WORD32)?,
            delta_n: q.q("Delta n", eph.orbit.delta_n, lsb::rate(), w::DELTA_N, true)?,
            idot: q.q("IDOT", eph.orbit.idot, lsb::rate(), w::IDOT, true)?,
            omega_dot: q.q(
                "Omega dot",
                eph.orbit.omega_dot,
                lsb::rate(),
                w::OMEGA_DOT,
                true,
            )?,
            cuc: q.q("Cuc", eph.harmonics.cuc, lsb::c_angle(), w::HARMONIC, true)?,
            cus: q.q("Cus", eph.harmonics.cus, lsb::c_angle(), w::HARMONIC, true)?,
            cic: q.q("Cic", eph.harmonics.cic, lsb::c_angle(), w::HARMONIC, true)?,
            cis: q.q("Cis", eph.harmonics.cis, lsb::c_angle(), w::HARMONIC, true)?,
            crc: q.q("Crc", eph.harmonics.crc, lsb::c_radius(), w::HARMONIC, true)?,
            crs: q.q("Crs", eph.harmonics.crs, lsb::c_radius(), w::HARMONIC, true)?,
        })
    }

    /// The ephemeris the message describes: `grid` (toe, toc on the 8 s grid) with every
    /// broadcast field replaced by its quantised value. Fields the message does not carry
    /// (satellite, class, fit interval) are kept; health becomes SatH1 (0 or 1).
    pub(super) fn to_ephemeris(self, grid: &BroadcastEphemeris) -> BroadcastEphemeris {
        let f = |n: i64, l: f64| n as f64 * l;
        let orbit = KeplerElements {
            sqrt_a: f(self.sqrt_a, lsb::sqrt_a()),
            e: f(self.e, lsb::e()),
            i0: f(self.i0, lsb::angle()),
            omega0: f(self.omega0, lsb::angle()),
            omega: f(self.omega, lsb::angle()),
            m0: f(self.m0, lsb::angle()),
            delta_n: f(self.delta_n, lsb::rate()),
            idot: f(self.idot, lsb::rate()),
            omega_dot: f(self.omega_dot, lsb::rate()),
        };
        let harmonics = HarmonicCorrections {
            cuc: f(self.cuc, lsb::c_angle()),
            cus: f(self.cus, lsb::c_angle()),
            crc: f(self.crc, lsb::c_radius()),
            crs: f(self.crs, lsb::c_radius()),
            cic: f(self.cic, lsb::c_angle()),
            cis: f(self.cis, lsb::c_angle()),
        };
        let clock = ClockParams {
            af0: f(self.a0, lsb::a0()),
            af1: f(self.a1, lsb::a1()),
            af2: f(self.a2, lsb::a2()),
            tgd_s: f(self.tgd1, lsb::TGD_S),
            tgd2_s: 0.0,
        };
        BroadcastEphemeris {
            toc: grid.toc,
            iode: self.aode as u32,
            iodc: self.aodc as u32,
            health: self.sat_h1 as u32,
            ..BroadcastEphemeris::from_elements(
                grid.sat,
                grid.class,
                grid.toe,
                orbit,
                harmonics,
                clock,
                grid.fit_interval_s,
            )
        }
    }
}

/// Klobuchar parameters as integers (alpha0..3, beta0..3).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct IonoFields {
    pub alpha: [i64; 4],
    pub beta: [i64; 4],
}

impl IonoFields {
    pub(super) fn quantise(k: &Klobuchar, q: Quantiser<'_>) -> Result<Self, BdsNavError> {
        const A: [&str; 4] = ["alpha0", "alpha1", "alpha2", "alpha3"];
        const B: [&str; 4] = ["beta0", "beta1", "beta2", "beta3"];
        let mut out = Self {
            alpha: [0; 4],
            beta: [0; 4],
        };
        for n in 0..4 {
            out.alpha[n] = q.q(A[n], k.alpha[n], lsb::alpha(n), width::KLOBUCHAR, true)?;
            out.beta[n] = q.q(B[n], k.beta[n], lsb::beta(n), width::KLOBUCHAR, true)?;
        }
        Ok(out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn quantiser() -> Quantiser<'static> {
        Quantiser { sat: "C19" }
    }

    #[test]
    fn ranges_follow_the_field_width() {
        let q = quantiser();
        assert_eq!(q.q("x", 127.4, 1.0, 8, true), Ok(127));
        assert_eq!(q.q("x", -128.4, 1.0, 8, true), Ok(-128));
        assert!(q.q("x", 127.6, 1.0, 8, true).is_err());
        assert!(q.q("x", -0.6, 1.0, 5, false).is_err());
        assert_eq!(q.q("x", 31.0, 1.0, 5, false), Ok(31));
        assert!(q.q("x", f64::NAN, 1.0, 5, false).is_err());
    }

    #[test]
    fn angles_wrap_into_the_32_bit_range() {
        let q = quantiser();
        assert_eq!(q.angle("a", PI, 32), Ok(-(1 << 31)));
        assert_eq!(q.angle("a", -PI, 32), Ok(-(1 << 31)));
        assert_eq!(q.angle("a", 3.0 * PI / 2.0, 32), Ok(-(1 << 30)));
        assert_eq!(q.angle("a", PI / 2.0, 32), Ok(1 << 30));
        let just_below_pi = PI - 0.4 * lsb::angle();
        assert_eq!(q.angle("a", just_below_pi, 32), Ok(-(1 << 31)));
    }
}
