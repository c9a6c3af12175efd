//! The multivariate constrained integer least-squares problem of attitude determination
//! (Teunissen 2010, "Integer least-squares theory for the GNSS compass"; Giorgi,
//! Teunissen, Verhagen & Buist 2010, "Testing a new multivariate GNSS carrier phase
//! attitude determination method"): the integers `z` and rotation `R` minimising
//!
//! `C(z) = ||a_hat - z||^2_{Q_a} + min_R ||b(z) - vec(R B_0)||^2_{Q_b(z)}`,
//!
//! with `b(z)` the baselines given `z` (eq. 2.4-64) and `B_0` the known body geometry.
//! Solved by search and shrink (exactly, up to the rotation fit of a candidate whose
//! Gauss-Newton iteration does not converge, scored by an upper bound of its misfit):
//! candidates are taken in increasing `||a_hat - z||^2` (LAMBDA's enumeration), each
//! scored with its rotation fit, until the next candidate's ambiguity term alone exceeds
//! the second-best score so far, so that no unseen candidate can beat the best two. A
//! candidate whose ambiguity term plus a cheap lower bound of its misfit
//! ([`MisfitFloor`]) reaches that score cannot change the best two and is not fitted. The
//! loop, [`search_with_misfit`], takes the misfit as a parameter and is shared with the
//! baseline-length constraint of [`super::length`].

use super::{ConstrainedSearch, Searched};
use crate::ambiguity::{MAX_CANDIDATES, Nearest};
use crate::attitude::frames::{baselines_to_frame, ned_frame};
use crate::attitude::least_squares::{misfit_upper_bound_with, weight_factor};
use crate::attitude::{AttitudeError, BodyGeometry, NedBaselines};
use crate::baseline::{BaselineError, Conditioned, FloatBaselines};
use crate::relative::resolve::FixMethod;
use nalgebra::{Cholesky, DMatrix, DVector, Dyn};
use skyforge_orbits::{Mat3, Vec3};

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
    /// Candidates fitted (those the misfit floor could not rule out).
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

/// A constraint's score of one candidate's baselines `b` (vec, ECEF, eq. 2.4-64), built
/// once per search from their covariance `Q_b` (eq. 2.4-65, the same for every
/// candidate): non-negative, `None` when nothing fits (the candidate is skipped).
pub trait CandidateMisfit {
    fn misfit(&self, b: &DVector<f64>) -> Option<f64>;
}

/// The rotation fit of one search's candidates: the master's NED frame, and the NED
/// covariance with its Cholesky factor, the same for every candidate (formed once; they
/// were formed per candidate, with the same numbers).
struct RotationFit<'a> {
    geometry: &'a BodyGeometry,
    /// ECEF -> NED at the master.
    frame: Mat3,
    /// Zero baselines with the NED covariance.
    template: NedBaselines,
    factor: Cholesky<f64, Dyn>,
}

impl<'a> RotationFit<'a> {
    /// `None` when the master has no geodetic frame or the covariance is unusable.
    fn new(
        covariance: &DMatrix<f64>,
        geometry: &'a BodyGeometry,
        master_ecef_m: &Vec3,
    ) -> Option<Self> {
        let zeros = vec![Vec3::zeros(); covariance.nrows() / 3];
        let frame = ned_frame(master_ecef_m).ok()?;
        let template = baselines_to_frame(&zeros, covariance, &frame).ok()?;
        let factor = weight_factor(geometry, &template).ok()?;
        Some(Self {
            geometry,
            frame,
            template,
            factor,
        })
    }
}

impl CandidateMisfit for RotationFit<'_> {
    /// Score of the baselines `b` (vec, ECEF) against the geometry: the weighted misfit of
    /// the best rotation (LS attitude in the master's NED frame; an upper bound of it where
    /// the fit does not converge within [`MISFIT_ITERATIONS`], which can only raise a
    /// candidate's score), or `None` when no rotation fits (degenerate).
    fn misfit(&self, b: &DVector<f64>) -> Option<f64> {
        let baselines: Vec<Vec3> = b
            .as_slice()
            .chunks_exact(3)
            .map(|c| self.frame * Vec3::new(c[0], c[1], c[2]))
            .collect();
        let ned = self.template.with_baselines(&baselines).ok()?;
        misfit_upper_bound_with(self.geometry, &ned, &self.factor, MISFIT_ITERATIONS).ok()
    }
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
    search_with_misfit(float, cond, held, geometry, accept_ratio, |covariance| {
        RotationFit::new(covariance, geometry, master_ecef_m)
    })
}

/// A lower bound of both constraints' misfits, cheap enough to try before a fit:
/// `sum_k (||b_k|| - l_k)^2 / lambda_max(Q_b)`. A misfit is `r^T Q^-1 r >= ||r||^2 /
/// lambda_max` with `r` the baselines' residual to a point `(b'_k)` with `||b'_k|| = l_k`
/// (the rotated body geometry, or each baseline's sphere; for a sphere's 3 x 3 block of
/// `Q_b` its largest eigenvalue is at most `Q_b`'s), and `||b_k - b'_k|| >= | ||b_k|| -
/// l_k |` by the triangle inequality. A candidate whose ambiguity term plus this bound
/// reaches the second-best score cannot change the best two, and is not fitted.
struct MisfitFloor {
    lengths_m: Vec<f64>,
    /// `1 / lambda_max(Q_b)`, slightly lowered against rounding; 0 (no bound) when the
    /// eigenvalue is not positive and finite.
    inverse_largest_variance: f64,
}

impl MisfitFloor {
    fn new(geometry: &BodyGeometry, covariance: &DMatrix<f64>) -> Self {
        let largest = covariance
            .clone()
            .symmetric_eigenvalues()
            .iter()
            .copied()
            .fold(f64::NEG_INFINITY, f64::max);
        let inverse_largest_variance = if largest.is_finite() && largest > 0.0 {
            (1.0 - 1e-9) / largest
        } else {
            0.0
        };
        Self {
            lengths_m: geometry.lengths_m(),
            inverse_largest_variance,
        }
    }

    /// The bound for the baselines `b` (vec, one 3-vector per baseline).
    fn of(&self, b: &DVector<f64>) -> f64 {
        let squared: f64 = b
            .as_slice()
            .chunks_exact(3)
            .zip(&self.lengths_m)
            .map(|(c, l)| (Vec3::new(c[0], c[1], c[2]).norm() - l).powi(2))
            .sum();
        squared * self.inverse_largest_variance
    }
}

/// The baselines `b(z) = b_hat - G (a_hat - a(z))` of the candidates (eq. 2.4-64) as
/// `c + G_free z`, with the held ambiguities' part in `c`: one product per candidate, no
/// allocation.
struct CandidateBaselines {
    constant: Vec<f64>,
    /// `G`'s columns of the free ambiguities.
    free_gain: DMatrix<f64>,
}

impl CandidateBaselines {
    fn new(
        float: &FloatBaselines,
        gain: &DMatrix<f64>,
        cond: &Conditioned,
        held: &[(usize, i64)],
    ) -> Self {
        // a_hat - a(z) with the free ambiguities at zero; any other keeps its float value.
        let a_hat = float.ambiguity_vector();
        let mut offset = DVector::zeros(a_hat.len());
        for &(i, v) in held {
            offset[i] = a_hat[i] - v as f64;
        }
        for &i in &cond.free {
            offset[i] = a_hat[i];
        }
        let constant = float.baseline_vector() - gain * offset;
        Self {
            constant: constant.as_slice().to_vec(),
            free_gain: gain.select_columns(&cond.free),
        }
    }

    /// `b(z)` into `out` for the free ambiguities' `integers`.
    fn write(&self, integers: &[i64], out: &mut [f64]) {
        out.copy_from_slice(&self.constant);
        for (column, &v) in self.free_gain.column_iter().zip(integers) {
            let v = v as f64;
            for (o, g) in out.iter_mut().zip(column.iter()) {
                *o += g * v;
            }
        }
    }
}

/// The failure of a search in which no candidate fits.
fn nothing_fits() -> ConstrainedError {
    AttitudeError::Singular("no candidate fits the body geometry".into()).into()
}

/// Candidates listed first; the longest list ([`MAX_CANDIDATES`]) follows when these do
/// not settle the search.
const SHORT_LIST: usize = 64;

/// The search and shrink shared by the constraints ([`search`] here, the baseline lengths
/// of [`super::length::search`]): the best and second-best of
/// `C(z) = ||a_hat - z||^2_{Q_a} + misfit(b(z), Q_b)` over the free ambiguities `cond` of
/// `float` (the held ones, `held`, kept at their values), for the body `geometry`.
/// `misfit_for(q_b)` builds the constraint's score ([`CandidateMisfit`]) from the
/// candidates' covariance; `None` (unusable) fails the search as one where nothing fits.
///
/// The enumeration grows until the best two are proven, or until the best is proven and
/// the lower bound of the second-best score already reaches `accept_ratio` times it (the
/// ratio test's verdict is then decided: more candidates could only tighten the bound);
/// `f64::INFINITY` always proves both.
pub fn search_with_misfit<F, M>(
    float: &FloatBaselines,
    cond: &Conditioned,
    held: &[(usize, i64)],
    geometry: &BodyGeometry,
    accept_ratio: f64,
    misfit_for: F,
) -> Result<ConstrainedFix, ConstrainedError>
where
    F: FnOnce(&DMatrix<f64>) -> Option<M>,
    M: CandidateMisfit,
{
    let (gain, covariance) = float.fix_gain()?;
    let Some(score) = misfit_for(&covariance) else {
        return Err(nothing_fits());
    };
    let floor = MisfitFloor::new(geometry, &covariance);
    let baselines = CandidateBaselines::new(float, &gain, cond, held);
    let mut b = DVector::zeros(gain.nrows());
    let nearest = Nearest::new(&cond.ambiguities, &cond.covariance)?;
    let mut count = SHORT_LIST.min(MAX_CANDIDATES);
    loop {
        let list = nearest.list(count)?;
        let mut best: Option<(f64, Vec<i64>)> = None;
        let mut second = f64::INFINITY;
        let mut scored = 0;
        // Every candidate not listed has an ambiguity term, and so a score, of at least
        // the last listed one's (infinite when the list holds every candidate).
        let unseen = if list.len() < count {
            f64::INFINITY
        } else {
            list.last().map_or(f64::INFINITY, |c| c.1)
        };
        for (z, squared_norm) in &list {
            if *squared_norm > second {
                break;
            }
            let integers = nearest.integers(z)?;
            baselines.write(&integers, b.as_mut_slice());
            // A candidate that cannot change the best two is not fitted.
            if squared_norm + floor.of(&b) >= second {
                continue;
            }
            scored += 1;
            let Some(fit) = score.misfit(&b) else {
                continue;
            };
            let cost = squared_norm + fit;
            match &best {
                Some((b_cost, _)) if cost >= *b_cost => second = second.min(cost),
                _ => {
                    if let Some((b_cost, _)) = best.take() {
                        second = second.min(b_cost);
                    }
                    best = Some((cost, integers));
                }
            }
        }
        let Some((cost, integers)) = best else {
            return Err(nothing_fits());
        };
        // A lower bound of the true second-best score.
        let second_bound = second.min(unseen);
        let proven = cost <= unseen && second <= unseen;
        let decided = cost <= unseen && second_bound >= accept_ratio * cost;
        let could_pass_with_more = second_bound < second && count < MAX_CANDIDATES;
        if !proven && !decided && could_pass_with_more {
            // Most epochs are settled by the short list; the others go to the longest at
            // once (listing is most of the work, and an intermediate list was usually
            // followed by the longest: 2.08 -> 1.58 ms per epoch, BENCHMARKS.md).
            count = MAX_CANDIDATES;
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

/// The search under the whole body geometry (`constraint = "geometry"`); it applies to
/// two or more baselines.
#[derive(Debug, Clone)]
pub struct GeometrySearch {
    geometry: BodyGeometry,
}

impl GeometrySearch {
    pub fn new(geometry: BodyGeometry) -> Self {
        Self { geometry }
    }
}

impl ConstrainedSearch for GeometrySearch {
    fn search(
        &self,
        float: &FloatBaselines,
        cond: &Conditioned,
        held: &[(usize, i64)],
        master_ecef_m: &Vec3,
        accept_ratio: f64,
    ) -> Searched {
        if self.geometry.len() < 2 {
            return Searched::Fallback("the geometry search needs two or more baselines".into());
        }
        let result = search(
            float,
            cond,
            held,
            &self.geometry,
            master_ecef_m,
            accept_ratio,
        );
        Searched::of("geometry", result)
    }

    fn method(&self) -> FixMethod {
        FixMethod::Geometry
    }
}
