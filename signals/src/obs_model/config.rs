//! The `[observation]` table of a scenario: which level produces the observables, and the
//! observation-level noise model.

use super::calibration::Calibration;
use serde::Deserialize;
use skyforge_gnss::observation::ElevationNoise;
use skyforge_gnss::signal::Signal;
use std::path::PathBuf;

/// Where observables come from.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Level {
    /// I/Q samples through the receiver (the reference path).
    #[default]
    Signal,
    /// The link truth plus a noise model, no samples.
    Observation,
}

/// `[observation]`.
#[derive(Debug, Clone, Default, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ObservationConfig {
    #[serde(default)]
    pub level: Level,
    /// The observation-level noise (`[observation.noise]`).
    #[serde(default)]
    pub noise: ObsNoiseConfig,
    /// Observed-only signals drawn at the observation level besides each system's
    /// synthesised one (`["gps-l2", "gps-l5", "bds-b2i", "bds-b3i"]`; default none): the
    /// multi-frequency baseline models of thesis 2.4.2 and 2.4.4.
    #[serde(default)]
    pub observed_signals: Vec<Signal>,
    /// Draw Doppler noise at the observation level (the calibrated model, or the constant
    /// one with `doppler_mps`; default off: the Doppler is the truth's).
    #[serde(default)]
    pub doppler_noise: bool,
    /// Observation epochs per second at the observation level (a divisor of 1000, at most
    /// 100; default 1). The signal level's rate is the receiver's (`[observables]`).
    #[serde(default)]
    pub rate_hz: Option<u32>,
}

impl ObservationConfig {
    /// Observation epochs per second (1 unless set).
    pub fn rate_hz(&self) -> u32 {
        self.rate_hz.unwrap_or(1)
    }

    /// The interval between observation epochs (s).
    pub fn step_s(&self) -> f64 {
        1.0 / f64::from(self.rate_hz())
    }
}

/// `[observation.noise]` as written in the scenario.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(try_from = "NoiseTable")]
pub enum ObsNoiseConfig {
    /// Loop formulas at each link's C/N0 times factors measured by `skyforge calibrate`;
    /// `file` relative to the scenario, the bundled calibration when absent.
    Calibrated { file: Option<PathBuf> },
    /// Thesis eqs. 2.4-9/2.4-10, white.
    Elevation {
        phase: ElevationNoise,
        code: ElevationNoise,
    },
    /// Constant standard deviations (m), white; the Doppler's as a range rate (m/s), for
    /// `doppler_noise`.
    Constant {
        phase_m: f64,
        code_m: f64,
        doppler_mps: Option<f64>,
    },
}

/// `[observation.noise]` field by field: read as a plain table (not an internally tagged
/// enum, which serde buffers, losing the position of a bad value), then checked against
/// its `model`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct NoiseTable {
    model: NoiseModel,
    file: Option<PathBuf>,
    phase: Option<ElevationNoise>,
    code: Option<ElevationNoise>,
    phase_m: Option<f64>,
    code_m: Option<f64>,
    doppler_mps: Option<f64>,
}

/// The `model` names.
#[derive(Debug, Clone, Copy, Deserialize)]
#[serde(rename_all = "lowercase")]
enum NoiseModel {
    Calibrated,
    Elevation,
    Constant,
}

impl TryFrom<NoiseTable> for ObsNoiseConfig {
    type Error = String;

    fn try_from(t: NoiseTable) -> Result<Self, String> {
        let given = [
            ("file", t.file.is_some()),
            ("phase", t.phase.is_some()),
            ("code", t.code.is_some()),
            ("phase_m", t.phase_m.is_some()),
            ("code_m", t.code_m.is_some()),
            ("doppler_mps", t.doppler_mps.is_some()),
        ];
        let (name, fields): (&str, &[&str]) = match t.model {
            NoiseModel::Calibrated => ("calibrated", &["file"]),
            NoiseModel::Elevation => ("elevation", &["phase", "code"]),
            NoiseModel::Constant => ("constant", &["phase_m", "code_m", "doppler_mps"]),
        };
        if let Some((extra, _)) = given.iter().find(|(f, set)| *set && !fields.contains(f)) {
            return Err(format!(
                "{extra} does not belong to model = \"{name}\" (its fields: {})",
                fields.join(", ")
            ));
        }
        let missing = |f: &str| format!("model = \"{name}\" needs {f}");
        Ok(match t.model {
            NoiseModel::Calibrated => Self::Calibrated { file: t.file },
            NoiseModel::Elevation => Self::Elevation {
                phase: t.phase.ok_or_else(|| missing("phase"))?,
                code: t.code.ok_or_else(|| missing("code"))?,
            },
            NoiseModel::Constant => Self::Constant {
                phase_m: t.phase_m.ok_or_else(|| missing("phase_m"))?,
                code_m: t.code_m.ok_or_else(|| missing("code_m"))?,
                doppler_mps: t.doppler_mps,
            },
        })
    }
}

impl Default for ObsNoiseConfig {
    fn default() -> Self {
        Self::Calibrated { file: None }
    }
}

/// The noise model, resolved (the calibration file read).
#[derive(Debug, Clone, PartialEq)]
pub enum ObsNoise {
    Calibrated(Calibration),
    Elevation {
        phase: ElevationNoise,
        code: ElevationNoise,
    },
    Constant {
        phase_m: f64,
        code_m: f64,
        doppler_mps: Option<f64>,
    },
}

#[cfg(test)]
mod tests {
    use super::*;

    fn noise(text: &str) -> Result<ObsNoiseConfig, String> {
        #[derive(Deserialize)]
        struct Doc {
            noise: ObsNoiseConfig,
        }
        toml::from_str::<Doc>(text)
            .map(|d| d.noise)
            .map_err(|e| e.to_string())
    }

    #[test]
    fn each_model_takes_its_own_fields_and_a_bad_value_keeps_its_position() {
        let ok = noise("[noise]\nmodel = \"constant\"\nphase_m = 0.001\ncode_m = 0.3\n");
        assert_eq!(
            ok,
            Ok(ObsNoiseConfig::Constant {
                phase_m: 0.001,
                code_m: 0.3,
                doppler_mps: None,
            })
        );
        let e = noise("[noise]\nmodel = \"constant\"\nphase_m = 0.001\n").unwrap_err();
        assert!(e.contains("model = \"constant\" needs code_m"), "{e}");
        let e = noise("[noise]\nmodel = \"calibrated\"\nphase_m = 0.001\n").unwrap_err();
        assert!(
            e.contains("phase_m does not belong to model = \"calibrated\""),
            "{e}"
        );
        // A value of the wrong type is reported at its own line, not at the table.
        let e =
            noise("[noise]\nmodel = \"constant\"\nphase_m = \"x\"\ncode_m = 0.3\n").unwrap_err();
        assert!(e.contains("line 3"), "{e}");
    }
}
