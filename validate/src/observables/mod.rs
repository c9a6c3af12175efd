//! Receiver observations against truth: read RINEX 3 observation files, compare a
//! receiver's pseudorange, carrier phase, Doppler and C/N0 with SkyForge's RINEX truth
//! ([`compare()`]), and form zero-baseline double differences between two receivers
//! ([`double_difference::zero_baseline`], thesis table 5.4-2).
//!
//! Signals: GPS L1 C/A (RINEX 3 codes `C1C L1C D1C S1C`) and BeiDou B1I (`C2I L2I D2I
//! S2I`; RINEX 3.02 files, e.g. GNSS-SDR's, code B1I as band 1: `C1I L1I D1I S1I`).

pub mod compare;
pub mod double_difference;
mod error_stats;
mod fixed_effects;
mod interpolate;
pub mod table;

pub use compare::{ObsComparison, SignalComparison, compare, compare_signals};
pub use error_stats::{ErrorStats, SatErrors};
pub use skyforge_gnss::observation::{ObsEpoch, ObsFile, ObsRecord, read_obs_file};

use skyforge_gnss::observation::ObsReadError;

/// Why observations could not be read or compared.
#[derive(Debug, thiserror::Error)]
pub enum ObsError {
    /// The file could not be read as RINEX observations.
    #[error(transparent)]
    Read(#[from] ObsReadError),
    /// No estimate epoch could be matched with the truth.
    #[error(
        "no estimate epoch overlaps the truth with a common satellite (estimate {estimate}, truth {truth})"
    )]
    NoOverlap { estimate: String, truth: String },
    /// No estimate epoch lies in the requested sample-time window.
    #[error("no estimate epoch was measured between {first} and {last}")]
    EmptyWindow { first: String, last: String },
    /// The two receivers of a double difference share no epoch.
    #[error("the two receivers share no epoch within {tolerance_s} s")]
    NoCommonEpoch { tolerance_s: f64 },
    /// One comparison covers one signal per system; the estimate holds several of one.
    #[error("the estimate holds several signals of one system ({0}): compare them one at a time")]
    SeveralSignals(String),
}
