//! The LEO numerical propagator: two-body + J2 (J3..J6 optional) + atmospheric drag,
//! integrated by an adaptive Dormand-Prince 5(4) with dense output.

pub(crate) mod atmosphere;
pub(crate) mod config;
pub(crate) mod dormand_prince;
pub(crate) mod elements;
pub(crate) mod forces;
pub(crate) mod leo;
pub(crate) mod sun;
pub(crate) mod tle;

pub use config::{
    DensityModel, ForceModelConfig, IntegratorConfig, KeplerianElementsConfig, LeoConfig,
};
pub use forces::ForceModel;
pub use leo::{DenseTrajectory, LeoPropagator};

pub use elements::KeplerianElements;

/// Error during propagation.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum PropagateError {
    /// The orbit decayed below the surface (or a minimum altitude).
    #[error("orbit decayed: altitude {altitude_m:.0} m at t = {t_s:.1} s")]
    Decayed { t_s: f64, altitude_m: f64 },
    /// The integrator could not meet its tolerance.
    #[error("integrator step size underflow at t = {t_s:.3} s")]
    StepUnderflow { t_s: f64 },
    /// A requested window lies before the retained history.
    #[error("window start {t0_s} s is before the retained history ({kept_from_s} s)")]
    WindowBeforeHistory { t0_s: f64, kept_from_s: f64 },
    /// A TLE could not be read or propagated.
    #[error("TLE: {0}")]
    Tle(String),
    /// The `[platform.leo]` configuration failed its checks (field path relative to it).
    #[error("invalid LEO configuration: {0}")]
    Config(#[from] crate::check::Invalid),
}
