//! Orbit determination on observation files: the receiver's single-point fixes (velocity
//! from the Doppler where it was measured) every `interval_s` into the position filter,
//! or every epoch's observations into the reduced-dynamic filter.
//! Reads only what a receiver could: observations, broadcast ephemerides and ionosphere,
//! the filter's own settings.

use super::stage::on_grid;
use super::{
    EcefEstimate, EpochFix, FixInput, OdConfig, OdFilterConfig, OrbitDetermination, OrbitEstimate,
    PositionFilter, PositionFilterConfig,
};
use crate::pvt::{Fix, PvtConfig, records_velocity};
use crate::relative::single_point_fixes;
use hifitime::{Epoch, Unit};
use skyforge_gnss::observation::{ObsEpoch, ObsFile};
use skyforge_gnss::signal::Signal;
use skyforge_orbits::Vec3;
use skyforge_orbits::ephemeris::rinex_nav_iono::BroadcastIono;
use skyforge_orbits::ephemeris::{BroadcastEphemeris, EphemerisStore};
use skyforge_orbits::time::TimeOrigin;
use std::collections::BTreeSet;

/// Why orbit determination could not run on a file.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum OdError {
    #[error("{0}: no epochs")]
    NoEpochs(String),
    #[error("{file}: none of the signals {wanted} (the file has {has})")]
    NoSignal {
        file: String,
        wanted: String,
        has: String,
    },
    #[error("no ephemeris in the navigation file for the satellites of {0}")]
    NoEphemeris(String),
}

/// What [`orbit_from_file`] estimated.
#[derive(Debug, Clone, PartialEq)]
pub struct OdRun {
    /// The epoch `t_s` counts from: the file's first.
    pub start: Epoch,
    /// The signals the fixes used.
    pub signals: Vec<Signal>,
    /// The estimate after every fix taken.
    pub estimates: Vec<EcefEstimate>,
    /// Epochs on the grid without a fix (too few satellites, no ephemeris).
    pub missed: usize,
}

/// The single-point fixes of `file` on the grid `k interval_s` (seconds since `origin`),
/// each with the Doppler velocity where one could be solved, in time order; and how
/// many epochs on the grid had no fix.
fn fixes_on_grid(
    file: &ObsFile,
    store: &EphemerisStore,
    origin: &TimeOrigin,
    signals: &[Signal],
    pvt: &PvtConfig,
    interval_s: f64,
) -> (Vec<FixInput>, usize) {
    let fixes = single_point_fixes(file, store, origin, signals, pvt);
    let mut out = Vec::new();
    let mut missed = 0;
    for (epoch, fix) in file.epochs.iter().zip(fixes) {
        if !on_grid(origin.seconds_since_start(epoch.time), interval_s) {
            continue;
        }
        let Ok(fix) = fix.as_ref() else {
            missed += 1;
            continue;
        };
        let velocity = doppler_velocity(epoch, signals, store, origin, fix);
        out.push(FixInput {
            t_s: fix.t_s,
            r_ecef_m: fix.r_ecef_m,
            v_ecef_mps: velocity,
            gdop: fix.dop.gdop,
        });
    }
    (out, missed)
}

/// The velocity the Doppler of `epoch` on `signals` gives beside `fix`, where it solves.
fn doppler_velocity(
    epoch: &ObsEpoch,
    signals: &[Signal],
    store: &EphemerisStore,
    origin: &TimeOrigin,
    fix: &Fix,
) -> Option<Vec3> {
    let t_s = origin.seconds_since_start(epoch.time);
    records_velocity(&epoch.sats, signals, t_s, store, fix)
}

/// The filter's estimates at every epoch of `file` on the grid `k interval_s` (seconds
/// since `origin`) that has a fix on `signals`.
pub fn position_filter_on_file(
    file: &ObsFile,
    store: &EphemerisStore,
    origin: &TimeOrigin,
    signals: &[Signal],
    pvt: &PvtConfig,
    filter: PositionFilterConfig,
    interval_s: f64,
) -> Vec<OrbitEstimate> {
    let (fixes, _) = fixes_on_grid(file, store, origin, signals, pvt, interval_s);
    let mut od = PositionFilter::new(filter, origin.start());
    fixes.iter().map(|f| od.update(f)).collect()
}

/// The single-point fixes of every epoch of `file` (first epoch `start`) on `signals` (velocity from the
/// Doppler, asked for on the stage's grid only) into the position filter's stage `od`.
fn fixes_into(
    mut od: OrbitDetermination,
    file: &ObsFile,
    start: Epoch,
    ephemerides: Vec<BroadcastEphemeris>,
    iono: &BroadcastIono,
    signals: &[Signal],
) -> OrbitDetermination {
    let origin = TimeOrigin::new(start);
    let store = EphemerisStore::new(ephemerides, &origin);
    let pvt = PvtConfig {
        elevation_mask_rad: od.config().elevation_mask_deg.to_radians(),
        iono_gps: iono.gps,
        iono_bds: iono.bds,
        ..PvtConfig::default()
    };
    let fixes = single_point_fixes(file, &store, &origin, signals, &pvt);
    for (epoch, fix) in file.epochs.iter().zip(fixes) {
        od.epoch(
            epoch.time,
            || {
                fix.ok().map(|fix| EpochFix {
                    time: origin.start() + Unit::Second * fix.t_s,
                    r_ecef_m: fix.r_ecef_m,
                    v_ecef_mps: doppler_velocity(epoch, signals, &store, &origin, &fix),
                    gdop: fix.dop.gdop,
                })
            },
            Vec::new,
        );
    }
    od
}

/// `skyforge od`: the orbit of the receiver that recorded `file`, from its observations,
/// the broadcast `ephemerides` and ionosphere, with `config`'s filter.
pub fn orbit_from_file(
    file: &ObsFile,
    ephemerides: Vec<BroadcastEphemeris>,
    iono: &BroadcastIono,
    config: &OdConfig,
) -> Result<OdRun, OdError> {
    let source = file.source.display().to_string();
    let start = file
        .epochs
        .first()
        .map(|e| e.time)
        .ok_or_else(|| OdError::NoEpochs(source.clone()))?;
    let has: BTreeSet<Signal> = (file.epochs.iter())
        .flat_map(|e| e.sats.iter().map(|r| r.signal))
        .collect();
    let signals: Vec<Signal> = if config.signals.is_empty() {
        has.iter().copied().collect()
    } else {
        (config.signals.iter())
            .filter(|s| has.contains(s))
            .copied()
            .collect()
    };
    if signals.is_empty() {
        let names = |s: &mut dyn Iterator<Item = &Signal>| {
            s.map(|s| s.to_string()).collect::<Vec<_>>().join(", ")
        };
        return Err(OdError::NoSignal {
            file: source,
            wanted: names(&mut config.signals.iter()),
            has: names(&mut has.iter()),
        });
    }
    let tracked: BTreeSet<_> = (file.epochs.iter())
        .flat_map(|e| e.sats.iter().map(|r| r.sat))
        .collect();
    if !ephemerides.iter().any(|e| tracked.contains(&e.sat)) {
        return Err(OdError::NoEphemeris(source));
    }
    let stage_config = OdConfig {
        signals: signals.clone(),
        ..config.clone()
    };
    let od = match config.filter {
        OdFilterConfig::PositionFilter(_) => {
            let od = OrbitDetermination::new(stage_config, Vec::new())
                .map_err(|_| OdError::NoEphemeris(source.clone()))?;
            fixes_into(od, file, start, ephemerides, iono, &signals)
        }
        OdFilterConfig::ReducedDynamic(_) => {
            let mut od = OrbitDetermination::new(stage_config, ephemerides)
                .map_err(|_| OdError::NoEphemeris(source.clone()))?;
            for epoch in &file.epochs {
                od.epoch(epoch.time, || None, || epoch.sats.clone());
            }
            od
        }
    };
    let (estimates, missed) = (od.estimates().to_vec(), od.missed());
    Ok(OdRun {
        start,
        signals,
        estimates,
        missed,
    })
}
