//! The attitude chain against the truth: an observation-level run in memory ([`run`]) and
//! the chain's integers, baselines and attitude compared with that run's truth
//! ([`compare`]).

pub mod compare;
pub mod run;
pub mod seeds;
pub mod success;

pub use compare::{ChainComparison, EpochErrors, compare, nominal_geometry};
pub use run::{ObservationRun, RunError, observation_run};
pub use seeds::seed_runs;
