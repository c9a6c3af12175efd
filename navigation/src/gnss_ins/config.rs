//! The integration filter's settings: what it assumes of the IMU and of its start.

use crate::ins::InsError;
use hifitime::Epoch;
use skyforge_orbits::Vec3;

/// The IMU's errors as the filter models them (per axis, 1 sigma, SI units).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ImuNoise {
    /// Gyro angle random walk (rad/sqrt(s)).
    pub gyro_arw: f64,
    /// Accelerometer velocity random walk (m/s/sqrt(s)).
    pub accel_vrw: f64,
    /// Gyro bias (rad/s): the initial uncertainty, and the stationary sigma of a
    /// first-order Gauss-Markov process of `gyro_bias_tau_s`.
    pub gyro_bias: f64,
    /// Its correlation time (s); `None`: a random constant (paper 001's model).
    pub gyro_bias_tau_s: Option<f64>,
    /// Accelerometer bias (m/s^2), as `gyro_bias`.
    pub accel_bias: f64,
    /// Its correlation time (s); `None`: a random constant.
    pub accel_bias_tau_s: Option<f64>,
}

/// Settings of [`super::LooselyCoupled`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LooselyCoupledConfig {
    /// The IMU's error model.
    pub imu: ImuNoise,
    /// The antenna's reference point from the IMU, body axes (m).
    pub lever_arm_body_m: Vec3,
    /// Initial 1-sigma error of the INS's position, per axis (m).
    pub initial_position_m: f64,
    /// Initial 1-sigma error of its velocity, per axis (m/s).
    pub initial_velocity_mps: f64,
    /// Initial 1-sigma tilt error about each horizontal axis (rad).
    pub initial_tilt_rad: f64,
    /// Initial 1-sigma heading error (rad).
    pub initial_heading_rad: f64,
}

/// Why the integration filter refused its input.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum IntegrationError {
    /// A setting outside what the filter can use.
    #[error("gnss/ins setting {field} = {value}: {allowed}")]
    Config {
        /// The setting.
        field: &'static str,
        /// Its value.
        value: f64,
        /// What is allowed.
        allowed: &'static str,
    },
    /// The INS refused an increment.
    #[error(transparent)]
    Ins(#[from] InsError),
    /// A fix with a value that is not finite or a covariance that is not positive
    /// definite.
    #[error("GNSS fix at {t}: {what}")]
    BadFix {
        /// The fix's time.
        t: Epoch,
        /// What is wrong.
        what: &'static str,
    },
    /// Time-differenced carrier phase could not be formed.
    #[error("time-differenced carrier phase: {0}")]
    Tdcp(String),
    /// A fix more than one IMU interval away from the INS's time.
    #[error(
        "GNSS fix at {t} is {offset_s} s from the INS time {ins_t}; update at most one IMU interval away"
    )]
    FixOutOfStep {
        /// The fix's time.
        t: Epoch,
        /// The INS's time.
        ins_t: Epoch,
        /// Their difference (s).
        offset_s: f64,
    },
}

impl LooselyCoupledConfig {
    /// Every sigma finite and non-negative (the initial ones positive), every correlation
    /// time positive and finite, the lever arm finite and under 1 km.
    pub fn check(&self) -> Result<(), IntegrationError> {
        let n = &self.imu;
        let non_negative = [
            ("imu.gyro_arw", n.gyro_arw),
            ("imu.accel_vrw", n.accel_vrw),
            ("imu.gyro_bias", n.gyro_bias),
            ("imu.accel_bias", n.accel_bias),
        ];
        for (field, value) in non_negative {
            if !(value.is_finite() && value >= 0.0) {
                return Err(config(field, value, "finite and not negative"));
            }
        }
        let positive = [
            ("initial_position_m", self.initial_position_m),
            ("initial_velocity_mps", self.initial_velocity_mps),
            ("initial_tilt_rad", self.initial_tilt_rad),
            ("initial_heading_rad", self.initial_heading_rad),
        ];
        for (field, value) in positive {
            if !(value.is_finite() && value > 0.0) {
                return Err(config(field, value, "finite and positive"));
            }
        }
        let taus = [
            ("imu.gyro_bias_tau_s", n.gyro_bias_tau_s),
            ("imu.accel_bias_tau_s", n.accel_bias_tau_s),
        ];
        for (field, tau) in taus {
            if let Some(t) = tau.filter(|t| !(t.is_finite() && *t > 0.0)) {
                return Err(config(
                    field,
                    t,
                    "positive and finite (or none: a constant)",
                ));
            }
        }
        for (k, x) in self.lever_arm_body_m.iter().enumerate() {
            if !(x.is_finite() && x.abs() <= 1000.0) {
                let field = [
                    "lever_arm_body_m[0]",
                    "lever_arm_body_m[1]",
                    "lever_arm_body_m[2]",
                ][k];
                return Err(config(field, *x, "finite, within 1 km"));
            }
        }
        Ok(())
    }
}

fn config(field: &'static str, value: f64, allowed: &'static str) -> IntegrationError {
    IntegrationError::Config {
        field,
        value,
        allowed,
    }
}

/// Why a run could not be made.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum InsRunError {
    /// Too little input to start.
    #[error("{0}")]
    Input(String),
    /// The filter refused its settings or a record.
    #[error(transparent)]
    Filter(#[from] IntegrationError),
}

impl From<InsError> for InsRunError {
    fn from(e: InsError) -> Self {
        Self::Filter(IntegrationError::Ins(e))
    }
}
