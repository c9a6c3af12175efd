//! Why no time differences or no solution.

use hifitime::Epoch;

/// Why [`super::time_differences`] or a solution failed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum TdcpError {
    /// A setting out of its range.
    #[error("TDCP setting {field} = {value} is out of range: {allowed}")]
    Config {
        /// The setting's name in [`super::TdcpConfig`].
        field: &'static str,
        /// Its value.
        value: String,
        /// What it may be.
        allowed: &'static str,
    },
    /// The second epoch is not after the first, or too long after it.
    #[error("epochs {t1} and {t2} are {gap_s} s apart: TDCP needs 0 < gap <= {max_gap_s} s")]
    Gap {
        t1: Epoch,
        t2: Epoch,
        gap_s: f64,
        max_gap_s: f64,
    },
    /// An input position (or another value named by `what`) is NaN or infinite.
    #[error("TDCP input {what} is not finite")]
    NonFinite { what: &'static str },
    /// A position too near the geocentre to have a local frame (norm < 6000 km).
    #[error("TDCP input {what} is not a position near the Earth's surface or above it")]
    NotAPosition { what: &'static str },
    /// Fewer usable satellites (or double differences) than unknowns.
    #[error("{have} usable satellites at {t}, {needed} needed")]
    TooFewSatellites {
        needed: usize,
        have: usize,
        t: Epoch,
    },
    /// The lines of sight do not determine the unknowns.
    #[error("singular TDCP geometry at {t}")]
    Singular { t: Epoch },
    /// The Gauss-Newton iteration did not settle.
    #[error("TDCP iteration at {t} did not converge (last step {step_m} m)")]
    NoConvergence { t: Epoch, step_m: f64 },
    /// No position for the first epoch of a pair (its anchor).
    #[error("no position at {t} to anchor the TDCP pair")]
    NoPosition { t: Epoch },
}
