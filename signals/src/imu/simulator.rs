//! The IMU simulator: error-free increments from the platform's kinematics, plus the
//! vibration the sensors feel, through each triad's errors.

use super::config::{DEG_PER_H, ImuConfig, ImuGrade, VibrationConfig};
use super::ideal::increments;
use super::sensor::Triad;
use crate::errors::{Stream, stream_rng};
use rand::Rng;
use skyforge_orbits::Vec3;
use skyforge_orbits::platform::Kinematics;
use std::f64::consts::TAU;

/// Why an IMU sample could not be made.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ImuError {
    /// The platform's motion is not known twice differentiable at `t_s`.
    #[error(
        "the platform has no acceleration and angular rate at t = {t_s} s: an IMU needs a \
         ground site or [platform.segments] (a LEO or a trajectory CSV has none)"
    )]
    NoKinematics { t_s: f64 },
}

/// One interval's output and truth.
#[derive(Debug, Clone, PartialEq)]
pub struct ImuSample {
    /// End of the interval (s since the run's start) and its length (s).
    pub t_s: f64,
    pub dt_s: f64,
    /// What the IMU output: angle (rad) and velocity (m/s) increments, body axes.
    pub dtheta_rad: Vec3,
    pub dv_mps: Vec3,
    /// The platform's error-free increments of the same interval.
    pub ideal_dtheta_rad: Vec3,
    pub ideal_dv_mps: Vec3,
    /// The platform's motion at the interval's end.
    pub truth: Kinematics,
    /// The gyro (rad/s) and accelerometer (m/s^2) biases during the interval.
    pub gyro_bias_rps: Vec3,
    pub accel_bias_mps2: Vec3,
}

/// A sinusoidal vibration per body axis, phases drawn once.
#[derive(Debug, Clone)]
struct Vibration {
    omega_rps: f64,
    gyro_rps: f64,
    accel_mps2: f64,
    gyro_phase: Vec3,
    accel_phase: Vec3,
}

impl Vibration {
    fn new(config: &VibrationConfig, seed: u64, index: u32) -> Self {
        let mut rng = stream_rng(seed, Stream::ImuVibration, index);
        let mut phases = || Vec3::from_fn(|_, _| rng.random_range(0.0..TAU));
        Self {
            omega_rps: TAU * config.frequency_hz,
            gyro_rps: config.gyro_dps * 3600.0 * DEG_PER_H,
            accel_mps2: config.accel_mps2,
            gyro_phase: phases(),
            accel_phase: phases(),
        }
    }

    /// Integral of `amplitude sin(w t + phase)` over `(t0, t1]`, per axis.
    fn integral(&self, amplitude: f64, phase: &Vec3, t0_s: f64, t1_s: f64) -> Vec3 {
        let w = self.omega_rps;
        phase.map(|p| amplitude / w * ((w * t0_s + p).cos() - (w * t1_s + p).cos()))
    }

    /// The vibration's angle and velocity increments over `(t0, t1]`.
    fn increments(&self, t0_s: f64, t1_s: f64) -> (Vec3, Vec3) {
        (
            self.integral(self.gyro_rps, &self.gyro_phase, t0_s, t1_s),
            self.integral(self.accel_mps2, &self.accel_phase, t0_s, t1_s),
        )
    }
}

/// An IMU at the body origin of a platform, sampling every `1 / rate_hz` from the run's
/// start.
#[derive(Debug, Clone)]
pub struct ImuSimulator {
    dt_s: f64,
    next: u64,
    gyro: Triad,
    accel: Triad,
    vibration: Option<Vibration>,
}

impl ImuSimulator {
    /// The IMU of `config` (checked), its random streams keyed by `seed` (the platform's
    /// receiver seed) and `index` (the IMU's).
    pub fn new(config: &ImuConfig, seed: u64, index: u32) -> Self {
        let (gyro, accel) = config.errors();
        let ideal = config.grade == ImuGrade::Ideal;
        Self {
            dt_s: 1.0 / config.rate_hz,
            next: 0,
            gyro: Triad::new(gyro, stream_rng(seed, Stream::ImuGyro, index)),
            accel: Triad::new(accel, stream_rng(seed, Stream::ImuAccel, index)),
            vibration: (config.vibration.as_ref())
                .filter(|_| !ideal)
                .map(|v| Vibration::new(v, seed, index)),
        }
    }

    /// The sampling interval (s).
    pub fn dt_s(&self) -> f64 {
        self.dt_s
    }

    /// The next interval's sample from the platform's `kinematics` (a function of seconds
    /// since the run's start).
    pub fn next_sample(
        &mut self,
        kinematics: &impl Fn(f64) -> Option<Kinematics>,
    ) -> Result<ImuSample, ImuError> {
        let t0_s = self.next as f64 * self.dt_s;
        let t_s = (self.next + 1) as f64 * self.dt_s;
        let missing = |t_s| ImuError::NoKinematics { t_s };
        let (ideal_dtheta_rad, ideal_dv_mps) =
            increments(kinematics, t0_s, self.dt_s).ok_or(missing(t0_s))?;
        let truth = kinematics(t_s).ok_or(missing(t_s))?;
        let (vib_dtheta, vib_dv) = (self.vibration.as_ref())
            .map_or((Vec3::zeros(), Vec3::zeros()), |v| v.increments(t0_s, t_s));
        let (gyro_bias_rps, accel_bias_mps2) = (self.gyro.bias(), self.accel.bias());
        self.next += 1;
        Ok(ImuSample {
            t_s,
            dt_s: self.dt_s,
            dtheta_rad: self.gyro.measure(ideal_dtheta_rad + vib_dtheta, self.dt_s),
            dv_mps: self.accel.measure(ideal_dv_mps + vib_dv, self.dt_s),
            ideal_dtheta_rad,
            ideal_dv_mps,
            truth,
            gyro_bias_rps,
            accel_bias_mps2,
        })
    }
}
