//! The settings of `skyforge od` (TOML, docs/orbit-determination.md): which fixes the
//! filter takes and which filter it is.

use super::PositionFilterConfig;
use super::reduced_dynamic::ReducedDynamicConfig;
use crate::config_file::read_settings;
use serde::Deserialize;
use skyforge_gnss::signal::Signal;
use std::path::Path;

/// What orbit determination runs on and with.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OdConfig {
    /// Fixes are taken every `interval_s` seconds of the run (epochs on that grid).
    /// # assumed: 10 s; the book's best was 50-60 s against SA's 150 s correlation, and
    /// today's errors are closer to white, so shorter is better (docs).
    #[serde(default = "default_interval_s")]
    pub interval_s: f64,
    /// The signals the fixes use; empty: every signal the file has.
    #[serde(default)]
    pub signals: Vec<Signal>,
    /// Satellites below this elevation are not used (deg), as the receiver's PVT.
    #[serde(default = "default_mask_deg")]
    pub elevation_mask_deg: f64,
    /// The filter.
    #[serde(default)]
    pub filter: OdFilterConfig,
}

/// The orbit-determination filter, chosen by `kind`.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(tag = "kind", rename_all = "kebab-case", deny_unknown_fields)]
pub enum OdFilterConfig {
    /// The book's position filter on single-point fixes (section 5.5.4).
    PositionFilter(PositionFilterConfig),
    /// The reduced-dynamic extended Kalman filter on the raw observations.
    ReducedDynamic(ReducedDynamicConfig),
}

impl Default for OdFilterConfig {
    fn default() -> Self {
        Self::PositionFilter(PositionFilterConfig::default())
    }
}

fn default_interval_s() -> f64 {
    10.0
}
fn default_mask_deg() -> f64 {
    10.0
}

impl Default for OdConfig {
    fn default() -> Self {
        Self {
            interval_s: default_interval_s(),
            signals: Vec::new(),
            elevation_mask_deg: default_mask_deg(),
            filter: OdFilterConfig::default(),
        }
    }
}

impl OdConfig {
    /// Parse and check a configuration's text.
    pub fn parse(text: &str) -> Result<Self, String> {
        let config: Self = toml::from_str(text).map_err(|e| e.to_string())?;
        config.check()?;
        Ok(config)
    }

    /// Read and check the configuration at `path`; errors name the file.
    pub fn read(path: &Path) -> Result<Self, String> {
        read_settings(path, "orbit-determination configuration", Self::parse)
    }

    /// Whether the values are usable: each names the field, its value and what is allowed.
    pub fn check(&self) -> Result<(), String> {
        if !(self.interval_s.is_finite() && (0.01..=86_400.0).contains(&self.interval_s)) {
            return Err(format!(
                "interval_s = {}: must be in [0.01, 86400] s",
                self.interval_s
            ));
        }
        if !(0.0..90.0).contains(&self.elevation_mask_deg) {
            return Err(format!(
                "elevation_mask_deg = {}: must be in [0, 90)",
                self.elevation_mask_deg
            ));
        }
        match &self.filter {
            OdFilterConfig::PositionFilter(p) => p.check(),
            OdFilterConfig::ReducedDynamic(r) => r.check(),
        }
        .map_err(|e| format!("filter.{e}"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn empty_text_is_the_documented_default() {
        assert_eq!(OdConfig::parse("").unwrap(), OdConfig::default());
    }

    #[test]
    fn position_filter_settings_and_forces_are_read() {
        let c = OdConfig::parse(
            "interval_s = 60\nsignals = [\"gps-l1ca\"]\n[filter]\nkind = \"position-filter\"\n\
             position_sigma_m = 18.6\n[filter.forces]\ndrag = false\n",
        )
        .unwrap();
        assert_eq!(c.interval_s, 60.0);
        assert_eq!(c.signals, [Signal::GpsL1Ca]);
        let OdFilterConfig::PositionFilter(p) = c.filter else {
            panic!("{:?}", c.filter)
        };
        assert_eq!(p.position_sigma_m, 18.6);
        assert!(!p.forces.drag && p.forces.j2);
        assert_eq!(
            p.velocity_sigma_mps,
            PositionFilterConfig::default().velocity_sigma_mps
        );
    }

    #[test]
    fn reduced_dynamic_settings_are_read_and_checked() {
        let c = OdConfig::parse(
            "[filter]\nkind = \"reduced-dynamic\"\nionosphere = \"dual-frequency\"\n\
             satellite_sigma_m = 0.05\n[filter.observables]\ncarrier = true\n",
        )
        .unwrap();
        let OdFilterConfig::ReducedDynamic(r) = c.filter else {
            panic!("{:?}", c.filter)
        };
        assert!(r.observables.carrier && r.observables.doppler);
        assert_eq!(
            r.ionosphere,
            crate::pvt::IonosphereCorrection::DualFrequency
        );
        assert_eq!(r.satellite_sigma_m, 0.05);
        assert_eq!(r.code_sigma_m, ReducedDynamicConfig::default().code_sigma_m);
        for (text, names) in [
            ("phase_sigma_m = 0", "filter.phase_sigma_m = 0"),
            ("empirical_tau_s = -1", "filter.empirical_tau_s = -1"),
            ("[filter.forces]\nmass_kg = 0", "filter.forces.mass_kg = 0"),
            ("code_sigma = 1", "code_sigma"),
        ] {
            let text = format!("[filter]\nkind = \"reduced-dynamic\"\n{text}");
            let e = OdConfig::parse(&text).unwrap_err();
            assert!(e.contains(names), "{text}: {e}");
        }
    }

    #[test]
    fn bad_values_and_unknown_keys_are_refused_by_name() {
        for (text, names) in [
            ("interval_s = 0", "interval_s = 0"),
            ("elevation_mask_deg = 95", "elevation_mask_deg = 95"),
            ("[filter]\nkind = \"ekf\"", "ekf"),
            (
                "[filter]\nkind = \"position-filter\"\nposition_sigma_m = -1",
                "position_sigma_m = -1",
            ),
            ("intervl_s = 10", "intervl_s"),
        ] {
            let e = OdConfig::parse(text).unwrap_err();
            assert!(e.contains(names), "{text}: {e}");
        }
    }
}
