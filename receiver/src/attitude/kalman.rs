//! The real-time KF of thesis eqs. 2.5-16, 2.5-17 on the 6-state `[xi, xi']`.
//!
//! The measurement `Y_k = h(X_k) + v_k`, `h(X) = vec(R(xi) B_0)`, is nonlinear; it is
//! linearised at the prediction with `H = [h J(xi), 0]` (eqs. 2.5-8, 2.5-10), which makes
//! this an extended KF. `R = Q_BB_NED`. The covariance update uses the Joseph form.

use super::filter::{
    AttitudeConfig, AttitudeFilter, AttitudeMethod, FilterCore, FilterInit, FilterState,
    UpdateInfo, angles_of,
};
use super::jacobian::design_matrix;
use super::{AttitudeError, BodyGeometry, NedBaselines};
use nalgebra::{DMatrix, DVector, Matrix6, Vector6};

/// The attitude EKF.
#[derive(Debug, Clone)]
pub struct EkfAttitude {
    core: FilterCore,
}

impl EkfAttitude {
    /// A filter for `geometry`; without `init` it starts from the first epoch's LS.
    pub fn new(
        config: &AttitudeConfig,
        geometry: BodyGeometry,
        init: Option<FilterInit>,
    ) -> Result<Self, AttitudeError> {
        Ok(Self {
            core: FilterCore::new(config, geometry, init)?,
        })
    }
}

impl AttitudeFilter for EkfAttitude {
    fn method(&self) -> AttitudeMethod {
        AttitudeMethod::Kf
    }

    fn predict(&mut self, dt_s: f64) -> Result<(), AttitudeError> {
        self.core.predict(dt_s)
    }

    fn update(&mut self, measured: &NedBaselines) -> Result<UpdateInfo, AttitudeError> {
        self.core.geometry.check_count(measured)?;
        let Some((x, p)) = self.core.xp else {
            return self.core.start_from_ls(measured);
        };
        let n = 3 * measured.len();
        let angles = angles_of(&x);
        let mut h = DMatrix::<f64>::zeros(n, 6);
        h.view_mut((0, 0), (n, 3))
            .copy_from(&design_matrix(&self.core.geometry, &angles));
        let pd = DMatrix::from_column_slice(6, 6, p.as_slice());
        let r = measured.covariance();
        let s = &h * &pd * h.transpose() + r;
        let s_chol = s.clone().cholesky().ok_or_else(|| {
            AttitudeError::Singular("KF innovation covariance is not positive definite".into())
        })?;
        let v: DVector<f64> = measured.vec() - self.core.geometry.predict(&angles);
        // K = P H^T S^-1.
        let k = s_chol.solve(&(&h * &pd)).transpose();
        let dx = &k * &v;
        let i_kh = DMatrix::<f64>::identity(6, 6) - &k * &h;
        let p_new = &i_kh * &pd * i_kh.transpose() + &k * r * k.transpose();
        let x_new = x + Vector6::from_iterator(dx.iter().copied());
        self.core
            .set(x_new, Matrix6::from_iterator(p_new.iter().copied()))?;
        Ok(UpdateInfo {
            chi_square: v.dot(&s_chol.solve(&v)),
            dof: n,
            initialised: false,
        })
    }

    fn state(&self) -> Option<FilterState> {
        self.core.state()
    }
}
