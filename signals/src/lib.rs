//! Signals: antennas, per-antenna geometry truth, and (later) the IF synthesiser.

pub mod antenna;
pub mod signal;
pub mod truth;
