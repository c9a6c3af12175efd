//! Which integers an epoch fixes: those held from earlier epochs (while they still fit the
//! float solution), then LAMBDA on the rest conditioned on them (thesis 2.4.6), accepted by
//! the ratio test and the bootstrapped success rate; otherwise the largest reliable subset
//! of decorrelated combinations (partial fixing), or none.

use super::search::{ConstrainedSearch, Searched};
use super::{RelativeConfig, RelativeError};
use crate::ambiguity::{lambda, partial};
use crate::baseline::{AmbiguityHold, FixedBaselines, FloatBaselines};
use crate::pvt::raim::test_threshold;
use nalgebra::DMatrix;
use skyforge_orbits::Vec3;

/// How far an epoch's ambiguities were resolved.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum AmbiguityStatus {
    /// No integer fixed.
    Float,
    /// `combinations` integer combinations fixed, not all ambiguities.
    Partial { combinations: usize },
    /// Every ambiguity fixed.
    Fixed,
}

/// What decided an epoch's integers.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FixMethod {
    /// Nothing fixed.
    None = 0,
    /// Every ambiguity held from earlier epochs.
    Held = 1,
    /// LAMBDA's ratio test and success-rate floor on the free ambiguities.
    Lambda = 2,
    /// The search under the body geometry ([`super::search::multivariate`]).
    Geometry = 3,
    /// The search under the baselines' lengths ([`super::search::length`]).
    Length = 4,
    /// The reliable decorrelated combinations only (partial fixing), besides any held.
    Partial = 5,
}

impl FixMethod {
    /// Every method, in the order of their codes (`method as u8`).
    pub const ALL: [FixMethod; 6] = [
        FixMethod::None,
        FixMethod::Held,
        FixMethod::Lambda,
        FixMethod::Geometry,
        FixMethod::Length,
        FixMethod::Partial,
    ];

    /// The word the outputs write.
    pub fn name(self) -> &'static str {
        match self {
            FixMethod::None => "none",
            FixMethod::Held => "held",
            FixMethod::Lambda => "lambda",
            FixMethod::Geometry => "geometry",
            FixMethod::Length => "length",
            FixMethod::Partial => "partial",
        }
    }
}

impl std::str::FromStr for FixMethod {
    type Err = ();
    fn from_str(s: &str) -> Result<Self, ()> {
        FixMethod::ALL.into_iter().find(|m| m.name() == s).ok_or(())
    }
}

/// The integers of one epoch.
#[derive(Debug, Clone, PartialEq)]
pub struct Resolution {
    pub status: AmbiguityStatus,
    /// What decided them.
    pub method: FixMethod,
    /// Why the configured constrained search did not decide, when it could not run or
    /// failed and LAMBDA decided instead (the search's error).
    pub fallback: Option<String>,
    /// Second-best over best score of the search on the free ambiguities: squared norms
    /// (LAMBDA), or constrained scores under the body geometry or the baseline lengths.
    pub ratio: Option<f64>,
    /// Bootstrapped success rate of the free (decorrelated) problem; 1 when none was free.
    pub success_rate: f64,
    /// Ambiguities taken from the hold.
    pub held: usize,
    /// vec(N) (baseline 1's first): the integer where every ambiguity is fixed.
    pub integers: Vec<Option<i64>>,
    /// The fixed integer combinations `Z^T vec(N)` (rows) and their values.
    combinations: (DMatrix<f64>, Vec<i64>),
}

impl Resolution {
    /// The baselines given the fixed combinations (`None` when nothing is fixed).
    pub fn fixed_baselines(
        &self,
        float: &FloatBaselines,
    ) -> Result<Option<FixedBaselines>, RelativeError> {
        let (z_t, values) = &self.combinations;
        if values.is_empty() {
            return Ok(None);
        }
        Ok(Some(float.fix_combinations(z_t, values)?))
    }
}

/// Unit rows of vec(N) for `indices`.
fn unit_rows(indices: &[usize], nm: usize) -> DMatrix<f64> {
    DMatrix::from_fn(indices.len(), nm, |r, c| {
        f64::from(u8::from(indices[r] == c))
    })
}

/// Resolve the ambiguities of `float`, using and updating `hold`. The free ambiguities are
/// searched by `search` too ([`super::search`]: under the body geometry or the baselines'
/// lengths, the master at `master_ecef_m`); its result is accepted when the search is
/// exhaustive and the ratio of its two best scores reaches `config.ratio_threshold`.
/// Without one, LAMBDA's ratio test and success-rate floor decide.
pub fn resolve(
    float: &FloatBaselines,
    hold: &mut AmbiguityHold,
    config: &RelativeConfig,
    search: &dyn ConstrainedSearch,
    master_ecef_m: &Vec3,
) -> Result<Resolution, RelativeError> {
    let layout = &float.model.layout;
    let m = float.model.baseline_count();
    let nm = float.ambiguities.len();
    let mut held: Vec<(usize, i64)> = if config.hold {
        hold.lookup(layout, m)
            .into_iter()
            .enumerate()
            .filter_map(|(i, v)| Some((i, v?)))
            .collect()
    } else {
        Vec::new()
    };
    let mut cond = float.conditioned(&held)?;
    if !held.is_empty() && cond.held_statistic > test_threshold(held.len(), config.hold_test_pfa) {
        hold.clear();
        held.clear();
        cond = float.conditioned(&held)?;
    }
    let mut integers: Vec<Option<i64>> = vec![None; nm];
    for &(i, v) in &held {
        integers[i] = Some(v);
    }
    let held_indices: Vec<usize> = held.iter().map(|(i, _)| *i).collect();
    let held_values: Vec<i64> = held.iter().map(|(_, v)| *v).collect();
    if cond.free.is_empty() {
        return Ok(Resolution {
            status: AmbiguityStatus::Fixed,
            method: FixMethod::Held,
            fallback: None,
            ratio: None,
            success_rate: 1.0,
            held: held.len(),
            combinations: (unit_rows(&held_indices, nm), held_values),
            integers,
        });
    }
    let plain = lambda(&cond.ambiguities, &cond.covariance, 2)?;
    let (geometric, fallback) =
        match search.search(float, &cond, &held, master_ecef_m, config.ratio_threshold) {
            Searched::Found(fix) => (Some(fix), None),
            Searched::NotConfigured => (None, None),
            Searched::Fallback(why) => (None, Some(why)),
        };
    let (ratio, success_rate, accepted, best, method) = match &geometric {
        Some(g) => (
            Some(g.ratio()),
            plain.success_rate,
            g.exhaustive && g.ratio() >= config.ratio_threshold,
            g.integers.clone(),
            search.method(),
        ),
        None => {
            let ratio = plain.ratio();
            let ok = ratio.is_some_and(|r| r >= config.ratio_threshold)
                && plain.success_rate >= config.min_success_rate;
            let best = plain.best().integers.clone();
            (ratio, plain.success_rate, ok, best, FixMethod::Lambda)
        }
    };
    if accepted {
        for (&i, &v) in cond.free.iter().zip(&best) {
            integers[i] = Some(v);
        }
        if config.hold {
            hold.store(layout, m, &integers);
        }
        let all: Vec<i64> = integers.iter().map(|v| v.unwrap_or(0)).collect();
        return Ok(Resolution {
            status: AmbiguityStatus::Fixed,
            method,
            fallback,
            ratio,
            success_rate,
            held: held.len(),
            combinations: (DMatrix::identity(nm, nm), all),
            integers,
        });
    }
    // Partial: the held integers plus the reliable decorrelated combinations of the rest.
    let part = partial(&cond.ambiguities, &cond.covariance, config.min_success_rate)?;
    let k = part.fixed_count();
    let mut z_t = DMatrix::zeros(held.len() + k, nm);
    z_t.view_mut((0, 0), (held.len(), nm))
        .copy_from(&unit_rows(&held_indices, nm));
    for j in 0..k {
        for (f, &i) in cond.free.iter().enumerate() {
            z_t[(held.len() + j, i)] = part.z_f[(f, j)];
        }
    }
    let values: Vec<i64> = held_values.into_iter().chain(part.integers).collect();
    let (status, method) = if values.is_empty() {
        (AmbiguityStatus::Float, FixMethod::None)
    } else {
        let combinations = values.len();
        (
            AmbiguityStatus::Partial { combinations },
            FixMethod::Partial,
        )
    };
    Ok(Resolution {
        status,
        method,
        fallback,
        ratio,
        success_rate,
        held: held.len(),
        combinations: (z_t, values),
        integers,
    })
}
