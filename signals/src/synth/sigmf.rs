//! SigMF 1.x metadata (`.sigmf-meta`) for one antenna's recording.

use crate::sample_format::SampleFormat;
use serde_json::{Value, json};

/// What a recording's metadata says.
#[derive(Debug, Clone, PartialEq)]
pub struct RecordingMeta {
    pub format: SampleFormat,
    pub sample_rate_hz: f64,
    /// Centre frequency of the recorded band (Hz): the carrier minus the IF.
    pub centre_frequency_hz: f64,
    /// Intermediate frequency of the signal within the recording (Hz, 0 for baseband).
    pub if_hz: f64,
    /// ISO-8601 UTC time of the first sample.
    pub datetime_utc: String,
    pub antenna_name: String,
    /// Nominal antenna position in the body frame (m).
    pub antenna_position_body_m: [f64; 3],
    pub scenario: String,
    pub seed: u64,
    pub description: String,
}

impl RecordingMeta {
    /// The `.sigmf-meta` JSON document (`core` namespace plus a `skyforge` extension).
    pub fn to_json(&self) -> Value {
        json!({
            "global": {
                "core:datatype": self.format.sigmf_datatype(),
                "core:sample_rate": self.sample_rate_hz,
                "core:version": "1.0.0",
                "core:num_channels": 1,
                "core:description": self.description,
                "core:recorder": concat!("skyforge ", env!("CARGO_PKG_VERSION")),
                "core:extensions": [{"name": "skyforge", "version": "1.0.0", "optional": true}],
                "skyforge:scenario": self.scenario,
                "skyforge:seed": self.seed,
                "skyforge:antenna": self.antenna_name,
                "skyforge:antenna_position_body_m": self.antenna_position_body_m,
                "skyforge:if_hz": self.if_hz,
            },
            "captures": [{
                "core:sample_start": 0,
                "core:frequency": self.centre_frequency_hz,
                "core:datetime": self.datetime_utc,
            }],
            "annotations": [],
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn has_the_core_fields_sigmf_readers_need() {
        let meta = RecordingMeta {
            format: SampleFormat::Ci8,
            sample_rate_hz: 4.092e6,
            centre_frequency_hz: 1575.42e6,
            if_hz: 0.0,
            datetime_utc: "2023-03-12T00:00:00.000Z".into(),
            antenna_name: "ant1".into(),
            antenna_position_body_m: [0.0, 1.0, 0.0],
            scenario: "thesis-leo".into(),
            seed: 3,
            description: "test".into(),
        };
        let v = meta.to_json();
        assert_eq!(v["global"]["core:datatype"], "ci8");
        assert_eq!(v["global"]["core:sample_rate"], 4.092e6);
        assert_eq!(v["captures"][0]["core:frequency"], 1575.42e6);
        assert_eq!(v["captures"][0]["core:sample_start"], 0);
        assert!(v["annotations"].as_array().unwrap().is_empty());
        // Every non-core global key belongs to a declared extension.
        let declared: Vec<&str> = v["global"]["core:extensions"]
            .as_array()
            .unwrap()
            .iter()
            .map(|e| e["name"].as_str().unwrap())
            .collect();
        for key in v["global"].as_object().unwrap().keys() {
            let ns = key.split(':').next().unwrap();
            assert!(ns == "core" || declared.contains(&ns), "{key}");
        }
    }
}
