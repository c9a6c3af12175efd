//! The attitude UKF of thesis eqs. 4.3-27..4.3-32 with the unscented transform of eqs.
//! 4.3-16..4.3-26 ([`super::unscented`]).
//!
//! State `[yaw, pitch, roll, yaw', pitch', roll']` (eq. 4.3-27), the linear prediction of
//! eqs. 4.3-16, 4.3-17 with `Phi` and `Q` of eqs. 4.3-28..4.3-30 (shared with the KF,
//! [`super::filter`]), sigma points from the predicted covariance, and the measurement
//! `Z_k = vec(B) = [R(xi) b'_1; R(xi) b'_2; ...] + r_k` with `R = Q_BB` (eqs. 4.3-31,
//! 4.3-32), for any number of baselines.

use super::filter::{
    AttitudeConfig, AttitudeFilter, AttitudeMethod, FilterCore, FilterInit, FilterState,
    UpdateInfo, angles_of,
};
use super::unscented::{transform, update};
use super::{AttitudeError, BodyGeometry, NedBaselines};

/// The attitude UKF.
#[derive(Debug, Clone)]
pub struct UkfAttitude {
    core: FilterCore,
}

impl UkfAttitude {
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

impl AttitudeFilter for UkfAttitude {
    fn method(&self) -> AttitudeMethod {
        AttitudeMethod::Ukf
    }

    fn predict(&mut self, dt_s: f64) -> Result<(), AttitudeError> {
        self.core.predict(dt_s)
    }

    fn update(&mut self, measured: &NedBaselines) -> Result<UpdateInfo, AttitudeError> {
        self.core.geometry.check_count(measured)?;
        let Some((x, p)) = self.core.xp else {
            return self.core.start_from_ls(measured);
        };
        let geometry = &self.core.geometry;
        let t = transform(&x, &p, self.core.config.kappa, |xj| {
            geometry.predict(&angles_of(xj))
        })
        .map_err(|e| AttitudeError::Filter(e.to_string()))?;
        let (x_new, p_new, v, s) = update(&x, &p, &t, &measured.vec(), measured.covariance())
            .map_err(|e| AttitudeError::Filter(e.to_string()))?;
        let chi_square = s
            .cholesky()
            .map(|c| v.dot(&c.solve(&v)))
            .unwrap_or(f64::NAN);
        self.core.set(x_new, p_new)?;
        Ok(UpdateInfo {
            chi_square,
            dof: v.len(),
            initialised: false,
        })
    }

    fn state(&self) -> Option<FilterState> {
        self.core.state()
    }
}
