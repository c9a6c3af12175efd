//! ECI <-> ECEF by Earth rotation only (document the neglected precession, nutation,
//! polar motion and UT1-UTC, with their sizes, in this module's docs).

use crate::{Mat3, Vec3};
use hifitime::Epoch;

/// Earth rotation angle about Z from the scenario's ECI frame to ECEF.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EarthRotation {
    theta0_rad: f64,
}

impl EarthRotation {
    /// The rotation whose angle at `start` is the Greenwich sidereal angle of `start`.
    pub fn at_origin(start: Epoch) -> Self {
        todo!("{start}")
    }
    /// Rotation angle (rad) at `t_s` seconds after the origin.
    pub fn angle_rad(&self, t_s: f64) -> f64 {
        todo!("{t_s} {}", self.theta0_rad)
    }
    /// `c_eci_ecef` at `t_s`.
    pub fn c_eci_ecef(&self, t_s: f64) -> Mat3 {
        todo!("{t_s}")
    }
    /// ECI position/velocity to ECEF position/velocity at `t_s` (velocity includes -w x r).
    pub fn eci_to_ecef(&self, t_s: f64, r_eci_m: &Vec3, v_eci_mps: &Vec3) -> (Vec3, Vec3) {
        todo!("{t_s} {r_eci_m} {v_eci_mps}")
    }
    /// ECEF position/velocity to ECI at `t_s`.
    pub fn ecef_to_eci(&self, t_s: f64, r_ecef_m: &Vec3, v_ecef_mps: &Vec3) -> (Vec3, Vec3) {
        todo!("{t_s} {r_ecef_m} {v_ecef_mps}")
    }
}
