//! Weighted least squares with a full measurement covariance, by whitening with its
//! Cholesky factor: `x = (H^T C^-1 H)^-1 H^T C^-1 z`.

use nalgebra::{DMatrix, DVector};

/// Smallest ratio of the normal matrix's Cholesky diagonal (smallest over largest): below
/// it the geometry does not determine the unknowns (a condition number above 1e16).
const MIN_CHOLESKY_RATIO: f64 = 1e-8;

/// A least-squares solution.
#[derive(Debug, Clone)]
pub(crate) struct Fit {
    /// The unknowns.
    pub x: DVector<f64>,
    /// Their covariance `(H^T C^-1 H)^-1`.
    pub covariance: DMatrix<f64>,
    /// Post-fit residuals `z - H x`.
    pub residuals: DVector<f64>,
    /// `v^T C^-1 v`: chi-square with `rows - unknowns` degrees of freedom when the model
    /// and `C` are right.
    pub chi2: f64,
}

/// The weighted least-squares solution of `z = H x + v`, `Cov(v) = covariance`; `None`
/// when `covariance` is not positive definite or `H` is (nearly) rank deficient.
pub(crate) fn weighted_least_squares(
    h: &DMatrix<f64>,
    z: &DVector<f64>,
    covariance: &DMatrix<f64>,
) -> Option<Fit> {
    let factor = covariance.clone().cholesky()?;
    let l = factor.l();
    let hw = l.solve_lower_triangular(h)?;
    let zw = l.solve_lower_triangular(z)?;
    let normal = hw.transpose() * &hw;
    let n_factor = normal.cholesky()?;
    let diagonal = n_factor.l().diagonal();
    if diagonal.min() < MIN_CHOLESKY_RATIO * diagonal.max() {
        return None;
    }
    let x = n_factor.solve(&(hw.transpose() * &zw));
    let chi2 = (zw - &hw * &x).norm_squared();
    Some(Fit {
        covariance: n_factor.inverse(),
        residuals: z - h * &x,
        x,
        chi2,
    })
}
