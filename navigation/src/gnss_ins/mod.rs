//! GNSS/INS integration: error-state Kalman filters that keep the strapdown INS
//! (`crate::ins`) on GNSS measurements and estimate the IMU's biases, with the IMU's
//! lever arm to the antenna.
//!
//! The loosely coupled filter ([`LooselyCoupled`]) takes position (and optionally
//! velocity) fixes of the antenna ([`GnssFix`]) from any GNSS solution. It is closed
//! loop: after every update the estimated errors are fed back into the INS and the bias
//! estimates, and the error state restarts at zero. The tightly coupled filter
//! ([`TightlyCoupled`], book 3.2.2's 18 states) adds the receiver clock and a barometer
//! and takes every satellite's pseudorange and range rate.
//!
//! Source: Groves 2013, "Principles of GNSS, Inertial, and Multisensor Integrated
//! Navigation Systems", 2nd ed.: sec. 14.2.3 (the ECEF-frame error equations), 14.2.7
//! (process noise), 14.1.1 (closed-loop correction), 14.3.1 (loosely coupled measurement
//! model with the lever arm, eqs. 14.110-14.111).

#![warn(missing_docs)]

mod aiding;
mod config;
mod error_state;
mod filter;
mod fix;
mod from_files;
mod receiver_states;
mod start;
mod tdcp_aided;
mod tight_from_files;
mod tightly_coupled;

#[cfg(test)]
mod aiding_tests;
#[cfg(test)]
mod tests;
#[cfg(test)]
mod tightly_coupled_tests;

pub use config::{ImuNoise, InsRunError, IntegrationError, LooselyCoupledConfig};
pub use error_state::STATES;
pub use filter::{InsFilter, LooselyCoupled, Update};
pub use fix::GnssFix;
pub use from_files::{
    FromFilesConfig, InsRun, InsSolution, ORBIT_HEIGHT_M, Outages, gravity_for,
    loosely_coupled_from_files,
};
pub use receiver_states::{BarometerNoise, ReceiverNoise, TIGHT_STATES};
pub use start::{Alignment, StaticAlignment, TrackAlignment};
pub use tdcp_aided::{TdcpAidedConfig, TdcpFilesConfig, tdcp_aided, tdcp_aided_from_files};
pub use tight_from_files::{TightFilesConfig, tightly_coupled_from_files};
pub use tightly_coupled::{TightlyCoupled, clock_from_epoch};
