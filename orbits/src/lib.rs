//! Orbits: time scales, reference frames, GNSS broadcast ephemerides (with the broadcast
//! ionosphere and the standard troposphere every user applies), the LEO numerical
//! propagator, receiving platforms with their attitude, and visibility geometry.
//!
//! Conventions (see `DESIGN.md`): SI units inside; time inside hot loops is `f64` seconds
//! since the scenario start ([`time::TimeOrigin`]); rotation matrices are named
//! `c_from_to` and map a vector's components from frame `from` to frame `to`.

// Library code returns errors instead of panicking; tests may unwrap.
#![cfg_attr(not(test), deny(clippy::unwrap_used, clippy::expect_used))]

pub mod angles;
pub mod bounded_read;
pub mod check;
pub mod constants;
pub mod ephemeris;
#[cfg(any(test, feature = "test-support"))]
pub mod fixtures;
pub mod frames;
pub mod gravity;
pub mod platform;
pub mod propagate;
pub mod real_data;
pub mod rinex_header;
pub mod time;
pub mod troposphere;
pub mod visibility;

/// A 3-vector of `f64` (frame and unit are carried by the variable name).
pub type Vec3 = nalgebra::Vector3<f64>;
/// A 3x3 matrix of `f64`, usually a rotation `c_from_to`.
pub type Mat3 = nalgebra::Matrix3<f64>;
