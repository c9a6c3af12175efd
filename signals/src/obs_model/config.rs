//! The `[observation]` table of a scenario: which level produces the observables, and the
//! observation-level noise model.

use super::calibration::Calibration;
use crate::observation::ElevationNoise;
use serde::Deserialize;
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
}

/// `[observation.noise]` as written in the scenario.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(tag = "model", rename_all = "lowercase", deny_unknown_fields)]
pub enum ObsNoiseConfig {
    /// Loop formulas at each link's C/N0 times factors measured by `skyforge calibrate`;
    /// `file` relative to the scenario, the bundled calibration when absent.
    Calibrated { file: Option<PathBuf> },
    /// Thesis eqs. 2.4-9/2.4-10, white.
    Elevation {
        phase: ElevationNoise,
        code: ElevationNoise,
    },
    /// Constant standard deviations (m), white.
    Constant { phase_m: f64, code_m: f64 },
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
    },
}
