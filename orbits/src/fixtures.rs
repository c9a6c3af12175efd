//! Test fixtures shared by this crate's unit and integration tests (and, through the
//! `test-support` feature, by other crates' tests): the thesis LEO and the osculating
//! node and argument of latitude of a broadcast orbit.

use crate::Vec3;
use crate::ephemeris::BoundEphemeris;
use crate::ephemeris::sat_id::system_constants;
use crate::propagate::config::KeplerianElementsConfig;

/// The thesis LEO (THESIS_TARGETS.md, common setup).
pub fn thesis_elements() -> KeplerianElementsConfig {
    KeplerianElementsConfig {
        semi_major_axis_km: 6971.593,
        eccentricity: 0.000846,
        inclination_deg: 34.911,
        raan_deg: -78.005,
        arg_perigee_deg: 47.757,
        mean_anomaly_deg: 351.636,
    }
}

/// Node longitude (deg, Earth-fixed) and argument of latitude (deg) of `b` at `t` from
/// its state (osculating: the J2 node drift in the velocity moves them by up to ~0.005
/// deg).
pub fn node_and_arg_lat(b: &BoundEphemeris, t: f64) -> (f64, f64) {
    let (r, v) = b.state_ecef(t);
    let omega_e = system_constants(b.eph.sat.system).omega_e;
    let w = Vec3::new(0.0, 0.0, omega_e);
    let h = r.cross(&(v + w.cross(&r)));
    let node = Vec3::z().cross(&h).normalize();
    let u = (r.dot(&node) / r.norm())
        .clamp(-1.0, 1.0)
        .acos()
        .to_degrees();
    let u = if r.z < 0.0 { 360.0 - u } else { u };
    (node.y.atan2(node.x).to_degrees(), u)
}

/// `a - b` wrapped to [-180, 180) deg.
pub fn angle_diff_deg(a: f64, b: f64) -> f64 {
    (a - b + 180.0).rem_euclid(360.0) - 180.0
}

/// A hand-made RINEX 3.05 navigation file of one GPS record (own values): G07, toc = toe =
/// 2022-01-01T00:00:00 GPST, healthy.
pub const RINEX3_GPS_NAV: &str =
    "     3.05           N: GNSS NAV DATA    G: GPS              RINEX VERSION / TYPE
                                                            END OF HEADER
G07 2022 01 01 00 00 00 1.000000000000E-05-1.000000000000E-12 0.000000000000E+00
     1.000000000000E+01 2.000000000000E+01 4.500000000000E-09 1.000000000000E+00
     1.000000000000E-06 1.000000000000E-02 5.000000000000E-06 5.153700000000E+03
     5.184000000000E+05 1.000000000000E-08-1.000000000000E+00-1.000000000000E-08
     9.600000000000E-01 2.000000000000E+02 5.000000000000E-01-8.000000000000E-09
     1.000000000000E-10 1.000000000000E+00 2.190000000000E+03 0.000000000000E+00
     2.000000000000E+00 0.000000000000E+00-1.000000000000E-08 1.000000000000E+01
     5.112000000000E+05 4.000000000000E+00
";
