//! The settings of `skyforge relnav` (TOML, docs/orbit-determination.md).

use super::double_difference::config::DoubleDifferenceConfig;
use super::hill_filter::HillFilterConfig;
use super::single_difference::config::SingleDifferenceConfig;
use crate::config_file::read_settings;
use crate::orbit_determination::PositionFilterConfig;
use crate::pvt::SmoothingConfig;
use serde::Deserialize;
use skyforge_gnss::signal::Signal;
use std::path::Path;

/// How the relative state is formed (module docs).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Default)]
#[serde(rename_all = "kebab-case")]
pub enum RelnavMode {
    /// Book eq. 5-56: each vehicle's own fix, differenced.
    Standalone,
    /// Book eq. 5-57's measurement: fixes on the common satellites, differenced.
    #[default]
    PositionDifference,
    /// Book eqs. 5-60..5-64 then as `PositionDifference`.
    CarrierSmoothed,
    /// Double-difference carrier phase and code between the spacecraft with integer
    /// ambiguities (beyond the book; `relnav::double_difference`).
    DoubleDifference,
    /// Book eq. 5-59: a filter on the single differences of pseudorange and range rate
    /// (`relnav::single_difference`).
    SingleDifference,
}

impl RelnavMode {
    /// The name the configuration and the outputs use.
    pub fn name(self) -> &'static str {
        match self {
            RelnavMode::Standalone => "standalone",
            RelnavMode::PositionDifference => "position-difference",
            RelnavMode::CarrierSmoothed => "carrier-smoothed",
            RelnavMode::DoubleDifference => "double-difference",
            RelnavMode::SingleDifference => "single-difference",
        }
    }
}

/// Which satellites each vehicle's fix uses in mode `carrier-smoothed`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Default)]
#[serde(rename_all = "kebab-case")]
pub enum SatelliteSets {
    /// Both fixes on the satellites both use, each smoother restarted where a satellite
    /// leaves the common set (the module docs of `relnav`).
    #[default]
    Common,
    /// The book's procedure (5.6.5): each vehicle smooths its own pseudoranges along its
    /// own tracks and fixes on the satellites it tracks; the target sends its state and
    /// the chaser differences. The two sets differ where one vehicle has lost a
    /// satellite the other still uses (the book's figures' events at 39 and 164 s).
    Own,
}

/// What relative navigation runs with.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RelnavConfig {
    #[serde(default)]
    pub mode: RelnavMode,
    /// The signals the fixes use; empty: every signal both files have.
    #[serde(default)]
    pub signals: Vec<Signal>,
    /// Satellites below this elevation are not used (deg), as the receiver's PVT.
    #[serde(default = "default_mask_deg")]
    pub elevation_mask_deg: f64,
    /// The carrier smoother's noise figures (mode `carrier-smoothed`).
    #[serde(default)]
    pub smoothing: SmoothingConfig,
    /// Whose satellites the fixes use (mode `carrier-smoothed`).
    #[serde(default)]
    pub satellite_sets: SatelliteSets,
    /// The target's own orbit filter (`skyforge od`'s position filter on its fixes,
    /// every epoch): its state orients the target frame (eq. 5-55's `M` and the frame's
    /// rate). One fix's Doppler velocity would turn the frame by its noise: 0.4 m/s of
    /// 7.6 km/s is 5e-5 rad, 1.7 m across a 32 km separation.
    #[serde(default)]
    pub target_orbit: PositionFilterConfig,
    /// The double-difference filter (mode `double-difference`).
    #[serde(default)]
    pub double_difference: DoubleDifferenceConfig,
    /// The single-difference filter (mode `single-difference`, book eq. 5-59).
    #[serde(default)]
    pub single_difference: SingleDifferenceConfig,
    /// `[filter]`: the book's relative filter (eqs. 5-57/5-58 with the Hill dynamics of
    /// eq. 5-34 about the target's orbit) on the differenced fixes of modes
    /// `standalone`, `position-difference` and `carrier-smoothed`; absent: the
    /// differences as they are.
    #[serde(default)]
    pub filter: Option<HillFilterConfig>,
}

fn default_mask_deg() -> f64 {
    10.0
}

impl Default for RelnavConfig {
    fn default() -> Self {
        Self {
            mode: RelnavMode::default(),
            signals: Vec::new(),
            elevation_mask_deg: default_mask_deg(),
            smoothing: SmoothingConfig::default(),
            satellite_sets: SatelliteSets::default(),
            target_orbit: PositionFilterConfig::default(),
            double_difference: DoubleDifferenceConfig::default(),
            single_difference: SingleDifferenceConfig::default(),
            filter: None,
        }
    }
}

impl RelnavConfig {
    /// Parse and check a configuration's text.
    pub fn parse(text: &str) -> Result<Self, String> {
        let config: Self = toml::from_str(text).map_err(|e| e.to_string())?;
        if !(0.0..90.0).contains(&config.elevation_mask_deg) {
            return Err(format!(
                "elevation_mask_deg = {}: must be in [0, 90)",
                config.elevation_mask_deg
            ));
        }
        config
            .target_orbit
            .check()
            .map_err(|e| format!("target_orbit.{e}"))?;
        config
            .double_difference
            .check()
            .map_err(|e| e.to_string())?;
        config.single_difference.check()?;
        if config.satellite_sets == SatelliteSets::Own && config.mode != RelnavMode::CarrierSmoothed
        {
            return Err(format!(
                "satellite_sets = \"own\": only with mode \"carrier-smoothed\" (mode \"{}\"; \
                 mode \"standalone\" is each vehicle's own satellites without smoothing)",
                config.mode.name()
            ));
        }
        if let Some(filter) = &config.filter {
            let own = match config.mode {
                RelnavMode::DoubleDifference => Some("double_difference"),
                RelnavMode::SingleDifference => Some("single_difference"),
                _ => None,
            };
            if let Some(table) = own {
                return Err(format!(
                    "filter: the book's relative filter takes the differenced fixes of modes \
                     standalone, position-difference and carrier-smoothed; mode {} is itself \
                     a filter ([{table}])",
                    config.mode.name()
                ));
            }
            filter.check().map_err(|e| format!("filter.{e}"))?;
        }
        let s = &config.smoothing;
        crate::config_file::check_positive(&[
            ("smoothing.code_sigma_m", s.code_sigma_m, 1e4),
            ("smoothing.phase_sigma_m", s.phase_sigma_m, 1e4),
            ("smoothing.max_gap_s", s.max_gap_s, 1e4),
        ])?;
        Ok(config)
    }

    /// Read and check the configuration at `path`; errors name the file.
    pub fn read(path: &Path) -> Result<Self, String> {
        read_settings(path, "relative-navigation configuration", Self::parse)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn modes_and_checks() {
        assert_eq!(RelnavConfig::parse("").unwrap(), RelnavConfig::default());
        let c =
            RelnavConfig::parse("mode = \"carrier-smoothed\"\n[smoothing]\ncode_sigma_m = 2.0\n")
                .unwrap();
        assert_eq!(c.mode, RelnavMode::CarrierSmoothed);
        assert_eq!(c.smoothing.code_sigma_m, 2.0);
        let c = RelnavConfig::parse(
            "mode = \"double-difference\"\n[double_difference]\nratio_threshold = 2.5\n",
        )
        .unwrap();
        assert_eq!(c.mode, RelnavMode::DoubleDifference);
        assert_eq!(c.double_difference.ratio_threshold, 2.5);
        assert_eq!(c.double_difference.min_success_rate, 0.999);
        let c = RelnavConfig::parse(
            "mode = \"single-difference\"\n[single_difference]\ncode_sigma_m = 2.0\n",
        )
        .unwrap();
        assert_eq!(c.mode, RelnavMode::SingleDifference);
        assert_eq!(c.mode.name(), "single-difference");
        assert_eq!(c.single_difference.code_sigma_m, 2.0);
        assert_eq!(c.single_difference.range_rate_sigma_mps, 0.21);
        let c = RelnavConfig::parse("[filter]\nacceleration_sigma_mps2 = 1e-6\n").unwrap();
        assert_eq!(c.filter.unwrap().acceleration_sigma_mps2, 1e-6);
        let c =
            RelnavConfig::parse("mode = \"carrier-smoothed\"\nsatellite_sets = \"own\"\n").unwrap();
        assert_eq!(c.satellite_sets, SatelliteSets::Own);
        for (text, names) in [
            (
                "satellite_sets = \"own\"",
                "satellite_sets = \"own\": only with mode \"carrier-smoothed\" (mode \"position-difference\"",
            ),
            (
                "mode = \"carrier-smoothed\"\nsatellite_sets = \"theirs\"",
                "theirs",
            ),
            ("mode = \"kalman\"", "kalman"),
            ("elevation_mask_deg = 90", "elevation_mask_deg = 90"),
            (
                "[smoothing]\ncode_sigma_m = 0",
                "smoothing.code_sigma_m = 0",
            ),
            ("mod = \"standalone\"", "mod"),
            (
                "[double_difference]\nratio_threshold = 0.5",
                "double_difference.ratio_threshold = 0.5: must be in [1, 1000000]",
            ),
            (
                "[double_difference]\nphase = { sigma0_m = 0.0, a0 = 0.0, elev0_deg = 10.0 }",
                "double_difference.phase.sigma0_m = 0",
            ),
            (
                "[double_difference]\nacceleration_sigma_mps2 = -1",
                "double_difference.acceleration_sigma_mps2 = -1",
            ),
            (
                "[filter]\nposition_sigma_m = 0",
                "filter.position_sigma_m = 0",
            ),
            (
                "mode = \"double-difference\"\n[filter]\n",
                "filter: the book's relative filter",
            ),
            (
                "mode = \"single-difference\"\n[filter]\n",
                "mode single-difference is itself a filter ([single_difference])",
            ),
            (
                "[single_difference]\ncode_sigma_m = 0",
                "single_difference.code_sigma_m = 0: must be in (0, 10000]",
            ),
            (
                "[single_difference]\nrange_rate_sigma_mps = nan",
                "single_difference.range_rate_sigma_mps = NaN: must be in (0, 1000]",
            ),
            (
                "[single_difference]\nacceleration_sigma_mps2 = 2",
                "single_difference.acceleration_sigma_mps2 = 2: must be in (0, 1]",
            ),
            (
                "[single_difference]\nclock_sigma_m_per_sqrt_s = -1",
                "single_difference.clock_sigma_m_per_sqrt_s = -1: must be in (0, 1000000]",
            ),
            (
                "[single_difference]\nclock_drift_sigma_mps_per_sqrt_s = 0",
                "single_difference.clock_drift_sigma_mps_per_sqrt_s = 0: must be in (0, 10000]",
            ),
            (
                "[single_difference.forces]\narea_m2 = 0",
                "single_difference.forces.area_m2 = 0",
            ),
            ("[single_difference]\ncode_sigma = 1", "code_sigma"),
        ] {
            let e = RelnavConfig::parse(text).unwrap_err();
            assert!(e.contains(names), "{text}: {e}");
        }
    }
}
