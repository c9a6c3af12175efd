//! The receiving platform: a numerically propagated LEO, a static ground site, or a
//! trajectory from CSV, each with its attitude.

pub mod config;
pub mod ground;
pub mod trajectory;

use crate::frames::euler::YawPitchRoll;
use crate::{Mat3, Vec3};

/// The platform at one instant.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlatformState {
    /// Centre-of-mass position (ECEF, m).
    pub r_ecef_m: Vec3,
    /// Centre-of-mass velocity (ECEF, m/s).
    pub v_ecef_mps: Vec3,
    /// Body -> ECEF rotation.
    pub c_body_ecef: Mat3,
    /// Attitude relative to the platform's reference frame (orbital frame for a LEO, NED
    /// otherwise).
    pub attitude: YawPitchRoll,
}

/// Error building or moving a platform.
#[derive(Debug, thiserror::Error)]
pub enum PlatformError {
    #[error(transparent)]
    Propagate(#[from] crate::propagate::PropagateError),
    /// A CSV input (trajectory or attitude) is unreadable or malformed.
    #[error("{path}:{line}: {message}")]
    Csv {
        path: String,
        line: usize,
        message: String,
    },
    /// A window outside the data a trajectory file covers.
    #[error("time {t_s} s is outside the trajectory ({first_s} .. {last_s} s)")]
    OutsideTrajectory { t_s: f64, first_s: f64, last_s: f64 },
}

/// A receiving platform.
#[derive(Debug)]
pub struct Platform {}

/// The platform over a window of time; cheap to query from many threads.
#[derive(Debug, Clone)]
pub struct PlatformWindow {}

impl Platform {
    /// The platform's state over `[t0_s, t1_s]` (windows move forward in time).
    pub fn window(&mut self, t0_s: f64, t1_s: f64) -> Result<PlatformWindow, PlatformError> {
        todo!("{t0_s} {t1_s}")
    }
}

impl PlatformWindow {
    /// The state at `t_s` within the window.
    pub fn state(&self, t_s: f64) -> PlatformState {
        todo!("{t_s}")
    }
}
