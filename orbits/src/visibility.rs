//! Visibility geometry: field of view about a boresight, elevation mask, Earth blockage.
//!
//! Earth blockage uses the WGS-84 ellipsoid inflated by the grazing height, modelled as the
//! ellipsoid with semi-axes `a + h` and `b + h` (it differs from the true constant-height
//! surface by less than `e^2 h sin^2(2 lat) / 8`, i.e. < 0.1 m for h = 100 km). Scaling Z
//! by `(a + h)/(b + h)` turns it into a sphere of radius `a + h`; the segment is blocked
//! when its point closest to the centre (in the scaled space) lies strictly between the
//! two end points and inside that sphere.
//!
//! Consequences: a receiver above the grazing surface is blocked exactly when the line
//! of sight dips below it; a receiver on or below the surface (a ground site with h = 0)
//! is blocked exactly when the line of sight points below its local (scaled-geocentric)
//! horizon. Ground receivers normally rely on their elevation mask instead.

use crate::Vec3;
use crate::constants::{WGS84_A_M, WGS84_F};

/// True when the unit line of sight is within `half_angle_rad` of the unit boresight.
///
/// The angle is computed as `atan2(|l x b|, l . b)`, accurate for tiny and large angles;
/// a half-angle of pi or more accepts every direction. Both vectors must be unit vectors
/// (only their directions matter).
pub fn within_fov(los_unit: &Vec3, boresight_unit: &Vec3, half_angle_rad: f64) -> bool {
    let angle = los_unit
        .cross(boresight_unit)
        .norm()
        .atan2(los_unit.dot(boresight_unit));
    angle <= half_angle_rad
}

/// True when the straight line from receiver to satellite (ECEF) passes below
/// `grazing_height_m` above the WGS-84 ellipsoid.
pub fn earth_blocked(r_rx_ecef_m: &Vec3, r_sat_ecef_m: &Vec3, grazing_height_m: f64) -> bool {
    segment_blocked(
        r_rx_ecef_m,
        r_sat_ecef_m,
        WGS84_A_M + grazing_height_m,
        WGS84_A_M * (1.0 - WGS84_F) + grazing_height_m,
    )
}

/// True when the straight segment from `r_rx_ecef_m` to `r_sat_ecef_m` passes, between its
/// ends, inside the spheroid about the geocentre of equatorial radius `radius_m` and polar
/// radius `polar_m` (a sphere when they are equal). Ends inside it do not count: only a
/// crossing does.
pub fn segment_blocked(
    r_rx_ecef_m: &Vec3,
    r_sat_ecef_m: &Vec3,
    radius_m: f64,
    polar_m: f64,
) -> bool {
    let scale = Vec3::new(1.0, 1.0, radius_m / polar_m);
    let p0 = r_rx_ecef_m.component_mul(&scale);
    let d = (r_sat_ecef_m - r_rx_ecef_m).component_mul(&scale);
    let dd = d.norm_squared();
    if dd == 0.0 {
        return false;
    }
    // Closest approach to the centre at p0 + s d, s = -(p0 . d) / |d|^2.
    let s = -p0.dot(&d) / dd;
    if s <= 0.0 || s >= 1.0 {
        return false;
    }
    (p0 + s * d).norm() < radius_m
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::{FRAC_PI_2, FRAC_PI_4, PI};

    #[test]
    fn fov_half_angles() {
        let b = Vec3::z();
        let at = |deg: f64| Vec3::new(deg.to_radians().sin(), 0.0, deg.to_radians().cos());
        assert!(within_fov(&b, &b, 0.0));
        assert!(within_fov(&at(44.9), &b, FRAC_PI_4));
        assert!(!within_fov(&at(45.1), &b, FRAC_PI_4));
        assert!(within_fov(&at(89.99), &b, FRAC_PI_2));
        assert!(!within_fov(&at(90.01), &b, FRAC_PI_2));
        assert!(!within_fov(&-b, &b, PI - 1e-6));
        assert!(within_fov(&-b, &b, PI));
        // Tiny angles are resolved (1 micro-radian off with a 0.5 micro-radian cone).
        let l = Vec3::new(1e-6, 0.0, 1.0).normalize();
        assert!(!within_fov(&l, &b, 0.5e-6) && within_fov(&l, &b, 1.5e-6));
    }

    #[test]
    fn a_spheroid_blocks_the_segments_that_cross_it() {
        let r = 6.4e6;
        let (leo, gnss) = (Vec3::new(7e6, 0.0, 0.0), Vec3::new(2.6e7, 0.0, 0.0));
        assert!(segment_blocked(&leo, &-gnss, r, r));
        assert!(!segment_blocked(&leo, &gnss, r, r));
        // Over the pole 1 m above a sphere; a larger polar radius brings the surface up.
        let (a, b) = (Vec3::new(-7e6, 0.0, r + 1.0), Vec3::new(7e6, 0.0, r + 1.0));
        assert!(!segment_blocked(&a, &b, r, r));
        assert!(segment_blocked(&a, &b, r, r + 2.0));
    }

    #[test]
    fn opposite_sides_of_the_earth_are_blocked() {
        let rx = Vec3::new(7e6, 0.0, 0.0);
        assert!(earth_blocked(&rx, &Vec3::new(-2.6e7, 0.0, 0.0), 0.0));
        assert!(earth_blocked(&rx, &Vec3::new(-2e7, 0.0, 5e6), 0.0));
        assert!(!earth_blocked(&rx, &Vec3::new(2.6e7, 1e6, 0.0), 0.0));
    }

    #[test]
    fn tangent_ray_at_the_grazing_height() {
        // In the equatorial plane the inflated ellipsoid is a circle of radius a + h. A
        // ray from (R, 0, 0) tangent to a circle of radius rho passes it at distance
        // R sin(alpha) from the centre, alpha = angle between -r and the ray.
        let r = 7_000_000.0;
        let h = 50_000.0;
        let rho = WGS84_A_M + h;
        let rx = Vec3::new(r, 0.0, 0.0);
        let ray = |miss_m: f64| {
            // Closest distance rho + miss_m: direction at angle alpha from -x.
            let alpha = ((rho + miss_m) / r).asin();
            rx + 5e7 * Vec3::new(-alpha.cos(), alpha.sin(), 0.0)
        };
        assert!(!earth_blocked(&rx, &ray(10.0), h));
        assert!(earth_blocked(&rx, &ray(-10.0), h));
        // A horizontal ray over the pole passes it at its closest approach, where the
        // inflated surface is at b + h.
        let rho_p = WGS84_A_M * (1.0 - WGS84_F) + h;
        let over_pole = |miss_m: f64| {
            let z = rho_p + miss_m;
            (Vec3::new(-1e7, 0.0, z), Vec3::new(1e7, 3.0, z))
        };
        let (a, b) = over_pole(1.0);
        assert!(!earth_blocked(&a, &b, h));
        let (a, b) = over_pole(-1.0);
        assert!(earth_blocked(&a, &b, h));
    }

    #[test]
    fn segment_ends_before_the_earth() {
        // A satellite between the receiver and the Earth is not blocked.
        let rx = Vec3::new(4e7, 0.0, 0.0);
        assert!(!earth_blocked(&rx, &Vec3::new(2e7, 0.0, 0.0), 0.0));
        // A ground receiver sees up, not down.
        let gnd = Vec3::new(WGS84_A_M, 0.0, 0.0);
        assert!(!earth_blocked(&gnd, &Vec3::new(2.6e7, 1e7, 0.0), 0.0));
        // 0.57 deg below the horizon, to a point 10 000 km away.
        assert!(earth_blocked(
            &gnd,
            &(gnd + 1e7 * Vec3::new(-0.01, 1.0, 0.0)),
            0.0
        ));
        // 0.57 deg above it: clear.
        assert!(!earth_blocked(
            &gnd,
            &(gnd + 1e7 * Vec3::new(0.01, 1.0, 0.0)),
            0.0
        ));
    }
}
