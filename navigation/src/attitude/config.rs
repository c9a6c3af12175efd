//! Settings of the attitude stage (`[attitude]`): which stage runs and its parameters.

use super::AttitudeError;
use super::least_squares::LsConfig;

/// Which attitude stage runs (`[stages] attitude` in a receiver TOML, later).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Deserialize, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum AttitudeMethod {
    /// Epoch-by-epoch iterated LS (eqs. 2.5-9..2.5-13), no rates (default).
    #[default]
    LeastSquares,
    /// The real-time KF of eqs. 2.5-16, 2.5-17, an EKF (linearised with J(xi)).
    Kf,
    /// The UKF of eqs. 4.3-16..4.3-32.
    Ukf,
}

/// Thesis section 4.3: the sigma-point spread kappa of its UKF simulations.
pub const THESIS_KAPPA: f64 = 0.5;

/// Settings of the attitude stage.
#[derive(Debug, Clone, Copy, PartialEq, serde::Deserialize, serde::Serialize)]
#[serde(default, deny_unknown_fields)]
pub struct AttitudeConfig {
    /// `least-squares`, `kf` or `ukf`.
    pub method: AttitudeMethod,
    /// Power spectral densities `S` of the yaw, pitch and roll accelerations
    /// (rad^2/s^3), eqs. 2.5-16 / 4.3-30. Default 1e-8 each (# assumed: the thesis gives
    /// no value; 1e-4 rad/s^2 of acceleration noise over 1 s, a slowly turning LEO).
    pub rate_psd_rad2_s3: [f64; 3],
    /// 1-sigma of the rates when a filter starts from its first LS attitude (rad/s).
    /// Default 0.01 rad/s (0.57 deg/s).
    pub initial_rate_sigma_rad_s: f64,
    /// UKF sigma-point spread kappa (eqs. 4.3-18..4.3-20), `6 + kappa > 0`. Default 0.5,
    /// the thesis's value.
    pub kappa: f64,
    /// The LS (the `least-squares` stage, and the filters' first epoch).
    pub least_squares: LsConfig,
}

impl Default for AttitudeConfig {
    fn default() -> Self {
        Self {
            method: AttitudeMethod::default(),
            rate_psd_rad2_s3: [1e-8; 3],
            initial_rate_sigma_rad_s: 0.01,
            kappa: THESIS_KAPPA,
            least_squares: LsConfig::default(),
        }
    }
}

impl AttitudeConfig {
    /// Every value finite; S >= 0, the rate sigma > 0, 6 + kappa > 0; the LS settings.
    pub fn check(&self) -> Result<(), AttitudeError> {
        if !settings_ok(
            6,
            &self.rate_psd_rad2_s3,
            self.initial_rate_sigma_rad_s,
            self.kappa,
        ) {
            return Err(AttitudeError::Config(format!(
                "rate_psd_rad2_s3 must be finite and >= 0, initial_rate_sigma_rad_s finite and > 0, kappa finite with 6 + kappa > 0; got {self:?}"
            )));
        }
        self.least_squares.check()
    }
}

/// The settings a constant-rate filter of `states` states shares: spectral densities `S`
/// finite and >= 0, the starting rate sigma finite and > 0, `states + kappa > 0`.
pub(crate) fn settings_ok(states: usize, psd: &[f64], rate_sigma: f64, kappa: f64) -> bool {
    psd.iter().all(|s| s.is_finite() && *s >= 0.0)
        && rate_sigma.is_finite()
        && rate_sigma > 0.0
        && kappa.is_finite()
        && states as f64 + kappa > 0.0
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn config_from_toml_rejects_unknown_fields() {
        let c: AttitudeConfig =
            toml::from_str("method = \"ukf\"\nrate_psd_rad2_s3 = [1e-6, 1e-6, 2e-6]\n").unwrap();
        assert_eq!(c.method, AttitudeMethod::Ukf);
        assert_eq!(c.kappa, THESIS_KAPPA);
        assert!(toml::from_str::<AttitudeConfig>("methd = \"kf\"").is_err());
        // The example of docs/attitude.md.
        let doc: AttitudeConfig = toml::from_str(
            "method = \"ukf\"\nrate_psd_rad2_s3 = [1e-8, 1e-8, 1e-8]\ninitial_rate_sigma_rad_s = 0.01\nkappa = 0.5\n[least_squares]\ntolerance_rad = 1e-12\nmax_iterations = 50\n",
        )
        .unwrap();
        assert_eq!(
            doc,
            AttitudeConfig {
                method: AttitudeMethod::Ukf,
                ..AttitudeConfig::default()
            }
        );
        assert!(toml::from_str::<AttitudeConfig>("[least_squares]\ntol = 1.0").is_err());
        assert!(toml::from_str::<AttitudeConfig>("method = \"ekf\"").is_err());
        let bad = AttitudeConfig {
            kappa: -7.0,
            ..AttitudeConfig::default()
        };
        assert!(bad.check().is_err());
    }
}
