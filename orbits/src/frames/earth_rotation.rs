//! ECI <-> ECEF by Earth rotation only.
//!
//! # The scenario ECI frame
//!
//! ECEF is WGS-84. The scenario ECI frame is the ECEF frame at the scenario start rotated
//! back about Z by the Greenwich mean sidereal angle of the start, and then frozen:
//!
//! ```text
//! theta(t) = theta0 + OMEGA_E_GPS * t,      c_eci_ecef(t) = R3(theta(t))
//! theta0   = GMST (IAU 1982) at the start epoch, with UT1 ~ UTC
//! ```
//!
//! So ECI is a pseudo-inertial "mean equator and equinox of date" frame, fixed at the
//! scenario start (it is, to the neglected terms below, the TEME/true-of-date frame that
//! SGP4 uses, which rotates to ECEF by GMST 1982 as well). `OMEGA_E_GPS` (IS-GPS-200) is
//! the inertial rotation rate of the Earth (the Earth-rotation-angle rate,
//! 1.00273781191135448 rev per UT1 day); GMST itself grows faster by the precession in
//! right ascension, which belongs to the slow frame motion neglected here.
//!
//! # What is neglected, and how big it is
//!
//! | term | size | effect here |
//! |---|---|---|
//! | precession since J2000 | ~50"/yr (about 20' by 2024) | ECI axes are "of date", not J2000/GCRF |
//! | nutation (GAST - GMST, obliquity) | <= ~17" in longitude, ~9" in obliquity | constant frame offset |
//! | precession + nutation during a scenario | <= ~0.2"/day | frame drift, <= 7 m/day at LEO radius |
//! | polar motion | <= ~0.5" (<= 15 m at the surface) | ECEF Z vs the rotation axis |
//! | UT1 - UTC | <= 0.9 s | <= 13.5" of rotation angle (constant) |
//!
//! None of these matters for SkyForge's geometry: GNSS satellite orbits come from the
//! broadcast ephemerides in ECEF and the receiver positions of ground sites and
//! trajectories are ECEF, so all ranges are formed in ECEF and never see the ECI axes.
//! ECI only carries the LEO's numerical propagation, and the LEO's initial elements are
//! *defined* in this very frame, so a constant frame offset of a few arc-seconds just
//! relabels the initial orbit (equivalent to shifting its RAAN by at most ~30"). The
//! dynamics (two-body, J2 and drag) are insensitive to such an offset: J2 acts about the
//! ECEF Z axis, whose misalignment with ECI Z (nutation + polar motion, < 20") changes
//! the J2 acceleration by < 1e-4 of itself. A drift of a few metres per day only means
//! the simulated LEO flies a slightly different, equally valid orbit: truth and every
//! observable are computed from the same ECEF states.

use crate::constants::OMEGA_E_GPS;
use crate::{Mat3, Vec3};
use hifitime::Epoch;
use std::f64::consts::TAU;

/// Earth rotation angle about Z from the scenario's ECI frame to ECEF.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EarthRotation {
    theta0_rad: f64,
}

/// Modified Julian Date of J2000.0 (2000-01-01 12:00).
const MJD_J2000: f64 = 51_544.5;

/// Greenwich mean sidereal angle (rad, in [0, 2 pi)) at a UT1 epoch given as the
/// Modified Julian Date. IAU 1982 (Aoki et al. 1982; Vallado, Fundamentals of
/// Astrodynamics, eq. 3-47):
/// `GMST = 67310.54841 s + (876600 h + 8640184.812866 s) T + 0.093104 s T^2 - 6.2e-6 s T^3`,
/// `T` in Julian centuries of UT1 since J2000.0. The `876600 h T` term is exactly one turn
/// per UT1 day, so it is evaluated as the fraction of the day to keep precision.
pub fn gmst82_rad(mjd_ut1: f64) -> f64 {
    let days = mjd_ut1 - MJD_J2000;
    let t = days / 36_525.0;
    let seconds = 67_310.548_41
        + days.rem_euclid(1.0) * 86_400.0
        + t * (8_640_184.812_866 + t * (0.093_104 - 6.2e-6 * t));
    seconds.rem_euclid(86_400.0) * (TAU / 86_400.0)
}

impl EarthRotation {
    /// The rotation whose angle at `start` is the Greenwich sidereal angle of `start`.
    /// UT1 is taken equal to UTC (|UT1 - UTC| <= 0.9 s, see the module docs).
    pub fn at_origin(start: Epoch) -> Self {
        Self {
            theta0_rad: gmst82_rad(start.to_mjd_utc_days()),
        }
    }
    /// Rotation angle (rad) at `t_s` seconds after the origin, wrapped to [0, 2 pi).
    pub fn angle_rad(&self, t_s: f64) -> f64 {
        (self.theta0_rad + OMEGA_E_GPS * t_s).rem_euclid(TAU)
    }
    /// `c_eci_ecef` at `t_s`: `R3(theta)`, maps ECI components to ECEF components.
    pub fn c_eci_ecef(&self, t_s: f64) -> Mat3 {
        let (s, c) = self.angle_rad(t_s).sin_cos();
        Mat3::new(c, s, 0.0, -s, c, 0.0, 0.0, 0.0, 1.0)
    }
    /// The Earth's angular velocity (rad/s), the same in ECI and ECEF.
    pub fn omega_rad_s(&self) -> Vec3 {
        Vec3::new(0.0, 0.0, OMEGA_E_GPS)
    }
    /// ECI position/velocity to ECEF position/velocity at `t_s` (velocity includes -w x r).
    pub fn eci_to_ecef(&self, t_s: f64, r_eci_m: &Vec3, v_eci_mps: &Vec3) -> (Vec3, Vec3) {
        let c = self.c_eci_ecef(t_s);
        let r_ecef_m = c * r_eci_m;
        let v_ecef_mps = c * v_eci_mps - self.omega_rad_s().cross(&r_ecef_m);
        (r_ecef_m, v_ecef_mps)
    }
    /// ECEF position/velocity to ECI at `t_s` (velocity includes +w x r).
    pub fn ecef_to_eci(&self, t_s: f64, r_ecef_m: &Vec3, v_ecef_mps: &Vec3) -> (Vec3, Vec3) {
        let c_ecef_eci = self.c_eci_ecef(t_s).transpose();
        let r_eci_m = c_ecef_eci * r_ecef_m;
        let v_eci_mps = c_ecef_eci * v_ecef_mps + self.omega_rad_s().cross(&r_eci_m);
        (r_eci_m, v_eci_mps)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    #[test]
    fn gmst_vallado_example_3_5() {
        // Vallado, Fundamentals of Astrodynamics, example 3-5: 1992-08-20 12:14 UT1,
        // GMST = 152.578787810 deg.
        let e = Epoch::from_gregorian_utc_hms(1992, 8, 20, 12, 14, 0);
        let rot = EarthRotation::at_origin(e);
        assert!((rot.angle_rad(0.0).to_degrees() - 152.578_787_810).abs() < 1e-6);
    }

    #[test]
    fn gmst_astronomical_almanac_1992_jan_1() {
        // Astronomical Almanac 1992 (quoted in Vallado example 3-6): GMST at
        // 1992-01-01 0h UT1 = 6h 39m 37.4863s.
        let e = Epoch::from_gregorian_utc_hms(1992, 1, 1, 0, 0, 0);
        let expected_deg = (6.0 + 39.0 / 60.0 + 37.4863 / 3600.0) * 15.0;
        let got = EarthRotation::at_origin(e).angle_rad(0.0).to_degrees();
        assert!((got - expected_deg).abs() < 1e-5, "{got} vs {expected_deg}");
    }

    #[test]
    fn one_sidereal_day_is_one_turn() {
        // 2 pi / OMEGA_E_GPS = 86164.0989 s (one sidereal day).
        let rot = EarthRotation::at_origin(Epoch::from_gregorian_utc_hms(2023, 3, 12, 0, 0, 0));
        let d = (rot.angle_rad(86_164.098_9) - rot.angle_rad(0.0)).abs();
        assert!(d.min(TAU - d) < 1e-8);
    }

    #[test]
    fn ecef_fixed_point_moves_with_omega_cross_r_in_eci() {
        let rot = EarthRotation::at_origin(Epoch::from_gregorian_utc_hms(2020, 6, 25, 0, 0, 0));
        let r_ecef = Vec3::new(4_000_000.0, -3_000_000.0, 3_500_000.0);
        for t in [0.0, 1000.0, 43_000.0] {
            let (r_eci, v_eci) = rot.ecef_to_eci(t, &r_ecef, &Vec3::zeros());
            let expected = Vec3::new(0.0, 0.0, OMEGA_E_GPS).cross(&r_eci);
            assert!((v_eci - expected).norm() < 1e-9);
            // Numerical derivative of the ECI position agrees.
            let h = 0.5;
            let (rp, _) = rot.ecef_to_eci(t + h, &r_ecef, &Vec3::zeros());
            let (rm, _) = rot.ecef_to_eci(t - h, &r_ecef, &Vec3::zeros());
            assert!(((rp - rm) / (2.0 * h) - v_eci).norm() < 1e-4);
        }
    }

    #[test]
    fn rotation_sense_is_eastward() {
        // An ECI-fixed point drifts westward in ECEF: its longitude decreases.
        let rot = EarthRotation::at_origin(Epoch::from_gregorian_utc_hms(2020, 6, 25, 0, 0, 0));
        let r_eci = Vec3::new(7e6, 0.0, 0.0);
        let (a, _) = rot.eci_to_ecef(0.0, &r_eci, &Vec3::zeros());
        let (b, _) = rot.eci_to_ecef(100.0, &r_eci, &Vec3::zeros());
        let dlon = b.y.atan2(b.x) - a.y.atan2(a.x);
        assert!((dlon + OMEGA_E_GPS * 100.0).abs() < 1e-12);
    }

    proptest! {
        #[test]
        fn eci_ecef_round_trip(
            t in -1e6f64..1e6,
            x in -5e7f64..5e7, y in -5e7f64..5e7, z in -5e7f64..5e7,
            vx in -1e4f64..1e4, vy in -1e4f64..1e4, vz in -1e4f64..1e4,
        ) {
            let rot = EarthRotation::at_origin(Epoch::from_gregorian_utc_hms(2023, 3, 12, 0, 0, 0));
            let (r, v) = (Vec3::new(x, y, z), Vec3::new(vx, vy, vz));
            let (re, ve) = rot.eci_to_ecef(t, &r, &v);
            let (ri, vi) = rot.ecef_to_eci(t, &re, &ve);
            prop_assert!((ri - r).norm() < 1e-7);
            prop_assert!((vi - v).norm() < 1e-9);
            let c = rot.c_eci_ecef(t);
            prop_assert!((c * c.transpose() - Mat3::identity()).norm() < 1e-14);
            prop_assert!((c.determinant() - 1.0).abs() < 1e-14);
        }
    }
}
