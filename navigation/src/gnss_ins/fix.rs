//! What a GNSS receiver tells the integration filter: where its antenna was.

use hifitime::Epoch;
use skyforge_orbits::{Mat3, Vec3};

/// A position (and optionally velocity) fix of the antenna, ECEF, with its covariance,
/// valid at `t` (GPS time, the receiver clock already corrected).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GnssFix {
    /// Time of validity.
    pub t: Epoch,
    /// Antenna position (m).
    pub r_ecef_m: Vec3,
    /// Its covariance (m^2).
    pub r_cov_m2: Mat3,
    /// Antenna velocity relative to the Earth (m/s) and its covariance ((m/s)^2), when
    /// the receiver measured one.
    pub v_ecef_mps: Option<(Vec3, Mat3)>,
}
