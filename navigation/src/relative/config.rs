//! Settings of the relative-positioning and attitude chain (`[relative]` of a TOML file).

use crate::attitude::config::{AttitudeConfig, THESIS_KAPPA};
use crate::baseline::{ElevationNoise, NoiseModel};
use crate::geometry_offset::stacked_ukf::OffsetConfig;
use serde::Deserialize;
use skyforge_gnss::observation::WEIGHT_SIGMA0_M;
use skyforge_gnss::signal::Signal;
use skyforge_orbits::bounded_read::read_text;

/// `[relative]`.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct RelativeConfig {
    /// Signals used (`gps-l1ca`, `bds-b1i`, `gps-l2`); default the two SkyForge
    /// synthesises. Every signal listed of a system must be observed on a satellite for
    /// it to enter the double differences.
    pub signals: Vec<Signal>,
    /// Weighting of the double differences: thesis eqs. 2.4-9/2.4-10 for phase and code.
    pub phase: ElevationNoise,
    pub code: ElevationNoise,
    /// Integers are accepted when the second-best squared norm is at least this many
    /// times the best (ratio test).
    pub ratio_threshold: f64,
    /// ... and the bootstrapped success rate of the decorrelated problem at least this.
    pub min_success_rate: f64,
    /// Keep accepted integers between epochs while the phase stays locked.
    pub hold: bool,
    /// `geometry`: search the integers under the known body geometry (multivariate
    /// constrained ILS, two or more baselines); `length`: under the known length of each
    /// baseline only (C-LAMBDA per baseline, any number of baselines); `none`: plain
    /// LAMBDA with the ratio test and the success-rate floor.
    pub constraint: Constraint,
    /// Carry the float ambiguities from epoch to epoch (constant ambiguities, the
    /// baselines new at every epoch: a kinematic filter's memory,
    /// [`crate::baseline::memory`]); a satellite's are forgotten when it loses lock.
    /// Default off: the thesis's chain solves every epoch on its own and holds only
    /// fixed integers.
    pub float_memory: bool,
    /// Held integers are dropped when their fit to the epoch's float solution exceeds
    /// the chi-square quantile of this false-alarm probability.
    pub hold_test_pfa: f64,
    /// Satellites below this elevation (deg) above the master's horizon are left out of
    /// the double differences. Default none (# assumed: on a LEO the local horizon does
    /// not bound tracking); a ground user sets one (e.g. 15).
    pub elevation_mask_deg: Option<f64>,
    /// Model the difference of the antennas' tropospheric delays in the chain over files
    /// ([`super::troposphere`]: the master's slant-delay gradient in the double-difference
    /// design, Saastamoinen with the standard atmosphere and Chao mapping). Ground
    /// stations apart see a satellite at different elevations (1.7 cm of slant delay at
    /// 15 deg over 3.3 km) and from different heights (0.3 mm per metre at the zenith);
    /// zero above 50 km, so a LEO platform's results do not change. Default on.
    pub troposphere: bool,
    /// The attitude stage.
    pub attitude: AttitudeConfig,
    /// The geometry-offset estimator (`skyforge attitude --estimate-geometry`).
    pub geometry_offsets: OffsetConfig,
    /// The reverse filtering of the baselines between the fix and the attitude (thesis
    /// 5.5, [`super::reverse`]; two baselines): present turns it on. Default none.
    pub reverse_filter: Option<ReverseConfig>,
}

/// What the integer search knows besides the float solution.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Constraint {
    /// Plain LAMBDA.
    None,
    /// The whole body geometry ([`super::search::multivariate`]).
    Geometry,
    /// The baseline lengths ([`super::search::length`]).
    Length,
}

impl Default for RelativeConfig {
    fn default() -> Self {
        // assumed: equal weights (a0 = 0): on a LEO the elevation above the local horizon
        // does not set the noise (satellites below it are tracked at full C/N0); a ground
        // user sets the elevation model of eqs. 2.4-9/2.4-10. Sigmas of a 45 dB-Hz
        // receiver: 2 mm phase, 0.3 m code.
        let elevation = |sigma0_m| ElevationNoise {
            sigma0_m,
            a0: 0.0,
            elev0_deg: 10.0,
        };
        Self {
            signals: Signal::DEFAULT_FIX.to_vec(),
            phase: elevation(0.002),
            code: elevation(0.3),
            ratio_threshold: 3.0,
            min_success_rate: 0.999,
            hold: true,
            constraint: Constraint::Geometry,
            float_memory: false,
            hold_test_pfa: 1e-4,
            elevation_mask_deg: None,
            troposphere: true,
            attitude: AttitudeConfig::default(),
            geometry_offsets: OffsetConfig::default(),
            reverse_filter: None,
        }
    }
}

impl RelativeConfig {
    /// The double-difference weighting model.
    pub fn noise_model(&self) -> NoiseModel {
        NoiseModel::new(self.phase, self.code)
    }
}

/// A TOML file with an optional `[relative]` table (other tables are the receiver's).
#[derive(Debug, Default, Deserialize)]
struct RelativeFile {
    #[serde(default)]
    relative: Option<RelativeConfig>,
}

/// Largest configuration file read (bytes).
const MAX_CONFIG_BYTES: u64 = 1 << 20;

impl RelativeConfig {
    /// The `[relative]` table of the TOML file at `path` (defaults without one); the
    /// error names the file and what is wrong.
    pub fn read(path: &std::path::Path) -> Result<Self, String> {
        let error = |e: &dyn std::fmt::Display| format!("{}: {e}", path.display());
        let text =
            read_text(path, MAX_CONFIG_BYTES, "configuration file").map_err(|e| error(&e))?;
        let file: RelativeFile = toml::from_str(&text).map_err(|e| error(&e))?;
        let config = file.relative.unwrap_or_default();
        for (key, noise) in [
            ("relative.phase", config.phase),
            ("relative.code", config.code),
        ] {
            noise.check(key, WEIGHT_SIGMA0_M).map_err(|e| error(&e))?;
        }
        let table =
            |key: &'static str| move |e: &dyn std::fmt::Display| error(&format!("{key}: {e}"));
        config
            .attitude
            .check()
            .map_err(|e| table("relative.attitude")(&e))?;
        config
            .geometry_offsets
            .check()
            .map_err(|e| table("relative.geometry_offsets")(&e))?;
        if let Some(r) = &config.reverse_filter {
            r.check()
                .map_err(|e| table("relative.reverse_filter")(&e))?;
        }
        let positive = [
            ("relative.ratio_threshold", config.ratio_threshold),
            ("relative.min_success_rate", config.min_success_rate),
            ("relative.hold_test_pfa", config.hold_test_pfa),
        ];
        for (name, v) in positive {
            if !(v.is_finite() && v > 0.0) {
                return Err(error(&format!("{name} = {v}: must be a positive number")));
            }
        }
        if config.min_success_rate > 1.0 || config.hold_test_pfa >= 1.0 {
            return Err(error(
                &"relative.min_success_rate must be at most 1 and relative.hold_test_pfa below 1",
            ));
        }
        if let Some(m) = config.elevation_mask_deg
            && !(m.is_finite() && (-90.0..=90.0).contains(&m))
        {
            return Err(error(&format!(
                "relative.elevation_mask_deg = {m}: must be between -90 and 90"
            )));
        }
        if config.signals.is_empty() {
            return Err(error(&"relative.signals: at least one signal"));
        }
        Ok(config)
    }
}

/// `reverse_filter` of `[relative]`: the reverse filter's settings (thesis 5.5;
/// `ReverseConfig::check` beside the filter in `reverse.rs`).
#[derive(Debug, Clone, Copy, PartialEq, serde::Deserialize, serde::Serialize)]
#[serde(default, deny_unknown_fields)]
pub struct ReverseConfig {
    /// `S` of eq. 5.5-7 for x1, y1, z1, x2, y2, z2 (ECEF, m^2/s^3). Default 1e-6 each
    /// (# assumed: the thesis gives no value; 1e-3 m/s^2 of acceleration noise over 1 s,
    /// a 1 m baseline turning with about 1 mrad/s^2).
    pub rate_psd_m2_s3: [f64; 6],
    /// 1-sigma of the baseline rates when the filter starts (m/s). Default 0.1 m/s
    /// (# assumed: a 1 m baseline turning at up to 6 deg/s).
    pub initial_rate_sigma_m_s: f64,
    /// Sigma-point spread kappa (eqs. 5.5-12..5.5-14), `12 + kappa > 0`. Default 0.5, the
    /// thesis's value.
    pub kappa: f64,
}

impl Default for ReverseConfig {
    fn default() -> Self {
        Self {
            rate_psd_m2_s3: [1e-6; 6],
            initial_rate_sigma_m_s: 0.1,
            kappa: THESIS_KAPPA,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn constraint(text: &str) -> Result<Constraint, String> {
        let file: RelativeFile = toml::from_str(text).map_err(|e| e.to_string())?;
        Ok(file.relative.unwrap_or_default().constraint)
    }

    #[test]
    fn constraint_values_parse_in_lowercase() {
        for (value, expected) in [
            ("none", Constraint::None),
            ("geometry", Constraint::Geometry),
            ("length", Constraint::Length),
        ] {
            let text = format!("[relative]\nconstraint = \"{value}\"\n");
            assert_eq!(constraint(&text), Ok(expected), "{value}");
        }
        assert_eq!(constraint(""), Ok(Constraint::Geometry));
        let bad = constraint("[relative]\nconstraint = \"Length\"\n").unwrap_err();
        assert!(bad.contains("length"), "{bad}");
    }

    /// Each setting outside its domain is one error naming the file, the key, the value
    /// and what is allowed.
    #[test]
    fn settings_outside_their_domain_are_refused_by_key() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("rel.toml");
        let cases = [
            (
                "phase = { sigma0_m = 0.0, a0 = 0.0, elev0_deg = 10.0 }",
                "relative.phase.sigma0_m = 0: must be in (0, 100] m",
            ),
            (
                "code = { sigma0_m = -0.3, a0 = 0.0, elev0_deg = 10.0 }",
                "relative.code.sigma0_m = -0.3",
            ),
            (
                "phase = { sigma0_m = 0.002, a0 = -1.0, elev0_deg = 10.0 }",
                "relative.phase.a0 = -1: must be in [0, 100]",
            ),
            (
                "phase = { sigma0_m = 1e300, a0 = 0.0, elev0_deg = 10.0 }",
                "relative.phase.sigma0_m = 1e300: must be in (0, 100] m",
            ),
            (
                "code = { sigma0_m = 0.3, a0 = 1e300, elev0_deg = 10.0 }",
                "relative.code.a0 = 1e300: must be in [0, 100]",
            ),
            (
                "code = { sigma0_m = 0.3, a0 = 1.0, elev0_deg = 1e300 }",
                "relative.code.elev0_deg = 1e300: must be in (0, 90] deg",
            ),
            (
                "code = { sigma0_m = 0.3, a0 = 1.0, elev0_deg = 0.0 }",
                "relative.code.elev0_deg = 0: must be in (0, 90] deg",
            ),
            (
                "reverse_filter = { rate_psd_m2_s3 = [1e300, 0, 0, 0, 0, 0] }",
                "relative.reverse_filter: reverse baseline filter: rate_psd_m2_s3[0] = 1e300: allowed 0 to 1e6",
            ),
            (
                "attitude = { initial_rate_sigma_rad_s = 0.0 }",
                "relative.attitude: attitude config: initial_rate_sigma_rad_s = 0e0: allowed above 0",
            ),
            (
                "geometry_offsets = { period_s = -1.0 }",
                "relative.geometry_offsets: attitude config: period_s = -1: must be finite and above 0",
            ),
        ];
        for (line, expected) in cases {
            std::fs::write(&path, format!("[relative]\n{line}\n")).unwrap();
            let e = RelativeConfig::read(&path).unwrap_err();
            assert!(e.starts_with(&format!("{}: ", path.display())), "{e}");
            assert!(e.contains(expected), "{line}: {e}");
        }
        std::fs::write(
            &path,
            "[relative]\nphase = { sigma0_m = 0.002, a0 = 0.0, elev0_deg = 10.0 }\n",
        )
        .unwrap();
        assert!(RelativeConfig::read(&path).is_ok());
    }

    #[test]
    fn the_reverse_filter_is_off_unless_its_table_is_given() {
        let read = |text: &str| -> Result<RelativeConfig, String> {
            let file: RelativeFile = toml::from_str(text).map_err(|e| e.to_string())?;
            Ok(file.relative.unwrap_or_default())
        };
        assert_eq!(read("").unwrap().reverse_filter, None);
        let on = read("[relative]\nreverse_filter = {}\n").unwrap();
        assert_eq!(on.reverse_filter, Some(ReverseConfig::default()));
        // The example of docs/attitude.md.
        let doc = read(
            "[relative]\nreverse_filter = { rate_psd_m2_s3 = [1e-6, 1e-6, 1e-6, 1e-6, 1e-6, 1e-6], initial_rate_sigma_m_s = 0.1, kappa = 0.5 }\n",
        )
        .unwrap();
        assert_eq!(doc.reverse_filter, Some(ReverseConfig::default()));
        assert!(read("[relative]\nreverse_filter = { kappa = 0.5, q = 1 }\n").is_err());
    }
}
