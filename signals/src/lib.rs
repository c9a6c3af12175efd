//! The simulator's signal side: antennas, error models, per-antenna geometry truth, the
//! observation-level model, and the IF synthesiser with its streaming session. The GNSS
//! vocabulary it speaks (signals, codes, navigation messages, observation records) is
//! `skyforge-gnss`.

// Library code returns errors instead of panicking; tests may unwrap.
#![cfg_attr(not(test), deny(clippy::unwrap_used, clippy::expect_used))]

pub mod antenna;
pub mod barometer;
pub mod errors;
pub mod imu;
pub mod interference;
pub mod obs_model;
pub mod synth;
pub mod truth;
