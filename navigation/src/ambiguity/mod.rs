//! Integer ambiguity resolution with the LAMBDA method.
//!
//! Given float ambiguities `a_hat` (cycles) and their covariance `Q`, integer least
//! squares (ILS) finds the integer vectors `a` minimising `(a_hat - a)^T Q^{-1} (a_hat - a)`
//! (Teunissen 1995). The steps, one file each:
//! - `ldl`: `Q = L^T D L`, unit lower-triangular `L` (de Jonge & Tiberius 1996 §3.3),
//!   with symmetric pivoting for [`lambda`] (Chang, Yang & Zhou 2005 §3);
//! - `decorrelate`: integer Gauss transformations and swaps giving a unimodular `Z`
//!   with `z = Z^T a` nearly decorrelated (de Jonge & Tiberius 1996 §3.5-3.7, the
//!   reduction of Chang, Yang & Zhou 2005 §3);
//! - `search`: depth-first search of the shrinking ellipsoid in Schnorr-Euchner order
//!   (Chang, Yang & Zhou 2005 §4), keeping the `count` best, pruned in long searches by
//!   lower bounds of what the levels below a node must add (Stojnic, Vikalo & Hassibi
//!   2008);
//! - `bootstrap`: the bootstrapped success rate (Teunissen 1998);
//! - `partial`: partial ambiguity resolution on the decorrelated ambiguities;
//! - [`problem_file`]: a float solution and its covariance read from JSON or CSV.
//!
//! Ordering convention (as in LAMBDA): with `Q = L^T D L`, `d_i` is the variance of
//! ambiguity `i` conditioned on ambiguities `i+1..n`, so the search and bootstrapping
//! start at the last ambiguity.

mod bootstrap;
mod decorrelate;
mod int_matrix;
mod ldl;
mod partial;
pub mod problem_file;
mod search;

pub use bootstrap::{bootstrapped_success_rate, erf, erfc};
pub use partial::{PartialSolution, partial};

use nalgebra::{DMatrix, DVector};

/// Largest number of ambiguities accepted.
pub const MAX_DIMENSION: usize = 500;
/// Largest number of candidates [`lambda`] returns.
pub const MAX_CANDIDATES: usize = 1000;
/// Largest float ambiguity magnitude accepted (cycles): integers stay exact in `f64`.
pub const MAX_ABS_FLOAT: f64 = 1e12;
/// Relative tolerance of the symmetry check: `|Q_ij - Q_ji| <= tol * max(|Q_ii|, |Q_jj|)`.
pub const SYMMETRY_TOLERANCE: f64 = 1e-9;
/// Smallest diagonal entry (variance) of `Q` accepted, cycles^2.
pub const MIN_VARIANCE: f64 = 1e-100;
/// Largest magnitude of an entry of `Q` accepted, cycles^2.
///
/// With every variance in `[MIN_VARIANCE, MAX_VARIANCE]`, far beyond any carrier-phase
/// covariance on either side, the factorisation's products of two entries, the
/// conditional variances (at least 1e-14 of a diagonal entry) and the squared norms of
/// 500 levels stay far inside the range of `f64`: no intermediate overflows, and no
/// squared norm underflows to 0 (a variance of 1e308 made every norm 0 and the ratio
/// 0/0).
pub const MAX_VARIANCE: f64 = 1e100;
/// Search nodes after which [`lambda`] gives up: the integer vectors within the search
/// bound are too many to enumerate (see `search`).
pub const MAX_SEARCH_NODES: u64 = 100_000_000;

/// Why an ambiguity problem was rejected. Indices are 0-based.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum AmbiguityError {
    #[error("empty problem: a_hat has no ambiguities (at least 1 is needed)")]
    Empty,
    #[error(
        "dimension mismatch: a_hat has {n} ambiguities but Q is {rows} x {cols} (Q must be {n} x {n})"
    )]
    DimensionMismatch { n: usize, rows: usize, cols: usize },
    #[error("{n} ambiguities exceed the limit of {MAX_DIMENSION}")]
    TooLarge { n: usize },
    #[error("{field} is not finite: {value} (only finite numbers are allowed)")]
    NonFinite { field: String, value: f64 },
    #[error("a_hat[{index}] = {value} is out of range (|a_hat| at most {MAX_ABS_FLOAT:e} cycles)")]
    OutOfRange { index: usize, value: f64 },
    #[error(
        "Q[{i}][{j}] = {value:e} is out of range (variances on the diagonal from {MIN_VARIANCE:e} to {MAX_VARIANCE:e} cycles^2, other entries at most {MAX_VARIANCE:e} in magnitude)"
    )]
    CovarianceOutOfRange { i: usize, j: usize, value: f64 },
    #[error(
        "Q is not symmetric: Q[{i}][{j}] = {a} but Q[{j}][{i}] = {b} (allowed difference: {SYMMETRY_TOLERANCE:e} relative)"
    )]
    NotSymmetric { i: usize, j: usize, a: f64, b: f64 },
    #[error(
        "Q is not positive definite: the conditional variance of ambiguity {index} is {value} (must be positive and above 1e-14 of Q[{index}][{index}])"
    )]
    NotPositiveDefinite { index: usize, value: f64 },
    #[error("count is 0: at least 1 candidate must be asked for")]
    ZeroCount,
    #[error("count {0} exceeds the limit of {MAX_CANDIDATES} candidates")]
    TooManyCandidates(usize),
    #[error("min_success_rate {0} is outside (0, 1]")]
    InvalidSuccessRate(f64),
    #[error("the decorrelating transformation overflowed 64-bit integers (Q too ill-conditioned)")]
    Overflow,
    #[error(
        "the search for the integers of {n} ambiguities stopped after {MAX_SEARCH_NODES} nodes: too many integer vectors lie within its bound to enumerate (fix fewer ambiguities, e.g. by partial ambiguity resolution)"
    )]
    SearchLimit { n: usize },
    #[error("Q is numerically degenerate: the decorrelation produced non-finite values")]
    Degenerate,
}

/// One integer candidate.
#[derive(Debug, Clone, PartialEq)]
pub struct Candidate {
    /// The integer ambiguities (cycles), in the order of `a_hat`.
    pub integers: Vec<i64>,
    /// `(a_hat - a)^T Q^{-1} (a_hat - a)`.
    pub squared_norm: f64,
}

/// The integer least-squares solution of [`lambda`].
#[derive(Debug, Clone)]
pub struct IntegerSolution {
    /// Best first; exactly as many as asked for.
    pub candidates: Vec<Candidate>,
    /// The unimodular decorrelating matrix `Z` (`z = Z^T a`): integer entries, `|det Z| = 1`.
    pub z: DMatrix<f64>,
    /// Bootstrapped success rate of the decorrelated problem (Teunissen 1998), a lower
    /// bound of the ILS success rate.
    pub success_rate: f64,
}

impl IntegerSolution {
    /// The best candidate (there is always one).
    pub fn best(&self) -> &Candidate {
        &self.candidates[0]
    }

    /// Ratio-test statistic: second-best over best squared norm (`None` with one candidate,
    /// infinite when the best fits exactly).
    pub fn ratio(&self) -> Option<f64> {
        let second = self.candidates.get(1)?;
        Some(second.squared_norm / self.candidates[0].squared_norm)
    }
}

/// Integer least-squares estimate of `a_hat` with covariance `q`: the `count` best integer
/// vectors (LAMBDA: Teunissen 1995; de Jonge & Tiberius 1996; Chang, Yang & Zhou 2005).
pub fn lambda(
    a_hat: &DVector<f64>,
    q: &DMatrix<f64>,
    count: usize,
) -> Result<IntegerSolution, AmbiguityError> {
    let nearest = Nearest::new(a_hat, q)?;
    let candidates = nearest
        .list(count)?
        .into_iter()
        .map(|(z, squared_norm)| {
            Ok(Candidate {
                integers: nearest.integers(&z)?,
                squared_norm,
            })
        })
        .collect::<Result<Vec<_>, AmbiguityError>>()?;
    let reduced = &nearest.problem.reduced;
    Ok(IntegerSolution {
        candidates,
        z: reduced.z.to_dmatrix(),
        success_rate: bootstrap::success_rate_of(&reduced.d),
    })
}

/// One problem decorrelated once, its nearest integer vectors listed on demand and
/// back-transformed one at a time (a caller that stops early skips the rest).
#[derive(Debug)]
pub struct Nearest {
    problem: Decorrelated,
}

impl Nearest {
    /// The problem `a_hat`, `q` (checked and decorrelated).
    pub fn new(a_hat: &DVector<f64>, q: &DMatrix<f64>) -> Result<Self, AmbiguityError> {
        Ok(Self {
            problem: Decorrelated::new(a_hat, q)?,
        })
    }

    /// The `count` nearest integer vectors, best first, as decorrelated integers `z`
    /// (whole `f64`s; [`Nearest::integers`] gives the ambiguities) with their squared
    /// norms.
    pub fn list(&self, count: usize) -> Result<Vec<(Vec<f64>, f64)>, AmbiguityError> {
        if count == 0 {
            return Err(AmbiguityError::ZeroCount);
        }
        if count > MAX_CANDIDATES {
            return Err(AmbiguityError::TooManyCandidates(count));
        }
        let reduced = &self.problem.reduced;
        search::search(&reduced.l, &reduced.d, reduced.z_hat.as_slice(), count)
    }

    /// The ambiguities of a listed `z`.
    pub fn integers(&self, z: &[f64]) -> Result<Vec<i64>, AmbiguityError> {
        self.problem.to_ambiguities(z)
    }
}

/// `x` rounded to the nearest whole number (ties to even below 2^51) without a libm call:
/// adding and subtracting 1.5 * 2^52 leaves no fractional bits.
#[inline]
pub(crate) fn round_fast(x: f64) -> f64 {
    const MAGIC: f64 = 6_755_399_441_055_744.0;
    if x.abs() < 2_251_799_813_685_248.0 {
        (x + MAGIC) - MAGIC
    } else {
        x.round()
    }
}

/// A checked problem after decorrelation: `a_hat = offset + frac` with integer `offset`,
/// and the reduction of `(frac, Q)`.
#[derive(Debug)]
struct Decorrelated {
    offset: Vec<i64>,
    reduced: decorrelate::Reduced,
}

impl Decorrelated {
    fn new(a_hat: &DVector<f64>, q: &DMatrix<f64>) -> Result<Self, AmbiguityError> {
        check_problem(a_hat, q)?;
        let offset: Vec<i64> = a_hat.iter().map(|&x| x.round() as i64).collect();
        let frac = DVector::from_iterator(a_hat.len(), a_hat.iter().map(|&x| x - x.round()));
        let factors = ldl::ldl(q, true)?;
        let reduced = decorrelate::reduce(factors, &frac)?;
        Ok(Self { offset, reduced })
    }

    /// `a = Z^{-T} z + offset` for an integer `z` (given as whole `f64`s).
    fn to_ambiguities(&self, z: &[f64]) -> Result<Vec<i64>, AmbiguityError> {
        let z: Vec<i64> = z.iter().map(|&v| v as i64).collect();
        let a = self.reduced.z_inv_t.mul_vec(&z)?;
        a.iter()
            .zip(&self.offset)
            .map(|(x, o)| x.checked_add(*o).ok_or(AmbiguityError::Overflow))
            .collect()
    }
}

/// Checks `q` alone: square, within the size limit, finite, within
/// [`MIN_VARIANCE`]..[`MAX_VARIANCE`], symmetric. A variance of 0 or below is left to the
/// factorisation (not positive definite).
fn check_q(q: &DMatrix<f64>) -> Result<(), AmbiguityError> {
    let n = q.nrows();
    if n != q.ncols() {
        return Err(AmbiguityError::DimensionMismatch {
            n,
            rows: q.nrows(),
            cols: q.ncols(),
        });
    }
    if n == 0 {
        return Err(AmbiguityError::Empty);
    }
    if n > MAX_DIMENSION {
        return Err(AmbiguityError::TooLarge { n });
    }
    for j in 0..n {
        for i in 0..n {
            let v = q[(i, j)];
            if !v.is_finite() {
                return Err(AmbiguityError::NonFinite {
                    field: format!("Q[{i}][{j}]"),
                    value: v,
                });
            }
            if v.abs() > MAX_VARIANCE || (i == j && v > 0.0 && v < MIN_VARIANCE) {
                return Err(AmbiguityError::CovarianceOutOfRange { i, j, value: v });
            }
        }
    }
    for j in 0..n {
        for i in j + 1..n {
            let (a, b) = (q[(i, j)], q[(j, i)]);
            let scale = q[(i, i)].abs().max(q[(j, j)].abs());
            if (a - b).abs() > SYMMETRY_TOLERANCE * scale {
                return Err(AmbiguityError::NotSymmetric { i, j, a, b });
            }
        }
    }
    Ok(())
}

/// Checks `a_hat` and `q` together (see [`AmbiguityError`]).
fn check_problem(a_hat: &DVector<f64>, q: &DMatrix<f64>) -> Result<(), AmbiguityError> {
    let n = a_hat.len();
    if n == 0 {
        return Err(AmbiguityError::Empty);
    }
    if q.nrows() != n || q.ncols() != n {
        return Err(AmbiguityError::DimensionMismatch {
            n,
            rows: q.nrows(),
            cols: q.ncols(),
        });
    }
    if n > MAX_DIMENSION {
        return Err(AmbiguityError::TooLarge { n });
    }
    for (index, &value) in a_hat.iter().enumerate() {
        if !value.is_finite() {
            return Err(AmbiguityError::NonFinite {
                field: format!("a_hat[{index}]"),
                value,
            });
        }
        if value.abs() > MAX_ABS_FLOAT {
            return Err(AmbiguityError::OutOfRange { index, value });
        }
    }
    check_q(q)
}

#[cfg(test)]
mod tests;
