//! The monitor's settings (TOML, docs/integrity.md).

use super::thresholds::ThresholdConfig;
use crate::config_file::read_settings;
use serde::{Deserialize, Serialize};
use skyforge_orbits::check::{GROUND_RADIUS_M, check_position};
use std::path::Path;

/// A station's antenna position, given instead of the RINEX header's approximate one.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StationPosition {
    pub name: String,
    pub position_ecef_m: [f64; 3],
}

/// What the monitor applies.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MonitorConfig {
    /// Time constant of the Hatch filter (s): paper 002 section 4.1, 100 s.
    #[serde(default = "default_smoothing_s")]
    pub smoothing_s: f64,
    /// Time constant of the divergence estimator (s). # assumed: the paper gives none;
    /// 200 s is the LAAS code-carrier divergence monitor's (Simili & Pervan 2006).
    #[serde(default = "default_divergence_s")]
    pub divergence_s: f64,
    /// Satellites below this elevation at the common point are not monitored (deg).
    /// # assumed: 10 deg, the receiver's PVT mask; the paper states none.
    #[serde(default = "default_mask_deg")]
    pub elevation_mask_deg: f64,
    /// Map the standard troposphere's delay too (besides the geometric range): stations at
    /// different heights see different delays (100 m of height: about 3 cm at the zenith,
    /// changing with elevation).
    #[serde(default = "default_troposphere")]
    pub troposphere: bool,
    /// Station antenna positions in file order (default: each file's APPROX POSITION).
    #[serde(default)]
    pub stations: Vec<StationPosition>,
    /// The common point the stations are mapped to (default: their mean position).
    #[serde(default)]
    pub common_point_ecef_m: Option<[f64; 3]>,
    pub thresholds: ThresholdConfig,
}

fn default_smoothing_s() -> f64 {
    100.0
}
fn default_divergence_s() -> f64 {
    200.0
}
fn default_troposphere() -> bool {
    true
}
fn default_mask_deg() -> f64 {
    10.0
}

impl MonitorConfig {
    /// The documented defaults with `thresholds`: no configured positions, the stations'
    /// mean as the common point.
    pub fn new(thresholds: ThresholdConfig) -> Self {
        Self {
            smoothing_s: default_smoothing_s(),
            divergence_s: default_divergence_s(),
            elevation_mask_deg: default_mask_deg(),
            troposphere: default_troposphere(),
            stations: Vec::new(),
            common_point_ecef_m: None,
            thresholds,
        }
    }

    /// Parse and check a configuration's text.
    pub fn parse(text: &str) -> Result<Self, String> {
        let config: Self = toml::from_str(text).map_err(|e| e.to_string())?;
        config.check()?;
        Ok(config)
    }

    /// Read and check the configuration at `path`; errors name the file.
    pub fn read(path: &Path) -> Result<Self, String> {
        read_settings(path, "monitor configuration", Self::parse)
    }

    /// Whether the values are usable.
    pub fn check(&self) -> Result<(), String> {
        for (name, v) in [
            ("smoothing_s", self.smoothing_s),
            ("divergence_s", self.divergence_s),
        ] {
            if !(v.is_finite() && (1e-3..=1e6).contains(&v)) {
                return Err(format!("{name} = {v}: must be in [0.001, 1e6] s"));
            }
        }
        if !(0.0..90.0).contains(&self.elevation_mask_deg) {
            return Err(format!(
                "elevation_mask_deg = {}: must be in [0, 90)",
                self.elevation_mask_deg
            ));
        }
        for (i, s) in self.stations.iter().enumerate() {
            check_position(
                &format!("stations[{i}].position_ecef_m"),
                &s.position_ecef_m,
                GROUND_RADIUS_M,
            )
            .map_err(|e| format!("station {:?}: {e}", s.name))?;
        }
        if let Some(p) = &self.common_point_ecef_m {
            check_position("common_point_ecef_m", p, GROUND_RADIUS_M).map_err(|e| e.to_string())?;
        }
        self.thresholds
            .check()
            .map_err(|e| format!("thresholds: {e}"))
    }
}
