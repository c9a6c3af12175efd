//! Signals: antennas, ranging codes, navigation messages, error models and per-antenna
//! geometry truth (the IF synthesiser builds on these).

pub mod antenna;
pub mod codes;
pub mod errors;
pub mod navmsg;
pub mod nco;
pub mod sample_format;
pub mod signal;
pub mod synth;
pub mod truth;
