//! Validation: compare what SkyForge computes with truth and with the thesis tables.

// Library code returns errors instead of panicking; tests may unwrap.
#![cfg_attr(not(test), deny(clippy::unwrap_used, clippy::expect_used))]

pub mod attitude;
pub mod draw;
pub mod ins;
pub mod integrity;
pub mod interference;
pub mod observables;
pub mod orbit;
pub mod relnav;
pub mod relnav_baseline;
pub mod report;
pub mod stats;
pub mod thesis;
