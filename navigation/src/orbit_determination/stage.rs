//! Orbit determination fed one epoch at a time: the epoch stage of `skyforge receive
//! --od` (the receiver's own fixes as it makes them) and the loop of
//! [`super::orbit_from_file`]. Fixes whose epoch tag lies on the grid `k interval_s`
//! (seconds since the first epoch offered) go into the filter the configuration chooses.

use super::{EcefEstimate, FixInput, OdConfig, OdFilterConfig, PositionFilter};
use hifitime::Epoch;
use skyforge_orbits::Vec3;

/// Epoch tags within this of a multiple of the interval are on the grid (s).
const ON_GRID_S: f64 = 1e-3;

/// Whether `t_s` (seconds since the grid's origin) lies on the grid `k interval_s`.
pub(crate) fn on_grid(t_s: f64, interval_s: f64) -> bool {
    let k = t_s / interval_s;
    (k - k.round()).abs() * interval_s < ON_GRID_S
}

/// One fix as the stage takes it: the receiver's solution at an epoch.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EpochFix {
    /// The time the fix refers to (GPST): the epoch tag less the receiver clock's offset.
    pub time: Epoch,
    pub r_ecef_m: Vec3,
    /// The Doppler velocity, where one was solved.
    pub v_ecef_mps: Option<Vec3>,
    pub gdop: f64,
}

/// The filter, built at the first epoch offered, and its estimates so far.
#[derive(Debug, Clone)]
pub struct OrbitDetermination {
    config: OdConfig,
    running: Option<(Epoch, PositionFilter)>,
    estimates: Vec<EcefEstimate>,
    missed: usize,
}

impl OrbitDetermination {
    pub fn new(config: OdConfig) -> Self {
        Self {
            config,
            running: None,
            estimates: Vec::new(),
            missed: 0,
        }
    }

    /// The epoch tag `tag`, with `fix` giving the receiver's fix there if it made one
    /// (asked only on the grid): the estimate when the tag is on the grid and there is a
    /// fix.
    pub fn epoch(
        &mut self,
        tag: Epoch,
        fix: impl FnOnce() -> Option<EpochFix>,
    ) -> Option<EcefEstimate> {
        let (start, filter) = self.running.get_or_insert_with(|| {
            let OdFilterConfig::PositionFilter(p) = &self.config.filter;
            (tag, PositionFilter::new(p.clone(), tag))
        });
        if !on_grid((tag - *start).to_seconds(), self.config.interval_s) {
            return None;
        }
        let Some(fix) = fix() else {
            self.missed += 1;
            return None;
        };
        let input = FixInput {
            t_s: (fix.time - *start).to_seconds(),
            r_ecef_m: fix.r_ecef_m,
            v_ecef_mps: fix.v_ecef_mps,
            gdop: fix.gdop,
        };
        let estimate = filter.update(&input);
        let e = filter.to_ecef_estimate(&estimate);
        self.estimates.push(e);
        Some(e)
    }

    /// The epoch the estimates' `t_s` count from (the first offered), if any was.
    pub fn start(&self) -> Option<Epoch> {
        self.running.as_ref().map(|(start, _)| *start)
    }

    /// Every estimate so far, in time order.
    pub fn estimates(&self) -> &[EcefEstimate] {
        &self.estimates
    }

    /// Epochs on the grid that had no fix.
    pub fn missed(&self) -> usize {
        self.missed
    }

    /// The settings.
    pub fn config(&self) -> &OdConfig {
        &self.config
    }
}
