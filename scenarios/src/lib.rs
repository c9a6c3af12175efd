//! Scenarios: the TOML schema (reference: `docs/scenario.md`), defaults, checks with
//! located errors, building the simulation world, and the bundled scenario files.
//!
//! ```text
//! text --parse--> Scenario (every check that needs no file)
//!      --build--> World    (navigation files, platform, antennas)
//! ```
//! Every failure is one [`ScenarioError`] naming the file, line/column, field path, value
//! and what is allowed.

// A scenario error is built once per run, on the way to exit code 2: its size (four
// strings and a position, as the error format requires) costs nothing worth boxing for.
#![allow(clippy::result_large_err)]
// Library code returns errors instead of panicking; tests may unwrap.
#![cfg_attr(not(test), deny(clippy::unwrap_used, clippy::expect_used))]

mod build;
mod bundled;
mod checks;
mod error;
mod locate;
mod observation;
mod parse;
mod schema;

pub use build::World;
pub use bundled::{Bundled, bundled};
pub use error::ScenarioError;
pub use observation::{BUNDLED_CALIBRATION, BUNDLED_MONITOR_CONFIG};
pub use parse::{SCENARIO_MAX_BYTES, load, locate_invalid, named, parse, parse_document, resolve};
pub use schema::{GnssConfig, Scenario, TimeSpan, TruthConfig};
