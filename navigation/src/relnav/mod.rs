//! Relative navigation of two spacecraft from their receivers' observation files (book
//! section 5.6): the chaser's position and velocity relative to the target, in the
//! target's orbit frame (x along-track, y the negative orbit normal, z nadir; eqs.
//! 5-54/5-55, `orbits::frames::relative_in_target_frame`).
//!
//! Modes ([`RelnavMode`]), as the book chooses them by range (section 5.6.3):
//! - `standalone`: each vehicle's own single-point fix on the satellites it tracks, then
//!   the difference (eq. 5-56); errors about sqrt(2) times a fix's where the satellite
//!   sets differ;
//! - `position-difference`: both fixes on the satellites both use, then the difference
//!   (the measurement of eq. 5-57): the satellites' orbit and clock errors and most of
//!   the atmosphere cancel (eq. 5-58: what remains is twice a receiver's noise variance).
//!   "Both use": each receiver's fix first with its own elevation mask and residual test,
//!   then both again on the satellites both of those fixes used, with neither (a
//!   satellite at the mask for one vehicle is just below it for the other, and under SA
//!   one satellite more or less moves a fix by tens of metres);
//! - `carrier-smoothed`: as `position-difference`, each vehicle's code first smoothed by
//!   its carrier with the book's growing-memory filter (eqs. 5-60..5-64,
//!   `pvt::CarrierSmoother`), restarted where a satellite leaves the common set; no
//!   filter after the smoothing (the book: the smoothed fixes are correlated in time);
//!   with `satellite_sets = "own"` the book's own procedure instead: each vehicle smooths
//!   its whole file along its own tracks and fixes on the satellites it tracks, so the
//!   sets differ where one vehicle loses a satellite the other keeps (the book's events);
//! - `single-difference`: the book's pseudorange relative DGPS filter (eq. 5-59): a
//!   Kalman filter of the relative position and velocity and of the receivers' clock
//!   difference and its drift on the single differences of pseudorange and Doppler range
//!   rate of every satellite both receivers track, predicted by the Hill dynamics of eq.
//!   5-34 with `U` as the book's relative filter (`relnav::single_difference`);
//! - `double-difference` (beyond the book): double-difference carrier phase and code
//!   between the spacecraft with integer ambiguities, a Kalman filter on the gravity
//!   difference of the two orbits (the module docs of `relnav::double_difference`).
//!
//! With a `[filter]` table the differenced fixes of the first three modes go through the
//! book's relative filter ([`HillFilter`]: eqs. 5-57/5-58 with the Hill dynamics of eq.
//! 5-34 about the target's orbit) before they are written.
//!
//! Velocities are the difference of the two Doppler velocities (eq. 5-56b's rotating-frame
//! rate). The frame (eq. 5-55's `M`, from the target's state) is oriented by the target's
//! own orbit filter on its fixes (`orbit_determination::PositionFilter`): the book's
//! target "sends its state", and a single fix's Doppler velocity would turn the frame by
//! its noise. Each chaser fix is moved to the target fix's instant with its own velocity (the
//! receivers' clocks tag their epochs differently: a millisecond is 7.5 m along-track).
//! Every mode is one engine epoch by epoch behind one trait (`engine`): looped over two
//! files by [`relative_from_files`], or run as the chaser receiver forms each epoch by
//! [`RelnavStage`] (`skyforge receive --relnav`).
//!
//! Reads only what the receivers could: observations, broadcast ephemerides, settings.

mod book_modes;
mod config;
mod double_difference;
mod engine;
mod estimate;
mod from_files;
mod hill_dynamics;
mod hill_filter;
mod same_satellites;
mod single_difference;
mod stage;

pub use config::{RelnavConfig, RelnavMode, SatelliteSets};
pub use double_difference::config::DoubleDifferenceConfig;
pub use double_difference::fixing::AmbiguityCount;
pub use estimate::{RelativeEstimate, RelnavRun};
pub use from_files::{RelnavError, relative_from_files};
pub use hill_dynamics::TargetState;
pub use hill_filter::{HillEstimate, HillFilter, HillFilterConfig};
pub use single_difference::config::SingleDifferenceConfig;
pub use stage::RelnavStage;
