//! The proper time of a receiver clock that moves with its platform, against GPS time
//! (`[errors.receiver_clock] relativity = true`; book Yuan 2000 eqs. 5-16/5-17).
//!
//! A clock at distance `r` from the Earth's centre moving at inertial speed `v` runs at
//! `dtau/dt = 1 - (mu / r + v^2 / 2 - W0) / c^2` of GPS time (which keeps the rate of a
//! clock on the geoid, potential `W0`). Its offset is the integral of that rate less one.
//! For a Keplerian orbit the integral is `-(3 mu / (2 a) - W0) t / c^2 - 2 (r . v) / c^2`
//! (+ a constant): a constant rate (eq. 5-16 writes it against the GPS satellites' clocks,
//! `3 mu / (2 c^2) (1 / r_u - 1 / r_s)`) and the periodic term of eq. 5-17,
//! `2 sqrt(mu a) e sin(E) / c^2 = 2 (r . v) / c^2` (about 1.2 ns at a = 7271 km, e =
//! 0.001). The truth integrates the exact rate along the platform's own trajectory (J2 and
//! drag included) by the trapezoid rule at the geometry step, and the renderer
//! interpolates between steps by cubic Hermite with the rates as slopes; the Earth's
//! potential is its point-mass term, as the book's (J2's adds about 1e-12 periodic).

use skyforge_orbits::Vec3;
use skyforge_orbits::constants::{C_MPS, GM_GPS, OMEGA_E_GPS};

/// The geoid's potential (m^2/s^2), IERS Conventions (2010) table 1.1: `L_G c^2`.
pub const W0_M2_S2: f64 = 62_636_856.0;

/// The fractional rate of a clock's proper time against GPS time, less one, at the
/// Earth-fixed position `r_ecef_m` with the Earth-fixed velocity `v_ecef_mps`.
pub fn proper_rate(r_ecef_m: &Vec3, v_ecef_mps: &Vec3) -> f64 {
    let v_inertial = v_ecef_mps + Vec3::new(0.0, 0.0, OMEGA_E_GPS).cross(r_ecef_m);
    -(GM_GPS / r_ecef_m.norm() + 0.5 * v_inertial.norm_squared() - W0_M2_S2) / (C_MPS * C_MPS)
}

/// One point of the offset: time (s), offset (s), rate (s/s).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OffsetPoint {
    pub t_s: f64,
    pub offset_s: f64,
    pub rate: f64,
}

/// The relativistic clock offset accumulated along a trajectory: the platform's rate at
/// each geometry epoch in, the offset out (zero at the first epoch).
#[derive(Debug, Clone, Default)]
pub struct RelativisticOffset {
    last: Option<OffsetPoint>,
}

impl RelativisticOffset {
    pub fn new() -> Self {
        Self::default()
    }

    /// The platform's rate `rate` ([`proper_rate`]) at `t_s` (increasing): the offset
    /// there, by the trapezoid rule from the previous epoch.
    pub fn push(&mut self, t_s: f64, rate: f64) -> OffsetPoint {
        let offset_s = match self.last {
            Some(p) => p.offset_s + 0.5 * (p.rate + rate) * (t_s - p.t_s),
            None => 0.0,
        };
        let point = OffsetPoint {
            t_s,
            offset_s,
            rate,
        };
        self.last = Some(point);
        point
    }
}

/// The offset and rate at `t_s` between two points (cubic Hermite with the rates as
/// slopes; the rate linearly), or at the one point outside them.
pub fn interpolate(a: &OffsetPoint, b: &OffsetPoint, t_s: f64) -> (f64, f64) {
    let h = b.t_s - a.t_s;
    if h <= 0.0 {
        return (a.offset_s + a.rate * (t_s - a.t_s), a.rate);
    }
    let s = ((t_s - a.t_s) / h).clamp(0.0, 1.0);
    let (s2, s3) = (s * s, s * s * s);
    let offset = (2.0 * s3 - 3.0 * s2 + 1.0) * a.offset_s
        + (s3 - 2.0 * s2 + s) * h * a.rate
        + (-2.0 * s3 + 3.0 * s2) * b.offset_s
        + (s3 - s2) * h * b.rate;
    (offset, a.rate + s * (b.rate - a.rate))
}

#[cfg(test)]
mod tests {
    use super::*;
    use skyforge_orbits::frames::earth_rotation::EarthRotation;

    /// A Keplerian orbit (a = 7271 km, e = 0.001) integrated at 1 s against the closed
    /// form `-(3 mu / (2a) - W0) t / c^2 - 2 (r . v - r0 . v0) / c^2` over two hours:
    /// within 1e-13 s; the secular rate about -2.2e-10 and the periodic term's amplitude
    /// 2 sqrt(mu a) e / c^2 = 1.2 ns.
    #[test]
    fn the_integral_is_the_keplerian_closed_form() {
        let (a, e) = (7.271e6_f64, 0.001_f64);
        let n = (GM_GPS / a.powi(3)).sqrt();
        let earth = EarthRotation::at_origin(hifitime::Epoch::from_gpst_seconds(1.0e9));
        // The orbit in the equatorial plane of ECI, by Kepler's equation.
        let state = |t: f64| {
            let m = n * t;
            let mut big_e = m;
            for _ in 0..30 {
                big_e = m + e * big_e.sin();
            }
            let (sin_e, cos_e) = big_e.sin_cos();
            let r = Vec3::new(a * (cos_e - e), a * (1.0 - e * e).sqrt() * sin_e, 0.0);
            let edot = n / (1.0 - e * cos_e);
            let v = Vec3::new(
                -a * sin_e * edot,
                a * (1.0 - e * e).sqrt() * cos_e * edot,
                0.0,
            );
            (r, v)
        };
        let c2 = C_MPS * C_MPS;
        let secular = -(1.5 * GM_GPS / a - W0_M2_S2) / c2;
        assert!((secular + 2.18e-10).abs() < 0.01e-10, "{secular}");
        let amplitude = 2.0 * (GM_GPS * a).sqrt() * e / c2;
        assert!((amplitude - 1.2e-9).abs() < 0.01e-9, "{amplitude}");
        let (r0, v0) = state(0.0);
        let mut offset = RelativisticOffset::new();
        for k in 0..=7200 {
            let t = f64::from(k);
            let (r, v) = state(t);
            let (r_e, v_e) = earth.eci_to_ecef(t, &r, &v);
            let p = offset.push(t, proper_rate(&r_e, &v_e));
            let closed = secular * t - 2.0 * (r.dot(&v) - r0.dot(&v0)) / c2;
            assert!(
                (p.offset_s - closed).abs() < 1e-13,
                "t {t}: {} vs {closed}",
                p.offset_s
            );
        }
    }

    /// A clock at rest on the equator at the geoid's radius runs at GPS time's rate to
    /// the geoid's flattening (within 1e-11; the point-mass potential ignores J2's part).
    #[test]
    fn a_clock_on_the_geoid_keeps_gps_time() {
        let r = Vec3::new(6_378_137.0, 0.0, 0.0);
        assert!(proper_rate(&r, &Vec3::zeros()).abs() < 1e-11);
    }

    /// Between two points the Hermite interpolant meets both, with their rates.
    #[test]
    fn interpolation_meets_the_points() {
        let (a, b) = (
            OffsetPoint {
                t_s: 10.0,
                offset_s: 1e-9,
                rate: -2e-10,
            },
            OffsetPoint {
                t_s: 11.0,
                offset_s: 0.8e-9,
                rate: -2.2e-10,
            },
        );
        assert_eq!(interpolate(&a, &b, 10.0), (1e-9, -2e-10));
        let (o, r) = interpolate(&a, &b, 11.0);
        assert!((o - 0.8e-9).abs() < 1e-24 && (r + 2.2e-10).abs() < 1e-24);
        let (mid, _) = interpolate(&a, &b, 10.5);
        assert!(mid < 1e-9 && mid > 0.8e-9);
    }
}
