//! Signals: antennas, ranging codes, navigation messages, error models, per-antenna
//! geometry truth, the observation vocabulary with its RINEX files, and the IF synthesiser
//! with its streaming session.

// Library code returns errors instead of panicking; tests may unwrap.
#![cfg_attr(not(test), deny(clippy::unwrap_used, clippy::expect_used))]

pub mod antenna;
pub mod codes;
pub mod errors;
pub mod navmsg;
pub mod nco;
pub mod obs_model;
pub mod observation;
pub mod sample_format;
pub mod signal;
pub mod synth;
pub mod truth;
