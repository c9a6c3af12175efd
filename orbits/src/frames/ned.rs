//! Local North-East-Down frame and azimuth/elevation.

use crate::{Mat3, Vec3};

/// `c_ecef_ned` at geodetic latitude/longitude.
pub fn c_ecef_ned(lat_rad: f64, lon_rad: f64) -> Mat3 {
    todo!("{lat_rad} {lon_rad}")
}

/// Azimuth (rad, from north through east, in [0, 2pi)) and elevation (rad) of a NED vector.
pub fn az_el(v_ned: &Vec3) -> (f64, f64) {
    todo!("{v_ned}")
}
