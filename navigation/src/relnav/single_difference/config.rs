//! The `[single_difference]` table of `skyforge relnav`'s settings (mode
//! `single-difference`, book eq. 5-59): the single differences' noise and the process
//! noise of the relative dynamics and of the relative clock. Every default is an
//! assumption a user can change (docs/orbit-determination.md).

use serde::Deserialize;
use skyforge_orbits::propagate::ForceModelConfig;

/// The single-difference filter's settings.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct SingleDifferenceConfig {
    /// 1-sigma of one pseudorange single difference (m); eq. 5-58: twice one receiver's
    /// variance. # assumed: 1.0 m: the position-difference mode's 3-D RMS on B-5.6 (1.49
    /// m, docs/orbit-determination.md) is this noise times the PDOP, about 1.5 with 8-10
    /// satellites over a zenith hemisphere.
    pub code_sigma_m: f64,
    /// 1-sigma of one range-rate single difference from the Doppler (m/s).
    /// # assumed: 0.21 m/s, SkyForge's Doppler noise at 45 dB-Hz (0.15 m/s per satellite
    /// per receiver, docs/orbit-determination.md) times sqrt(2).
    pub range_rate_sigma_mps: f64,
    /// 1-sigma of the unmodelled relative acceleration per axis (m/s^2): `Q` of eq. 5-34.
    /// # assumed: 1e-5 m/s^2, the book's relative filter's (`[filter]`): the Hill
    /// equations' neglect of the orbit's eccentricity dominates.
    pub acceleration_sigma_mps2: f64,
    /// White frequency noise of the relative clock `c (dt_c - dt_t)`: its random walk (m
    /// per sqrt(s)). # assumed: 0.05 m/sqrt(s): two `tcxo` oscillators (h0 = 2e-21 s
    /// each, c sqrt(h0) = 0.013 m/sqrt(s) for the pair) with a margin for their flicker
    /// floor, which a two-state clock leaves out.
    pub clock_sigma_m_per_sqrt_s: f64,
    /// Random walk of the relative clock drift `c (dt_c' - dt_t')` (m/s per sqrt(s)).
    /// # assumed: 0.27 m/s/sqrt(s): two `tcxo` oscillators' random-walk frequency noise
    /// (h_-2 = 2e-20 /s each: c sqrt(2 pi^2 h_-2) = 0.19 m/s/sqrt(s) per receiver).
    pub clock_drift_sigma_mps_per_sqrt_s: f64,
    /// The perturbations whose difference is `U` (the book: J2 and drag).
    pub forces: ForceModelConfig,
}

impl Default for SingleDifferenceConfig {
    fn default() -> Self {
        Self {
            code_sigma_m: 1.0,
            range_rate_sigma_mps: 0.21,
            acceleration_sigma_mps2: 1e-5,
            clock_sigma_m_per_sqrt_s: 0.05,
            clock_drift_sigma_mps_per_sqrt_s: 0.27,
            forces: ForceModelConfig::default(),
        }
    }
}

impl SingleDifferenceConfig {
    /// Every field inside its range; the error names `single_difference.<field>`.
    pub fn check(&self) -> Result<(), String> {
        crate::config_file::check_positive(&[
            ("single_difference.code_sigma_m", self.code_sigma_m, 1e4),
            (
                "single_difference.range_rate_sigma_mps",
                self.range_rate_sigma_mps,
                1e3,
            ),
            (
                "single_difference.acceleration_sigma_mps2",
                self.acceleration_sigma_mps2,
                1.0,
            ),
            (
                "single_difference.clock_sigma_m_per_sqrt_s",
                self.clock_sigma_m_per_sqrt_s,
                1e6,
            ),
            (
                "single_difference.clock_drift_sigma_mps_per_sqrt_s",
                self.clock_drift_sigma_mps_per_sqrt_s,
                1e4,
            ),
        ])?;
        crate::orbit_determination::position_filter::check_forces(&self.forces)
            .map_err(|e| format!("single_difference.{e}"))
    }
}
