//! The ephemerides of a scenario, bound to its time origin, with selection by time and
//! health.

use super::{BoundEphemeris, BroadcastEphemeris, SatId};
use crate::time::TimeOrigin;

/// All usable ephemerides per satellite, sorted by toe.
#[derive(Debug, Clone, Default)]
pub struct EphemerisStore {
    /// Per satellite, ephemerides sorted by `toe_s`.
    sats: Vec<(SatId, Vec<BoundEphemeris>)>,
}

impl EphemerisStore {
    /// Bind and index `ephemerides` (unhealthy sets dropped).
    pub fn new(ephemerides: Vec<BroadcastEphemeris>, origin: &TimeOrigin) -> Self {
        todo!("{} {origin:?}", ephemerides.len())
    }
    /// Merge another store into this one.
    pub fn extend(&mut self, other: EphemerisStore) {
        todo!("{}", other.sats.len())
    }
    /// Satellites with at least one ephemeris, in order.
    pub fn satellites(&self) -> Vec<SatId> {
        todo!()
    }
    /// Keep only the listed satellites.
    pub fn retain(&mut self, keep: impl Fn(SatId) -> bool) {
        todo!(
            "{}",
            keep(SatId {
                system: super::System::Gps,
                prn: 1
            })
        )
    }
    /// The ephemeris to use for `sat` at `t_s`: healthy, within its fit interval, nearest
    /// toe (GPS: latest toe not after `t_s + fit/2`...; document the rule).
    pub fn select(&self, sat: SatId, t_s: f64) -> Option<&BoundEphemeris> {
        todo!("{sat} {t_s}")
    }
}
