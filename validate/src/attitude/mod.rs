//! The attitude chain against the truth: a run in memory (`skyforge_runner::ObservationRun`, at the observation or
//! the signal level) and the chain's integers, baselines and attitude compared with that
//! run's truth ([`compare`]); or the chain's files (`skyforge attitude`'s output) compared
//! with the truth files of the run they came from ([`outputs`], `skyforge validate
//! attitude`).

pub mod compare;
pub(crate) mod epochs;
pub(crate) mod outputs;
pub(crate) mod seeds;
pub(crate) mod success;

pub use epochs::{FixedEpoch, fixed_baselines, true_attitudes};
pub use success::{SuccessRate, single_epoch, single_epoch_each};

pub use compare::{ChainComparison, EpochErrors, compare, nominal_geometry};
pub use outputs::{
    AntennaPosition, AttitudeValidation, AxisStats, OutputsComparison, OutputsError,
    compare_outputs, print_validation,
};
pub use seeds::seed_runs;
