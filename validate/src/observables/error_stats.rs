//! Count, mean and standard deviation of observation errors, and their serialisation.

use serde::{Serialize, Serializer};
use skyforge_orbits::ephemeris::SatId;
use std::fmt::Display;

/// Count, mean and standard deviation of a set of errors. `mean` is `None` where the
/// method removes it (an error with a per-epoch term has no identifiable overall mean);
/// `std` is `None` without degrees of freedom.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ErrorStats {
    pub count: usize,
    pub mean: Option<f64>,
    pub std: Option<f64>,
}

impl ErrorStats {
    /// Sample mean and standard deviation (`n - 1` in the denominator) of `values`.
    pub fn of(values: &[f64]) -> Self {
        let n = values.len();
        let mean = (n > 0).then(|| values.iter().sum::<f64>() / n as f64);
        let std = mean.filter(|_| n > 1).map(|m| {
            (values.iter().map(|v| (v - m) * (v - m)).sum::<f64>() / (n - 1) as f64).sqrt()
        });
        Self {
            count: n,
            mean,
            std,
        }
    }

    /// Pool independent sets: count-weighted mean of the means, and the pooled
    /// within-set standard deviation `sqrt(sum (n_i - 1) s_i^2 / sum (n_i - 1))` (each
    /// set's own mean removed).
    pub fn pooled(parts: &[ErrorStats]) -> Self {
        let count: usize = parts.iter().map(|p| p.count).sum();
        let with_mean: Vec<(usize, f64)> = parts
            .iter()
            .filter_map(|p| p.mean.map(|m| (p.count, m)))
            .collect();
        let n_mean: usize = with_mean.iter().map(|(n, _)| n).sum();
        let mean = (n_mean > 0)
            .then(|| with_mean.iter().map(|&(n, m)| n as f64 * m).sum::<f64>() / n_mean as f64);
        let (ss, dof) = parts
            .iter()
            .filter_map(|p| p.std.map(|s| (p.count.saturating_sub(1), s)))
            .fold((0.0, 0usize), |(ss, d), (n, s)| {
                (ss + n as f64 * s * s, d + n)
            });
        Self {
            count,
            mean,
            std: (dof > 0).then(|| (ss / dof as f64).sqrt()),
        }
    }
}

/// One satellite's error statistics.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SatErrors {
    #[serde(serialize_with = "display")]
    pub sat: SatId,
    #[serde(flatten)]
    pub stats: ErrorStats,
}

/// Serialise with `Display` (satellites as `G05`, epochs as `2023-03-12T00:00:00 GPST`).
pub(crate) fn display<T: Display, S: Serializer>(v: &T, s: S) -> Result<S::Ok, S::Error> {
    s.collect_str(v)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sample_and_pooled_statistics() {
        let a = ErrorStats::of(&[1.0, 2.0, 3.0]);
        assert_eq!((a.count, a.mean, a.std), (3, Some(2.0), Some(1.0)));
        let b = ErrorStats::of(&[10.0, 14.0]);
        assert_eq!(b.std, Some(8f64.sqrt()));
        let p = ErrorStats::pooled(&[a, b]);
        assert_eq!(p.count, 5);
        assert_eq!(p.mean, Some(6.0));
        // (2 * 1 + 1 * 8) / 3
        assert!((p.std.unwrap() - (10.0f64 / 3.0).sqrt()).abs() < 1e-15);
        let e = ErrorStats::of(&[]);
        assert_eq!((e.count, e.mean, e.std), (0, None, None));
        assert_eq!(ErrorStats::of(&[5.0]).std, None);
    }
}
