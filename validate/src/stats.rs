//! Small descriptive statistics.

use crate::observables::ErrorStats;

/// Minimum, maximum, mean and median of a sample.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Summary {
    pub min: f64,
    pub max: f64,
    pub mean: f64,
    pub median: f64,
    pub count: usize,
}

impl Summary {
    /// Summary of `values`; `None` when empty or when any value is NaN.
    pub fn of(values: &[f64]) -> Option<Self> {
        if values.is_empty() || values.iter().any(|v| v.is_nan()) {
            return None;
        }
        let mut sorted = values.to_vec();
        sorted.sort_by(f64::total_cmp);
        let n = sorted.len();
        let median = if n % 2 == 1 {
            sorted[n / 2]
        } else {
            0.5 * (sorted[n / 2 - 1] + sorted[n / 2])
        };
        Some(Self {
            min: sorted[0],
            max: sorted[n - 1],
            mean: sorted.iter().sum::<f64>() / n as f64,
            median,
            count: n,
        })
    }
}

/// One statistic measured on independent runs (one per seed): the mean over runs and its
/// standard error. Runs are independent where samples within a run are not (loop and
/// filter noise correlated over seconds, double differences sharing a reference), so the
/// spread between runs gives an honest standard error.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AcrossRuns {
    pub mean: f64,
    /// Standard deviation of the runs' values over `sqrt(runs)` (`None` for one run).
    pub standard_error: Option<f64>,
    pub min: f64,
    pub max: f64,
    pub runs: usize,
}

impl AcrossRuns {
    /// The runs' `values`; `None` when empty or when any is NaN.
    pub fn of(values: &[f64]) -> Option<Self> {
        let s = Summary::of(values)?;
        let n = values.len();
        let standard_error = ErrorStats::of(values).std.map(|sd| sd / (n as f64).sqrt());
        Some(Self {
            mean: s.mean,
            standard_error,
            min: s.min,
            max: s.max,
            runs: n,
        })
    }

    /// `mean +- se (min..max over n runs)`, values scaled by `scale` and printed with
    /// `digits` decimals.
    pub fn describe(&self, scale: f64, digits: usize) -> String {
        let se = self
            .standard_error
            .map_or(String::new(), |e| format!(" +- {:.digits$}", e * scale));
        format!(
            "{:.digits$}{se} ({:.digits$}..{:.digits$} over {} runs)",
            self.mean * scale,
            self.min * scale,
            self.max * scale,
            self.runs
        )
    }
}

/// The standard error of the mean of a correlated series by batch means: `values` as
/// (sample index, value), averaged over consecutive batches of `batch` indices
/// (`index / batch`), and `std(batch means) / sqrt(batches)`; `None` with fewer than two
/// batches. Batches several correlation times long are nearly independent, so this
/// respects correlation that `std / sqrt(n)` ignores.
pub fn batch_means_standard_error(
    values: impl IntoIterator<Item = (usize, f64)>,
    batch: usize,
) -> Option<f64> {
    let mut batches: std::collections::BTreeMap<usize, (f64, usize)> = Default::default();
    for (k, v) in values {
        let b = batches.entry(k / batch.max(1)).or_default();
        *b = (b.0 + v, b.1 + 1);
    }
    let means: Vec<f64> = batches.values().map(|&(s, n)| s / n as f64).collect();
    let std = crate::observables::ErrorStats::of(&means).std?;
    Some(std / (means.len() as f64).sqrt())
}

/// Root mean square of `values` (0 when empty).
pub fn rms(values: &[f64]) -> f64 {
    if values.is_empty() {
        return 0.0;
    }
    (values.iter().map(|v| v * v).sum::<f64>() / values.len() as f64).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn summary_of_a_small_sample() {
        let s = Summary::of(&[3.0, 1.0, 2.0, 10.0]).unwrap();
        assert_eq!((s.min, s.max, s.count), (1.0, 10.0, 4));
        assert_eq!(s.mean, 4.0);
        assert_eq!(s.median, 2.5);
        assert!(Summary::of(&[]).is_none());
        assert!(Summary::of(&[1.0, f64::NAN]).is_none());
    }

    #[test]
    fn across_runs_standard_error_is_the_spread_over_root_n() {
        let a = AcrossRuns::of(&[1.0, 3.0, 2.0, 2.0]).unwrap();
        assert_eq!((a.mean, a.min, a.max, a.runs), (2.0, 1.0, 3.0, 4));
        let sd = (2.0f64 / 3.0).sqrt();
        assert!((a.standard_error.unwrap() - sd / 2.0).abs() < 1e-12);
        assert!(AcrossRuns::of(&[5.0]).unwrap().standard_error.is_none());
        assert_eq!(rms(&[3.0, -4.0]), (12.5f64).sqrt());
    }
}
