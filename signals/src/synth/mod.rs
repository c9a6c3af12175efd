//! IF/baseband synthesis: the signal configuration, transmitters (code + data), per-channel
//! mixing, thermal noise, front-end quantisation, the per-antenna renderer, the sample-file
//! formats with their SigMF metadata, and the streaming session that drives them.

pub(crate) mod budget;
pub mod config;
pub mod constellation;
pub mod filter;
pub mod gnss_sdr;
pub mod link;
pub mod link_terms;
pub mod mix;
pub(crate) mod noise;
pub(crate) mod quantise;
pub mod render;
pub mod session;
pub mod sigmf;
pub(crate) mod transmitter;

pub use budget::Budget;
pub use noise::ThermalNoise;
pub use quantise::Quantiser;
pub use transmitter::Transmitter;
