//! The bundled software receiver. It sees samples and what a real receiver could be told
//! (ephemerides, approximate time and position), never simulator truth: of
//! `skyforge-signals` it uses only the signal definitions every receiver has (ranging
//! codes, navigation-message formats, sample-file formats, NCO helpers), which
//! `tests/tests/truth_firewall.rs` checks.

// Library code returns errors instead of panicking; tests may unwrap.
#![cfg_attr(not(test), deny(clippy::unwrap_used, clippy::expect_used))]

pub mod acquisition;
pub mod ambiguity;
pub mod assist;
pub mod attitude;
pub mod baseline;
pub mod continued_fraction;
pub mod fast_sync;
pub mod geometry_offset;
pub mod input;
pub mod integrity;
pub mod navdecode;
pub mod observables;
pub mod pipeline;
pub mod pvt;
pub mod relative;
pub mod session;
pub mod tracking;
