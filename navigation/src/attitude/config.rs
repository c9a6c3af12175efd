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
    /// The filter settings in their domain ([`check_filter`], `6 + kappa > 0`); the LS
    /// settings.
    pub fn check(&self) -> Result<(), AttitudeError> {
        check_filter(
            6,
            ("rate_psd_rad2_s3", &self.rate_psd_rad2_s3),
            ("initial_rate_sigma_rad_s", self.initial_rate_sigma_rad_s),
            self.kappa,
        )
        .map_err(AttitudeError::Config)?;
        self.least_squares.check()
    }
}

/// Largest power spectral density a filter accepts (its unit squared per s^3): 1e3 m/s^2
/// (or rad/s^2) of white acceleration noise over a second, far beyond any body; larger
/// values only overflow the predicted covariance.
pub const MAX_PSD: f64 = 1e6;
/// Largest starting rate sigma a filter accepts (m/s or rad/s).
pub const MAX_RATE_SIGMA: f64 = 1e3;

/// The settings a constant-rate filter of `states` states shares, each named by its key:
/// every spectral density in `[0, MAX_PSD]`, the starting rate sigma in
/// `(0, MAX_RATE_SIGMA]`, kappa finite with `states + kappa > 0`. The error names the key,
/// the value and the range allowed.
pub(crate) fn check_filter(
    states: usize,
    (psd_key, psd): (&str, &[f64]),
    (sigma_key, sigma): (&str, f64),
    kappa: f64,
) -> Result<(), String> {
    if let Some((i, v)) = psd
        .iter()
        .enumerate()
        .find(|(_, v)| !(0.0..=MAX_PSD).contains(*v))
    {
        return Err(format!("{psd_key}[{i}] = {v:e}: allowed 0 to {MAX_PSD:e}"));
    }
    if !(sigma > 0.0 && sigma <= MAX_RATE_SIGMA) {
        return Err(format!(
            "{sigma_key} = {sigma:e}: allowed above 0 and at most {MAX_RATE_SIGMA:e}"
        ));
    }
    if !(kappa.is_finite() && states as f64 + kappa > 0.0) {
        return Err(format!(
            "kappa = {kappa}: must be finite with {states} + kappa > 0"
        ));
    }
    Ok(())
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
