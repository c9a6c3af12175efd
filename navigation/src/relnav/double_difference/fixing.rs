//! Integer resolution of the double-difference ambiguities and their hold.
//!
//! The double-difference ambiguities `a = D N` of the epoch's pairings (`D`: +1 at the
//! satellite's single-difference state, -1 at the reference's) have the float values
//! `a_hat = D x` and covariance `Q = D P D^T`. Those whose variance is already below
//! [`HELD_VARIANCE`] were fixed before and are held; LAMBDA (`ambiguity::lambda`) searches
//! the others. They are fixed when the ratio test (second-best over best squared norm at
//! least `ratio_threshold`) and the bootstrapped success rate (at least
//! `min_success_rate`) both pass; if not, the least precise one is dropped and the rest
//! tried again (partial fixing by subsets). Fixed integers enter the filter as
//! measurements `D x = a` of variance [`HOLD_VARIANCE`]: the baseline is then the fixed
//! solution, and the integers stay while the satellites are tracked without a slip
//! (fix and hold). A held constraint needs no re-mapping when the reference changes:
//! it constrains single-difference states, and any double difference of two satellites
//! linked through held constraints is as precise.
//!
//! A held integer can be wrong: the tests judge the float solution of the moment, and
//! errors the model lacks (the satellites' orbit errors through a 200 km baseline bias
//! the double differences by centimetres, without `orbit_error_sigma_m`'s states) can
//! make a wrong candidate look right. So a float filter runs beside the holding one on
//! the same epochs, never constrained ([`check_held`]), and the held integers are
//! released once either test finds them wrong: its own float values of the held double
//! differences resolve, with the same tests, to other integers ([`resolves_otherwise`]),
//! or they are farther from the held values than their covariance allows
//! ([`inconsistent`]).

use super::filter::{DdFilter, Key, Pairing};
use crate::ambiguity::lambda;
use crate::pvt::raim::test_threshold;
use nalgebra::{DMatrix, DVector};

/// A double-difference ambiguity with a variance below this (cycles^2) counts as fixed.
pub(crate) const HELD_VARIANCE: f64 = 1e-6;
/// The variance of a fixed integer's constraint (cycles^2).
const HOLD_VARIANCE: f64 = 1e-12;

/// The double-difference ambiguities of one epoch after resolution.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct AmbiguityCount {
    pub fixed: usize,
    pub float: usize,
}

/// The row `D` of one pairing's double-difference ambiguity.
fn row(filter: &DdFilter, p: &Pairing) -> Option<DVector<f64>> {
    let s = filter.index(Key::Ambiguity(p.sat, p.signal))?;
    let r = filter.index(Key::Ambiguity(p.reference, p.signal))?;
    let mut d = DVector::zeros(filter.x.len());
    d[s] = 1.0;
    d[r] = -1.0;
    Some(d)
}

/// Resolve the float ambiguities of `pairings` and hold those fixed; the epoch's count.
pub(crate) fn resolve(filter: &mut DdFilter, pairings: &[Pairing]) -> AmbiguityCount {
    let rows: Vec<DVector<f64>> = pairings.iter().filter_map(|p| row(filter, p)).collect();
    let variance = |d: &DVector<f64>| (d.transpose() * &filter.p * d)[(0, 0)];
    let mut float: Vec<(f64, DVector<f64>)> = (rows.iter())
        .map(|d| (variance(d), d.clone()))
        .filter(|(v, _)| *v >= HELD_VARIANCE)
        .collect();
    let held = rows.len() - float.len();
    // Most precise first: a failed test drops the last.
    float.sort_by(|a, b| a.0.total_cmp(&b.0));
    while !float.is_empty() {
        let d = DMatrix::from_fn(float.len(), filter.x.len(), |i, j| float[i].1[j]);
        let (a_hat, q) = float_of(filter, &d);
        if let Some(integers) = fixed_integers(filter, &a_hat, &q) {
            let values = DVector::from_iterator(integers.len(), integers.iter().map(|&k| k as f64));
            let innovation = values - &a_hat;
            let r = DMatrix::from_diagonal_element(float.len(), float.len(), HOLD_VARIANCE);
            filter.measure(&d, &innovation, &r);
            return AmbiguityCount {
                fixed: held + float.len(),
                float: rows.len() - held - float.len(),
            };
        }
        float.pop();
    }
    AmbiguityCount {
        fixed: held,
        float: rows.len() - held,
    }
}

/// `D x` and `D P D^T` (symmetrised) of `filter` for the rows of `d`.
fn float_of(filter: &DdFilter, d: &DMatrix<f64>) -> (DVector<f64>, DMatrix<f64>) {
    let q = d * &filter.p * d.transpose();
    (d * &filter.x, (&q + q.transpose()) * 0.5)
}

/// Fix and hold's check: `twin`, a float filter on the same epochs that never holds,
/// against the integers `filter` holds on `pairings`, by the tests of `held_test`
/// ([`resolves_otherwise`], [`inconsistent`]). Where one finds them wrong, `filter`
/// becomes the twin (every hold released) and resolves afresh. Whether it released.
pub(crate) fn check_held(filter: &mut DdFilter, twin: &DdFilter, pairings: &[Pairing]) -> bool {
    if filter.keys != twin.keys {
        return false;
    }
    let Some(d) = held_rows(filter, pairings) else {
        return false;
    };
    let test = filter.config.held_test;
    let wrong = (test.lambda() && resolves_otherwise(filter, twin, &d))
        || (test.consistency() && inconsistent(filter, twin, &d));
    if wrong {
        *filter = twin.clone();
    }
    wrong
}

/// The rows `D` of the double differences of `pairings` that `filter` holds; `None` where
/// it holds none.
fn held_rows(filter: &DdFilter, pairings: &[Pairing]) -> Option<DMatrix<f64>> {
    let held: Vec<DVector<f64>> = (pairings.iter())
        .filter_map(|p| row(filter, p))
        .filter(|d| (d.transpose() * &filter.p * d)[(0, 0)] < HELD_VARIANCE)
        .collect();
    (!held.is_empty()).then(|| DMatrix::from_fn(held.len(), filter.x.len(), |i, j| held[i][j]))
}

/// The twin-LAMBDA test: LAMBDA on `twin`'s float values of the held double differences
/// `d` finds integers other than `filter`'s, and they pass the ratio and success-rate
/// tests.
fn resolves_otherwise(filter: &DdFilter, twin: &DdFilter, d: &DMatrix<f64>) -> bool {
    let (a_float, q) = float_of(twin, d);
    let Some(integers) = fixed_integers(twin, &a_float, &q) else {
        return false;
    };
    let holding = d * &filter.x;
    (integers.iter().zip(holding.iter())).any(|(&k, a)| k as f64 != a.round())
}

/// The consistency test of the held double differences `a = D x` (k of them) between
/// `filter` (`a_h`, covariance `Q_h = D P_h D^T`) and `twin` (`a_t`, `Q_t`):
///
/// `T = (a_h - a_t)^T (Q_t - Q_h)^-1 (a_h - a_t) > chi2_k^-1(1 - alpha)`
///
/// (`alpha`: `consistency_false_alarm`). With the right integers the holding filter is
/// the twin conditioned on them (the constant ambiguities make an old hold one on
/// today's states), and the difference of two conditional means on nested information
/// has the difference of their covariances: `a_h - a_t ~ N(0, Q_t - Q_h)`, so `T` is
/// chi-square with k degrees of freedom. It is Teunissen's ellipsoidal integer aperture
/// test of the integers (as Verhagen describes it): they stand while the float solution
/// lies in the ellipsoid about them that the float covariance and the false-alarm
/// probability set. Where rounding makes `Q_t - Q_h` not positive definite, no decision.
/// Errors the model lacks raise `T` for right integers too: under broadcast-quality
/// satellite orbits it releases them as well unless `orbit_error_sigma_m` gives the
/// filter their states (docs/orbit-determination.md).
fn inconsistent(filter: &DdFilter, twin: &DdFilter, d: &DMatrix<f64>) -> bool {
    let (a_h, q_h) = float_of(filter, d);
    let (a_t, q_t) = float_of(twin, d);
    let Some(chol) = (q_t - q_h).cholesky() else {
        return false;
    };
    let e = a_h - a_t;
    let t = e.dot(&chol.solve(&e));
    t > test_threshold(d.nrows(), filter.config.consistency_false_alarm)
}

/// The integers of `a_hat` (covariance `q`) when the ratio and success-rate tests pass.
fn fixed_integers(filter: &DdFilter, a_hat: &DVector<f64>, q: &DMatrix<f64>) -> Option<Vec<i64>> {
    let solution = lambda(a_hat, q, 2).ok()?;
    let ratio = solution.ratio().unwrap_or(f64::INFINITY);
    let config = &filter.config;
    (ratio >= config.ratio_threshold && solution.success_rate >= config.min_success_rate)
        .then(|| solution.best().integers.clone())
}
