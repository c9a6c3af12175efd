//! The attitude stage's trait ([`AttitudeFilter`]) and the Kalman core both filters share:
//! the process model, the constant-rate state and its canonical angles.
//!
//! State `X = [yaw, pitch, roll, yaw', pitch', roll']` (rad, rad/s; eqs. 2.5-16, 4.3-27),
//! transition `Phi = [[I_3, T I_3], [0, I_3]]` (eqs. 2.5-16, 4.3-28) and process noise
//! `Q = [[T^3/3, T^2/2], [T^2/2, T]] (x) diag(S_yaw', S_pitch', S_roll')` (eqs. 2.5-16,
//! 4.3-29, 4.3-30: white noise on the angular accelerations with power spectral densities
//! S, rad^2/s^3). The measurement is one epoch's `vec(B_NED)` with `R = Q_BB_NED`
//! (eqs. 2.5-17, 4.3-31, 4.3-32).
//!
//! Angles: after every step yaw and roll are wrapped into [-pi, pi) and a pitch beyond
//! +/-pi/2 is mapped to the same rotation (yaw + pi, pi - pitch, roll + pi; the pitch rate
//! changes sign). The measurement is a vector of baselines, so its innovation has no
//! angle to wrap; angle *differences* (errors, NEES) use [`super::wrap_diff`].

use super::config::{AttitudeConfig, AttitudeMethod};
use super::least_squares::solve;
use super::{AttitudeError, BodyGeometry, NedBaselines, YawPitchRoll, wrap_pi};
use nalgebra::{DMatrix, Matrix3, Matrix6, SMatrix, Vector3, Vector6};
use std::f64::consts::{FRAC_PI_2, PI};

/// A filter's state.
#[derive(Debug, Clone, PartialEq)]
pub struct FilterState {
    /// The angles (yaw and roll in [-pi, pi), pitch in [-pi/2, pi/2]).
    pub angles: YawPitchRoll,
    /// Yaw, pitch and roll rates (rad/s); `None` for the LS stage, which has none.
    pub rates_rad_s: Option<Vector3<f64>>,
    /// Covariance: 6x6 (angles then rates; rad^2, rad^2/s, rad^2/s^2) with rates, else the
    /// angles' 3x3 (rad^2).
    pub covariance: DMatrix<f64>,
}

/// What one update saw: the innovation's (or post-fit residual's) chi-square and its
/// degrees of freedom, to check that `Q_BB` and the filter agree with the data.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct UpdateInfo {
    /// `v^T S^-1 v` of the innovation (filters) or `r^T Q^-1 r` of the residual (LS).
    pub chi_square: f64,
    /// 3m for a filter's innovation, 3m - 3 for the LS residual.
    pub dof: usize,
    /// True when this update started the filter (from the LS attitude).
    pub initialised: bool,
}

/// An attitude stage: a filter (KF, UKF) or the epoch-by-epoch LS.
pub trait AttitudeFilter: std::fmt::Debug + Send {
    /// Which stage this is.
    fn method(&self) -> AttitudeMethod;
    /// Propagate the state by `dt_s` (s, finite and >= 0); nothing before the first
    /// update, and nothing for the LS stage.
    fn predict(&mut self, dt_s: f64) -> Result<(), AttitudeError>;
    /// Use one epoch's baselines. A filter without a state starts from the LS attitude of
    /// this epoch (which needs two baselines) unless it was given an initial state.
    fn update(&mut self, measured: &NedBaselines) -> Result<UpdateInfo, AttitudeError>;
    /// The current state; `None` before the first successful update.
    fn state(&self) -> Option<FilterState>;
}

/// A filter's starting point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FilterInit {
    pub angles: YawPitchRoll,
    pub rates_rad_s: Vector3<f64>,
    /// 6x6, positive definite (angles then rates).
    pub covariance: Matrix6<f64>,
}

/// Eqs. 2.5-16, 4.3-28, 5.5-5: `Phi(T) = [[I, T I], [0, I]]` of a constant-rate model
/// whose state is `N / 2` quantities followed by their rates (`N` even).
pub fn transition<const N: usize>(dt_s: f64) -> SMatrix<f64, N, N> {
    let mut phi = SMatrix::<f64, N, N>::identity();
    for i in 0..N / 2 {
        phi[(i, i + N / 2)] = dt_s;
    }
    phi
}

/// Eqs. 2.5-16, 4.3-30, 5.5-7: `Q(T) = [[T^3/3, T^2/2], [T^2/2, T]] (x) diag(S)` for the
/// state of [`transition`]: white noise on the accelerations of the `N / 2` quantities,
/// with power spectral densities `s` (`N / 2` values).
pub fn process_noise<const N: usize>(dt_s: f64, s: &[f64]) -> SMatrix<f64, N, N> {
    debug_assert_eq!(2 * s.len(), N, "one spectral density per quantity");
    let t = dt_s;
    let half = N / 2;
    let block = [[t.powi(3) / 3.0, t * t / 2.0], [t * t / 2.0, t]];
    let mut q = SMatrix::<f64, N, N>::zeros();
    for (bi, row) in block.iter().enumerate() {
        for (bj, v) in row.iter().enumerate() {
            for (k, sk) in s.iter().take(half).enumerate() {
                q[(half * bi + k, half * bj + k)] = v * sk;
            }
        }
    }
    q
}

/// What distinguishes the EKF from the UKF: the measurement update of a predicted state.
pub trait MeasurementUpdate: std::fmt::Debug + Clone + Send {
    /// The stage this update makes.
    const METHOD: AttitudeMethod;

    /// The state and covariance after `measured`, from the prediction `(x, p)` of a filter
    /// with `config` on `geometry`, and what the update saw.
    fn update(
        config: &AttitudeConfig,
        geometry: &BodyGeometry,
        x: &Vector6<f64>,
        p: &Matrix6<f64>,
        measured: &NedBaselines,
    ) -> Result<(Vector6<f64>, Matrix6<f64>, UpdateInfo), AttitudeError>;
}

/// A 6-state attitude filter: the shared prediction and start of [`FilterCore`], the
/// measurement update of `U` ([`super::kalman::Linearised`],
/// [`super::ukf::Unscented`]).
#[derive(Debug, Clone)]
pub struct KalmanAttitude<U> {
    core: FilterCore,
    update: std::marker::PhantomData<U>,
}

impl<U: MeasurementUpdate> KalmanAttitude<U> {
    /// A filter for `geometry`; without `init` it starts from the first epoch's LS.
    pub fn new(
        config: &AttitudeConfig,
        geometry: BodyGeometry,
        init: Option<FilterInit>,
    ) -> Result<Self, AttitudeError> {
        Ok(Self {
            core: FilterCore::new(config, geometry, init)?,
            update: std::marker::PhantomData,
        })
    }
}

impl<U: MeasurementUpdate> AttitudeFilter for KalmanAttitude<U> {
    fn method(&self) -> AttitudeMethod {
        U::METHOD
    }

    fn predict(&mut self, dt_s: f64) -> Result<(), AttitudeError> {
        self.core.predict(dt_s)
    }

    fn update(&mut self, measured: &NedBaselines) -> Result<UpdateInfo, AttitudeError> {
        self.core.geometry.check_count(measured)?;
        let Some((x, p)) = self.core.xp else {
            return self.core.start_from_ls(measured);
        };
        let (x_new, p_new, info) =
            U::update(&self.core.config, &self.core.geometry, &x, &p, measured)?;
        self.core.set(x_new, p_new)?;
        Ok(info)
    }

    fn state(&self) -> Option<FilterState> {
        self.core.state()
    }
}

/// The state and covariance both filters carry, their shared prediction (eqs. 2.5-16,
/// 4.3-16, 4.3-17) and their start from the LS.
#[derive(Debug, Clone)]
struct FilterCore {
    config: AttitudeConfig,
    geometry: BodyGeometry,
    /// `(X, P)` once started.
    xp: Option<(Vector6<f64>, Matrix6<f64>)>,
}

impl FilterCore {
    fn new(
        config: &AttitudeConfig,
        geometry: BodyGeometry,
        init: Option<FilterInit>,
    ) -> Result<Self, AttitudeError> {
        config.check()?;
        let xp = match init {
            None => None,
            Some(i) => {
                let x = state_vector(&i.angles, &i.rates_rad_s);
                let p = i.covariance;
                if !x.iter().chain(p.iter()).all(|v| v.is_finite())
                    || (p - p.transpose()).amax() > 1e-9 * p.amax()
                    || p.cholesky().is_none()
                {
                    return Err(AttitudeError::Covariance(
                        "the initial state must be finite and its covariance symmetric positive definite"
                            .into(),
                    ));
                }
                Some(canonical(x, p))
            }
        };
        Ok(Self {
            config: *config,
            geometry,
            xp,
        })
    }

    /// Eqs. 2.5-16, 4.3-16, 4.3-17.
    fn predict(&mut self, dt_s: f64) -> Result<(), AttitudeError> {
        if !(dt_s.is_finite() && dt_s >= 0.0) {
            return Err(AttitudeError::Filter(format!(
                "prediction interval {dt_s} s must be finite and >= 0"
            )));
        }
        if let Some((x, p)) = self.xp {
            let phi = transition::<6>(dt_s);
            let p =
                phi * p * phi.transpose() + process_noise::<6>(dt_s, &self.config.rate_psd_rad2_s3);
            self.xp = Some(canonical(phi * x, 0.5 * (p + p.transpose())));
        }
        Ok(())
    }

    /// Start from this epoch's LS attitude: angles and their covariance eq. 2.5-13, rates
    /// zero with [`AttitudeConfig::initial_rate_sigma_rad_s`].
    fn start_from_ls(&mut self, measured: &NedBaselines) -> Result<UpdateInfo, AttitudeError> {
        let est = solve(&self.geometry, measured, None, &self.config.least_squares)?;
        let mut p = Matrix6::zeros();
        p.fixed_view_mut::<3, 3>(0, 0).copy_from(&est.covariance);
        let s2 = self.config.initial_rate_sigma_rad_s.powi(2);
        p.fixed_view_mut::<3, 3>(3, 3)
            .copy_from(&(Matrix3::identity() * s2));
        self.xp = Some((state_vector(&est.angles, &Vector3::zeros()), p));
        Ok(UpdateInfo {
            chi_square: est.chi_square,
            dof: 3 * measured.len() - 3,
            initialised: true,
        })
    }

    /// Keep an updated state (canonical angles), or fail if it is not finite.
    fn set(&mut self, x: Vector6<f64>, p: Matrix6<f64>) -> Result<(), AttitudeError> {
        if !x.iter().chain(p.iter()).all(|v| v.is_finite()) {
            return Err(AttitudeError::Filter(
                "the updated state is not finite".into(),
            ));
        }
        self.xp = Some(canonical(x, 0.5 * (p + p.transpose())));
        Ok(())
    }

    fn state(&self) -> Option<FilterState> {
        self.xp.map(|(x, p)| FilterState {
            angles: YawPitchRoll::new(x[0], x[1], x[2]),
            rates_rad_s: Some(Vector3::new(x[3], x[4], x[5])),
            covariance: DMatrix::from_column_slice(6, 6, p.as_slice()),
        })
    }
}

/// `[yaw, pitch, roll, rates]`.
pub(crate) fn state_vector(angles: &YawPitchRoll, rates: &Vector3<f64>) -> Vector6<f64> {
    Vector6::new(
        angles.yaw_rad,
        angles.pitch_rad,
        angles.roll_rad,
        rates[0],
        rates[1],
        rates[2],
    )
}

/// The angles of a state vector.
pub(crate) fn angles_of(x: &Vector6<f64>) -> YawPitchRoll {
    YawPitchRoll::new(x[0], x[1], x[2])
}

/// Canonical angles: pitch in [-pi/2, pi/2] (else the same rotation with yaw + pi,
/// pi - pitch, roll + pi, and the pitch rate's sign and covariance rows flipped), yaw and
/// roll in [-pi, pi).
fn canonical(mut x: Vector6<f64>, mut p: Matrix6<f64>) -> (Vector6<f64>, Matrix6<f64>) {
    let pitch = wrap_pi(x[1]);
    x[1] = pitch;
    if pitch.abs() > FRAC_PI_2 {
        x[0] += PI;
        x[1] = PI.copysign(pitch) - pitch;
        x[2] += PI;
        x[4] = -x[4];
        let d = Matrix6::from_diagonal(&Vector6::new(1.0, -1.0, 1.0, 1.0, -1.0, 1.0));
        p = d * p * d;
    }
    x[0] = wrap_pi(x[0]);
    x[2] = wrap_pi(x[2]);
    (x, p)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn process_noise_is_the_integral_of_the_continuous_model() {
        // Q = int_0^T Phi(s) diag(0, 0, 0, S) Phi(s)^T ds (white acceleration noise).
        let (t, s) = (0.7, [1e-3, 2e-3, 5e-4]);
        let steps = 20_000;
        let mut num = Matrix6::zeros();
        let mut g = Matrix6::zeros();
        for k in 0..3 {
            g[(k + 3, k + 3)] = s[k];
        }
        for i in 0..steps {
            let tau = (i as f64 + 0.5) * t / steps as f64;
            let phi = transition::<6>(tau);
            num += phi * g * phi.transpose() * (t / steps as f64);
        }
        assert!((num - process_noise::<6>(t, &s)).amax() < 1e-10);
    }

    #[test]
    fn pitch_beyond_90_deg_is_the_same_rotation() {
        let x = Vector6::new(0.2, 2.0, -0.3, 0.01, 0.02, 0.03);
        let (y, p) = canonical(x, Matrix6::identity());
        let a = angles_of(&x).c_body_ref();
        let b = angles_of(&y).c_body_ref();
        assert!((a - b).amax() < 1e-14);
        assert!(y[1].abs() <= FRAC_PI_2 && y[4] == -0.02);
        assert_eq!(p, Matrix6::identity());
    }
}
