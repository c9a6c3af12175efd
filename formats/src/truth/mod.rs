//! `truth.h5`, the geometry and signal truth of a run (`skyforge run`, `skyforge synth`):
//! the writer that streams it chunk by chunk ([`TruthWriter`]), the reader that validate
//! and the report use ([`TruthFile`]), and the names of its groups, datasets and
//! attributes, once. The schema is documented in `docs/truth-h5.md`; change both together.

mod jammers;
mod read;
mod write;

pub use jammers::{JAMMERS_GROUP, JammerTruth};
pub use read::{PlatformSeries, TruthFile, VisibleLinks};
pub use write::{RunMeta, SCHEMA_VERSION, TruthWriter, size_bound};

/// The file's name in a run directory.
pub const TRUTH_H5: &str = "truth.h5";

/// Root attribute: the scenario's name.
const SCENARIO_ATTR: &str = "scenario";
/// Root attribute: the scenario file's text.
const SCENARIO_TOML_ATTR: &str = "scenario_toml";
/// Root attribute: the GPST epoch that `time/t_s` counts from.
const START_EPOCH_ATTR: &str = "start_epoch";

/// Group and dataset of the geometry epochs' times.
const TIME_GROUP: &str = "time";
const T_S: &str = "t_s";
/// Group of the platform's state per geometry epoch, and its datasets.
const PLATFORM_GROUP: &str = "platform";
const POSITION: &str = "r_ecef_m";
const VELOCITY: &str = "v_ecef_mps";
const ROTATION: &str = "q_body_ecef";
/// Group of the satellites (columns of the visibility masks), and their identifiers.
const SATELLITES_GROUP: &str = "satellites";
const SATELLITE_ID: &str = "id";
/// Group of one group per antenna.
const ANTENNAS_GROUP: &str = "antennas";
/// An antenna's attributes: nominal and true body positions (m).
pub const NOMINAL_BODY_ATTR: &str = "nominal_body_m";
pub const TRUE_BODY_ATTR: &str = "true_body_m";
/// An antenna's `[epoch, satellite]` visibility mask and the epoch row and satellite
/// column of each visible link.
const VISIBLE: &str = "visible";
const EPOCH_INDEX: &str = "epoch_index";
const SAT_INDEX: &str = "sat_index";
/// Per-link geometry datasets of an antenna that the report draws.
pub const DOPPLER_HZ: &str = "doppler_hz";
pub const DOPPLER_RATE_HZPS: &str = "doppler_rate_hzps";
pub const DOPPLER_ACCEL_HZPS2: &str = "doppler_accel_hzps2";

/// `group/name`.
fn dataset(group: &str, name: &str) -> String {
    format!("{group}/{name}")
}

/// `antennas/<antenna>/<name>`.
fn antenna_dataset(antenna: &str, name: &str) -> String {
    format!("{ANTENNAS_GROUP}/{antenna}/{name}")
}
