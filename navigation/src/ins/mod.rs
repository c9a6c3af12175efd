//! Strapdown inertial navigation in the Earth-centred, Earth-fixed frame: the state
//! ([`InsState`]), its propagation over IMU increments with the two-sample coning and
//! sculling corrections ([`InsState::propagate`]), and the alignment of a stationary IMU
//! ([`coarse_alignment`], then [`fine_alignment`]).
//!
//! Sources: Savage 1998, "Strapdown inertial navigation integration algorithm design",
//! parts 1 (attitude) and 2 (velocity and position), J. Guidance, Control, and Dynamics
//! 21(1)/21(2); Groves 2013, "Principles of GNSS, Inertial, and Multisensor Integrated
//! Navigation Systems", 2nd ed., sec. 5.2 (ECEF-frame navigation equations), 5.5
//! (precision) and 5.6 (initialisation and alignment); Titterton & Weston 2004, "Strapdown
//! Inertial Navigation Technology", ch. 10 (alignment).
//!
//! Inputs are `skyforge_gnss::imu::ImuIncrement`s: the integrals of the body's angular
//! rate relative to inertial space and of the specific force over each interval, body
//! axes front-right-down. Gravity is the normal gravity of
//! `skyforge_orbits::gravity` (gravitation plus centrifugal), or in orbit its zonal field
//! (`InsState::propagate_in` with a `GravityModel`). Increments that are not
//! positive, not finite, out of order or leave gaps are refused with an [`InsError`].

#![warn(missing_docs)]

mod alignment;
mod checks;
mod coning_sculling;
mod error;
mod fine_alignment;
mod mechanisation;
mod rotation;
mod state;

#[cfg(test)]
pub(crate) mod tests;

pub use alignment::{
    StaticMeans, coarse_alignment, heading_error_from_east_gyro_bias_rad, static_means,
};
pub use checks::CONTIGUITY_TOLERANCE_S;
pub use error::InsError;
pub use fine_alignment::{FineAlignment, FineAlignmentConfig, fine_alignment};
pub use rotation::attitude_difference;
pub use state::{InsState, attitude_ned};
