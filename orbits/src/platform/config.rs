//! `[platform]`: exactly one of `leo`, `ground`, `trajectory`, plus `attitude`.

use crate::platform::attitude::AttitudeConfig;
use crate::propagate::config::LeoConfig;
use std::path::PathBuf;

/// `[platform]`.
#[derive(Debug, Clone, PartialEq, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PlatformConfig {
    #[serde(default)]
    pub leo: Option<LeoConfig>,
    #[serde(default)]
    pub ground: Option<GroundConfig>,
    #[serde(default)]
    pub trajectory: Option<TrajectoryConfig>,
    #[serde(default)]
    pub attitude: AttitudeConfig,
}

/// `[platform.ground]`: a static site, by geodetic coordinates or ECEF.
#[derive(Debug, Clone, PartialEq, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GroundConfig {
    #[serde(default)]
    pub latitude_deg: Option<f64>,
    #[serde(default)]
    pub longitude_deg: Option<f64>,
    #[serde(default)]
    pub height_m: Option<f64>,
    #[serde(default)]
    pub ecef_m: Option<[f64; 3]>,
}

/// `[platform.trajectory]`: CSV with columns `t_s,x_m,y_m,z_m[,vx_mps,vy_mps,vz_mps]`
/// (ECEF, t from the scenario start).
#[derive(Debug, Clone, PartialEq, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TrajectoryConfig {
    pub csv: PathBuf,
}
