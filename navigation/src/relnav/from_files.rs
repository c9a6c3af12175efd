//! Relative navigation on two observation files (module docs of [`super`]).

use super::double_difference::{self, Inputs};
use super::hill_filter::{HillFilter, TargetState};
use super::same_satellites::SameSatellites;
use super::single_difference;
use super::{AmbiguityCount, RelnavConfig, RelnavMode, SatelliteSets};
use crate::orbit_determination::{FixInput, PositionFilter};
use crate::pvt::IonosphereCorrection;
use crate::pvt::{Fix, PvtConfig, records_velocity};
use crate::relative::files::{carrier_smoothed_file, records_at};
use crate::relative::single_point_fixes;
use hifitime::Epoch;
use skyforge_gnss::observation::{ObsEpoch, ObsFile, ObsRecord};
use skyforge_gnss::signal::Signal;
use skyforge_orbits::Vec3;
use skyforge_orbits::ephemeris::rinex_nav_iono::BroadcastIono;
use skyforge_orbits::ephemeris::{BroadcastEphemeris, EphemerisStore, SatId};
use skyforge_orbits::frames::earth_rotation::EarthRotation;
use skyforge_orbits::frames::relative_in_frame_of;
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

/// The chaser relative to the target at one epoch (target orbit frame).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RelativeEstimate {
    /// The target fix's time, seconds since the target file's first epoch (GPST).
    pub t_s: f64,
    pub position_m: Vec3,
    /// The rate in the rotating frame.
    pub velocity_mps: Vec3,
    /// How long both fixes have used the same satellites as each other, neither set
    /// changed and no epoch missed (s; 0 while the sets differ): the book's steady state
    /// (5.6.5) needs both vehicles on one set, neither having changed satellites, and the
    /// smoothing to have run.
    pub same_satellites_s: f64,
    /// The baseline chaser minus target in the Earth-fixed frame (m), where the mode
    /// estimates it as such (`double-difference`): free of the frame's orientation.
    pub baseline_ecef_m: Option<Vec3>,
    /// The double-difference ambiguities fixed and float after the epoch
    /// (`double-difference`).
    pub ambiguities: Option<AmbiguityCount>,
}

/// What [`relative_from_files`] estimated.
#[derive(Debug, Clone, PartialEq)]
pub struct RelnavRun {
    /// The epoch `t_s` counts from: the target file's first.
    pub start: Epoch,
    pub mode: RelnavMode,
    pub signals: Vec<Signal>,
    pub estimates: Vec<RelativeEstimate>,
    /// Common epochs without both fixes and velocities.
    pub missed: usize,
}

/// The epochs the two files share, each vehicle's records of `signals` at them: all of
/// them with `common == false`, those of satellite and signal pairs both have a
/// pseudorange for otherwise.
fn paired_files(
    target: &ObsFile,
    chaser: &ObsFile,
    signals: &[Signal],
    common: bool,
) -> (ObsFile, ObsFile) {
    let keep = |r: &ObsRecord| signals.contains(&r.signal) && r.pseudorange_m.is_some();
    let (mut t_out, mut c_out) = (
        target.with_epochs(Vec::new()),
        chaser.with_epochs(Vec::new()),
    );
    let mut cursor = 0;
    for epoch in &target.epochs {
        let Some((time, records)) = records_at(chaser, &mut cursor, epoch.time) else {
            continue;
        };
        let t_keys: BTreeSet<_> = (epoch.sats.iter().filter(|r| keep(r)))
            .map(|r| (r.sat, r.signal))
            .collect();
        let c_keys: BTreeSet<_> = (records.iter().filter(|r| keep(r)))
            .map(|r| (r.sat, r.signal))
            .collect();
        let both = |r: &&ObsRecord| {
            keep(r)
                && (!common
                    || (t_keys.contains(&(r.sat, r.signal)) && c_keys.contains(&(r.sat, r.signal))))
        };
        t_out.epochs.push(ObsEpoch {
            time: epoch.time,
            sats: epoch.sats.iter().filter(both).cloned().collect(),
        });
        c_out.epochs.push(ObsEpoch {
            time,
            sats: records.iter().filter(both).cloned().collect(),
        });
    }
    (t_out, c_out)
}

/// The two files' epochs with the records of the satellites both fixes of the epoch
/// used (none where either has no fix).
fn restricted(
    (target, chaser): (&ObsFile, &ObsFile),
    t_fixes: &[Result<Fix, String>],
    c_fixes: &[Result<Fix, String>],
) -> (ObsFile, ObsFile) {
    let (mut t_out, mut c_out) = (target.clone(), chaser.clone());
    let epochs = t_out.epochs.iter_mut().zip(c_out.epochs.iter_mut());
    for (k, (t, c)) in epochs.enumerate() {
        let both: BTreeSet<SatId> = used_satellites(&t_fixes[k])
            .intersection(&used_satellites(&c_fixes[k]))
            .copied()
            .collect();
        t.sats.retain(|r| both.contains(&r.sat));
        c.sats.retain(|r| both.contains(&r.sat));
    }
    (t_out, c_out)
}

/// The satellites `fix` used (none without one).
fn used_satellites(fix: &Result<Fix, String>) -> BTreeSet<SatId> {
    (fix.as_ref())
        .map(|f| f.used.iter().map(|u| u.0).collect())
        .unwrap_or_default()
}

/// The satellites the target's and the chaser's fix of an epoch used.
#[derive(Debug, PartialEq)]
struct SatelliteSetPair {
    target: BTreeSet<SatId>,
    chaser: BTreeSet<SatId>,
}

impl SatelliteSetPair {
    fn of(target: &Result<Fix, String>, chaser: &Result<Fix, String>) -> Self {
        Self {
            target: used_satellites(target),
            chaser: used_satellites(chaser),
        }
    }

    /// Both fixes on the same satellites.
    fn same(&self) -> bool {
        self.target == self.chaser
    }
}

/// One vehicle's solution at an epoch: its fix's time (s since the start), position and
/// Doppler velocity (ECEF).
struct Solution {
    t_s: f64,
    r_ecef_m: Vec3,
    v_ecef_mps: Vec3,
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
    let earth = EarthRotation::at_origin(start);
    let pvt = PvtConfig {
        elevation_mask_rad: config.elevation_mask_deg.to_radians(),
        iono_gps: iono.gps,
        iono_bds: iono.bds,
        carrier_smoothing: (config.mode == RelnavMode::CarrierSmoothed && !own)
            .then_some(config.smoothing),
        ..PvtConfig::default()
    };
    let inputs = Inputs {
        store: &store,
        origin: &origin,
        start,
        signals: &signals,
        config,
        pvt: &pvt,
    };
    let filtered = match config.mode {
        RelnavMode::DoubleDifference => {
            // Dual-frequency fixes where two carriers are measured: the ionosphere-free
            // code (the receive instants and the target's anchor).
            let carriers: BTreeSet<u64> = signals.iter().map(|s| s.carrier_hz() as u64).collect();
            let pvt = PvtConfig {
                ionosphere: if carriers.len() > 1 {
                    IonosphereCorrection::DualFrequency
                } else {
                    IonosphereCorrection::Broadcast
                },
                carrier_smoothing: None,
                ..pvt.clone()
            };
            Some(double_difference::run(
                &t_file,
                &c_file,
                &Inputs {
                    pvt: &pvt,
                    ..inputs
                },
            ))
        }
        RelnavMode::SingleDifference => Some(single_difference::run(&t_file, &c_file, &inputs)),
        _ => None,
    };
    if let Some((estimates, missed)) = filtered {
        return Ok(RelnavRun {
            start,
            mode: config.mode,
            signals,
            estimates,
            missed,
        });
    }
    let mut t_fixes = single_point_fixes(&t_file, &store, &origin, &signals, &pvt);
    let mut c_fixes = single_point_fixes(&c_file, &store, &origin, &signals, &pvt);
    if common {
        // Each receiver's elevation mask and residual test choose among the common
        // satellites on their own (a satellite at the mask for one vehicle is just below
        // it for the other, 32 km away): the fixes again on the satellites both fixes
        // used, with neither (module docs).
        let (t_file, c_file) = restricted((&t_file, &c_file), &t_fixes, &c_fixes);
        let same = PvtConfig {
            elevation_mask_rad: -std::f64::consts::FRAC_PI_2,
            raim_pfa: 0.0,
            ..pvt
        };
        t_fixes = single_point_fixes(&t_file, &store, &origin, &signals, &same);
        c_fixes = single_point_fixes(&c_file, &store, &origin, &signals, &same);
    }
    let solution = |epoch: &ObsEpoch, fix: &Fix| {
        let t_rx = origin.seconds_since_start(epoch.time);
        Some(Solution {
            t_s: fix.t_s,
            r_ecef_m: fix.r_ecef_m,
            v_ecef_mps: records_velocity(&epoch.sats, &signals, t_rx, &store, fix)?,
        })
    };
    let mut orbit = PositionFilter::new(config.target_orbit.clone(), start);
    let mut relative_filter = (config.filter.clone()).map(|f| HillFilter::new(f, start));
    let mut estimates = Vec::new();
    let mut missed = 0;
    let mut sets = SameSatellites::new();
    for k in 0..t_file.epochs.len() {
        let both = match (&t_fixes[k], &c_fixes[k]) {
            (Ok(tf), Ok(cf)) => solution(&t_file.epochs[k], tf)
                .zip(solution(&c_file.epochs[k], cf))
                .map(|both| (tf, both)),
            _ => None,
        };
        let Some((tf, (t, c))) = both else {
            missed += 1;
            sets.missed();
            continue;
        };
        let used = SatelliteSetPair::of(&t_fixes[k], &c_fixes[k]);
        let same = used.same();
        let unchanged_s = sets.at(used, t.t_s);
        let same_satellites_s = if same { unchanged_s } else { 0.0 };
        // The chaser's fix moved to the target fix's instant (ECEF, its own velocity).
        let r_c = c.r_ecef_m + c.v_ecef_mps * (t.t_s - c.t_s);
        let (rt, vt) = earth.ecef_to_eci(t.t_s, &t.r_ecef_m, &t.v_ecef_mps);
        let (rc, vc) = earth.ecef_to_eci(t.t_s, &r_c, &c.v_ecef_mps);
        // The frame from the target's filtered orbit (config docs).
        let filtered = orbit.update(&FixInput {
            t_s: t.t_s,
            r_ecef_m: t.r_ecef_m,
            v_ecef_mps: Some(t.v_ecef_mps),
            gdop: tf.dop.gdop,
        });
        let (mut position_m, mut velocity_mps) = relative_in_frame_of(
            &filtered.r_eci_m,
            &filtered.v_eci_mps,
            &(rc - rt),
            &(vc - vt),
        );
        if let Some(f) = relative_filter.as_mut() {
            let target = TargetState {
                t_s: t.t_s,
                r_eci_m: filtered.r_eci_m,
                v_eci_mps: filtered.v_eci_mps,
            };
            let e = f.update(target, position_m, Some(velocity_mps));
            (position_m, velocity_mps) = (e.position_m, e.velocity_mps);
        }
        estimates.push(RelativeEstimate {
            t_s: t.t_s,
            position_m,
            velocity_mps,
            same_satellites_s,
            baseline_ecef_m: None,
            ambiguities: None,
        });
    }
    Ok(RelnavRun {
        start,
        mode: config.mode,
        signals,
        estimates,
        missed,
    })
}
