//! Orbit determination of the receiving spacecraft from its own GNSS measurements.
//!
//! Two filters, chosen and set by [`OdConfig`] (`skyforge od --config`): the book's
//! position filter (section 5.5.4) on single-point fixes, with Clohessy-Wiltshire
//! dynamics about a refreshed reference circle; and the reduced-dynamic extended Kalman
//! filter on the raw pseudoranges, Doppler and carrier phases ([`reduced_dynamic`]).

pub(crate) mod clohessy_wiltshire;
mod config;
pub(crate) mod from_files;
pub(crate) mod position_filter;
pub mod reduced_dynamic;
pub(crate) mod stage;

pub use clohessy_wiltshire::{input, transition};
pub use config::{OdConfig, OdFilterConfig};
pub use from_files::{OdError, OdRun, orbit_from_file, position_filter_on_file};
pub use position_filter::{
    EcefEstimate, FixInput, OrbitEstimate, PositionFilter, PositionFilterConfig,
};
pub use stage::{EpochFix, NeedsEphemerides, OrbitDetermination};
