//! Local North-East-Down frame and azimuth/elevation.
//!
//! The NED frame of thesis section 2.5.1 (`O_d X_n Y_e Z_d`): X to geodetic north, Y to
//! east, Z down along the WGS-84 ellipsoid normal.

use crate::{Mat3, Vec3};
use std::f64::consts::TAU;

/// `c_ecef_ned` at geodetic latitude/longitude: maps ECEF components to NED components
/// (its rows are the north, east and down unit vectors in ECEF).
pub fn c_ecef_ned(lat_rad: f64, lon_rad: f64) -> Mat3 {
    let (sl, cl) = lat_rad.sin_cos();
    let (so, co) = lon_rad.sin_cos();
    Mat3::new(
        -sl * co,
        -sl * so,
        cl, // north
        -so,
        co,
        0.0, // east
        -cl * co,
        -cl * so,
        -sl, // down
    )
}

/// Azimuth (rad, from north through east, in [0, 2pi)) and elevation (rad) of a NED vector.
pub fn az_el(v_ned: &Vec3) -> (f64, f64) {
    let az = v_ned.y.atan2(v_ned.x).rem_euclid(TAU);
    // rem_euclid can round up to exactly 2 pi for tiny negative angles.
    let az = if az >= TAU { 0.0 } else { az };
    let el = (-v_ned.z).atan2(v_ned.x.hypot(v_ned.y));
    (az, el)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::frames::geodetic::{Geodetic, geodetic_to_ecef};
    use proptest::prelude::*;
    use std::f64::consts::{FRAC_PI_2, FRAC_PI_4};

    #[test]
    fn axes_at_lat0_lon0() {
        let c = c_ecef_ned(0.0, 0.0);
        assert_eq!(c * Vec3::z(), Vec3::new(1.0, 0.0, 0.0)); // ECEF Z is north
        assert_eq!(c * Vec3::y(), Vec3::new(0.0, 1.0, 0.0)); // ECEF Y is east
        assert_eq!(c * Vec3::x(), Vec3::new(0.0, 0.0, -1.0)); // ECEF X is up
    }

    #[test]
    fn up_is_the_height_direction_and_north_increases_latitude() {
        let (lat, lon) = (0.7, -1.9);
        let c = c_ecef_ned(lat, lon);
        let at = |dlat: f64, h: f64| {
            geodetic_to_ecef(&Geodetic {
                lat_rad: lat + dlat,
                lon_rad: lon,
                h_m: h,
            })
        };
        let up = (at(0.0, 1.0) - at(0.0, 0.0)).normalize();
        assert!((c * up - Vec3::new(0.0, 0.0, -1.0)).norm() < 1e-9);
        let north = (at(1e-7, 0.0) - at(-1e-7, 0.0)).normalize();
        assert!((c * north - Vec3::new(1.0, 0.0, 0.0)).norm() < 1e-6);
    }

    #[test]
    fn az_el_cardinal_directions() {
        let close =
            |a: (f64, f64), b: (f64, f64)| (a.0 - b.0).abs() < 1e-15 && (a.1 - b.1).abs() < 1e-15;
        assert!(close(az_el(&Vec3::new(1.0, 0.0, 0.0)), (0.0, 0.0)));
        assert!(close(az_el(&Vec3::new(0.0, 2.0, 0.0)), (FRAC_PI_2, 0.0)));
        assert!(close(
            az_el(&Vec3::new(0.0, -2.0, 0.0)),
            (3.0 * FRAC_PI_2, 0.0)
        ));
        assert!((az_el(&Vec3::new(0.0, 0.0, -5.0)).1 - FRAC_PI_2).abs() < 1e-15);
        let (az, el) = az_el(&Vec3::new(1.0, 1.0, -2f64.sqrt()));
        assert!((az - FRAC_PI_4).abs() < 1e-15 && (el - FRAC_PI_4).abs() < 1e-15);
        let (_, el) = az_el(&Vec3::new(1.0, 0.0, 1.0));
        assert!((el + FRAC_PI_4).abs() < 1e-15);
    }

    proptest! {
        #[test]
        fn c_ecef_ned_is_a_rotation(lat in -FRAC_PI_2..FRAC_PI_2, lon in -4.0f64..4.0) {
            let c = c_ecef_ned(lat, lon);
            prop_assert!((c * c.transpose() - Mat3::identity()).norm() < 1e-15 * 10.0);
            prop_assert!((c.determinant() - 1.0).abs() < 1e-14);
        }

        #[test]
        fn az_el_reconstructs_direction(x in -1e3f64..1e3, y in -1e3f64..1e3, z in -1e3f64..1e3) {
            let v = Vec3::new(x, y, z);
            prop_assume!(v.norm() > 1e-6);
            let (az, el) = az_el(&v);
            prop_assert!((0.0..TAU).contains(&az));
            let u = Vec3::new(el.cos() * az.cos(), el.cos() * az.sin(), -el.sin());
            prop_assert!((u - v.normalize()).norm() < 1e-12);
        }
    }
}
