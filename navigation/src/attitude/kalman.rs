//! The real-time KF of thesis eqs. 2.5-16, 2.5-17 on the 6-state `[xi, xi']`.
//!
//! The measurement `Y_k = h(X_k) + v_k`, `h(X) = vec(R(xi) B_0)`, is nonlinear; it is
//! linearised at the prediction with `H = [h J(xi), 0]` (eqs. 2.5-8, 2.5-10), which makes
//! this an extended KF. `R = Q_BB_NED`. The covariance update uses the Joseph form.

use super::config::{AttitudeConfig, AttitudeMethod};
use super::filter::{KalmanAttitude, MeasurementUpdate, UpdateInfo, angles_of};
use super::jacobian::design_matrix;
use super::{AttitudeError, BodyGeometry, NedBaselines};
use nalgebra::{DMatrix, DVector, Matrix6, Vector6};

/// The attitude EKF.
pub type EkfAttitude = KalmanAttitude<Linearised>;

/// The EKF's update: linearised at the prediction, Joseph-form covariance.
#[derive(Debug, Clone, Copy)]
pub struct Linearised;

impl MeasurementUpdate for Linearised {
    const METHOD: AttitudeMethod = AttitudeMethod::Kf;

    fn update(
        _config: &AttitudeConfig,
        geometry: &BodyGeometry,
        x: &Vector6<f64>,
        p: &Matrix6<f64>,
        measured: &NedBaselines,
    ) -> Result<(Vector6<f64>, Matrix6<f64>, UpdateInfo), AttitudeError> {
        let n = 3 * measured.len();
        let angles = angles_of(x);
        let mut h = DMatrix::<f64>::zeros(n, 6);
        h.view_mut((0, 0), (n, 3))
            .copy_from(&design_matrix(geometry, &angles));
        let pd = DMatrix::from_column_slice(6, 6, p.as_slice());
        let r = measured.covariance();
        let s = &h * &pd * h.transpose() + r;
        let s_chol = s.clone().cholesky().ok_or_else(|| {
            AttitudeError::Singular("KF innovation covariance is not positive definite".into())
        })?;
        let v: DVector<f64> = measured.vec() - geometry.predict(&angles);
        // K = P H^T S^-1.
        let k = s_chol.solve(&(&h * &pd)).transpose();
        let dx = &k * &v;
        let i_kh = DMatrix::<f64>::identity(6, 6) - &k * &h;
        let p_new = &i_kh * &pd * i_kh.transpose() + &k * r * k.transpose();
        let x_new = x + Vector6::from_iterator(dx.iter().copied());
        Ok((
            x_new,
            Matrix6::from_iterator(p_new.iter().copied()),
            UpdateInfo {
                chi_square: v.dot(&s_chol.solve(&v)),
                dof: n,
                initialised: false,
            },
        ))
    }
}
