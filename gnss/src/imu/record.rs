//! One IMU output: the increments over one sampling interval.

use hifitime::Epoch;
use skyforge_orbits::Vec3;

/// The sensor outputs of one interval `(t_end - dt_s, t_end]`, as a strapdown IMU gives
/// them (the raw integrals; coning and sculling are the INS's to correct).
///
/// Body axes are SkyForge's (docs/scenario.md, `[platform.attitude]`): for a vehicle with
/// zero attitude x points forward (north), y right (east), z down, the front-right-down
/// axes most GNSS/INS packages use.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ImuIncrement {
    /// End of the interval (GPS time).
    pub t_end: Epoch,
    /// Interval length (s), positive.
    pub dt_s: f64,
    /// Integral of the body's angular rate relative to inertial space over the interval,
    /// body axes (rad).
    pub dtheta_rad: Vec3,
    /// Integral of the specific force (non-gravitational acceleration) over the
    /// interval, body axes (m/s).
    pub dv_mps: Vec3,
}
