//! The work a user runs over many runs, above validation: Monte Carlo studies (a base
//! scenario over a grid of parameter values and seeds, each run measured against its own
//! truth: [`study`]), the receiver's noise calibration against the loop formulas
//! ([`calibrate`]), and the HTML report over a run's, a study's and the tables' outputs
//! ([`html_report`]). The study files (`*.toml`) beside this crate are the bundled studies.

// Library code returns errors instead of panicking; tests may unwrap.
#![cfg_attr(not(test), deny(clippy::unwrap_used, clippy::expect_used))]

pub mod calibrate;
pub mod html_report;
pub mod study;
