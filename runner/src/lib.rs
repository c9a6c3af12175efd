//! A scenario run end to end in memory, as a user runs it and as the tables need it:
//!
//! - [`synth_and_receive`]: synthesise a scenario's I/Q into SigMF recordings beside their
//!   navigation file and `receiver.toml`, and run the bundled receiver over them;
//! - [`StreamedChain`]: the same two sessions side by side with no recording between
//!   them (`skyforge synth --receive`);
//! - [`run_at_level`]: each antenna's observables at the scenario's level (observation
//!   level, or the receiver on the synthesised samples) with the observation truth, the
//!   platform's true states and the broadcast navigation data beside them.
//!
//! It sits on the simulator side of the truth firewall: it holds truth and observations
//! together, for `skyforge-validate` to compare and for the product to write.

// Library code returns errors instead of panicking; tests may unwrap.
#![cfg_attr(not(test), deny(clippy::unwrap_used, clippy::expect_used))]

mod chain;
mod run;

pub use chain::{ChainError, ChainOutput, StreamSinks, StreamedChain, synth_and_receive};
pub use run::{
    ObservationRun, PositionFix, RunError, observation_run, run_at_level, signal_run,
    signal_run_with,
};
