//! Partial ambiguity resolution: fix only the decorrelated ambiguities that can be fixed
//! reliably. After the Z-transformation, `z_k..z_n` (the end of the `L^T D L` order, whose
//! conditional variances the search and bootstrapping use first) form a sub-problem with
//! factors `L[k.., k..]`, `d[k..]`; the smallest `k` whose bootstrapped success rate
//! `prod_{i>=k} erf(1/sqrt(8 d_i))` reaches the threshold is fixed by ILS (partial
//! ambiguity resolution, Teunissen, Joosten & Tiberius 1999, ION GPS-99; the
//! bootstrapped rate is a lower bound of the subset's ILS success rate, Teunissen 1999).

use super::{AmbiguityError, Decorrelated, bootstrap, search};
use nalgebra::{DMatrix, DVector};

/// Which combinations of the ambiguities were fixed, and to what.
///
/// With `m` the number fixed (0 when even the most precise one misses the threshold):
/// `z_hat = Z_F^T a_hat` are the float combinations, `integers` their ILS values and
/// `q_zz = Z_F^T Q Z_F` their covariance. A baseline `b_hat` with covariance `Q_ba`
/// to `a_hat` is then fixed as `b_fixed = b_hat - Q_ba Z_F q_zz^{-1} (z_hat - integers)`
/// (`Q_bz = Q_ba Z_F`), with covariance `Q_bb - Q_ba Z_F q_zz^{-1} Z_F^T Q_ab`.
#[derive(Debug, Clone)]
pub struct PartialSolution {
    /// `Z_F`, `n x m`: column `j` holds the integer coefficients of fixed combination `j`
    /// (a column of the decorrelating `Z`), `z_F = Z_F^T a`.
    pub z_f: DMatrix<f64>,
    /// `Z_F^T a_hat`.
    pub z_hat: DVector<f64>,
    /// The integer least-squares values of the fixed combinations.
    pub integers: Vec<i64>,
    /// `Z_F^T Q Z_F`.
    pub q_zz: DMatrix<f64>,
    /// Bootstrapped success rate of the fixed subset (1 when nothing is fixed).
    pub success_rate: f64,
}

impl PartialSolution {
    /// Number of fixed combinations `m`.
    pub fn fixed_count(&self) -> usize {
        self.integers.len()
    }
}

/// Fix the largest trailing subset of the decorrelated ambiguities whose bootstrapped
/// success rate is at least `min_success_rate` (in `(0, 1]`).
pub fn partial(
    a_hat: &DVector<f64>,
    q: &DMatrix<f64>,
    min_success_rate: f64,
) -> Result<PartialSolution, AmbiguityError> {
    if !(min_success_rate > 0.0 && min_success_rate <= 1.0) {
        return Err(AmbiguityError::InvalidSuccessRate(min_success_rate));
    }
    let problem = Decorrelated::new(a_hat, q)?;
    let r = &problem.reduced;
    let n = r.d.len();
    // Smallest start index k with the product over k..n at the threshold.
    let mut start = n;
    let mut rate = 1.0;
    for k in (0..n).rev() {
        let with = rate * bootstrap::success_rate_of(&r.d[k..k + 1]);
        if with < min_success_rate {
            break;
        }
        rate = with;
        start = k;
    }
    let m = n - start;
    let z_f = DMatrix::from_fn(n, m, |i, j| r.z.get(i, start + j) as f64);
    let z_hat = z_f.transpose() * a_hat;
    let q_zz = z_f.transpose() * q * &z_f;
    let mut integers = Vec::with_capacity(m);
    if m > 0 {
        let l = r.l.view((start, start), (m, m)).into_owned();
        let found = search::search(&l, &r.d[start..], &r.z_hat.as_slice()[start..], 1)?;
        // z_F = Z_F^T (offset + frac): the search solved the fractional part.
        for (j, zj) in found[0].0.iter().enumerate() {
            let shift = (0..n).try_fold(0i64, |acc, i| {
                r.z.get(i, start + j)
                    .checked_mul(problem.offset[i])
                    .and_then(|p| acc.checked_add(p))
                    .ok_or(AmbiguityError::Overflow)
            })?;
            integers.push(
                (*zj as i64)
                    .checked_add(shift)
                    .ok_or(AmbiguityError::Overflow)?,
            );
        }
    }
    Ok(PartialSolution {
        z_f,
        z_hat,
        integers,
        q_zz,
        success_rate: rate,
    })
}
