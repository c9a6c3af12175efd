//! Keplerian elements <-> Cartesian state.

use crate::Vec3;

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
    /// Position and velocity for gravitational parameter `mu`.
    pub fn to_cartesian(&self, mu: f64) -> (Vec3, Vec3) {
        todo!("{mu}")
    }
    /// Elements of a bound orbit from position and velocity.
    pub fn from_cartesian(r_m: &Vec3, v_mps: &Vec3, mu: f64) -> Self {
        todo!("{r_m} {v_mps} {mu}")
    }
}
