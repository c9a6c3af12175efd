//! Relative navigation as an epoch stage of the chaser's receiver (`skyforge receive
//! --relnav`): the chaser's observations as its receiver forms them, epoch by epoch, the
//! target's from its observation file, as a link would deliver them (the book's target
//! "sends its state"; every mode but `standalone` needs its observations). Every mode,
//! through the engine `skyforge relnav` loops over two files ([`super::engine`]); with
//! each vehicle's own satellite sets the chaser's smoother runs along every epoch its
//! receiver forms, the target's along its whole file, as on files.

use super::engine::{Context, Engine};
use super::estimate::{RelativeEstimate, RelnavRun};
use super::from_files::{RelnavError, engine, pair_records, pvt_settings};
use super::{RelnavConfig, RelnavMode, SatelliteSets};
use crate::pvt::CarrierSmoother;
use crate::relative::files::{carrier_smoothed_file, records_at, smoothed};
use hifitime::Epoch;
use skyforge_gnss::observation::{ObsEpoch, ObsFile, ObsRecord};
use skyforge_gnss::signal::Signal;
use skyforge_orbits::ephemeris::rinex_nav_iono::BroadcastIono;
use skyforge_orbits::ephemeris::{BroadcastEphemeris, EphemerisStore};
use skyforge_orbits::time::TimeOrigin;

/// The stage (module docs).
#[derive(Debug)]
pub struct RelnavStage {
    target: ObsFile,
    /// The target's next epoch to pair.
    cursor: usize,
    store: EphemerisStore,
    origin: TimeOrigin,
    start: Epoch,
    mode: RelnavMode,
    signals: Vec<Signal>,
    common: bool,
    /// With each vehicle's own satellite sets: the chaser's smoother.
    chaser_smoother: Option<CarrierSmoother>,
    engine: Box<dyn Engine>,
    estimates: Vec<RelativeEstimate>,
}

impl RelnavStage {
    /// The stage for `config` against the target's observations `target`, with the
    /// broadcast `ephemerides` and ionosphere. The signals are `config`'s, or every one
    /// the target's file has; `t_s` counts from the target's first epoch, as on files.
    pub fn new(
        target: ObsFile,
        ephemerides: Vec<BroadcastEphemeris>,
        iono: &BroadcastIono,
        config: &RelnavConfig,
    ) -> Result<Self, RelnavError> {
        let start = (target.epochs.first())
            .map(|e| e.time)
            .ok_or_else(|| RelnavError::NoEpochs(target.source.display().to_string()))?;
        let signals = if config.signals.is_empty() {
            target.signals()
        } else {
            config.signals.clone()
        };
        let origin = TimeOrigin::new(start);
        let own = config.mode == RelnavMode::CarrierSmoothed
            && config.satellite_sets == SatelliteSets::Own;
        let target = if own {
            carrier_smoothed_file(&target, &origin, config.smoothing)
        } else {
            target
        };
        let common = config.mode != RelnavMode::Standalone && !own;
        let engine = engine(config, &pvt_settings(config, iono), &signals, start, common);
        Ok(Self {
            target,
            cursor: 0,
            store: EphemerisStore::new(ephemerides, &origin),
            origin,
            start,
            mode: config.mode,
            signals,
            common,
            chaser_smoother: own.then(|| CarrierSmoother::new(config.smoothing)),
            engine,
            estimates: Vec::new(),
        })
    }

    /// The chaser's epoch tagged `time` by its receiver, with its `records`: paired with
    /// the target's epoch of the same tag (within the files' tolerance), the chaser
    /// relative to the target, kept for [`Self::run`]. Epochs the target lacks are passed
    /// by.
    pub fn epoch(&mut self, time: Epoch, records: &[ObsRecord]) {
        let own_smoothed;
        let records = match self.chaser_smoother.as_mut() {
            Some(s) => {
                own_smoothed = smoothed(s, records, self.origin.seconds_since_start(time));
                &own_smoothed[..]
            }
            None => records,
        };
        let Some((t_time, t_records)) = records_at(&self.target, &mut self.cursor, time) else {
            return;
        };
        let (t_sats, c_sats) = pair_records((t_records, records), &self.signals, self.common);
        let target = ObsEpoch {
            time: t_time,
            sats: t_sats,
        };
        let chaser = ObsEpoch { time, sats: c_sats };
        let at = Context {
            store: &self.store,
            origin: &self.origin,
        };
        self.estimates
            .extend(self.engine.epoch((&target, &chaser), &at));
    }

    /// What the stage estimated so far.
    pub fn run(&self) -> RelnavRun {
        RelnavRun {
            start: self.start,
            mode: self.mode,
            signals: self.signals.clone(),
            estimates: self.estimates.clone(),
            missed: self.engine.missed(),
        }
    }
}
