//! WGS-84 geodetic latitude/longitude/height <-> ECEF.
//!
//! Forward: the closed form `r = ((N + h) cos(lat) cos(lon), (N + h) cos(lat) sin(lon),
//! (N (1 - e^2) + h) sin(lat))`, `N = a / sqrt(1 - e^2 sin^2(lat))` (NIMA TR8350.2 eq. 4-14).
//! Inverse: Bowring's iteration on the parametric (reduced) latitude (Bowring 1976), which
//! converges to machine precision in two or three steps for every point from the Earth's
//! interior to far space, poles included; the height uses the form
//! `h = p cos(lat) + (z + e^2 N sin(lat)) sin(lat) - N`, well conditioned at all latitudes.

use crate::Vec3;
use crate::constants::{WGS84_A_M, WGS84_F};
use crate::frames::ned::c_ecef_ned;

/// Geodetic coordinates on WGS-84 (radians, metres).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Geodetic {
    pub lat_rad: f64,
    pub lon_rad: f64,
    pub h_m: f64,
}

impl Geodetic {
    /// Latitude and longitude in degrees, height in metres.
    pub fn from_degrees(lat_deg: f64, lon_deg: f64, h_m: f64) -> Self {
        Self {
            lat_rad: lat_deg.to_radians(),
            lon_rad: lon_deg.to_radians(),
            h_m,
        }
    }

    /// The unit ellipsoidal normal (local up, ECEF) at this latitude and longitude: minus
    /// the NED frame's down axis.
    pub fn up(&self) -> Vec3 {
        -c_ecef_ned(self.lat_rad, self.lon_rad).row(2).transpose()
    }
}

/// First eccentricity squared of WGS-84.
const E2: f64 = WGS84_F * (2.0 - WGS84_F);
/// Semi-minor axis of WGS-84 (m).
const B_M: f64 = WGS84_A_M * (1.0 - WGS84_F);

/// Prime-vertical radius of curvature `N` (m) at latitude `lat_rad`.
fn prime_vertical_radius_m(sin_lat: f64) -> f64 {
    WGS84_A_M / (1.0 - E2 * sin_lat * sin_lat).sqrt()
}

/// The meridian and prime-vertical radii of curvature `(M, N)` (m) at `lat_rad`
/// (Groves 2013 eqs. 2.105/2.106): the rates of latitude and longitude of a point moving
/// at `v_ned` are `v_N / (M + h)` and `v_E / ((N + h) cos(lat))`.
pub fn radii_of_curvature_m(lat_rad: f64) -> (f64, f64) {
    let s2 = lat_rad.sin().powi(2);
    let n = prime_vertical_radius_m(lat_rad.sin());
    (WGS84_A_M * (1.0 - E2) / (1.0 - E2 * s2).powf(1.5), n)
}

/// Geodetic -> ECEF.
pub fn geodetic_to_ecef(g: &Geodetic) -> Vec3 {
    let (sin_lat, cos_lat) = g.lat_rad.sin_cos();
    let (sin_lon, cos_lon) = g.lon_rad.sin_cos();
    let n = prime_vertical_radius_m(sin_lat);
    Vec3::new(
        (n + g.h_m) * cos_lat * cos_lon,
        (n + g.h_m) * cos_lat * sin_lon,
        (n * (1.0 - E2) + g.h_m) * sin_lat,
    )
}

/// ECEF -> geodetic (iterative or closed form, accurate to < 1 mm from -1e5 m to 1e8 m).
///
/// Longitude is in (-pi, pi] (0 on the polar axis); latitude in [-pi/2, pi/2].
pub fn ecef_to_geodetic(r_ecef_m: &Vec3) -> Geodetic {
    let (x, y, z) = (r_ecef_m.x, r_ecef_m.y, r_ecef_m.z);
    let p = x.hypot(y);
    let lon_rad = y.atan2(x);
    // e'^2 b = (a^2 - b^2) / b.
    let ep2_b = E2 / (1.0 - E2) * B_M;
    let e2_a = E2 * WGS84_A_M;
    // Parametric latitude, first guess from the point's direction.
    let mut beta = z.atan2((1.0 - WGS84_F) * p);
    let mut lat_rad = 0.0;
    for _ in 0..8 {
        let (sb, cb) = beta.sin_cos();
        lat_rad = (z + ep2_b * sb * sb * sb).atan2(p - e2_a * cb * cb * cb);
        let next = ((1.0 - WGS84_F) * lat_rad.sin()).atan2(lat_rad.cos());
        let done = (next - beta).abs() < 1e-15;
        beta = next;
        if done {
            break;
        }
    }
    let (sin_lat, cos_lat) = lat_rad.sin_cos();
    let n = prime_vertical_radius_m(sin_lat);
    let h_m = p * cos_lat + (z + E2 * n * sin_lat) * sin_lat - n;
    Geodetic {
        lat_rad,
        lon_rad,
        h_m,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;
    use std::f64::consts::{FRAC_PI_2, PI};

    #[test]
    fn equator_and_poles_analytic() {
        let g = ecef_to_geodetic(&Vec3::new(WGS84_A_M + 100.0, 0.0, 0.0));
        assert_eq!((g.lat_rad, g.lon_rad), (0.0, 0.0));
        assert!((g.h_m - 100.0).abs() < 1e-9);
        // WGS-84 semi-minor axis b = 6356752.3142 m (NIMA TR8350.2 table 3.3).
        for sign in [1.0, -1.0] {
            let g = ecef_to_geodetic(&Vec3::new(0.0, 0.0, sign * 6_356_752.314_2));
            assert!((g.lat_rad - sign * FRAC_PI_2).abs() < 1e-15);
            assert!(g.h_m.abs() < 1e-4);
            let r = geodetic_to_ecef(&Geodetic {
                lat_rad: sign * FRAC_PI_2,
                lon_rad: 1.0,
                h_m: 0.0,
            });
            assert!((r.z - sign * 6_356_752.314_2).abs() < 1e-4 && r.x.hypot(r.y) < 1e-9);
        }
        let r = geodetic_to_ecef(&Geodetic {
            lat_rad: 0.0,
            lon_rad: FRAC_PI_2,
            h_m: -50.0,
        });
        assert!((r - Vec3::new(0.0, WGS84_A_M - 50.0, 0.0)).norm() < 1e-9);
    }

    #[test]
    fn surface_point_lies_on_ellipsoid_with_normal_at_latitude() {
        // Independent of the formulas above: a surface point satisfies
        // (p/a)^2 + (z/b)^2 = 1 and the ellipsoid normal (p/a^2, z/b^2) makes the angle
        // `lat` with the equator.
        for lat_deg in [-89.0, -45.0, -10.0, 0.0, 30.0, 60.0, 89.9] {
            let lat: f64 = f64::to_radians(lat_deg);
            let r = geodetic_to_ecef(&Geodetic {
                lat_rad: lat,
                lon_rad: 0.3,
                h_m: 0.0,
            });
            let p = r.x.hypot(r.y);
            let on = (p / WGS84_A_M).powi(2) + (r.z / B_M).powi(2);
            assert!((on - 1.0).abs() < 1e-15);
            let normal_lat = (r.z / (B_M * B_M)).atan2(p / (WGS84_A_M * WGS84_A_M));
            assert!((normal_lat - lat).abs() < 1e-14);
            // A height moves the point along that normal.
            let up = geodetic_to_ecef(&Geodetic {
                lat_rad: lat,
                lon_rad: 0.3,
                h_m: 1000.0,
            }) - r;
            let n = Vec3::new(
                lat.cos() * 0.3f64.cos(),
                lat.cos() * 0.3f64.sin(),
                lat.sin(),
            );
            assert!((up - 1000.0 * n).norm() < 1e-8);
        }
    }

    proptest! {
        #[test]
        fn geodetic_ecef_round_trip(
            lat in prop_oneof![Just(FRAC_PI_2), Just(-FRAC_PI_2), Just(0.0), -FRAC_PI_2..FRAC_PI_2],
            lon in -PI..PI,
            h in prop_oneof![-1e5f64..1e5, 1e5f64..1e8],
        ) {
            let g = Geodetic { lat_rad: lat, lon_rad: lon, h_m: h };
            let r = geodetic_to_ecef(&g);
            let back = ecef_to_geodetic(&r);
            prop_assert!((geodetic_to_ecef(&back) - r).norm() < 1e-3);
            prop_assert!((back.h_m - h).abs() < 1e-3);
            prop_assert!((back.lat_rad - lat).abs() * (r.norm() + 1.0) < 1e-3);
            if lat.abs() < FRAC_PI_2 - 1e-9 {
                prop_assert!((back.lon_rad - lon).abs() * r.x.hypot(r.y) < 1e-3);
            }
        }
    }
}
