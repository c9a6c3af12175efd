//! The attitude chain (`receiver::relative`) over an observation-level run, compared with
//! the truth of that run: every fixed integer against the true double-difference integer,
//! the fixed baselines (ECEF and the master's NED) against the true ones, the attitude
//! against the true yaw/pitch/roll from NED (thesis eqs. 2.5-3..2.5-6).

use hifitime::Epoch;
use skyforge_gnss::observation::{ObsFile, ObsRecord};
use skyforge_gnss::signal::Signal;
use skyforge_navigation::attitude::{angle_error, wrap_diff};
use skyforge_navigation::geometry_file::BodyGeometryFile;
use skyforge_navigation::relative::{AmbiguityStatus, RelativeConfig, RelativeEpoch};
use skyforge_navigation::relative::{EpochOutcome, FilesError, run_files};
use skyforge_orbits::ephemeris::SatId;
use skyforge_orbits::frames::YawPitchRoll;
use skyforge_orbits::frames::c_ecef_ned;
use skyforge_orbits::frames::ecef_to_geodetic;
use skyforge_orbits::{Mat3, Vec3};
use skyforge_runner::ObservationRun;
use skyforge_signals::synth::GEOMETRY_STEP_S;
use std::collections::HashMap;

/// Estimate minus truth at one fixed epoch.
#[derive(Debug, Clone, PartialEq)]
pub struct EpochErrors {
    /// Seconds since the run's start.
    pub t_s: f64,
    /// Per baseline: ECEF X, Y, Z (m).
    pub baseline_ecef_m: Vec<[f64; 3]>,
    /// Per baseline: N, E, D (m) in the master's local frame.
    pub baseline_ned_m: Vec<[f64; 3]>,
    /// Yaw, pitch, roll (deg) where the attitude stage updated at this epoch.
    pub attitude_deg: Option<[f64; 3]>,
    /// Yaw, pitch, roll rates (deg/s) where the attitude stage updated and estimates
    /// rates (the filters), against the true rates (central difference of the true
    /// attitude one geometry step either side).
    pub rate_deg_s: Option<[f64; 3]>,
}

/// The chain's outcome over a run.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ChainComparison {
    /// Epochs of the master's observations.
    pub epochs: usize,
    /// Seconds from the start to the first fixed epoch.
    pub first_fix_s: Option<f64>,
    /// Epochs from the first fixed one on.
    pub after_first_fix: usize,
    /// The errors of every fixed epoch.
    pub fixed: Vec<EpochErrors>,
    /// Fixed integers compared with the truth's, and how many differed.
    pub integers_checked: usize,
    pub integers_wrong: usize,
    /// Largest distance (cycles) of an observed-minus-true double difference from its
    /// nearest integer over the checked integers (noise; 0.5 would be ambiguous).
    pub largest_integer_distance_cycles: f64,
    /// Epochs whose every ambiguity was fixed, and those of them with a wrong integer.
    pub fixed_epochs: usize,
    pub fixed_epochs_wrong: usize,
}

impl ChainComparison {
    /// Fixed epochs over epochs from the first fix on (0 without a fix).
    pub fn fix_rate(&self) -> f64 {
        self.fixed.len() as f64 / self.after_first_fix.max(1) as f64
    }

    /// Record the integers `check` compared with the truth's.
    pub(super) fn record_integers(&mut self, check: &IntegerCheck) {
        self.integers_checked = check.checked;
        self.integers_wrong = check.wrong;
        self.largest_integer_distance_cycles = check.largest_distance_cycles;
    }

    /// `pick` of each fixed epoch that has it.
    fn values(&self, pick: impl Fn(&EpochErrors) -> Option<f64>) -> Vec<f64> {
        self.fixed.iter().filter_map(pick).collect()
    }

    /// Component `i` of baseline `k`'s ECEF (`ned` false) or NED errors.
    pub fn baseline_axis(&self, k: usize, i: usize, ned: bool) -> Vec<f64> {
        self.values(|e| {
            let v = if ned {
                &e.baseline_ned_m
            } else {
                &e.baseline_ecef_m
            };
            v.get(k).map(|c| c[i])
        })
    }

    /// Attitude error of axis `i` (0 yaw, 1 pitch, 2 roll), deg.
    pub fn attitude_axis(&self, i: usize) -> Vec<f64> {
        self.values(|e| e.attitude_deg.map(|a| a[i]))
    }

    /// Attitude-rate error of axis `i` (0 yaw, 1 pitch, 2 roll), deg/s.
    pub fn rate_axis(&self, i: usize) -> Vec<f64> {
        self.values(|e| e.rate_deg_s.map(|a| a[i]))
    }

    /// `pick` of each fixed epoch that has it, against the epoch's time (s since the
    /// start).
    pub fn along(&self, pick: impl Fn(&EpochErrors) -> Option<f64>) -> Vec<(f64, f64)> {
        self.fixed
            .iter()
            .filter_map(|e| Some((e.t_s, pick(e)?)))
            .collect()
    }
}

/// Values per (second, satellite, signal); looked up four times per fixed integer per
/// epoch, hence the fast hasher.
type BySecond = HashMap<(i64, SatId, Signal), f64, foldhash::fast::FixedState>;

/// Measured minus true carrier phase (cycles) per (second, satellite, signal) of one
/// antenna: its integer ambiguity plus noise.
pub(crate) type PhaseOffsets = BySecond;

/// Epochs this close (s) to a whole second since the start are that second's; the
/// observation truth is written at whole seconds.
const WHOLE_SECOND_S: f64 = 1e-3;

/// Whole seconds from `start` to `t`, when `t` lies on one.
pub(crate) fn whole_second(t: Epoch, start: Epoch) -> Option<i64> {
    let s = (t - start).to_seconds();
    ((s - s.round()).abs() <= WHOLE_SECOND_S).then_some(s.round() as i64)
}

/// Measured minus true `pick` (an observable of a record, in its unit) per (second,
/// satellite, signal) wherever both exist at a whole second since `start`, in the order of
/// `measured`'s epochs and records.
pub fn offsets(
    measured: &ObsFile,
    truth: &ObsFile,
    start: Epoch,
    pick: fn(&ObsRecord) -> Option<f64>,
) -> Vec<((i64, SatId, Signal), f64)> {
    let second = |t: Epoch| whole_second(t, start);
    let truth: BySecond = truth
        .epochs
        .iter()
        .filter_map(|e| Some((second(e.time)?, e)))
        .flat_map(|(s, e)| {
            e.sats
                .iter()
                .filter_map(move |r| Some(((s, r.sat, r.signal), pick(r)?)))
        })
        .collect();
    measured
        .epochs
        .iter()
        .filter_map(|e| Some((second(e.time)?, e)))
        .flat_map(|(s, e)| {
            let truth = &truth;
            e.sats.iter().filter_map(move |r| {
                let key = (s, r.sat, r.signal);
                Some((key, pick(r)? - truth.get(&key)?))
            })
        })
        .collect()
}

/// Measured minus true carrier phase (cycles) of one antenna ([`offsets`]).
pub(crate) fn phase_offsets(measured: &ObsFile, truth: &ObsFile, start: Epoch) -> PhaseOffsets {
    offsets(measured, truth, start, |r| r.carrier_phase_cycles)
        .into_iter()
        .collect()
}

/// Observed minus true double difference (cycles) of `sat` against `reference` on
/// `signal`, baseline `rover` (antenna `rover` minus the master, antenna 0) at `second`:
/// the true double-difference integer plus noise. `None` when an antenna lacks a phase.
pub(super) fn dd_offset(
    offsets: &[PhaseOffsets],
    second: i64,
    rover: usize,
    signal: Signal,
    sat: SatId,
    reference: SatId,
) -> Option<f64> {
    let d = |a: usize, s: SatId| offsets.get(a)?.get(&(second, s, signal)).copied();
    Some(d(rover, sat)? - d(0, sat)? - (d(rover, reference)? - d(0, reference)?))
}

/// Fixed integers checked against the truth's double-difference integers.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(crate) struct IntegerCheck {
    pub checked: usize,
    pub wrong: usize,
    pub largest_distance_cycles: f64,
}

impl IntegerCheck {
    /// Check `integer` against `dd`, the observed minus true double difference.
    pub fn add(&mut self, dd: f64, integer: i64) {
        self.checked += 1;
        self.wrong += usize::from(dd.round() as i64 != integer);
        self.largest_distance_cycles = self.largest_distance_cycles.max((dd - dd.round()).abs());
    }

    /// Two checks together (over several runs): counts summed, the largest distance.
    pub fn merge(self, other: Self) -> Self {
        Self {
            checked: self.checked + other.checked,
            wrong: self.wrong + other.wrong,
            largest_distance_cycles: self
                .largest_distance_cycles
                .max(other.largest_distance_cycles),
        }
    }
}

/// The nominal body geometry of `run` as `skyforge synth` writes it.
pub fn nominal_geometry(run: &ObservationRun) -> BodyGeometryFile {
    BodyGeometryFile::from_positions(
        run.antennas
            .iter()
            .cloned()
            .zip(run.nominal_body_m.iter().copied()),
    )
}

/// The truth at one epoch: true ECEF and NED baselines and the true attitude from NED
/// at the master.
pub(crate) struct EpochTruth {
    pub ecef: Vec<Vec3>,
    pub ned: Vec<Vec3>,
    pub attitude: YawPitchRoll,
}

/// The truth of a platform at `r_ecef_m` (centre of mass) turned by `c_body_ecef`, with
/// antennas at `true_body_m` (master first; at least one).
pub(crate) fn epoch_truth(r_ecef_m: &Vec3, c_body_ecef: &Mat3, true_body_m: &[Vec3]) -> EpochTruth {
    let origin = true_body_m.first().copied().unwrap_or_else(Vec3::zeros);
    let master = r_ecef_m + c_body_ecef * origin;
    let g = ecef_to_geodetic(&master);
    let c_ned_ecef = c_ecef_ned(g.lat_rad, g.lon_rad);
    let c_body_ned = c_ned_ecef * c_body_ecef;
    let ecef: Vec<Vec3> = true_body_m
        .iter()
        .skip(1)
        .map(|b| c_body_ecef * (b - origin))
        .collect();
    EpochTruth {
        ned: ecef.iter().map(|b| c_ned_ecef * b).collect(),
        ecef,
        attitude: YawPitchRoll::from_c_ref_body(&c_body_ned.transpose()),
    }
}

/// Estimated minus true yaw, pitch, roll (deg, wrapped; the receiver's own
/// [`angle_error`]).
pub(crate) fn attitude_errors_deg(estimate: &YawPitchRoll, truth: &YawPitchRoll) -> [f64; 3] {
    let e = angle_error(estimate, truth);
    [e.x, e.y, e.z].map(f64::to_degrees)
}

/// The true yaw, pitch and roll rates (rad/s) of `run` at `t_s`: central difference of
/// the true attitude (from NED at the master) one geometry step either side.
fn true_rates(run: &ObservationRun, t_s: f64) -> Option<Vec3> {
    let h = GEOMETRY_STEP_S;
    let at = |t: f64| {
        let p = run.platform_at(t)?;
        Some(epoch_truth(&p.r_ecef_m, &p.c_body_ecef, &run.true_body_m).attitude)
    };
    let (a, b) = (at(t_s - h)?, at(t_s + h)?);
    Some(
        Vec3::new(
            wrap_diff(b.yaw_rad, a.yaw_rad),
            wrap_diff(b.pitch_rad, a.pitch_rad),
            wrap_diff(b.roll_rad, a.roll_rad),
        ) / (2.0 * h),
    )
}

/// The errors of a fixed epoch `e` against `truth`, the rates against `true_rates`
/// (asked only of a state with rates).
fn errors(
    e: &RelativeEpoch,
    t_s: f64,
    truth: &EpochTruth,
    true_rates: impl FnOnce() -> Option<Vec3>,
) -> Option<EpochErrors> {
    let fixed = e.fixed.as_ref()?;
    let ned = e.fixed_ned.as_ref()?;
    let diff = |a: &Vec3, b: &Vec3| [a.x - b.x, a.y - b.y, a.z - b.z];
    let baseline_ecef_m = fixed
        .baselines
        .column_iter()
        .zip(&truth.ecef)
        .map(|(c, t)| diff(&c.into_owned(), t))
        .collect();
    let baseline_ned_m = ned
        .baselines()
        .iter()
        .zip(&truth.ned)
        .map(|(b, t)| diff(b, t))
        .collect();
    let updated = match (&e.attitude, &e.attitude_skipped) {
        (Some(s), None) => Some(s),
        _ => None,
    };
    let attitude_deg = updated.map(|s| attitude_errors_deg(&s.angles, &truth.attitude));
    let rate_deg_s = updated
        .and_then(|s| s.rates_rad_s)
        .and_then(|r| Some(r - true_rates()?))
        .map(|d| [d.x, d.y, d.z].map(f64::to_degrees));
    Some(EpochErrors {
        t_s,
        baseline_ecef_m,
        baseline_ned_m,
        attitude_deg,
        rate_deg_s,
    })
}

/// Each fixed integer of `e` (at `second`, whole seconds since the start) against the
/// truth's.
pub(crate) fn check_integers(
    e: &RelativeEpoch,
    second: Option<i64>,
    offsets: &[PhaseOffsets],
    check: &mut IntegerCheck,
) {
    let Some(second) = second else { return };
    let ids: Vec<_> = e.float.model.layout.ambiguity_ids().collect();
    for (i, value) in e.resolution.integers.iter().enumerate() {
        let Some(v) = value else { continue };
        let (signal, sat, reference) = ids[i % ids.len()];
        let rover = i / ids.len() + 1;
        if let Some(dd) = dd_offset(offsets, second, rover, signal, sat, reference) {
            check.add(dd, *v);
        }
    }
}

/// Run the chain with `config` over `run` with `geometry` (master first; the run's
/// nominal geometry unless a study says otherwise) and compare with the truth.
pub fn compare(
    run: &ObservationRun,
    geometry: &BodyGeometryFile,
    config: RelativeConfig,
) -> Result<ChainComparison, FilesError> {
    let start = run.start;
    let offsets: Vec<PhaseOffsets> = run
        .measured
        .iter()
        .zip(&run.truth)
        .map(|(m, t)| phase_offsets(m, t, start))
        .collect();
    let mut out = ChainComparison::default();
    let mut integers = IntegerCheck::default();
    run_files(
        &run.measured,
        run.ephemerides.clone(),
        geometry,
        config,
        |o: EpochOutcome| {
            out.epochs += 1;
            let t_s = (o.time - start).to_seconds();
            let Ok(e) = &o.result else {
                out.after_first_fix += usize::from(out.first_fix_s.is_some());
                return;
            };
            let is_fixed = e.resolution.status == AmbiguityStatus::Fixed;
            if is_fixed && out.first_fix_s.is_none() {
                out.first_fix_s = Some(t_s);
            }
            if out.first_fix_s.is_none() {
                return;
            }
            out.after_first_fix += 1;
            let wrong_before = integers.wrong;
            check_integers(e, whole_second(o.time, start), &offsets, &mut integers);
            if is_fixed {
                out.fixed_epochs += 1;
                out.fixed_epochs_wrong += usize::from(integers.wrong > wrong_before);
            }
            let Some(p) = run.platform_at(t_s) else {
                return;
            };
            if is_fixed {
                let truth = epoch_truth(&p.r_ecef_m, &p.c_body_ecef, &run.true_body_m);
                out.fixed
                    .extend(errors(e, t_s, &truth, || true_rates(run, t_s)));
            }
        },
    )?;
    out.record_integers(&integers);
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The yaw difference of `d` degrees, as the attitude errors wrap it.
    fn wrap_deg(d: f64) -> f64 {
        let truth = YawPitchRoll::new(0.0, 0.0, 0.0);
        attitude_errors_deg(&YawPitchRoll::new(d.to_radians(), 0.0, 0.0), &truth)[0]
    }

    #[test]
    fn wrapped_differences() {
        assert!((wrap_deg(359.0) + 1.0).abs() < 1e-12);
        assert!((wrap_deg(-181.0) - 179.0).abs() < 1e-12);
        assert!((wrap_deg(0.5) - 0.5).abs() < 1e-12);
    }
}
