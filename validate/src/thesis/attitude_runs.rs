//! The attitude tables' common part: runs on independent seeds
//! ([`seed_runs`](crate::attitude::seed_runs)) summarised as rows whose value is the mean
//! over runs of a per-run statistic.

use crate::attitude::ChainComparison;
use crate::observables::ErrorStats;
use crate::report::{Row, Verdict};
use crate::stats::{AcrossRuns, rms};
use crate::thesis::ValidateError;

/// Sample standard deviation (`n - 1`), or NaN with fewer than two values.
pub fn std(values: &[f64]) -> f64 {
    ErrorStats::of(values).std.unwrap_or(f64::NAN)
}

/// Mean, or NaN without values.
pub fn mean(values: &[f64]) -> f64 {
    ErrorStats::of(values).mean.unwrap_or(f64::NAN)
}

/// One error series per run, summarised three ways over the runs.
#[derive(Debug, Clone, Copy)]
pub struct SeriesStats {
    pub std: AcrossRuns,
    pub mean: AcrossRuns,
    pub rms: AcrossRuns,
}

impl SeriesStats {
    /// `series(run)` for every run; `None` when a run has fewer than two values.
    pub fn of(
        runs: &[ChainComparison],
        series: impl Fn(&ChainComparison) -> Vec<f64>,
    ) -> Option<Self> {
        let all: Vec<Vec<f64>> = runs.iter().map(series).collect();
        if all.iter().any(|v| v.len() < 2) {
            return None;
        }
        let per =
            |f: fn(&[f64]) -> f64| AcrossRuns::of(&all.iter().map(|v| f(v)).collect::<Vec<_>>());
        Some(Self {
            std: per(std)?,
            mean: per(mean)?,
            rms: per(rms)?,
        })
    }

    /// The note of a std row: the std over runs, the mean and RMS of the errors.
    pub fn note(&self, scale: f64, unit: &str, digits: usize) -> String {
        format!(
            "std {}; mean {}; RMS {} {unit}",
            self.std.describe(scale, digits),
            self.mean.describe(scale, digits),
            self.rms.describe(scale, digits)
        )
    }
}

/// [`SeriesStats::of`] of `scenario`'s runs, its failure as a table's error.
pub fn stats(
    scenario: &str,
    runs: &[ChainComparison],
    series: impl Fn(&ChainComparison) -> Vec<f64>,
) -> Result<SeriesStats, ValidateError> {
    SeriesStats::of(runs, series).ok_or_else(|| {
        ValidateError::Pipeline(format!("{scenario}: a run has fewer than two fixed epochs"))
    })
}

/// How the chain did over the runs: fix rate, first fix, integers against the truth.
pub fn chain_note(runs: &[ChainComparison]) -> String {
    let fixed: usize = runs.iter().map(|r| r.fixed.len()).sum();
    let after: usize = runs.iter().map(|r| r.after_first_fix).sum();
    let checked: usize = runs.iter().map(|r| r.integers_checked).sum();
    let wrong: usize = runs.iter().map(|r| r.integers_wrong).sum();
    let first = runs
        .iter()
        .filter_map(|r| r.first_fix_s)
        .fold(0.0f64, f64::max);
    let attitudes: usize = runs.iter().map(|r| r.attitude_axis(0).len()).sum();
    format!(
        "{} runs: {fixed} of {after} epochs fixed from the first fix on (first fix within {first:.0} s), {attitudes} attitude epochs, {checked} fixed integers checked against the truth, {wrong} wrong",
        runs.len()
    )
}

/// A std row: `ours` against `thesis` within a factor `factor` either way.
pub fn factor_row(
    table: &str,
    row: String,
    unit: &str,
    thesis: f64,
    ours: f64,
    factor: f64,
) -> Row {
    let ratio = ours / thesis;
    let ok = ratio >= 1.0 / factor && ratio <= factor;
    Row::measured(
        table,
        row,
        "std",
        unit,
        Some(thesis),
        ours,
        (format!("factor {factor}"), Verdict::from_ok(ok)),
    )
}

/// A row saying whether a quantity grew: `ours` (a ratio of stds) must exceed 1; the
/// thesis's own ratio beside it.
pub fn growth_row(table: &str, row: String, thesis: f64, ours: f64) -> Row {
    Row::measured(
        table,
        row,
        "ratio",
        "-",
        Some(thesis),
        ours,
        ("> 1 (grows)".into(), Verdict::from_ok(ours > 1.0)),
    )
}

/// [`crate::attitude::seed_runs`] with `N` configurations, its error as a table's.
pub fn seed_runs<const N: usize>(
    scenario: &skyforge_scenarios::Scenario,
    configs: [skyforge_navigation::relative::RelativeConfig; N],
    draw: crate::draw::Draw,
) -> Result<[Vec<ChainComparison>; N], ValidateError> {
    crate::attitude::seed_runs(scenario, &configs, draw)
        .map_err(ValidateError::Pipeline)?
        .try_into()
        .map_err(|_| {
            ValidateError::Pipeline(format!(
                "{}: one set of runs per configuration",
                scenario.name
            ))
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn factor_and_growth_verdicts() {
        let r = factor_row("T", "r".into(), "deg", 0.1, 0.159, 1.6);
        assert_eq!(r.verdict, Verdict::Reproduced);
        let r = factor_row("T", "r".into(), "deg", 0.1, 0.0620, 1.6);
        assert_eq!(r.verdict, Verdict::Deviates);
        assert_eq!(
            growth_row("T", "g".into(), 3.0, 0.9).verdict,
            Verdict::Deviates
        );
        assert_eq!(
            growth_row("T", "g".into(), 3.0, 1.2).verdict,
            Verdict::Reproduced
        );
        assert!(std(&[1.0]).is_nan());
        assert!((std(&[1.0, 3.0]) - 2f64.sqrt()).abs() < 1e-12);
    }
}
