//! The multivariate constrained integer least-squares problem of attitude determination
//! (Teunissen 2010, "Integer least-squares theory for the GNSS compass"; Giorgi,
//! Teunissen, Verhagen & Buist 2010, "Testing a new multivariate GNSS carrier phase
//! attitude determination method"): the integers `z` and rotation `R` minimising
//!
//! `C(z) = ||a_hat - z||^2_{Q_a} + min_R ||b(z) - vec(R B_0)||^2_{Q_b(z)}`,
//!
//! with `b(z)` the baselines given `z` (eq. 2.4-64) and `B_0` the known body geometry.
//! Solved by search and shrink (exactly, up to the rotation fit of a candidate whose
//! Gauss-Newton iteration does not converge, scored by an upper bound of its misfit): candidates are taken in increasing
//! `||a_hat - z||^2` (LAMBDA's enumeration), each scored with its rotation fit, until the
//! next candidate's ambiguity term alone exceeds the second-best score so far, so that no
//! unseen candidate can beat the best two. The loop, [`search_with_misfit`], takes the
//! misfit as a parameter and is shared with the baseline-length constraint of
//! [`super::length`].

use crate::ambiguity::{MAX_CANDIDATES, lambda};
use crate::attitude::frames::ned_baselines_from_ecef;
use crate::attitude::least_squares::misfit_upper_bound;
use crate::attitude::{AttitudeError, BodyGeometry};
use crate::baseline::{BaselineError, Conditioned, FloatBaselines};
use nalgebra::{DMatrix, DVector};
use skyforge_orbits::Vec3;

/// The best two candidates of the constrained problem.
#[derive(Debug, Clone, PartialEq)]
pub struct ConstrainedFix {
    /// Integers of the free ambiguities (in `Conditioned::free` order).
    pub integers: Vec<i64>,
    /// Its score `C(z)`.
    pub cost: f64,
    /// The second-best score, or a lower bound of it when candidates beyond the list
    /// could score lower (the list's last ambiguity term).
    pub second_cost: f64,
    /// Candidates scored.
    pub scored: usize,
    /// The best is proven: no candidate beyond the list can score lower.
    pub exhaustive: bool,
}

impl ConstrainedFix {
    /// Second-best over best score.
    pub fn ratio(&self) -> f64 {
        self.second_cost / self.cost
    }
}

/// Why the constrained search failed.
#[derive(Debug, thiserror::Error)]
pub enum ConstrainedError {
    #[error(transparent)]
    Baseline(#[from] BaselineError),
    #[error(transparent)]
    Ambiguity(#[from] crate::ambiguity::AmbiguityError),
    #[error(transparent)]
    Attitude(#[from] AttitudeError),
}

/// Gauss-Newton steps allowed per candidate: the right candidate's small-residual fit
/// converges in a few from the Wahba start; a wrong one's may not converge at all.
const MISFIT_ITERATIONS: usize = 10;

/// Score of the baselines `b` (vec, ECEF) against the geometry: the weighted misfit of
/// the best rotation (LS attitude in the master's NED frame; an upper bound of it where
/// the fit does not converge within [`MISFIT_ITERATIONS`], which can only raise a
/// candidate's score), or `None` when no rotation fits (degenerate).
fn rotation_misfit(
    b: &DVector<f64>,
    covariance: &DMatrix<f64>,
    geometry: &BodyGeometry,
    master_ecef_m: &Vec3,
) -> Option<f64> {
    let baselines: Vec<Vec3> = b
        .as_slice()
        .chunks_exact(3)
        .map(|c| Vec3::new(c[0], c[1], c[2]))
        .collect();
    let ned = ned_baselines_from_ecef(&baselines, covariance, master_ecef_m).ok()?;
    misfit_upper_bound(geometry, &ned, MISFIT_ITERATIONS).ok()
}

/// The constrained best and second-best integers of the free ambiguities `cond` of
/// `float` (the held ones, `held`, kept at their values); `accept_ratio` as in
/// [`search_with_misfit`].
pub fn search(
    float: &FloatBaselines,
    cond: &Conditioned,
    held: &[(usize, i64)],
    geometry: &BodyGeometry,
    master_ecef_m: &Vec3,
    accept_ratio: f64,
) -> Result<ConstrainedFix, ConstrainedError> {
    search_with_misfit(float, cond, held, accept_ratio, |b, covariance| {
        rotation_misfit(b, covariance, geometry, master_ecef_m)
    })
}

/// The search and shrink shared by the constraints ([`search`] here, the baseline lengths
/// of [`super::length::search`]): the best and second-best of
/// `C(z) = ||a_hat - z||^2_{Q_a} + misfit(b(z), Q_b)` over the free ambiguities `cond` of
/// `float` (the held ones, `held`, kept at their values). `misfit(b, q_b)` scores the
/// baselines `b(z)` of one candidate (vec, ECEF, eq. 2.4-64) given their covariance `q_b`
/// (eq. 2.4-65, the same for every candidate); it must be non-negative, and `None`
/// (nothing fits) skips the candidate.
///
/// The enumeration grows until the best two are proven, or until the best is proven and
/// the lower bound of the second-best score already reaches `accept_ratio` times it (the
/// ratio test's verdict is then decided: more candidates could only tighten the bound);
/// `f64::INFINITY` always proves both.
pub fn search_with_misfit<F>(
    float: &FloatBaselines,
    cond: &Conditioned,
    held: &[(usize, i64)],
    accept_ratio: f64,
    mut misfit: F,
) -> Result<ConstrainedFix, ConstrainedError>
where
    F: FnMut(&DVector<f64>, &DMatrix<f64>) -> Option<f64>,
{
    let (gain, covariance) = float.fix_gain()?;
    let a_hat = float.ambiguity_vector();
    let b_hat = float.baseline_vector();
    let mut full = a_hat.clone();
    for &(i, v) in held {
        full[i] = v as f64;
    }
    let mut count = 64.min(MAX_CANDIDATES);
    loop {
        let list = lambda(&cond.ambiguities, &cond.covariance, count)?;
        let mut best: Option<(f64, Vec<i64>)> = None;
        let mut second = f64::INFINITY;
        let mut scored = 0;
        // Every candidate not listed has an ambiguity term, and so a score, of at least
        // the last listed one's (infinite when the list holds every candidate).
        let unseen = if list.candidates.len() < count {
            f64::INFINITY
        } else {
            list.candidates
                .last()
                .map_or(f64::INFINITY, |c| c.squared_norm)
        };
        for c in &list.candidates {
            if c.squared_norm > second {
                break;
            }
            for (&i, &v) in cond.free.iter().zip(&c.integers) {
                full[i] = v as f64;
            }
            let b = &b_hat - &gain * (&a_hat - &full);
            scored += 1;
            let Some(fit) = misfit(&b, &covariance) else {
                continue;
            };
            let cost = c.squared_norm + fit;
            match &best {
                Some((b_cost, _)) if cost >= *b_cost => second = second.min(cost),
                _ => {
                    if let Some((b_cost, _)) = best.take() {
                        second = second.min(b_cost);
                    }
                    best = Some((cost, c.integers.clone()));
                }
            }
        }
        let Some((cost, integers)) = best else {
            return Err(
                AttitudeError::Singular("no candidate fits the body geometry".into()).into(),
            );
        };
        // A lower bound of the true second-best score.
        let second_bound = second.min(unseen);
        let proven = cost <= unseen && second <= unseen;
        let decided = cost <= unseen && second_bound >= accept_ratio * cost;
        let could_pass_with_more = second_bound < second && count < MAX_CANDIDATES;
        if !proven && !decided && could_pass_with_more {
            count = (count * 4).min(MAX_CANDIDATES);
            continue;
        }
        return Ok(ConstrainedFix {
            integers,
            cost,
            second_cost: second_bound,
            scored,
            exhaustive: cost <= unseen,
        });
    }
}
