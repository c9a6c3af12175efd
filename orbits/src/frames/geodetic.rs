//! WGS-84 geodetic latitude/longitude/height <-> ECEF.

use crate::Vec3;

/// Geodetic coordinates on WGS-84 (radians, metres).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Geodetic {
    pub lat_rad: f64,
    pub lon_rad: f64,
    pub h_m: f64,
}

/// Geodetic -> ECEF.
pub fn geodetic_to_ecef(g: &Geodetic) -> Vec3 {
    todo!("{g:?}")
}

/// ECEF -> geodetic (iterative or closed form, accurate to < 1 mm from -1e5 m to 1e8 m).
pub fn ecef_to_geodetic(r_ecef_m: &Vec3) -> Geodetic {
    todo!("{r_ecef_m}")
}
