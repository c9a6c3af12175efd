//! Relative navigation of two spacecraft from their receivers' observation files (book
//! section 5.6): the chaser's position and velocity relative to the target, in the
//! target's orbit frame (x along-track, y the negative orbit normal, z nadir; eqs.
//! 5-54/5-55, `orbits::frames::relative_in_target_frame`).
//!
//! Modes ([`RelnavMode`]), as the book chooses them by range (section 5.6.3):
//! - `standalone`: each vehicle's own single-point fix on the satellites it tracks, then
//!   the difference (eq. 5-56); errors about sqrt(2) times a fix's where the satellite
//!   sets differ;
//! - `position-difference`: both fixes on the satellites both track, then the difference
//!   (the measurement of eq. 5-57): the satellites' orbit and clock errors and most of
//!   the atmosphere cancel (eq. 5-58: what remains is twice a receiver's noise variance);
//! - `carrier-smoothed`: as `position-difference`, each vehicle's code first smoothed by
//!   its carrier with the book's growing-memory filter (eqs. 5-60..5-64,
//!   `pvt::CarrierSmoother`), restarted where a satellite leaves the common set; no
//!   filter after the smoothing (the book: the smoothed fixes are correlated in time).
//!
//! Velocities are the difference of the two Doppler velocities (eq. 5-56b's rotating-frame
//! rate). Each chaser fix is moved to the target fix's instant with its own velocity (the
//! receivers' clocks tag their epochs differently: a millisecond is 7.5 m along-track).
//! Reads only what the receivers could: observations, broadcast ephemerides, settings.

mod config;
mod from_files;

pub use config::{RelnavConfig, RelnavMode};
pub use from_files::{RelativeEstimate, RelnavError, RelnavRun, relative_from_files};
