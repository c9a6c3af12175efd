//! Relative navigation on two observation files (module docs of [`super`]).

use super::book_modes::BookModes;
use super::double_difference::DdEngine;
use super::engine::{Context, Engine};
use super::estimate::RelnavRun;
use super::single_difference::SdEngine;
use super::{RelnavConfig, RelnavMode, SatelliteSets};
use crate::pvt::PvtConfig;
use crate::relative::files::{carrier_smoothed_file, records_at};
use hifitime::Epoch;
use skyforge_gnss::observation::{ObsEpoch, ObsFile, ObsRecord};
use skyforge_gnss::signal::Signal;
use skyforge_orbits::ephemeris::rinex_nav_iono::BroadcastIono;
use skyforge_orbits::ephemeris::{BroadcastEphemeris, EphemerisStore};
use skyforge_orbits::time::TimeOrigin;
use std::collections::BTreeSet;

/// Why relative navigation could not run on two files.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum RelnavError {
    #[error("{0}: no epochs")]
    NoEpochs(String),
    #[error("{target} and {chaser} share no epoch (within a millisecond)")]
    NoCommonEpoch { target: String, chaser: String },
    #[error("{target} and {chaser} share none of the signals {wanted}")]
    NoSignal {
        target: String,
        chaser: String,
        wanted: String,
    },
}

/// The records of `signals` with a pseudorange of one epoch of each vehicle: all of them
/// with `common == false`, those of the satellite and signal pairs both have otherwise.
pub(crate) fn pair_records(
    (target, chaser): (&[ObsRecord], &[ObsRecord]),
    signals: &[Signal],
    common: bool,
) -> (Vec<ObsRecord>, Vec<ObsRecord>) {
    let keep = |r: &ObsRecord| signals.contains(&r.signal) && r.pseudorange_m.is_some();
    let keys = |records: &[ObsRecord]| -> BTreeSet<_> {
        (records.iter().filter(|r| keep(r)))
            .map(|r| (r.sat, r.signal))
            .collect()
    };
    let (t_keys, c_keys) = (keys(target), keys(chaser));
    let both = |r: &&ObsRecord| {
        keep(r)
            && (!common
                || (t_keys.contains(&(r.sat, r.signal)) && c_keys.contains(&(r.sat, r.signal))))
    };
    (
        target.iter().filter(both).cloned().collect(),
        chaser.iter().filter(both).cloned().collect(),
    )
}

/// The epochs the two files share, each vehicle's records of them as [`pair_records`]
/// keeps them.
fn paired_files(
    target: &ObsFile,
    chaser: &ObsFile,
    signals: &[Signal],
    common: bool,
) -> (ObsFile, ObsFile) {
    let (mut t_out, mut c_out) = (
        target.with_epochs(Vec::new()),
        chaser.with_epochs(Vec::new()),
    );
    let mut cursor = 0;
    for epoch in &target.epochs {
        let Some((time, records)) = records_at(chaser, &mut cursor, epoch.time) else {
            continue;
        };
        let (t_sats, c_sats) = pair_records((&epoch.sats, records), signals, common);
        t_out.epochs.push(ObsEpoch {
            time: epoch.time,
            sats: t_sats,
        });
        c_out.epochs.push(ObsEpoch { time, sats: c_sats });
    }
    (t_out, c_out)
}

/// The engine of `config`'s mode on `signals` from `start`, the fixes with `pvt`;
/// `common`: the book modes' fixes on the satellites both use.
pub(crate) fn engine(
    config: &RelnavConfig,
    pvt: &PvtConfig,
    signals: &[Signal],
    start: Epoch,
    common: bool,
) -> Box<dyn Engine> {
    match config.mode {
        RelnavMode::DoubleDifference => Box::new(DdEngine::new(config, pvt, signals, start)),
        RelnavMode::SingleDifference => Box::new(SdEngine::new(config, pvt, signals, start)),
        _ => Box::new(BookModes::new(config, pvt, signals, start, common)),
    }
}

/// The single-point fixes' settings of `config`'s mode: its mask, the broadcast
/// ionosphere, and the carrier smoother in mode `carrier-smoothed` on the common
/// satellites (each vehicle's own sets smooth their whole files first).
pub(crate) fn pvt_settings(config: &RelnavConfig, iono: &BroadcastIono) -> PvtConfig {
    let smoothed_here = config.mode == RelnavMode::CarrierSmoothed
        && config.satellite_sets == SatelliteSets::Common;
    PvtConfig {
        elevation_mask_rad: config.elevation_mask_deg.to_radians(),
        iono_gps: iono.gps,
        iono_bds: iono.bds,
        carrier_smoothing: smoothed_here.then_some(config.smoothing),
        ..PvtConfig::default()
    }
}

/// The signals both files have among `wanted` (all of them when empty).
fn shared_signals(target: &ObsFile, chaser: &ObsFile, wanted: &[Signal]) -> Vec<Signal> {
    let has = |f: &ObsFile| -> BTreeSet<Signal> {
        (f.epochs.iter())
            .flat_map(|e| e.sats.iter().map(|r| r.signal))
            .collect()
    };
    let both: Vec<Signal> = has(target).intersection(&has(chaser)).copied().collect();
    if wanted.is_empty() {
        both
    } else {
        wanted
            .iter()
            .filter(|s| both.contains(s))
            .copied()
            .collect()
    }
}

/// `skyforge relnav`: the chaser (that recorded `chaser`) relative to the target (that
/// recorded `target`), from their observations, the broadcast `ephemerides` and
/// ionosphere, in `config`'s mode.
pub fn relative_from_files(
    target: &ObsFile,
    chaser: &ObsFile,
    ephemerides: Vec<BroadcastEphemeris>,
    iono: &BroadcastIono,
    config: &RelnavConfig,
) -> Result<RelnavRun, RelnavError> {
    let name = |f: &ObsFile| f.source.display().to_string();
    for f in [target, chaser] {
        if f.epochs.is_empty() {
            return Err(RelnavError::NoEpochs(name(f)));
        }
    }
    let start = target.epochs[0].time;
    let signals = shared_signals(target, chaser, &config.signals);
    if signals.is_empty() {
        let wanted: Vec<String> = config.signals.iter().map(|s| s.to_string()).collect();
        return Err(RelnavError::NoSignal {
            target: name(target),
            chaser: name(chaser),
            wanted: if wanted.is_empty() {
                "of either file".into()
            } else {
                wanted.join(", ")
            },
        });
    }
    let origin = TimeOrigin::new(start);
    // The book's own procedure smooths each vehicle's whole file along its own tracks
    // first: an epoch only one vehicle missed restarts only that vehicle's smoothers.
    let own =
        config.mode == RelnavMode::CarrierSmoothed && config.satellite_sets == SatelliteSets::Own;
    let smoothed = own.then(|| {
        let smooth = |f| carrier_smoothed_file(f, &origin, config.smoothing);
        (smooth(target), smooth(chaser))
    });
    let (target_in, chaser_in) = match &smoothed {
        Some((t, c)) => (t, c),
        None => (target, chaser),
    };
    let common = config.mode != RelnavMode::Standalone && !own;
    let (t_file, c_file) = paired_files(target_in, chaser_in, &signals, common);
    if t_file.epochs.is_empty() {
        return Err(RelnavError::NoCommonEpoch {
            target: name(target),
            chaser: name(chaser),
        });
    }
    let store = EphemerisStore::new(ephemerides, &origin);
    let pvt = pvt_settings(config, iono);
    let mut engine = engine(config, &pvt, &signals, start, common);
    let at = Context {
        store: &store,
        origin: &origin,
    };
    let estimates = (t_file.epochs.iter().zip(&c_file.epochs))
        .filter_map(|pair| engine.epoch(pair, &at))
        .collect();
    let missed = engine.missed();
    Ok(RelnavRun {
        start,
        mode: config.mode,
        signals,
        estimates,
        missed,
    })
}
