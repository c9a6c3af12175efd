//! A generic unscented transform (Julier-Uhlmann with the spread `kappa`), thesis eqs.
//! 4.3-18..4.3-26 (the same equations as 3.3-65..3.3-73 and 5.5-12..5.5-20):
//!
//! * sigma points `X^0 = x`, `X^i = x + (sqrt((n + kappa) P))_i`,
//!   `X^(i+n) = x - (sqrt((n + kappa) P))_i` with weights `w^0 = kappa / (n + kappa)`,
//!   `w^i = w^(i+n) = 1 / (2 (n + kappa))` (eqs. 4.3-18..4.3-20); the square root is the
//!   lower Cholesky factor and `(.)_i` its i-th column;
//! * `Y^j = h(X^j)`, their weighted mean, covariance and cross-covariance (eqs.
//!   4.3-21..4.3-24);
//! * the update `W = P_XY (P_YY + R)^-1`, `x += W (z - y)`, `P -= W (P_YY + R) W^T`
//!   (eqs. 4.3-25, 4.3-26).
//!
//! The state has a compile-time dimension `N`, the measurement any run-time dimension. It
//! knows nothing about attitude: written once, so that the UKF carrier tracker
//! (`receiver::tracking::ukf_carrier`, which has its own copy for N = 4, M = 2) can use it later.
//! Differences are plain subtractions: a caller with angles in its *measurement* must map
//! them to a continuous space first (this crate's attitude UKF measures baseline vectors,
//! so it need not).

use nalgebra::{DMatrix, DVector, Dyn, OMatrix, SMatrix, SVector};

/// Why a transform could not be computed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum UnscentedError {
    /// `n + kappa` must be positive for the square root.
    #[error("unscented transform: n + kappa = {0} must be > 0")]
    Spread(f64),
    /// The state covariance has no Cholesky factor.
    #[error("unscented transform: the state covariance is not positive definite")]
    NotPositiveDefinite,
    /// The measurement function gave vectors of different lengths or non-finite values.
    #[error("unscented transform: {0}")]
    Measurement(String),
    /// `P_YY + R` could not be inverted, or sizes disagree.
    #[error("unscented update: {0}")]
    Update(String),
}

/// The 2N + 1 sigma points and weights of eqs. 4.3-18..4.3-20.
#[derive(Debug, Clone, PartialEq)]
pub struct SigmaPoints<const N: usize> {
    /// `X^0 .. X^2N`.
    pub points: Vec<SVector<f64, N>>,
    /// `w^0 .. w^2N` (they sum to 1).
    pub weights: Vec<f64>,
}

/// Eqs. 4.3-18..4.3-20 for mean `x` and covariance `p`.
pub fn sigma_points<const N: usize>(
    x: &SVector<f64, N>,
    p: &SMatrix<f64, N, N>,
    kappa: f64,
) -> Result<SigmaPoints<N>, UnscentedError> {
    let n_k = N as f64 + kappa;
    if !(n_k.is_finite() && n_k > 0.0) {
        return Err(UnscentedError::Spread(n_k));
    }
    let l = (p * n_k)
        .cholesky()
        .ok_or(UnscentedError::NotPositiveDefinite)?
        .l();
    let mut points = Vec::with_capacity(2 * N + 1);
    points.push(*x);
    for i in 0..N {
        points.push(x + l.column(i));
    }
    for i in 0..N {
        points.push(x - l.column(i));
    }
    let mut weights = vec![1.0 / (2.0 * n_k); 2 * N + 1];
    weights[0] = kappa / n_k;
    Ok(SigmaPoints { points, weights })
}

/// The transformed statistics of eqs. 4.3-22..4.3-24.
#[derive(Debug, Clone, PartialEq)]
pub struct Transformed<const N: usize> {
    /// `Y_k|k-1` (M).
    pub y_mean: DVector<f64>,
    /// `P_YY` (M x M).
    pub p_yy: DMatrix<f64>,
    /// `P_XY` (N x M).
    pub p_xy: OMatrix<f64, nalgebra::Const<N>, Dyn>,
}

/// Eqs. 4.3-18..4.3-24: push the sigma points of `(x, p)` through `h`.
pub fn transform<const N: usize>(
    x: &SVector<f64, N>,
    p: &SMatrix<f64, N, N>,
    kappa: f64,
    mut h: impl FnMut(&SVector<f64, N>) -> DVector<f64>,
) -> Result<Transformed<N>, UnscentedError> {
    let sp = sigma_points(x, p, kappa)?;
    let ys: Vec<DVector<f64>> = sp.points.iter().map(&mut h).collect();
    let m = ys[0].len();
    if ys
        .iter()
        .any(|y| y.len() != m || !y.iter().all(|v| v.is_finite()))
    {
        return Err(UnscentedError::Measurement(
            "h gave vectors of different lengths or non-finite values".into(),
        ));
    }
    let mut y_mean = DVector::zeros(m);
    for (y, w) in ys.iter().zip(&sp.weights) {
        y_mean += y * *w;
    }
    let mut p_yy = DMatrix::zeros(m, m);
    let mut p_xy = OMatrix::<f64, nalgebra::Const<N>, Dyn>::zeros(m);
    for ((y, xj), w) in ys.iter().zip(&sp.points).zip(&sp.weights) {
        let dy = y - &y_mean;
        let dx = xj - x;
        p_yy += *w * &dy * dy.transpose();
        p_xy += *w * dx * dy.transpose();
    }
    Ok(Transformed { y_mean, p_yy, p_xy })
}

/// Eqs. 4.3-25, 4.3-26: the updated mean and covariance from the prediction `(x, p)`, its
/// transform `t`, the measurement `z` and its noise covariance `r`. Also returns the
/// innovation `z - y` and its covariance `P_YY + R` (for consistency checks).
#[allow(clippy::type_complexity)]
pub fn update<const N: usize>(
    x: &SVector<f64, N>,
    p: &SMatrix<f64, N, N>,
    t: &Transformed<N>,
    z: &DVector<f64>,
    r: &DMatrix<f64>,
) -> Result<
    (
        SVector<f64, N>,
        SMatrix<f64, N, N>,
        DVector<f64>,
        DMatrix<f64>,
    ),
    UnscentedError,
> {
    let m = t.y_mean.len();
    if z.len() != m || r.nrows() != m || r.ncols() != m {
        return Err(UnscentedError::Update(format!(
            "measurement has {} values and R is {}x{}, the transform gives {m}",
            z.len(),
            r.nrows(),
            r.ncols()
        )));
    }
    let s = &t.p_yy + r;
    let s_chol = s
        .clone()
        .cholesky()
        .ok_or_else(|| UnscentedError::Update("P_YY + R is not positive definite".into()))?;
    // W = P_XY S^-1, i.e. W^T = S^-1 P_XY^T (S symmetric).
    let gain_t = s_chol.solve(&t.p_xy.transpose());
    let gain = gain_t.transpose();
    let innovation = z - &t.y_mean;
    let dx = &gain * &innovation;
    let dp = &gain * &s * gain.transpose();
    let x_new = x + SVector::<f64, N>::from_iterator(dx.iter().copied());
    let p_new = p - SMatrix::<f64, N, N>::from_iterator(dp.iter().copied());
    Ok((x_new, 0.5 * (p_new + p_new.transpose()), innovation, s))
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{Matrix2, Vector2};

    #[test]
    fn weights_sum_to_one_and_reproduce_mean_and_covariance() {
        let x = Vector2::new(1.0, -2.0);
        let p = Matrix2::new(4.0, 1.0, 1.0, 2.0);
        let sp = sigma_points(&x, &p, 0.5).unwrap();
        assert!((sp.weights.iter().sum::<f64>() - 1.0).abs() < 1e-15);
        let mean: Vector2<f64> = sp.points.iter().zip(&sp.weights).map(|(x, w)| x * *w).sum();
        assert!((mean - x).amax() < 1e-14);
        let cov: Matrix2<f64> = sp
            .points
            .iter()
            .zip(&sp.weights)
            .map(|(xj, w)| *w * (xj - x) * (xj - x).transpose())
            .sum();
        assert!((cov - p).amax() < 1e-13);
    }

    #[test]
    fn a_linear_measurement_gives_the_kalman_update() {
        // For h(x) = H x the unscented update is the Kalman update exactly.
        let x = Vector2::new(0.3, 0.1);
        let p = Matrix2::new(2.0, 0.5, 0.5, 1.0);
        let hm = DMatrix::from_row_slice(3, 2, &[1.0, 0.0, 0.0, 1.0, 1.0, -2.0]);
        let r = DMatrix::from_diagonal(&DVector::from_vec(vec![0.1, 0.2, 0.3]));
        let z = DVector::from_vec(vec![0.5, 0.0, 1.0]);
        let t = transform(&x, &p, 0.5, |x| {
            &hm * DVector::from_column_slice(x.as_slice())
        })
        .unwrap();
        let (xu, pu, _, _) = update(&x, &p, &t, &z, &r).unwrap();
        let pd = DMatrix::from_column_slice(2, 2, p.as_slice());
        let xd = DVector::from_column_slice(x.as_slice());
        let s = &hm * &pd * hm.transpose() + &r;
        let k = &pd * hm.transpose() * s.try_inverse().unwrap();
        let xk = &xd + &k * (&z - &hm * &xd);
        let pk = (DMatrix::identity(2, 2) - &k * &hm) * &pd;
        assert!((DVector::from_column_slice(xu.as_slice()) - xk).amax() < 1e-12);
        assert!((DMatrix::from_column_slice(2, 2, pu.as_slice()) - pk).amax() < 1e-12);
    }

    #[test]
    fn bad_inputs_are_errors() {
        let x = Vector2::new(0.0, 0.0);
        assert!(sigma_points(&x, &Matrix2::new(1.0, 2.0, 2.0, 1.0), 0.5).is_err());
        assert!(sigma_points(&x, &Matrix2::identity(), -3.0).is_err());
    }
}
