//! Keplerian elements <-> Cartesian state.
//!
//! Conventions (Vallado, *Fundamentals of Astrodynamics and Applications*, algorithms 9 and
//! 10, written for robustness at small eccentricity and inclination):
//! - near-circular orbits (`e < 1e-11`): the argument of perigee is set to 0 and the mean
//!   anomaly carries the argument of latitude;
//! - near-equatorial orbits (`sin i < 1e-11`): the ascending node is set to the X axis
//!   (RAAN = 0), so the argument of perigee / mean anomaly are measured from X.
//!
//! Whatever the branch, `to_cartesian(from_cartesian(r, v))` reproduces `(r, v)`: the
//! conventions only decide how a nearly undefined angle is split between its neighbours.

use crate::Vec3;
use crate::angles::wrap_two_pi;
use std::f64::consts::{PI, TAU};

/// Below this eccentricity the argument of perigee is undefined (set to 0).
const E_CIRCULAR: f64 = 1e-11;
/// Below this `sin i` the node is undefined (set to the X axis).
const SIN_I_EQUATORIAL: f64 = 1e-11;
/// Kepler's equation is solved to this residual (rad).
const KEPLER_TOL_RAD: f64 = 1e-14;

/// Classical osculating elements (SI, radians).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct KeplerianElements {
    pub a_m: f64,
    pub e: f64,
    pub i_rad: f64,
    pub raan_rad: f64,
    pub argp_rad: f64,
    pub mean_anomaly_rad: f64,
}

impl KeplerianElements {
    /// Position and velocity for gravitational parameter `mu` (m^3/s^2), for `0 <= e < 1`.
    pub fn to_cartesian(&self, mu: f64) -> (Vec3, Vec3) {
        let e = self.e;
        let ecc_anomaly = solve_kepler(self.mean_anomaly_rad, e);
        let (sin_e, cos_e) = ecc_anomaly.sin_cos();
        let b_over_a = (1.0 - e * e).sqrt();
        // Perifocal frame: P to perigee, Q 90 deg ahead in the orbit plane.
        let x_p = self.a_m * (cos_e - e);
        let y_p = self.a_m * b_over_a * sin_e;
        let n = self.mean_motion_rad_s(mu);
        let rate = n * self.a_m / (1.0 - e * cos_e);
        let vx_p = -rate * sin_e;
        let vy_p = rate * b_over_a * cos_e;
        let (p_hat, q_hat) = perifocal_axes(self.raan_rad, self.i_rad, self.argp_rad);
        (p_hat * x_p + q_hat * y_p, p_hat * vx_p + q_hat * vy_p)
    }

    /// Elements of a bound orbit from position and velocity (`mu` in m^3/s^2). Angles are
    /// in `[0, 2 pi)`; see the module docs for the circular / equatorial conventions.
    /// For an unbound state (`v^2 >= 2 mu / r`) the result is meaningless.
    pub fn from_cartesian(r_m: &Vec3, v_mps: &Vec3, mu: f64) -> Self {
        let r = r_m.norm();
        let h = r_m.cross(v_mps);
        let h_norm = h.norm();
        let h_hat = h / h_norm;
        let energy = 0.5 * v_mps.norm_squared() - mu / r;
        let a_m = -mu / (2.0 * energy);
        let e_vec = (r_m * (v_mps.norm_squared() - mu / r) - v_mps * r_m.dot(v_mps)) / mu;
        let e = e_vec.norm();
        // Node line: Z x h; atan2 keeps i accurate near 0 and 180 deg.
        let node = Vec3::new(-h.y, h.x, 0.0);
        let sin_i = node.norm() / h_norm;
        let i_rad = sin_i.atan2(h_hat.z);
        let raan_rad = if sin_i < SIN_I_EQUATORIAL {
            0.0
        } else {
            h.x.atan2(-h.y)
        };
        // In-plane axes: n_hat along the node (X when equatorial), m_hat = h_hat x n_hat.
        let (sin_raan, cos_raan) = raan_rad.sin_cos();
        let n_hat = Vec3::new(cos_raan, sin_raan, 0.0);
        let n_hat = (n_hat - h_hat * h_hat.dot(&n_hat)).normalize();
        let m_hat = h_hat.cross(&n_hat);
        let arg_latitude = r_m.dot(&m_hat).atan2(r_m.dot(&n_hat));
        let argp_rad = if e < E_CIRCULAR {
            0.0
        } else {
            e_vec.dot(&m_hat).atan2(e_vec.dot(&n_hat))
        };
        let true_anomaly = arg_latitude - argp_rad;
        let (sin_nu, cos_nu) = true_anomaly.sin_cos();
        let ecc_anomaly = ((1.0 - e * e).sqrt() * sin_nu).atan2(e + cos_nu);
        let mean_anomaly = ecc_anomaly - e * ecc_anomaly.sin();
        Self {
            a_m,
            e,
            i_rad,
            raan_rad: wrap_two_pi(raan_rad),
            argp_rad: wrap_two_pi(argp_rad),
            mean_anomaly_rad: wrap_two_pi(mean_anomaly),
        }
    }

    /// Keplerian mean motion `sqrt(mu / a^3)` (rad/s).
    pub fn mean_motion_rad_s(&self, mu: f64) -> f64 {
        (mu / self.a_m.powi(3)).sqrt()
    }

    /// Keplerian period (s).
    pub fn period_s(&self, mu: f64) -> f64 {
        TAU / self.mean_motion_rad_s(mu)
    }
}

/// Unit vectors P (to perigee) and Q of the perifocal frame in the inertial frame
/// (rotation R3(-raan) R1(-i) R3(-argp)).
fn perifocal_axes(raan: f64, i: f64, argp: f64) -> (Vec3, Vec3) {
    let (so, co) = raan.sin_cos();
    let (si, ci) = i.sin_cos();
    let (sw, cw) = argp.sin_cos();
    let p_hat = Vec3::new(co * cw - so * sw * ci, so * cw + co * sw * ci, sw * si);
    let q_hat = Vec3::new(-co * sw - so * cw * ci, -so * sw + co * cw * ci, cw * si);
    (p_hat, q_hat)
}

/// Eccentric anomaly `E` with `E - e sin E = M`, to a residual below 1e-14 rad
/// (Newton's method, started at `M` for `e < 0.8`, at `pi` otherwise; 0 <= e < 1).
pub fn solve_kepler(mean_anomaly_rad: f64, e: f64) -> f64 {
    // Reduce M to (-pi, pi] so the residual tolerance is meaningful in absolute terms.
    let m = mean_anomaly_rad - TAU * ((mean_anomaly_rad + PI) / TAU).floor();
    let mut ecc = if e < 0.8 { m } else { PI.copysign(m) };
    for _ in 0..60 {
        let residual = ecc - e * ecc.sin() - m;
        if residual.abs() <= KEPLER_TOL_RAD {
            break;
        }
        ecc -= residual / (1.0 - e * ecc.cos());
    }
    // Back to the branch of the caller's mean anomaly.
    ecc + (mean_anomaly_rad - m)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::constants::GM_GPS;
    use proptest::prelude::*;

    /// Vallado, *Fundamentals of Astrodynamics and Applications* (4th ed.), example 2-5
    /// (RV2COE): r = (6524.834, 6862.875, 6448.296) km, v = (4.901327, 5.533756,
    /// -1.976341) km/s gives a = 36127.343 km, e = 0.832853, i = 87.870 deg,
    /// RAAN = 227.898 deg, argp = 53.38 deg, true anomaly = 92.335 deg.
    #[test]
    fn vallado_example_2_5() {
        let mu = 3.986_004_418e14;
        let r = Vec3::new(6524.834e3, 6862.875e3, 6448.296e3);
        let v = Vec3::new(4.901327e3, 5.533756e3, -1.976341e3);
        let el = KeplerianElements::from_cartesian(&r, &v, mu);
        assert!((el.a_m - 36127.343e3).abs() < 50.0, "a {}", el.a_m);
        assert!((el.e - 0.832853).abs() < 2e-6, "e {}", el.e);
        assert!((el.i_rad.to_degrees() - 87.870).abs() < 1e-3);
        assert!((el.raan_rad.to_degrees() - 227.898).abs() < 1e-2);
        assert!((el.argp_rad.to_degrees() - 53.38).abs() < 1e-2);
        let ecc = solve_kepler(el.mean_anomaly_rad, el.e);
        let nu = ((1.0 - el.e * el.e).sqrt() * ecc.sin()).atan2(ecc.cos() - el.e);
        assert!((wrap_two_pi(nu).to_degrees() - 92.335).abs() < 1e-2);
    }

    #[test]
    fn kepler_equation_residual_is_tiny_for_hard_cases() {
        for &e in &[0.0, 1e-6, 0.5, 0.9, 0.99, 0.999] {
            for k in -20..=20 {
                let m = 0.31 * f64::from(k);
                let ecc = solve_kepler(m, e);
                let residual = ecc - e * ecc.sin() - m;
                assert!(residual.abs() < 1e-13, "e {e} M {m}: residual {residual:e}");
            }
        }
    }

    #[test]
    fn circular_equatorial_orbit_is_well_defined() {
        let el = KeplerianElements {
            a_m: 7.0e6,
            e: 0.0,
            i_rad: 0.0,
            raan_rad: 0.0,
            argp_rad: 0.0,
            mean_anomaly_rad: 1.0,
        };
        let (r, v) = el.to_cartesian(GM_GPS);
        assert!((r.norm() - 7.0e6).abs() < 1e-6);
        assert!((v.norm() - (GM_GPS / 7.0e6).sqrt()).abs() < 1e-9);
        let back = KeplerianElements::from_cartesian(&r, &v, GM_GPS);
        assert_eq!(back.raan_rad, 0.0);
        assert_eq!(back.argp_rad, 0.0);
        assert!((back.mean_anomaly_rad - 1.0).abs() < 1e-12);
        assert!(back.i_rad.abs() < 1e-12);
    }

    fn angle_diff(a: f64, b: f64) -> f64 {
        let d = (a - b).rem_euclid(TAU);
        d.min(TAU - d)
    }

    proptest! {
        /// Elements -> state -> elements -> state reproduces the state for any bound
        /// orbit, including (nearly) circular and (nearly) equatorial ones.
        #[test]
        fn cartesian_round_trip(
            a_km in 6500.0..45_000.0f64,
            e in prop_oneof![Just(0.0), 0.0..1e-9f64, 0.0..0.95f64],
            i in prop_oneof![Just(0.0), Just(PI), 0.0..PI],
            raan in 0.0..TAU,
            argp in 0.0..TAU,
            m in -10.0..10.0f64,
        ) {
            let el = KeplerianElements {
                a_m: a_km * 1e3, e, i_rad: i, raan_rad: raan, argp_rad: argp,
                mean_anomaly_rad: m,
            };
            let (r, v) = el.to_cartesian(GM_GPS);
            let back = KeplerianElements::from_cartesian(&r, &v, GM_GPS);
            let (r2, v2) = back.to_cartesian(GM_GPS);
            prop_assert!((r2 - r).norm() < 1e-6 * r.norm(), "{el:?} {back:?}");
            prop_assert!((v2 - v).norm() < 1e-6 * v.norm());
            prop_assert!((back.a_m - el.a_m).abs() < 1e-8 * el.a_m);
            prop_assert!((back.e - e).abs() < 1e-9);
            prop_assert!(angle_diff(back.i_rad, i) < 1e-9);
        }

        /// Away from the singular cases every element comes back individually.
        #[test]
        fn elements_round_trip(
            a_km in 6500.0..45_000.0f64,
            e in 1e-3..0.9f64,
            i in 0.01..(PI - 0.01),
            raan in 0.0..TAU,
            argp in 0.0..TAU,
            m in 0.0..TAU,
        ) {
            let el = KeplerianElements {
                a_m: a_km * 1e3, e, i_rad: i, raan_rad: raan, argp_rad: argp,
                mean_anomaly_rad: m,
            };
            let (r, v) = el.to_cartesian(GM_GPS);
            let back = KeplerianElements::from_cartesian(&r, &v, GM_GPS);
            prop_assert!(angle_diff(back.raan_rad, raan) < 1e-9);
            prop_assert!(angle_diff(back.argp_rad, argp) < 1e-7 / e);
            prop_assert!(angle_diff(back.mean_anomaly_rad, m) < 1e-7 / e);
            prop_assert!(angle_diff(back.argp_rad + back.mean_anomaly_rad, argp + m) < 1e-9);
        }
    }
}
