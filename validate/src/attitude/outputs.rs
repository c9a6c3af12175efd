//! The attitude chain's files against the truth of the run they came from: what
//! `skyforge validate attitude` compares.
//!
//! Inputs are three directories:
//! - the simulation (`skyforge run`/`synth`): `truth.h5` (the platform's position and
//!   body-to-ECEF quaternion at every geometry epoch, each antenna's nominal and true body
//!   position), `geometry.toml` (the antennas' names and order, master first) and
//!   `<antenna>.obs.rnx` (the observation truth: carrier phase without ambiguity);
//! - the observations the chain read (`skyforge receive`'s directory, or the
//!   simulation's `observations/`): `<antenna>.obs.rnx`;
//! - the chain's output (`skyforge attitude`): `attitude.csv` and `ambiguities.csv`.
//!
//! The truth baselines come from the antennas' *true* body positions (`true_body_m` in
//! `truth.h5`: nominal plus the scenario's offset), the true attitude from the body
//! frame against the NED frame at the master antenna, as [`super::compare`] does for an
//! in-memory run. Epochs between truth rows take the platform linearly interpolated
//! (position) and slerped (attitude).

use super::compare::{
    ChainComparison, EpochErrors, EpochTruth, IntegerCheck, PhaseOffsets, attitude_errors_deg,
    dd_offset, epoch_truth, phase_offsets, whole_second,
};
use crate::observables::ErrorStats;
use crate::stats::rms;
use crate::thesis::attitude_realtime::{ATTITUDE_ROW, BASELINE_ROWS};
use hifitime::Epoch;
use nalgebra::UnitQuaternion;
use serde::Serialize;
use skyforge_formats::FormatError;
use skyforge_formats::attitude::{
    AMBIGUITIES_CSV, ATTITUDE_CSV, Line, Status, read_ambiguities_csv, read_attitude_csv,
};
use skyforge_formats::truth::{NOMINAL_BODY_ATTR, TRUE_BODY_ATTR, TRUTH_H5, TruthFile};
use skyforge_gnss::observation::{ObsReadError, read_obs_file};

use skyforge_gnss::antenna_name::check_antenna_name;
use skyforge_navigation::geometry_file::{BodyGeometryFile, GeometryFileError};
use skyforge_orbits::frames::YawPitchRoll;
use skyforge_orbits::{Mat3, Vec3};
use std::io::Write;
use std::path::{Path, PathBuf};

/// Most rows of a `truth.h5` series read (48 days at 1 Hz).
const MAX_TRUTH_ROWS: usize = 1 << 22;
/// Truth rows this close (s) to an epoch are that epoch's.
const SAME_TIME_S: f64 = 1e-6;

/// Thesis table 5.4-4's N, E, D error std (m) of baseline `k` (0-based), where printed.
fn thesis_ned_std_m(k: usize) -> Option<[f64; 3]> {
    BASELINE_ROWS.get(k).map(|r| [r[3], r[4], r[5]])
}

/// Why the directories could not be compared. Every variant names the file.
#[derive(Debug, thiserror::Error)]
pub enum OutputsError {
    /// A file is missing, unreadable, too large or not what it should be.
    #[error("{path}: {message}")]
    File { path: PathBuf, message: String },
    /// `truth.h5` or one of the chain's CSV files is unreadable or malformed, or a line is
    /// not of this run.
    #[error(transparent)]
    Format(#[from] FormatError),
    #[error(transparent)]
    Observations(#[from] ObsReadError),
    #[error(transparent)]
    Geometry(#[from] GeometryFileError),
}

fn file_error(path: &Path, message: impl Into<String>) -> OutputsError {
    OutputsError::File {
        path: path.to_path_buf(),
        message: message.into(),
    }
}

/// One antenna of the run.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct AntennaPosition {
    pub name: String,
    /// What the receiver is told (`geometry.toml`, `truth.h5`'s `nominal_body_m`), m.
    pub nominal_body_m: [f64; 3],
    /// Nominal plus the scenario's offset (`truth.h5`'s `true_body_m`), m: what the truth
    /// baselines are made of.
    pub true_body_m: [f64; 3],
}

/// The platform truth of `truth.h5`.
#[derive(Debug, Clone)]
struct PlatformTruth {
    start: Epoch,
    t_s: Vec<f64>,
    r_ecef_m: Vec<Vec3>,
    q_body_ecef: Vec<UnitQuaternion<f64>>,
    antennas: Vec<AntennaPosition>,
    true_body_m: Vec<Vec3>,
}

impl PlatformTruth {
    /// Read `path` for the antennas of `geometry` (names and nominal positions checked).
    fn read(path: &Path, geometry: &BodyGeometryFile) -> Result<Self, OutputsError> {
        let file = TruthFile::open(path)?;
        let start = file.start_epoch()?;
        let platform = file.platform(MAX_TRUTH_ROWS)?;
        let mut antennas = Vec::new();
        for a in &geometry.antennas {
            let nominal = file.antenna_vector(&a.name, NOMINAL_BODY_ATTR)?;
            let true_m = file.antenna_vector(&a.name, TRUE_BODY_ATTR)?;
            if nominal
                .iter()
                .zip(&a.position_body_m)
                .any(|(x, y)| (x - y).abs() > 1e-9)
            {
                return Err(file_error(
                    path,
                    format!(
                        "antenna {} is at {nominal:?} (nominal) here but at {:?} in geometry.toml: not the same run",
                        a.name, a.position_body_m
                    ),
                ));
            }
            antennas.push(AntennaPosition {
                name: a.name.clone(),
                nominal_body_m: nominal,
                true_body_m: true_m,
            });
        }
        Ok(Self {
            start,
            r_ecef_m: platform.r_ecef_m,
            q_body_ecef: platform.q_body_ecef,
            true_body_m: antennas.iter().map(|a| Vec3::from(a.true_body_m)).collect(),
            antennas,
            t_s: platform.t_s,
        })
    }

    /// The platform (position, body-to-ECEF rotation) at `t` s since the start; `None`
    /// outside the truth's span.
    fn at(&self, t: f64) -> Option<(Vec3, Mat3)> {
        let i = self.t_s.partition_point(|x| *x <= t);
        let row = |k: usize| {
            (
                self.r_ecef_m[k],
                self.q_body_ecef[k].to_rotation_matrix().into_inner(),
            )
        };
        if i == 0 {
            return ((self.t_s[0] - t) <= SAME_TIME_S).then(|| row(0));
        }
        let a = i - 1;
        if t - self.t_s[a] <= SAME_TIME_S {
            return Some(row(a));
        }
        if i == self.t_s.len() {
            return None;
        }
        let w = (t - self.t_s[a]) / (self.t_s[i] - self.t_s[a]);
        let r = self.r_ecef_m[a] + (self.r_ecef_m[i] - self.r_ecef_m[a]) * w;
        let q = self.q_body_ecef[a].slerp(&self.q_body_ecef[i], w);
        Some((r, q.to_rotation_matrix().into_inner()))
    }

    fn truth_at(&self, t: f64) -> Option<EpochTruth> {
        let (r, c) = self.at(t)?;
        Some(epoch_truth(&r, &c, &self.true_body_m))
    }

    fn span(&self) -> (f64, f64) {
        let last = self.t_s.last().copied().unwrap_or(0.0);
        (self.t_s[0], last)
    }
}

/// The chain's files compared with the truth.
#[derive(Debug, Clone)]
pub struct OutputsComparison {
    pub truth_dir: PathBuf,
    pub observations_dir: PathBuf,
    pub attitude_dir: PathBuf,
    /// The run's start (`truth.h5`'s `start_epoch`); `t_s` counts from it.
    pub start: Epoch,
    /// Master first, in `geometry.toml`'s order.
    pub antennas: Vec<AntennaPosition>,
    /// Epochs, fixes, per-epoch errors and integer checks.
    pub chain: ChainComparison,
    /// Fixed epochs (every `fixed` row from the first fix on, with or without NED
    /// baselines).
    pub fixed_epochs: usize,
}

/// Compare the chain's output in `attitude_dir` (`attitude.csv`, `ambiguities.csv`) with
/// the truth in `truth_dir` (`truth.h5`, `geometry.toml`, `<antenna>.obs.rnx`), the
/// integers also with the observations in `observations_dir` the chain read.
pub fn compare_outputs(
    truth_dir: &Path,
    observations_dir: &Path,
    attitude_dir: &Path,
) -> Result<OutputsComparison, OutputsError> {
    for dir in [truth_dir, observations_dir, attitude_dir] {
        if !dir.is_dir() {
            return Err(file_error(dir, "not a directory"));
        }
    }
    let geometry_path = truth_dir.join("geometry.toml");
    let geometry = BodyGeometryFile::read(&geometry_path)?;
    // Names become file names (`<name>.obs.rnx` in both directories): the antenna rule.
    for a in &geometry.antennas {
        check_antenna_name(&a.name).map_err(|rule| {
            file_error(&geometry_path, format!("antenna name {:?}: {rule}", a.name))
        })?;
    }
    let truth = PlatformTruth::read(&truth_dir.join(TRUTH_H5), &geometry)?;
    let baselines = geometry.antennas.len() - 1;
    let att_path = attitude_dir.join(ATTITUDE_CSV);
    let int_path = attitude_dir.join(AMBIGUITIES_CSV);
    // Both of the chain's files before the (slower) observation files.
    for p in [&att_path, &int_path] {
        std::fs::metadata(p).map_err(|e| file_error(p, e.to_string()))?;
    }
    let (chain, fixed_epochs) = read_attitude(&att_path, &truth, baselines)?;
    let offsets = geometry
        .antennas
        .iter()
        .map(|a| {
            let file = format!("{}.obs.rnx", a.name);
            let (m_path, t_path) = (observations_dir.join(&file), truth_dir.join(&file));
            let measured = read_obs_file(&m_path)?;
            if std::fs::canonicalize(&m_path).ok() == std::fs::canonicalize(&t_path).ok() {
                return Err(file_error(
                    &m_path,
                    "is the observation truth itself; the observations are those the chain read (skyforge receive's directory, or SIMDIR/observations)",
                ));
            }
            let observed_truth = read_obs_file(&t_path)?;
            Ok(phase_offsets(&measured, &observed_truth, truth.start))
        })
        .collect::<Result<Vec<_>, OutputsError>>()?;
    let (integers, wrong_epochs) = check_integers(&int_path, &offsets, truth.start, baselines)?;
    let mut chain = chain;
    chain.fixed_epochs = fixed_epochs;
    chain.fixed_epochs_wrong = wrong_epochs;
    chain.record_integers(&integers);
    Ok(OutputsComparison {
        truth_dir: truth_dir.to_path_buf(),
        observations_dir: observations_dir.to_path_buf(),
        attitude_dir: attitude_dir.to_path_buf(),
        start: truth.start,
        antennas: truth.antennas.clone(),
        chain,
        fixed_epochs,
    })
}

/// `attitude.csv` against the truth: epochs, the first fix, and the errors of every
/// fixed epoch (counted from the first fix on, as [`super::compare()`] does).
fn read_attitude(
    path: &Path,
    truth: &PlatformTruth,
    baselines: usize,
) -> Result<(ChainComparison, usize), OutputsError> {
    let file = read_attitude_csv(path)?;
    if file.baselines != baselines {
        return Err(file_error(
            path,
            format!(
                "{} baselines, but geometry.toml has {} antennas ({baselines} baselines): not the chain of this run",
                file.baselines,
                baselines + 1
            ),
        ));
    }
    let mut out = ChainComparison::default();
    let mut fixed_epochs = 0usize;
    let (first, last) = truth.span();
    for Line { line, row: v } in &file.rows {
        let row_error = |m: String| OutputsError::from(FormatError::row(path, *line, m));
        out.epochs += 1;
        let t_s = (v.time - truth.start).to_seconds();
        let is_fixed = v.status == Status::Fixed;
        if is_fixed && out.first_fix_s.is_none() {
            out.first_fix_s = Some(t_s);
        }
        if out.first_fix_s.is_none() {
            continue;
        }
        out.after_first_fix += 1;
        if !is_fixed {
            continue;
        }
        fixed_epochs += 1;
        if v.ecef_m.len() != baselines {
            return Err(row_error("a fixed epoch without its baselines".into()));
        }
        let tr = truth.truth_at(t_s).ok_or_else(|| {
            row_error(format!(
                "{} is {t_s} s after the truth's start, outside truth.h5 ({first} .. {last} s): not the same run",
                v.time
            ))
        })?;
        let diff = |a: &[f64; 3], b: &Vec3| [a[0] - b.x, a[1] - b.y, a[2] - b.z];
        let baseline_ecef_m = (0..baselines)
            .map(|k| diff(&v.ecef_m[k], &tr.ecef[k]))
            .collect();
        // NED baselines are blank when the ECEF -> NED rotation failed; such an epoch
        // is fixed but has no NED errors.
        let baseline_ned_m = v.ned_m.as_ref().map_or_else(Vec::new, |ned| {
            (0..baselines)
                .map(|k| diff(&ned[k].ned_m, &tr.ned[k]))
                .collect()
        });
        // A note on a fixed epoch says the attitude stage skipped it (what it shows is
        // its last state): no attitude error, as for an in-memory run.
        let attitude_deg = match &v.attitude {
            Some(a) if v.note.is_empty() => {
                let [y, p, r] = a.angles_deg.map(f64::to_radians);
                let estimate = YawPitchRoll {
                    yaw_rad: y,
                    pitch_rad: p,
                    roll_rad: r,
                };
                Some(attitude_errors_deg(&estimate, &tr.attitude))
            }
            _ => None,
        };
        out.fixed.push(EpochErrors {
            t_s,
            baseline_ecef_m,
            baseline_ned_m,
            attitude_deg,
            rate_deg_s: None,
        });
    }
    Ok((out, fixed_epochs))
}

/// Every integer of `ambiguities.csv` against the truth's double-difference integer,
/// `round(DD(observed phase) - DD(truth phase))` of the same epoch. Integers whose
/// epoch is not a whole second, or whose phases an antenna's file lacks, are not
/// checked. Also returns how many epochs had a wrong integer.
fn check_integers(
    path: &Path,
    offsets: &[PhaseOffsets],
    start: Epoch,
    baselines: usize,
) -> Result<(IntegerCheck, usize), OutputsError> {
    let mut check = IntegerCheck::default();
    let mut wrong_seconds = std::collections::BTreeSet::new();
    for Line { line, row } in read_ambiguities_csv(path)? {
        let k = row.baseline;
        if k == 0 || k > baselines {
            let m = format!("baseline = {k}; the run has baselines 1..{baselines}");
            return Err(FormatError::row(path, line, m).into());
        }
        let Some(second) = whole_second(row.time, start) else {
            continue;
        };
        if let Some(dd) = dd_offset(offsets, second, k, row.signal, row.sat, row.reference) {
            let wrong_before = check.wrong;
            check.add(dd, row.integer);
            if check.wrong > wrong_before {
                wrong_seconds.insert(second);
            }
        }
    }
    Ok((check, wrong_seconds.len()))
}

/// Count, mean, standard deviation (`n - 1`) and RMS of one error axis.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct AxisStats {
    pub count: usize,
    pub mean: Option<f64>,
    pub std: Option<f64>,
    pub rms: Option<f64>,
}

impl AxisStats {
    pub fn of(values: &[f64]) -> Self {
        let s = ErrorStats::of(values);
        Self {
            count: s.count,
            mean: s.mean,
            std: s.std,
            rms: (!values.is_empty()).then(|| rms(values)),
        }
    }
}

/// N, E, D.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Ned<T> {
    pub n: T,
    pub e: T,
    pub d: T,
}

/// ECEF X, Y, Z.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Xyz<T> {
    pub x: T,
    pub y: T,
    pub z: T,
}

/// Yaw, pitch, roll.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Ypr<T> {
    pub yaw: T,
    pub pitch: T,
    pub roll: T,
}

impl<T> From<[T; 3]> for Ned<T> {
    fn from([n, e, d]: [T; 3]) -> Self {
        Self { n, e, d }
    }
}

impl<T> From<[T; 3]> for Xyz<T> {
    fn from([x, y, z]: [T; 3]) -> Self {
        Self { x, y, z }
    }
}

impl<T> From<[T; 3]> for Ypr<T> {
    fn from([yaw, pitch, roll]: [T; 3]) -> Self {
        Self { yaw, pitch, roll }
    }
}

impl<T> Ned<T> {
    pub fn axes(&self) -> [&T; 3] {
        [&self.n, &self.e, &self.d]
    }
}

impl<T> Ypr<T> {
    pub fn axes(&self) -> [&T; 3] {
        [&self.yaw, &self.pitch, &self.roll]
    }
}

/// One baseline's errors (m).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BaselineErrors {
    /// 1-based: antenna `baseline` (0-based, after the master) minus the master.
    pub baseline: usize,
    pub antenna: String,
    /// N, E, D in the master's local frame.
    pub ned_m: Ned<AxisStats>,
    /// ECEF X, Y, Z.
    pub ecef_m: Xyz<AxisStats>,
    /// Thesis table 5.4-4's std of this baseline (N, E, D), for the first two baselines.
    pub thesis_ned_std_m: Option<Ned<f64>>,
}

/// Integers checked against the truth.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct IntegerSummary {
    pub checked: usize,
    pub wrong: usize,
    pub largest_distance_cycles: f64,
}

/// What `skyforge validate attitude` prints and writes as JSON.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct AttitudeValidation {
    pub truth: String,
    pub observations: String,
    pub attitude: String,
    pub antennas: Vec<AntennaPosition>,
    /// Rows of `attitude.csv` (master epochs).
    pub epochs: usize,
    /// Seconds from the run's start to the first fixed epoch.
    pub first_fix_s: Option<f64>,
    pub epochs_from_first_fix: usize,
    pub fixed_epochs: usize,
    /// Fixed epochs over epochs from the first fix on (0 without a fix).
    pub fixed_fraction: f64,
    /// Fixed epochs with an attitude update.
    pub attitude_epochs: usize,
    pub integers: IntegerSummary,
    pub baselines: Vec<BaselineErrors>,
    /// Yaw, pitch, roll error (deg).
    pub attitude_deg: Ypr<AxisStats>,
    /// Thesis table 5.4-5's yaw, pitch, roll std (deg; real-time KF).
    pub thesis_attitude_std_deg: Ypr<f64>,
}

impl OutputsComparison {
    /// Statistics of the comparison.
    pub fn summary(&self) -> AttitudeValidation {
        let c = &self.chain;
        let axes = |f: &dyn Fn(usize) -> Vec<f64>| [0, 1, 2].map(|i| AxisStats::of(&f(i)));
        let baselines = self
            .antennas
            .iter()
            .skip(1)
            .enumerate()
            .map(|(k, a)| BaselineErrors {
                baseline: k + 1,
                antenna: a.name.clone(),
                ned_m: axes(&|i| c.baseline_axis(k, i, true)).into(),
                ecef_m: axes(&|i| c.baseline_axis(k, i, false)).into(),
                thesis_ned_std_m: thesis_ned_std_m(k).map(Ned::from),
            })
            .collect();
        AttitudeValidation {
            truth: self.truth_dir.display().to_string(),
            observations: self.observations_dir.display().to_string(),
            attitude: self.attitude_dir.display().to_string(),
            antennas: self.antennas.clone(),
            epochs: c.epochs,
            first_fix_s: c.first_fix_s,
            epochs_from_first_fix: c.after_first_fix,
            fixed_epochs: self.fixed_epochs,
            fixed_fraction: self.fixed_epochs as f64 / c.after_first_fix.max(1) as f64,
            attitude_epochs: c.attitude_axis(0).len(),
            integers: IntegerSummary {
                checked: c.integers_checked,
                wrong: c.integers_wrong,
                largest_distance_cycles: c.largest_integer_distance_cycles,
            },
            baselines,
            attitude_deg: axes(&|i| c.attitude_axis(i)).into(),
            thesis_attitude_std_deg: ATTITUDE_ROW.into(),
        }
    }
}

/// `value * scale` with `digits` decimals, or `-`.
fn cell(v: Option<f64>, scale: f64, digits: usize) -> String {
    v.map_or_else(|| "-".into(), |v| format!("{:.digits$}", v * scale))
}

/// The short table of `skyforge validate attitude`.
pub fn print_validation(v: &AttitudeValidation, out: &mut impl Write) -> std::io::Result<()> {
    writeln!(out, "truth:        {}", v.truth)?;
    writeln!(out, "observations: {}", v.observations)?;
    writeln!(out, "attitude:     {}", v.attitude)?;
    let names: Vec<String> = v
        .antennas
        .iter()
        .map(|a| {
            let [x, y, z] = a.true_body_m;
            format!("{} [{x:.4}, {y:.4}, {z:.4}]", a.name)
        })
        .collect();
    writeln!(
        out,
        "antennas (true body positions, m; master first): {}",
        names.join(", ")
    )?;
    let first = v.first_fix_s.map_or_else(
        || "none".to_string(),
        |t| format!("{t:.1} s after the start"),
    );
    writeln!(out, "epochs {}, first fix {first}", v.epochs)?;
    writeln!(
        out,
        "fixed {} of {} epochs from the first fix on ({:.1} %), attitude at {}",
        v.fixed_epochs,
        v.epochs_from_first_fix,
        100.0 * v.fixed_fraction,
        v.attitude_epochs
    )?;
    writeln!(
        out,
        "integers: {} checked against the truth, {} wrong (largest distance of an observed DD from the truth's integer {:.3} cycles)",
        v.integers.checked, v.integers.wrong, v.integers.largest_distance_cycles
    )?;
    writeln!(out)?;
    writeln!(
        out,
        "{:<22} {:>6} {:>9} {:>9} {:>9}   thesis std",
        "error", "count", "mean", "std", "rms"
    )?;
    for b in &v.baselines {
        for (i, axis) in ["N", "E", "D"].iter().enumerate() {
            let s = b.ned_m.axes()[i];
            let thesis = b.thesis_ned_std_m.map_or_else(
                || "-".to_string(),
                |t| format!("{:.3} (table 5.4-4)", t.axes()[i] * 1e3),
            );
            writeln!(
                out,
                "{:<22} {:>6} {:>9} {:>9} {:>9}   {thesis}",
                format!("b{} ({}) {axis} mm", b.baseline, b.antenna),
                s.count,
                cell(s.mean, 1e3, 3),
                cell(s.std, 1e3, 3),
                cell(s.rms, 1e3, 3),
            )?;
        }
    }
    for (i, axis) in ["yaw", "pitch", "roll"].iter().enumerate() {
        let s = v.attitude_deg.axes()[i];
        writeln!(
            out,
            "{:<22} {:>6} {:>9} {:>9} {:>9}   {:.4} (table 5.4-5, KF)",
            format!("{axis} deg"),
            s.count,
            cell(s.mean, 1.0, 4),
            cell(s.std, 1.0, 4),
            cell(s.rms, 1.0, 4),
            v.thesis_attitude_std_deg.axes()[i]
        )?;
    }
    writeln!(
        out,
        "thesis std: the thesis's real-time experiment (GPS L1, 1 Hz, KF; tables 5.4-4 and 5.4-5), for scale, not a bar"
    )?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_geometry_antenna_name_that_is_a_path_is_refused() {
        let dir = tempfile::tempdir().unwrap();
        let text = "[[antennas]]\nname = \"ant1\"\nposition_body_m = [0.0, 0.0, 0.0]\n\n[[antennas]]\nname = \"../../etc/ant2\"\nposition_body_m = [1.0, 0.0, 0.0]\n";
        std::fs::write(dir.path().join("geometry.toml"), text).unwrap();
        let d = dir.path();
        let e = compare_outputs(d, d, d).unwrap_err().to_string();
        assert!(
            e.contains("../../etc/ant2") && e.contains("geometry.toml"),
            "{e}"
        );
    }

    #[test]
    fn axis_stats_of_a_small_sample() {
        let s = AxisStats::of(&[1.0, -1.0, 3.0]);
        assert_eq!((s.count, s.mean), (3, Some(1.0)));
        assert_eq!(s.std, Some(2.0));
        assert!((s.rms.unwrap() - (11.0f64 / 3.0).sqrt()).abs() < 1e-15);
        let e = AxisStats::of(&[]);
        assert_eq!((e.count, e.mean, e.std, e.rms), (0, None, None, None));
    }

    #[test]
    fn platform_between_rows_is_interpolated() {
        let q0 = UnitQuaternion::identity();
        let q1 = UnitQuaternion::from_euler_angles(0.0, 0.0, 0.2);
        let p = PlatformTruth {
            start: Epoch::from_gpst_seconds(0.0),
            t_s: vec![0.0, 1.0],
            r_ecef_m: vec![Vec3::new(7e6, 0.0, 0.0), Vec3::new(7e6, 10.0, 0.0)],
            q_body_ecef: vec![q0, q1],
            antennas: Vec::new(),
            true_body_m: vec![Vec3::zeros()],
        };
        let (r, c) = p.at(0.5).unwrap();
        assert!((r.y - 5.0).abs() < 1e-9);
        let half = UnitQuaternion::from_euler_angles(0.0, 0.0, 0.1);
        assert!((c - half.to_rotation_matrix().into_inner()).norm() < 1e-12);
        assert_eq!(p.at(1.0).unwrap().0.y, 10.0);
        assert!(p.at(-0.1).is_none() && p.at(1.1).is_none());
    }
}
