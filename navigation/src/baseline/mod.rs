//! Relative positioning between antennas on one platform (thesis sections 2.3 and 2.4):
//! double-differenced carrier phase and code, the multivariate baseline model of all
//! baselines at once, its float solution and its solution given integer ambiguities.
//!
//! Antenna 0 is the master; baseline `k` (1..=m) is the vector from antenna 0 to antenna
//! `k`, `b_k = x_k - x_0`, in ECEF. Single differences are antenna `k` minus antenna 0
//! (eq. 2.3-3), double differences satellite `i` minus the reference satellite of its
//! system (eq. 2.3-9). Each system has its own reference satellite (eqs. 2.4-31..2.4-34),
//! shared by all its signals (eqs. 2.4-46..2.4-49), so one model covers the four cases of
//! sections 2.4.1..2.4.4.
//!
//! With satellites common to all antennas and the noise model of eqs. 2.4-9..2.4-15, the
//! covariance of vec(Y) is `Q_M (x) Q_t` and the design `[I_m (x) A, I_m (x) G]`
//! (eq. 2.4-61), so the least-squares float solution of all baselines (eqs. 2.4-62,
//! 2.4-63) is one small solve shared by every baseline: see [`float`].

pub(crate) mod differences;
pub(crate) mod float;
pub(crate) mod hold;
pub(crate) mod memory;
pub(crate) mod model;
pub(crate) mod noise;

pub use differences::{DdBlock, DdLayout, LineOfSight};
pub use float::AmbiguityPrior;
pub use float::{Conditioned, FixedBaselines, FloatBaselines};
pub use hold::AmbiguityHold;
pub use memory::FloatMemory;
pub use model::DdModel;
pub use noise::{ElevationNoise, NoiseModel};

use skyforge_gnss::signal::Signal;
use skyforge_orbits::ephemeris::SatId;

/// Why an epoch's baselines could not be formed or solved.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum BaselineError {
    #[error("at least two antennas are needed for a baseline, got {0}")]
    TooFewAntennas(usize),
    #[error(
        "three double differences are needed for the three baseline components, the \
         satellites common to all antennas with phase and code give {found}"
    )]
    TooFewDoubleDifferences { found: usize },
    #[error("{sat} has no phase and code on {signal} at one of the antennas")]
    MissingObservation { sat: SatId, signal: Signal },
    #[error("the double-difference normal matrix is singular (satellite geometry degenerate)")]
    Singular,
    #[error("{what} is not finite")]
    NotFinite { what: &'static str },
    #[error("{what}: expected {expected} values, got {found}")]
    Dimension {
        what: &'static str,
        expected: usize,
        found: usize,
    },
}
