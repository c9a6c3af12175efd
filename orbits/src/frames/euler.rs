//! Yaw/pitch/roll, 3-2-1 rotation (thesis eq. 2.5-3..2.5-6), DCMs and quaternions.

use crate::Mat3;
use nalgebra::UnitQuaternion;

/// Attitude angles of the body frame relative to a reference frame (rad).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct YawPitchRoll {
    pub yaw_rad: f64,
    pub pitch_rad: f64,
    pub roll_rad: f64,
}

impl YawPitchRoll {
    /// `c_ref_body`: the 3-2-1 rotation (yaw about Z, then pitch about Y, then roll about X).
    pub fn c_ref_body(&self) -> Mat3 {
        todo!("{self:?}")
    }
    /// Angles from `c_ref_body` (pitch in [-pi/2, pi/2]).
    pub fn from_c_ref_body(c_ref_body: &Mat3) -> Self {
        todo!("{c_ref_body}")
    }
    /// The rotation as a unit quaternion (body->ref, i.e. rotates body components into ref).
    pub fn q_body_ref(&self) -> UnitQuaternion<f64> {
        todo!("{self:?}")
    }
}
