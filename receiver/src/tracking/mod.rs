//! Carrier and code tracking: the correlator kernel, discriminators, loop filters, lock
//! detectors and C/N0, bit synchronisation, and the per-satellite channel tracker that
//! ties them together.

pub(crate) mod bit_sync;
pub(crate) mod carrier;
pub(crate) mod channel;
pub(crate) mod config;
pub(crate) mod correlator;
pub(crate) mod discriminators;
pub mod error_budget;
pub(crate) mod lock;
pub(crate) mod loop_filter;
pub(crate) mod ukf_carrier;

pub use channel::{ChannelTracker, FrontEnd, Handover, TrackingRecord};
pub use config::{THESIS_KAPPA, THESIS_PROPOSED_Q, TrackingConfig};
pub use correlator::{Correlator, NcoState, TapSet};
pub use ukf_carrier::{UkfCarrier, UkfConfig};

impl From<skyforge_orbits::check::Invalid> for TrackingError {
    fn from(e: skyforge_orbits::check::Invalid) -> Self {
        Self::InvalidConfig(e.to_string())
    }
}

/// Errors of the tracking stage.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum TrackingError {
    /// A configuration value is out of range (the message names it and what is allowed).
    #[error("invalid tracking configuration: {0}")]
    InvalidConfig(String),
    /// The PRN has no ranging code for the signal.
    #[error(transparent)]
    UnknownPrn(#[from] skyforge_gnss::signal::UnknownPrn),
    /// A block did not start where the previous one ended.
    #[error("sample blocks must be contiguous: expected first sample {expected}, got {got}")]
    NonContiguous {
        /// The sample index the channel expected.
        expected: u64,
        /// The sample index it was given.
        got: u64,
    },
}
