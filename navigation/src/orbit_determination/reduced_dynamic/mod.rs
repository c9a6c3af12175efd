//! The reduced-dynamic orbit filter (issue #35's modern orbit determination): an extended
//! Kalman filter on the receiver's raw pseudoranges, range rates and carrier phases, whose
//! orbit follows a force model plus empirical accelerations that absorb what the model
//! lacks (Wu, Yunck and Thornton 1991; Montenbruck and Gill 2000, section 8.2.2). It
//! takes every epoch of an observation file; `interval_s` of [`super::OdConfig`] chooses
//! which estimates are written.

mod config;
mod dynamics;
mod filter;
mod observed;
mod rows;
mod state;

pub use config::{Observables, ReducedDynamicConfig};
pub use filter::ReducedDynamicFilter;
