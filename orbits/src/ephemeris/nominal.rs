//! Embedded default constellations expressed as broadcast ephemerides (so the orbit a
//! signal follows and the ephemeris its navigation message carries are the same model).
//! Sources of the slot data are documented on each function.

use super::{BroadcastEphemeris, config::BeidouSet};
use hifitime::Epoch;

/// The nominal GPS constellation (31 PRNs), with toe/toc at `epoch`.
pub fn gps(epoch: Epoch) -> Vec<BroadcastEphemeris> {
    todo!("{epoch}")
}

/// The nominal BeiDou constellation of `set`, with toe/toc at `epoch`.
pub fn beidou(set: BeidouSet, epoch: Epoch) -> Vec<BroadcastEphemeris> {
    todo!("{set:?} {epoch}")
}
