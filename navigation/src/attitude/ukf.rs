//! The attitude UKF of thesis eqs. 4.3-27..4.3-32 with the unscented transform of eqs.
//! 4.3-16..4.3-26 ([`super::unscented`]).
//!
//! State `[yaw, pitch, roll, yaw', pitch', roll']` (eq. 4.3-27), the linear prediction of
//! eqs. 4.3-16, 4.3-17 with `Phi` and `Q` of eqs. 4.3-28..4.3-30 (shared with the KF,
//! [`super::filter`]), sigma points from the predicted covariance, and the measurement
//! `Z_k = vec(B) = [R(xi) b'_1; R(xi) b'_2; ...] + r_k` with `R = Q_BB` (eqs. 4.3-31,
//! 4.3-32), for any number of baselines.

use super::config::{AttitudeConfig, AttitudeMethod};
use super::filter::{KalmanAttitude, MeasurementUpdate, UpdateInfo, angles_of};
use super::unscented::{transform, update};
use super::{AttitudeError, BodyGeometry, NedBaselines};
use nalgebra::{Matrix6, Vector6};

/// The attitude UKF.
pub type UkfAttitude = KalmanAttitude<Unscented>;

/// The UKF's update: sigma points of the prediction through the measurement.
#[derive(Debug, Clone, Copy)]
pub struct Unscented;

impl MeasurementUpdate for Unscented {
    const METHOD: AttitudeMethod = AttitudeMethod::Ukf;

    fn update(
        config: &AttitudeConfig,
        geometry: &BodyGeometry,
        x: &Vector6<f64>,
        p: &Matrix6<f64>,
        measured: &NedBaselines,
    ) -> Result<(Vector6<f64>, Matrix6<f64>, UpdateInfo), AttitudeError> {
        let t = transform(x, p, config.kappa, |xj| geometry.predict(&angles_of(xj)))
            .map_err(|e| AttitudeError::Filter(e.to_string()))?;
        let (x_new, p_new, v, s) = update(x, p, &t, &measured.vec(), measured.covariance())
            .map_err(|e| AttitudeError::Filter(e.to_string()))?;
        let chi_square = s
            .cholesky()
            .map(|c| v.dot(&c.solve(&v)))
            .unwrap_or(f64::NAN);
        Ok((
            x_new,
            p_new,
            UpdateInfo {
                chi_square,
                dof: v.len(),
                initialised: false,
            },
        ))
    }
}
