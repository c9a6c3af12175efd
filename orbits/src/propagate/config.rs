//! `[platform.leo]` configuration: initial state, force model, integrator.

use crate::check::Invalid;

/// `[platform.leo]`: exactly one of `elements`, `tle`, `state` gives the initial state.
#[derive(Debug, Clone, PartialEq, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LeoConfig {
    #[serde(default)]
    pub elements: Option<KeplerianElementsConfig>,
    #[serde(default)]
    pub tle: Option<TleConfig>,
    #[serde(default)]
    pub state: Option<StateVectorConfig>,
    #[serde(default)]
    pub forces: ForceModelConfig,
    #[serde(default)]
    pub integrator: IntegratorConfig,
}

/// Osculating Keplerian elements in the scenario ECI frame at the scenario start.
#[derive(Debug, Clone, PartialEq, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct KeplerianElementsConfig {
    pub semi_major_axis_km: f64,
    pub eccentricity: f64,
    pub inclination_deg: f64,
    pub raan_deg: f64,
    pub arg_perigee_deg: f64,
    pub mean_anomaly_deg: f64,
}

/// A two-line element set; SGP4 gives the state at the scenario start (TEME taken as the
/// scenario ECI frame, a documented simplification).
#[derive(Debug, Clone, PartialEq, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TleConfig {
    pub line1: String,
    pub line2: String,
}

/// Frame of a state vector.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum StateFrame {
    Eci,
    Ecef,
}

/// A Cartesian state at the scenario start.
#[derive(Debug, Clone, PartialEq, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StateVectorConfig {
    pub frame: StateFrame,
    pub position_m: [f64; 3],
    pub velocity_mps: [f64; 3],
}

/// Atmospheric density model.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Deserialize, Default)]
#[serde(rename_all = "kebab-case")]
pub enum DensityModel {
    /// Piecewise exponential (Vallado, table 8-4).
    #[default]
    Exponential,
    /// Harris-Priester with diurnal bulge (mean solar activity).
    HarrisPriester,
}

/// Forces acting on the LEO.
#[derive(Debug, Clone, PartialEq, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ForceModelConfig {
    #[serde(default = "yes")]
    pub j2: bool,
    /// Add J3..J6 zonal terms.
    #[serde(default)]
    pub higher_zonals: bool,
    #[serde(default = "yes")]
    pub drag: bool,
    #[serde(default)]
    pub density_model: DensityModel,
    #[serde(default = "default_cd")]
    pub drag_coefficient: f64,
    #[serde(default = "default_area")]
    pub area_m2: f64,
    #[serde(default = "default_mass")]
    pub mass_kg: f64,
}

/// Integrator tolerances.
#[derive(Debug, Clone, PartialEq, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct IntegratorConfig {
    #[serde(default = "default_rel_tol")]
    pub rel_tol: f64,
    #[serde(default = "default_abs_tol")]
    pub abs_tol_m: f64,
}

fn yes() -> bool {
    true
}
fn default_cd() -> f64 {
    2.2
}
fn default_area() -> f64 {
    1.0
}
fn default_mass() -> f64 {
    100.0
}
fn default_rel_tol() -> f64 {
    1e-12
}
fn default_abs_tol() -> f64 {
    1e-4
}

impl Default for ForceModelConfig {
    fn default() -> Self {
        Self {
            j2: true,
            higher_zonals: false,
            drag: true,
            density_model: DensityModel::default(),
            drag_coefficient: default_cd(),
            area_m2: default_area(),
            mass_kg: default_mass(),
        }
    }
}

impl Default for IntegratorConfig {
    fn default() -> Self {
        Self {
            rel_tol: default_rel_tol(),
            abs_tol_m: default_abs_tol(),
        }
    }
}

impl LeoConfig {
    /// Physical checks: exactly one initial state; e in [0, 1); perigee above the surface;
    /// positive mass, area, Cd; sane tolerances; TLE readable.
    pub fn check(&self) -> Result<(), Invalid> {
        todo!()
    }
}
