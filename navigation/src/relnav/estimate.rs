//! What relative navigation estimates: the chaser relative to the target at an epoch,
//! and a run's estimates.

use super::{AmbiguityCount, RelnavMode};
use hifitime::Epoch;
use skyforge_gnss::signal::Signal;
use skyforge_orbits::Vec3;

/// The chaser relative to the target at one epoch (target orbit frame).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RelativeEstimate {
    /// The target fix's time, seconds since the target file's first epoch (GPST).
    pub t_s: f64,
    pub position_m: Vec3,
    /// The rate in the rotating frame.
    pub velocity_mps: Vec3,
    /// How long both fixes have used the same satellites as each other, neither set
    /// changed and no epoch missed (s; 0 while the sets differ): the book's steady state
    /// (5.6.5) needs both vehicles on one set, neither having changed satellites, and the
    /// smoothing to have run.
    pub same_satellites_s: f64,
    /// The baseline chaser minus target in the Earth-fixed frame (m), where the mode
    /// estimates it as such (`double-difference`): free of the frame's orientation.
    pub baseline_ecef_m: Option<Vec3>,
    /// The double-difference ambiguities fixed and float after the epoch
    /// (`double-difference`).
    pub ambiguities: Option<AmbiguityCount>,
}

/// What a run estimated: [`super::relative_from_files`] on two files, or a receiver's
/// [`super::RelnavStage`].
#[derive(Debug, Clone, PartialEq)]
pub struct RelnavRun {
    /// The epoch `t_s` counts from: the target file's first.
    pub start: Epoch,
    pub mode: RelnavMode,
    pub signals: Vec<Signal>,
    pub estimates: Vec<RelativeEstimate>,
    /// Common epochs without both fixes and velocities.
    pub missed: usize,
}
