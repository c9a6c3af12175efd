//! Tropospheric delay for receivers inside the neutral atmosphere: the scenario's choice
//! of model. The model itself (Saastamoinen zenith delays from a standard atmosphere,
//! Chao mapping; formulas and sources) is `skyforge_orbits::troposphere`, shared with the
//! receiver.
//!
//! The troposphere is not dispersive: code and carrier are both delayed by the same amount.

use skyforge_orbits::check::Invalid;

pub use skyforge_orbits::troposphere::{
    TROPOSPHERE_CEILING_M, chao_mapping, saastamoinen_zenith_m, standard_atmosphere,
};

/// Troposphere model choice.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum TropoModel {
    Saastamoinen,
    Off,
}

/// `[errors.troposphere]`.
#[derive(Debug, Clone, PartialEq, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TropoConfig {
    pub model: TropoModel,
    /// Relative humidity at sea level, 0..1 (default 0.5, Berg's standard atmosphere).
    #[serde(default = "default_rh0")]
    pub sea_level_relative_humidity: f64,
}

fn default_rh0() -> f64 {
    0.5
}

impl Default for TropoConfig {
    /// Saastamoinen with the standard atmosphere at 50 % sea-level humidity.
    fn default() -> Self {
        Self {
            model: TropoModel::Saastamoinen,
            sea_level_relative_humidity: default_rh0(),
        }
    }
}

impl TropoConfig {
    /// Checks: `sea_level_relative_humidity` in [0, 1].
    pub fn check(&self) -> Result<(), Invalid> {
        let rh = self.sea_level_relative_humidity;
        if !(0.0..=1.0).contains(&rh) {
            return Err(Invalid::new(
                "sea_level_relative_humidity",
                rh,
                "must be in [0, 1]",
            ));
        }
        Ok(())
    }

    /// Slant delay (m, code and carrier alike) for a receiver at geodetic latitude
    /// `lat_rad` and height `height_m`, satellite at elevation `el_rad`.
    pub fn delay_m(&self, lat_rad: f64, height_m: f64, el_rad: f64) -> f64 {
        match self.model {
            TropoModel::Off => 0.0,
            TropoModel::Saastamoinen => skyforge_orbits::troposphere::standard_slant_delay_m(
                lat_rad,
                height_m,
                el_rad,
                self.sea_level_relative_humidity,
            ),
        }
    }
}
