//! The scenario schema: the TOML file as written ([`ScenarioFile`], private) and the
//! checked [`Scenario`] the rest of SkyForge uses. Field-by-field reference:
//! `docs/scenario.md`.

use hifitime::Epoch;
use serde::Deserialize;
use skyforge_orbits::ephemeris::{BeidouSet, ConstellationConfig, ConstellationSource, System};
use skyforge_orbits::platform::PlatformConfig;
use skyforge_signals::antenna::AntennaConfig;
use skyforge_signals::errors::{ErrorsConfig, EventConfig, OscillatorConfig, vehicle_seed};
use skyforge_signals::imu::ImuConfig;
use skyforge_signals::interference::JammerConfig;
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
    /// `[imu]`: the IMU at the platform's body origin (with `[[vehicles]]`: of every
    /// vehicle without a `[vehicles.imu]` of its own); none when absent.
    pub imu: Option<ImuConfig>,
    /// `[[vehicles]]`: the platforms of a scenario with several (empty: the one
    /// `[platform]` with its `[[antennas]]`). `platform` and `antennas` are the first
    /// vehicle's; such a scenario runs per vehicle ([`Scenario::vehicle_views`]).
    pub vehicles: Vec<VehicleConfig>,
    /// `[[jammers]]`: transmitters of interference the samples receive (none: a clean
    /// sky); unique names, `[signal]` samples of a complex format.
    pub jammers: Vec<JammerConfig>,
    /// The vehicle this scenario is the view of ([`Scenario::vehicle_views`]): its
    /// receiver-side random streams are keyed by its name ([`Scenario::receiver_seed`]).
    /// `None` for a single-platform scenario, whose streams keep the scenario seed.
    pub vehicle: Option<String>,
    /// Where the scenario came from: the file path as given, or `bundled:NAME`.
    pub source: String,
    /// Directory relative paths in the scenario are resolved from (the scenario file's
    /// directory; the current directory for bundled scenarios).
    pub base_dir: PathBuf,
    /// The TOML text the scenario was parsed from (for provenance in outputs, and to
    /// locate errors found by [`Scenario::build`]).
    pub text: String,
}

/// One `[[vehicles]]` entry: a platform with its antennas and, optionally, its own
/// oscillator.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct VehicleConfig {
    /// Its name: the subdirectory of its outputs and the key of its receiver-side random
    /// streams.
    pub name: String,
    /// `[vehicles.platform]`, as a single-platform scenario's `[platform]`.
    pub platform: PlatformConfig,
    /// `[[vehicles.antennas]]`, as a single-platform scenario's `[[antennas]]`.
    #[serde(default)]
    pub antennas: Vec<AntennaConfig>,
    /// `[vehicles.receiver_clock]`: its oscillator (absent: the scenario's
    /// `[errors.receiver_clock]`, drawn from its own stream all the same).
    #[serde(default)]
    pub receiver_clock: Option<OscillatorConfig>,
    /// `[[vehicles.events]]`: faults on this vehicle's antennas only (an outage of one
    /// receiver), as `[[errors.events]]`, which reach every vehicle.
    #[serde(default)]
    pub events: Vec<EventConfig>,
    /// `[vehicles.imu]`: its IMU (absent: the scenario's `[imu]`, if any).
    #[serde(default)]
    pub imu: Option<ImuConfig>,
}

impl Scenario {
    /// The single-platform scenarios this one runs as: itself when it has one platform;
    /// one per `[[vehicles]]` entry otherwise, each with that vehicle's platform,
    /// antennas, oscillator and events (after the scenario's), the scenario's everything
    /// else (satellites, their errors, the atmosphere, the signal), and `vehicle` set.
    pub fn vehicle_views(&self) -> Vec<Scenario> {
        if self.vehicles.is_empty() {
            return vec![self.clone()];
        }
        (self.vehicles.iter())
            .map(|v| {
                let mut view = self.clone();
                view.platform = v.platform.clone();
                view.antennas = v.antennas.clone();
                if let Some(clock) = &v.receiver_clock {
                    view.errors.receiver_clock = Some(clock.clone());
                }
                view.errors.events.extend(v.events.iter().cloned());
                view.imu = v.imu.clone().or_else(|| self.imu.clone());
                view.vehicles = Vec::new();
                view.vehicle = Some(v.name.clone());
                view
            })
            .collect()
    }

    /// The seed of the receiver-side random streams (oscillator, thermal noise, tracking
    /// and Doppler noise, carrier ambiguities): the scenario seed for a single-platform
    /// scenario (its outputs unchanged), keyed by the vehicle's name for a vehicle's view,
    /// so two vehicles never share receiver noise. Satellite-side streams always use the
    /// scenario seed: every vehicle sees the same satellite errors.
    pub fn receiver_seed(&self) -> u64 {
        match &self.vehicle {
            None => self.seed,
            Some(name) => vehicle_seed(self.seed, name),
        }
    }
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
    /// Required unless `[[vehicles]]` is given (checked with a located message).
    #[serde(default)]
    pub platform: Option<PlatformConfig>,
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
    #[serde(default)]
    pub imu: Option<ImuConfig>,
    #[serde(default)]
    pub vehicles: Vec<VehicleConfig>,
    #[serde(default)]
    pub jammers: Vec<JammerConfig>,
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
