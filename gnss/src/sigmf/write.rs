//! Writing a `.sigmf-meta` document: what one antenna's SkyForge recording says.

use super::keys;
use crate::sample_format::SampleFormat;
use crate::signal::Signal;
use serde_json::{Value, json};

/// What SkyForge writes as `core:recorder`: its name and this build's version.
pub const RECORDER: &str = concat!("skyforge ", env!("CARGO_PKG_VERSION"));

/// The SigMF version the documents follow.
const SIGMF_VERSION: &str = "1.0.0";
/// The version of the `skyforge` extension.
const SKYFORGE_EXTENSION_VERSION: &str = "1.0.0";

/// What a recording's metadata says.
#[derive(Debug, Clone, PartialEq)]
pub struct RecordingMeta {
    /// Sample container (`core:datatype`).
    pub format: SampleFormat,
    /// Samples per second (`core:sample_rate`).
    pub sample_rate_hz: f64,
    /// Centre frequency of the recorded band (Hz): the carrier minus the IF.
    pub centre_frequency_hz: f64,
    /// Intermediate frequency of the signal within the recording (Hz, 0 for baseband).
    pub if_hz: f64,
    /// ISO-8601 UTC time of the first sample (see [`super::datetime::format_utc`]).
    pub datetime_utc: String,
    /// The antenna recorded (`skyforge:antenna`).
    pub antenna_name: String,
    /// Nominal antenna position in the body frame (m).
    pub antenna_position_body_m: [f64; 3],
    /// The scenario synthesised (`skyforge:scenario`).
    pub scenario: String,
    /// The synthesis's random seed (`skyforge:seed`).
    pub seed: u64,
    /// The vehicle recorded in a scenario of several (`skyforge:vehicle`; absent for a
    /// single platform).
    pub vehicle: Option<String>,
    /// What the recording is, for people (`core:description`).
    pub description: String,
    /// The signals the recording carries; `skyforge:signals` where there are several.
    pub signals: Vec<Signal>,
}

impl RecordingMeta {
    /// The `.sigmf-meta` JSON document (`core` namespace plus a `skyforge` extension).
    pub fn to_json(&self) -> Value {
        let mut doc = json!({
            (keys::GLOBAL): {
                (keys::DATATYPE): self.format.sigmf_datatype(),
                (keys::SAMPLE_RATE): self.sample_rate_hz,
                (keys::VERSION): SIGMF_VERSION,
                (keys::NUM_CHANNELS): 1,
                (keys::DESCRIPTION): self.description,
                (keys::RECORDER): RECORDER,
                (keys::EXTENSIONS): [{
                    (keys::EXTENSION_NAME): keys::SKYFORGE,
                    (keys::EXTENSION_VERSION): SKYFORGE_EXTENSION_VERSION,
                    (keys::EXTENSION_OPTIONAL): true,
                }],
                (keys::SCENARIO): self.scenario,
                (keys::SEED): self.seed,
                (keys::ANTENNA): self.antenna_name,
                (keys::ANTENNA_POSITION_BODY_M): self.antenna_position_body_m,
                (keys::IF_HZ): self.if_hz,
            },
            (keys::CAPTURES): [{
                (keys::SAMPLE_START): 0,
                (keys::FREQUENCY): self.centre_frequency_hz,
                (keys::DATETIME): self.datetime_utc,
            }],
            (keys::ANNOTATIONS): [],
        });
        if let Some(global) = doc.get_mut(keys::GLOBAL).and_then(Value::as_object_mut) {
            if self.signals.len() > 1 {
                let tags: Vec<&str> = self.signals.iter().map(|s| s.tag()).collect();
                global.insert(keys::SIGNALS.to_owned(), json!(tags));
            }
            if let Some(vehicle) = &self.vehicle {
                global.insert(keys::VEHICLE.to_owned(), json!(vehicle));
            }
        }
        doc
    }

    /// The `.sigmf-meta` file's text: the document pretty-printed, with a final newline.
    pub fn to_text(&self) -> String {
        format!("{:#}\n", self.to_json())
    }
}
