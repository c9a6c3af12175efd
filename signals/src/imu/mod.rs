//! The IMU simulator (`[imu]`): a strapdown IMU at the body origin of a platform whose
//! motion is known twice differentiable (a ground site, `[platform.segments]`), its
//! angle and velocity increments with the errors of a grade: turn-on bias, Gauss-Markov
//! bias instability, angle and velocity random walk, scale factor, misalignment and
//! non-orthogonality, quantisation, and an optional vibration. Random streams keyed like
//! every other receiver-side source (the platform's receiver seed and the IMU's index).

mod config;
mod grades;
mod ideal;
mod sensor;
mod simulator;
#[cfg(test)]
mod tests;

pub use config::{
    AccelSpec, DEG_PER_H, DEG_PER_ROOT_H, GyroSpec, ImuConfig, ImuGrade, MICRO_G, MPS_PER_ROOT_H,
    RATE_HZ, TriadErrors, VibrationConfig,
};
pub use grades::{BOOK_TABLE_3_1, CONSUMER, NAVIGATION, TACTICAL};
pub use ideal::{Sensed, increments, sensed};
pub use sensor::Triad;
pub use simulator::{ImuError, ImuSample, ImuSimulator};
