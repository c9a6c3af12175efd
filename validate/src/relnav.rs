//! `skyforge validate relnav`: `skyforge relnav`'s estimates (`relnav.csv`) against the
//! run's relative truth (`relative.csv`), both in the target's orbit frame: per axis the
//! RMS and the largest absolute error, and the 3-D RMS, of position and velocity, from a
//! settling time on. Estimates with an Earth-fixed baseline (mode `double-difference`)
//! are also compared as such, free of the frame's orientation, with the fraction of
//! their ambiguities fixed ([`crate::relnav_baseline`]).

use crate::relnav_baseline::{FixedFraction, compare_baselines};
use crate::stats::rms;
use serde::Serialize;
use skyforge_formats::FormatError;
use skyforge_formats::relative::{RelativeRow, read_relative_csv};
use skyforge_orbits::Vec3;
use std::path::Path;

/// One quantity's errors per axis (x along-track, y negative orbit normal, z nadir).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct AxisErrors {
    pub rms: [f64; 3],
    pub max_abs: [f64; 3],
    pub rms_3d: f64,
}

impl AxisErrors {
    fn of(errors: &[Vec3]) -> Self {
        let axis = |i: usize| -> Vec<f64> { errors.iter().map(|e| e[i]).collect() };
        Self {
            rms: std::array::from_fn(|i| rms(&axis(i))),
            max_abs: std::array::from_fn(|i| axis(i).iter().fold(0.0, |m, x| x.abs().max(m))),
            rms_3d: rms(&errors.iter().map(|e| e.norm()).collect::<Vec<_>>()),
        }
    }
}

/// The Earth-fixed baselines against the truth (`relnav_baseline`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BaselineComparison {
    /// Estimates with a baseline compared.
    pub compared: usize,
    /// Their errors in the target's true orbit frame (m).
    pub position_m: AxisErrors,
    /// The double-difference ambiguities fixed over them.
    pub ambiguities: Option<FixedFraction>,
}

/// What `validate relnav` measured.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RelnavComparison {
    pub vehicle: String,
    pub target: String,
    /// Estimates in the file, and those compared (from `settle_s` on, inside the truth).
    pub estimates: usize,
    pub compared: usize,
    pub settle_s: f64,
    pub position_m: AxisErrors,
    pub velocity_mps: AxisErrors,
    /// The Earth-fixed baselines' errors in the target's true frame and the ambiguities
    /// fixed, where the estimates carry them.
    pub baseline: Option<BaselineComparison>,
    /// Each compared estimate's time (s since the first estimate) and position and
    /// velocity errors, for plots and the book's transients.
    #[serde(skip)]
    pub series: Vec<(f64, Vec3, Vec3)>,
}

/// The truth rows of `vehicle` relative to `target`, linearly interpolated at `time`
/// (inside their span; rows in time order).
fn truth_at(rows: &[&RelativeRow], time: hifitime::Epoch) -> Option<(Vec3, Vec3)> {
    let k = rows.partition_point(|r| r.time <= time);
    let a = rows.get(k.checked_sub(1)?)?;
    let Some(b) = rows.get(k) else {
        // At (within a millisecond of) the last row, or past the truth.
        return ((time - a.time).to_seconds() < 1e-3).then_some((a.position_m, a.velocity_mps));
    };
    let span = (b.time - a.time).to_seconds();
    let f = if span > 0.0 {
        (time - a.time).to_seconds() / span
    } else {
        0.0
    };
    if !(0.0..=1.0).contains(&f) {
        return None;
    }
    let lerp = |x: Vec3, y: Vec3| x + (y - x) * f;
    Some((
        lerp(a.position_m, b.position_m),
        lerp(a.velocity_mps, b.velocity_mps),
    ))
}

/// Compare the estimates at `relnav_csv` with the truth at `truth_csv` from `settle_s`
/// seconds after the first estimate on.
pub fn compare_relnav(
    truth_csv: &Path,
    relnav_csv: &Path,
    settle_s: f64,
) -> Result<RelnavComparison, FormatError> {
    let truth = read_relative_csv(truth_csv)?;
    let estimates = read_relative_csv(relnav_csv)?;
    let Some(first) = estimates.first() else {
        return Err(FormatError::file(relnav_csv, "no estimates"));
    };
    let (vehicle, target) = (first.vehicle.clone(), first.target.clone());
    let rows: Vec<&RelativeRow> = (truth.iter())
        .filter(|r| r.vehicle == vehicle && r.target == target)
        .collect();
    if rows.is_empty() {
        let pairs: std::collections::BTreeSet<String> = (truth.iter())
            .map(|r| format!("{} relative to {}", r.vehicle, r.target))
            .collect();
        return Err(FormatError::file(
            truth_csv,
            format!(
                "no truth of {vehicle} relative to {target} (the estimates'); it has: {}",
                pairs.into_iter().collect::<Vec<_>>().join(", ")
            ),
        ));
    }
    let mut series = Vec::new();
    for e in &estimates {
        let t = (e.time - first.time).to_seconds();
        if t < settle_s {
            continue;
        }
        if let Some((p, v)) = truth_at(&rows, e.time) {
            series.push((t, e.position_m - p, e.velocity_mps - v));
        }
    }
    if series.is_empty() {
        return Err(FormatError::file(
            relnav_csv,
            format!("no estimate from {settle_s} s on inside the truth's span"),
        ));
    }
    let truth_dir = truth_csv.parent().unwrap_or(Path::new("."));
    let baseline =
        compare_baselines(truth_dir, &estimates, settle_s)?.map(|b| BaselineComparison {
            compared: b.errors.len(),
            position_m: AxisErrors::of(&b.errors),
            ambiguities: b.ambiguities,
        });
    let dp: Vec<Vec3> = series.iter().map(|s| s.1).collect();
    let dv: Vec<Vec3> = series.iter().map(|s| s.2).collect();
    Ok(RelnavComparison {
        vehicle,
        target,
        estimates: estimates.len(),
        compared: series.len(),
        settle_s,
        position_m: AxisErrors::of(&dp),
        velocity_mps: AxisErrors::of(&dv),
        baseline,
        series,
    })
}

/// The comparison as a table.
pub fn print_relnav(c: &RelnavComparison, out: &mut impl std::io::Write) -> std::io::Result<()> {
    writeln!(
        out,
        "relative   {} relative to {}: {} estimates, {} compared (from {} s)",
        c.vehicle, c.target, c.estimates, c.compared, c.settle_s
    )?;
    writeln!(
        out,
        "{:<24}{:>12}{:>12}{:>12}{:>12}",
        "error (target frame)", "x along", "y -normal", "z nadir", "3-D"
    )?;
    for (name, a, d) in [
        ("position RMS (m)", &c.position_m, 3),
        ("velocity RMS (m/s)", &c.velocity_mps, 5),
    ] {
        writeln!(
            out,
            "{name:<24}{:>12.d$}{:>12.d$}{:>12.d$}{:>12.d$}",
            a.rms[0], a.rms[1], a.rms[2], a.rms_3d
        )?;
        let max = name.replace("RMS", "max |e|");
        writeln!(
            out,
            "{max:<24}{:>12.d$}{:>12.d$}{:>12.d$}",
            a.max_abs[0], a.max_abs[1], a.max_abs[2]
        )?;
    }
    if let Some(b) = &c.baseline {
        let a = &b.position_m;
        writeln!(
            out,
            "{:<24}{:>12.5}{:>12.5}{:>12.5}{:>12.5}",
            "baseline RMS (m)", a.rms[0], a.rms[1], a.rms[2], a.rms_3d
        )?;
        writeln!(
            out,
            "{:<24}{:>12.5}{:>12.5}{:>12.5}   ({} estimates; Earth-fixed, in the true frame)",
            "baseline max |e| (m)", a.max_abs[0], a.max_abs[1], a.max_abs[2], b.compared
        )?;
        if let Some(f) = &b.ambiguities {
            writeln!(
                out,
                "integers   {} of {} double-difference ambiguities fixed ({:.1} %)",
                f.fixed,
                f.fixed + f.float,
                100.0 * f.fraction
            )?;
        }
    }
    Ok(())
}
