//! The bundled software receiver. It sees samples and what a real receiver could be told
//! (ephemerides, approximate time and position), never simulator truth: it depends on the
//! GNSS vocabulary (`skyforge-gnss`) and not on the simulator, which
//! `tests/tests/truth_firewall.rs` checks in the resolved dependency graph.

// Library code returns errors instead of panicking; tests may unwrap.
#![cfg_attr(not(test), deny(clippy::unwrap_used, clippy::expect_used))]

pub mod acquisition;
pub mod assist;
pub mod input;
pub mod navdecode;
pub mod observables;
pub mod pipeline;
pub mod replica;
pub mod session;
pub mod tracking;
