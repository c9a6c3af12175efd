//! Navigation: observations to solutions. Single-point PVT with RAIM, double differences
//! and float baselines, ambiguity resolution (LAMBDA and the constrained searches),
//! relative positioning and attitude, geometry-offset estimation, and the integrity
//! monitor. It reads what a real receiver's navigation software could: observation
//! records, navigation data, surveyed or nominal geometry; never simulator truth
//! (tests/tests/truth_firewall.rs). Orbit determination, relative navigation between
//! vehicles and GNSS/INS belong here too.

// Library code returns errors instead of panicking; tests may unwrap.
#![cfg_attr(not(test), deny(clippy::unwrap_used, clippy::expect_used))]

pub mod ambiguity;
pub mod attitude;
pub mod baseline;
mod config_file;
pub mod continued_fraction;
pub mod geometry_file;
pub mod geometry_offset;
pub mod gnss_ins;
pub mod ins;
pub mod integrity;
pub mod interference;
pub mod orbit_determination;
pub mod pvt;
pub mod relative;
pub mod relnav;
pub mod tdcp;
