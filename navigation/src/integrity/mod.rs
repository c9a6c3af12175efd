//! Integrity monitoring with several reference receivers: the carrier-phase B-value
//! consistency monitor of paper 002 (`../shared/reference/papers_001_002_digest.md`).
//!
//! Every station's pseudorange and carrier phase of a satellite are mapped from its
//! antenna to a common point (the difference of the geometric ranges from the broadcast
//! ephemeris), and four statistics are formed per station: the changes since the track
//! began of the virtual pseudorange, of its Hatch-smoothed value and of the virtual
//! carrier phase, and the code-carrier divergence rate. A station's B value is its
//! statistic minus the mean of the other stations'; terms common to the stations
//! (satellite motion, satellite clock, the shared receiver clock, ionosphere and
//! troposphere over short distances, integer ambiguities through the change) cancel, and
//! a fault at one station stands out at the full size there and a third of it at the
//! others (four stations). Each B value is tested against a threshold.
//!
//! What the paper leaves out and how it is reconstructed here (docs/integrity.md):
//! - the B-value equation: the only candidate that fits its numbers ([`b_values`]);
//! - the change of the virtual observations: cumulative since the track began, since the
//!   paper's carrier B holds at 100 cycles after a slip instead of spiking for one epoch;
//! - the Hatch filter: the standard form ([`Hatch`]);
//! - the divergence: the LAAS geometric moving average on smoothed code minus carrier
//!   ([`Divergence`]);
//! - the mapping to the common point: geometric ranges from the broadcast ephemeris;
//! - thresholds other than the paper's 0.5 m: a false-alarm probability times the
//!   fault-free spread by elevation ([`ThresholdConfig`]), as GBAS monitors set theirs.

mod b_value;
mod config;
mod divergence;
pub(crate) mod files;
mod hatch;
mod monitor;
mod statistic;
mod thresholds;

pub use files::{Monitored, run_files, stations};

pub use b_value::b_values;
pub use config::{MonitorConfig, StationPosition};
pub use divergence::Divergence;
pub use hatch::Hatch;
pub use monitor::{
    Monitor, MonitorEpoch, MonitorError, SatelliteEpoch, Station, StationValues, Unmonitored,
};
pub use statistic::{PerStatistic, Statistic};
pub use thresholds::{SigmaCalibrator, SigmaTable, ThresholdConfig};
