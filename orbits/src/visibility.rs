//! Visibility geometry: field of view about a boresight, elevation mask, Earth blockage.

use crate::Vec3;

/// True when the unit line of sight is within `half_angle_rad` of the unit boresight.
pub fn within_fov(los_unit: &Vec3, boresight_unit: &Vec3, half_angle_rad: f64) -> bool {
    todo!("{los_unit} {boresight_unit} {half_angle_rad}")
}

/// True when the straight line from receiver to satellite (ECEF) passes below
/// `grazing_height_m` above the WGS-84 ellipsoid.
pub fn earth_blocked(r_rx_ecef_m: &Vec3, r_sat_ecef_m: &Vec3, grazing_height_m: f64) -> bool {
    todo!("{r_rx_ecef_m} {r_sat_ecef_m} {grazing_height_m}")
}
