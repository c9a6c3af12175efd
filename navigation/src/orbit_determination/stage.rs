//! Orbit determination fed one epoch at a time: the epoch stage of `skyforge receive
//! --od` (the receiver's own fixes and observations as it makes them) and the loop of
//! [`super::orbit_from_file`]. The position filter takes the fixes whose epoch tag lies
//! on the grid `k interval_s` (seconds since the first epoch offered); the reduced-dynamic
//! filter takes every epoch's observations and gives its estimates on that grid.

use super::reduced_dynamic::ReducedDynamicFilter;
use super::{EcefEstimate, FixInput, OdConfig, OdFilterConfig, PositionFilter};
use hifitime::Epoch;
use skyforge_gnss::observation::ObsRecord;
use skyforge_orbits::Vec3;
use skyforge_orbits::ephemeris::{BroadcastEphemeris, EphemerisStore, System};
use skyforge_orbits::time::TimeOrigin;

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

/// The filter the configuration chose, once running.
#[derive(Debug, Clone)]
enum Running {
    /// The position filter on the receiver's fixes.
    Fixes(PositionFilter),
    /// The reduced-dynamic filter on the receiver's observations.
    Observations(ReducedDynamicFilter),
}

/// The broadcast ephemerides the observation filter predicts its ranges with.
#[derive(Debug, Clone)]
struct Ephemerides {
    store: EphemerisStore,
    origin: TimeOrigin,
}

/// The filter, built at the first epoch offered, and its estimates so far.
#[derive(Debug, Clone)]
pub struct OrbitDetermination {
    config: OdConfig,
    /// Every ephemeris known (the observation filter's); bound at the first epoch.
    ephemerides: Vec<BroadcastEphemeris>,
    bound: Option<Ephemerides>,
    running: Option<(Epoch, Running)>,
    estimates: Vec<EcefEstimate>,
    missed: usize,
}

/// Why the stage cannot run as configured.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error(
    "filter kind \"reduced-dynamic\" ranges to the satellites: it needs the broadcast ephemerides (give a navigation file)"
)]
pub struct NeedsEphemerides;

impl OrbitDetermination {
    /// The stage with `config`'s filter; the reduced-dynamic filter needs `ephemerides`
    /// (the position filter takes fixes and ignores them).
    pub fn new(
        config: OdConfig,
        ephemerides: Vec<BroadcastEphemeris>,
    ) -> Result<Self, NeedsEphemerides> {
        if matches!(config.filter, OdFilterConfig::ReducedDynamic(_)) && ephemerides.is_empty() {
            return Err(NeedsEphemerides);
        }
        Ok(Self {
            config,
            ephemerides,
            bound: None,
            running: None,
            estimates: Vec::new(),
            missed: 0,
        })
    }

    /// The epoch tag `tag`, with `fix` giving the receiver's fix there if it made one
    /// (the position filter asks only on the grid) and `records` its observations (the
    /// reduced-dynamic filter takes every epoch's): the estimate when the tag is on the
    /// grid and the filter has one.
    pub fn epoch(
        &mut self,
        tag: Epoch,
        fix: impl FnOnce() -> Option<EpochFix>,
        records: impl FnOnce() -> Vec<ObsRecord>,
    ) -> Option<EcefEstimate> {
        let records = matches!(self.config.filter, OdFilterConfig::ReducedDynamic(_))
            .then(|| self.wanted(records()));
        let (start, running) = match &mut self.running {
            Some((start, running)) => (*start, running),
            None => {
                let running = self.begin(tag, records.as_deref().unwrap_or_default());
                let (_, running) = self.running.insert((tag, running));
                (tag, running)
            }
        };
        let on = on_grid((tag - start).to_seconds(), self.config.interval_s);
        let estimate = match running {
            Running::Fixes(filter) => {
                if !on {
                    return None;
                }
                let Some(fix) = fix() else {
                    self.missed += 1;
                    return None;
                };
                let input = FixInput {
                    t_s: (fix.time - start).to_seconds(),
                    r_ecef_m: fix.r_ecef_m,
                    v_ecef_mps: fix.v_ecef_mps,
                    gdop: fix.gdop,
                };
                let estimate = filter.update(&input);
                filter.to_ecef_estimate(&estimate)
            }
            Running::Observations(filter) => {
                let bound = self.bound.as_ref()?;
                let records = records.unwrap_or_default();
                let tag_s = bound.origin.seconds_since_start(tag);
                let estimate = filter.epoch(tag_s, &records, &bound.store, &bound.origin);
                match (on, estimate) {
                    (false, _) => return None,
                    (true, None) => {
                        self.missed += 1;
                        return None;
                    }
                    (true, Some(e)) => e,
                }
            }
        };
        self.estimates.push(estimate);
        Some(estimate)
    }

    /// The configured filter for a run starting at `start` with the observations
    /// `first`.
    fn begin(&mut self, start: Epoch, first: &[ObsRecord]) -> Running {
        match &self.config.filter {
            OdFilterConfig::PositionFilter(p) => {
                Running::Fixes(PositionFilter::new(p.clone(), start))
            }
            OdFilterConfig::ReducedDynamic(r) => {
                let origin = TimeOrigin::new(start);
                let store = EphemerisStore::new(std::mem::take(&mut self.ephemerides), &origin);
                self.bound = Some(Ephemerides { store, origin });
                let systems = self.systems(first);
                Running::Observations(ReducedDynamicFilter::new(
                    r.clone(),
                    start,
                    &systems,
                    self.config.elevation_mask_deg,
                ))
            }
        }
    }

    /// The systems the filter estimates clocks for: those of the first epoch first (GPS,
    /// Galileo, BeiDou in that order; the first one's clock is the receiver's), then the
    /// others of the configured signals (of every signal when none are configured).
    fn systems(&self, first: &[ObsRecord]) -> Vec<System> {
        let all = [System::Gps, System::Galileo, System::Beidou];
        let configured = |s: &System| {
            self.config.signals.is_empty()
                || self.config.signals.iter().any(|sig| sig.system() == *s)
        };
        let seen = |s: &System| first.iter().any(|r| r.sat.system == *s);
        let mut systems: Vec<System> = all.into_iter().filter(seen).collect();
        systems.extend(all.into_iter().filter(|s| configured(s) && !seen(s)));
        systems
    }

    /// The records of the configured signals.
    fn wanted(&self, mut records: Vec<ObsRecord>) -> Vec<ObsRecord> {
        if !self.config.signals.is_empty() {
            records.retain(|r| self.config.signals.contains(&r.signal));
        }
        records
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
