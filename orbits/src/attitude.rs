//! Attitude profiles: yaw/pitch/roll relative to the platform's reference frame, constant,
//! per-axis sinusoid, or read from CSV.

use crate::frames::euler::YawPitchRoll;
use std::path::PathBuf;

/// One axis: `offset + amplitude * sin(2 pi t / period + phase)`; `period_s = 0` means
/// constant `offset`.
#[derive(Debug, Clone, PartialEq, Default, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AxisProfileConfig {
    #[serde(default)]
    pub offset_deg: f64,
    #[serde(default)]
    pub amplitude_deg: f64,
    #[serde(default)]
    pub period_s: f64,
    #[serde(default)]
    pub phase_deg: f64,
}

/// `[platform.attitude]`: per-axis profiles, or a CSV `t_s,yaw_deg,pitch_deg,roll_deg`.
#[derive(Debug, Clone, PartialEq, Default, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AttitudeConfig {
    #[serde(default)]
    pub yaw: AxisProfileConfig,
    #[serde(default)]
    pub pitch: AxisProfileConfig,
    #[serde(default)]
    pub roll: AxisProfileConfig,
    #[serde(default)]
    pub csv: Option<PathBuf>,
}

/// A resolved attitude profile.
#[derive(Debug, Clone)]
pub enum AttitudeProfile {}

impl AttitudeProfile {
    /// Attitude at `t_s`.
    pub fn at(&self, t_s: f64) -> YawPitchRoll {
        todo!("{t_s}")
    }
}
