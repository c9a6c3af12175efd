//! The scenario schema: the TOML file as written ([`ScenarioFile`], private) and the
//! checked [`Scenario`] the rest of SkyForge uses. Field-by-field reference:
//! `docs/scenario.md`.

use hifitime::Epoch;
use serde::Deserialize;
use skyforge_orbits::ephemeris::{BeidouSet, ConstellationConfig, ConstellationSource, System};
use skyforge_orbits::platform::PlatformConfig;
use skyforge_signals::antenna::AntennaConfig;
use skyforge_signals::errors::ErrorsConfig;
use skyforge_signals::obs_model::ObservationConfig;
use skyforge_signals::synth::SignalConfig;
use std::path::PathBuf;

/// A checked scenario: every value parsed, defaulted and checked (checks that need files
/// run in [`Scenario::build`]).
#[derive(Debug, Clone, PartialEq)]
pub struct Scenario {
    /// `name`: short identifier of the scenario.
    pub name: String,
    /// `description`: free text.
    pub description: Option<String>,
    /// `seed`: the one seed every random stream is derived from.
    pub seed: u64,
    /// `[time]`.
    pub time: TimeSpan,
    /// `[truth]`.
    pub truth: TruthConfig,
    /// `[gnss]`.
    pub gnss: GnssConfig,
    /// `[platform]`.
    pub platform: PlatformConfig,
    /// `[[antennas]]`, at least one, unique names.
    pub antennas: Vec<AntennaConfig>,
    /// `[signal]`: present when the scenario asks for I/Q samples.
    pub signal: Option<SignalConfig>,
    /// `[errors]`: error sources applied to the signal.
    pub errors: ErrorsConfig,
    /// `[observation]`: signal-level or observation-level observables.
    pub observation: ObservationConfig,
    /// Where the scenario came from: the file path as given, or `bundled:NAME`.
    pub source: String,
    /// Directory relative paths in the scenario are resolved from (the scenario file's
    /// directory; the current directory for bundled scenarios).
    pub base_dir: PathBuf,
    /// The TOML text the scenario was parsed from (for provenance in outputs, and to
    /// locate errors found by [`Scenario::build`]).
    pub text: String,
}

/// `[time]`: the simulated span.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TimeSpan {
    /// `start`: the scenario epoch `t = 0`.
    pub start: Epoch,
    /// `duration_s`: length of the span (s), > 0.
    pub duration_s: f64,
}

/// `[truth]`: sampling of the true geometry.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TruthConfig {
    /// Rate of the geometry time series (Hz), > 0, at least one step within the span.
    #[serde(default = "default_geometry_rate_hz")]
    pub geometry_rate_hz: f64,
}

impl Default for TruthConfig {
    fn default() -> Self {
        Self {
            geometry_rate_hz: default_geometry_rate_hz(),
        }
    }
}

fn default_geometry_rate_hz() -> f64 {
    1.0
}

/// `[gnss]`: the constellations (GPS and BeiDou default to their embedded constellations,
/// enabled; Galileo is opt-in: enabled when its table is written).
#[derive(Debug, Clone, PartialEq)]
pub struct GnssConfig {
    /// `[gnss.gps]`.
    pub gps: ConstellationConfig,
    /// `[gnss.beidou]`.
    pub beidou: ConstellationConfig,
    /// `[gnss.galileo]`.
    pub galileo: ConstellationConfig,
}

impl GnssConfig {
    /// Each constellation with its table's name and settings, GPS, BeiDou, Galileo.
    pub fn tables(&self) -> [(System, &'static str, &ConstellationConfig); 3] {
        [
            (System::Gps, "gnss.gps", &self.gps),
            (System::Beidou, "gnss.beidou", &self.beidou),
            (System::Galileo, "gnss.galileo", &self.galileo),
        ]
    }

    /// The enabled constellations, in the order of [`Self::tables`].
    pub fn enabled_systems(&self) -> Vec<System> {
        self.tables()
            .into_iter()
            .filter(|t| t.2.enabled)
            .map(|t| t.0)
            .collect()
    }
}

/// A constellation table left out of the file: the embedded constellation, enabled.
pub(crate) fn default_constellation() -> ConstellationConfig {
    ConstellationConfig {
        enabled: true,
        source: ConstellationSource::Embedded,
        nav_file: None,
        embedded_set: BeidouSet::default(),
        prns: None,
        gst_gps_ns: 0.0,
        gst_gps_drift_ns_per_day: 0.0,
    }
}

/// The Galileo table left out of the file: disabled, so that scenarios written before
/// Galileo existed keep their outputs.
pub(crate) fn absent_galileo() -> ConstellationConfig {
    ConstellationConfig {
        enabled: false,
        ..default_constellation()
    }
}

/// The scenario file as written.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct ScenarioFile {
    pub name: String,
    #[serde(default)]
    pub description: Option<String>,
    #[serde(default)]
    pub seed: u64,
    pub time: TimeFile,
    #[serde(default)]
    pub truth: TruthConfig,
    #[serde(default)]
    pub gnss: GnssFile,
    pub platform: PlatformConfig,
    /// Defaulted so that a file without antennas gets the "at least one" message rather
    /// than a bare "missing field".
    #[serde(default)]
    pub antennas: Vec<AntennaConfig>,
    #[serde(default)]
    pub signal: Option<SignalConfig>,
    #[serde(default)]
    pub errors: ErrorsConfig,
    #[serde(default)]
    pub observation: ObservationConfig,
}

/// `[time]` as written.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct TimeFile {
    pub start: String,
    pub duration_s: f64,
}

/// `[gnss]` as written.
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct GnssFile {
    #[serde(default)]
    pub gps: Option<ConstellationConfig>,
    #[serde(default)]
    pub beidou: Option<ConstellationConfig>,
    #[serde(default)]
    pub galileo: Option<ConstellationConfig>,
}
