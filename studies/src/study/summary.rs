//! What a study keeps of each metric at each grid point: over the point's runs (each an
//! independent seed), the mean with its 95 % confidence interval (normal, from the
//! standard error over runs), the standard deviation, and the median and 95th percentile
//! with distribution-free 95 % intervals from order statistics (the ranks a binomial
//! count of values below the quantile reaches with 95 % probability, normal
//! approximation). Runs without a value (NaN) are counted apart.

/// The normal quantile of a two-sided 95 % interval.
const Z95: f64 = 1.959_963_984_540_054;

/// One metric at one grid point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MetricSummary {
    /// Runs with a value.
    pub n: usize,
    /// Runs without one (NaN).
    pub missing: usize,
    pub mean: f64,
    pub mean_ci: (f64, f64),
    /// Sample standard deviation over runs (NaN for fewer than two).
    pub std: f64,
    pub p50: f64,
    pub p50_ci: (f64, f64),
    pub p95: f64,
    pub p95_ci: (f64, f64),
}

impl MetricSummary {
    /// The summary of `values` (one per run, NaN where a run has none).
    pub fn of(values: &[f64]) -> Self {
        let mut sorted: Vec<f64> = values.iter().copied().filter(|v| !v.is_nan()).collect();
        sorted.sort_by(f64::total_cmp);
        let n = sorted.len();
        let nan = f64::NAN;
        let mean = if n == 0 {
            nan
        } else {
            sorted.iter().sum::<f64>() / n as f64
        };
        let std = if n < 2 {
            nan
        } else {
            (sorted.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1) as f64).sqrt()
        };
        let half = Z95 * std / (n as f64).sqrt();
        Self {
            n,
            missing: values.len() - n,
            mean,
            mean_ci: (mean - half, mean + half),
            std,
            p50: quantile(&sorted, 0.5),
            p50_ci: quantile_ci(&sorted, 0.5),
            p95: quantile(&sorted, 0.95),
            p95_ci: quantile_ci(&sorted, 0.95),
        }
    }
}

/// Quantile `q` of ascending `sorted` (linear between order statistics, Hyndman & Fan
/// type 7); NaN when empty.
pub fn quantile(sorted: &[f64], q: f64) -> f64 {
    match sorted.len() {
        0 => f64::NAN,
        n => {
            let h = (n - 1) as f64 * q;
            let (lo, frac) = (h.floor() as usize, h - h.floor());
            let hi = (lo + 1).min(n - 1);
            sorted[lo] + frac * (sorted[hi] - sorted[lo])
        }
    }
}

/// The order statistics bounding quantile `q` of `sorted` with about 95 % confidence:
/// ranks `n q -+ z sqrt(n q (1 - q))`, widened to whole ranks and clamped to the sample
/// (so with few runs the interval is the sample's range: it cannot claim more).
pub fn quantile_ci(sorted: &[f64], q: f64) -> (f64, f64) {
    let n = sorted.len();
    if n == 0 {
        return (f64::NAN, f64::NAN);
    }
    let centre = n as f64 * q;
    let spread = Z95 * (n as f64 * q * (1.0 - q)).sqrt();
    let lo = (centre - spread).floor().max(1.0) as usize;
    let hi = ((centre + spread).ceil() + 1.0).min(n as f64) as usize;
    (sorted[lo - 1], sorted[hi - 1])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quantiles_interpolate_between_order_statistics() {
        let v = [1.0, 2.0, 3.0, 4.0, 5.0];
        assert_eq!(quantile(&v, 0.5), 3.0);
        assert_eq!(quantile(&v, 0.0), 1.0);
        assert_eq!(quantile(&v, 1.0), 5.0);
        assert!((quantile(&v, 0.95) - 4.8).abs() < 1e-12);
        assert!(quantile(&[], 0.5).is_nan());
    }

    #[test]
    fn the_median_interval_covers_the_true_median_about_95_percent_of_the_time() {
        // Oracle: uniform samples of 50 (true median 0.5), coverage over many draws.
        use rand::{Rng, SeedableRng};
        let mut rng = rand_chacha::ChaCha20Rng::seed_from_u64(7);
        let trials = 4000;
        let mut covered = 0;
        for _ in 0..trials {
            let mut v: Vec<f64> = (0..50).map(|_| rng.random::<f64>()).collect();
            v.sort_by(f64::total_cmp);
            let (lo, hi) = quantile_ci(&v, 0.5);
            covered += usize::from(lo <= 0.5 && 0.5 <= hi);
        }
        let rate = covered as f64 / trials as f64;
        assert!((0.93..0.99).contains(&rate), "coverage {rate}");
    }

    #[test]
    fn a_summary_leaves_out_and_counts_runs_without_a_value() {
        let s = MetricSummary::of(&[1.0, f64::NAN, 3.0]);
        assert_eq!((s.n, s.missing), (2, 1));
        assert_eq!(s.mean, 2.0);
        assert!((s.std - 2f64.sqrt()).abs() < 1e-12);
        assert!(s.mean_ci.0 < 2.0 && s.mean_ci.1 > 2.0);
        let empty = MetricSummary::of(&[f64::NAN]);
        assert!(empty.mean.is_nan() && empty.p50.is_nan() && empty.n == 0);
    }
}
