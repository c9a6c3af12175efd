//! The reduced-dynamic filter's settings (`[filter] kind = "reduced-dynamic"` of
//! `skyforge od --config`); every default is an assumption a user can change.

use crate::pvt::IonosphereCorrection;
use skyforge_orbits::propagate::ForceModelConfig;

/// Which observables the filter takes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Observables {
    /// Doppler (range rate) beside the code.
    #[serde(default = "yes")]
    pub doppler: bool,
    /// Carrier phase, with one float ambiguity per satellite and ranging while the
    /// receiver keeps lock.
    #[serde(default)]
    pub carrier: bool,
}

fn yes() -> bool {
    true
}

impl Default for Observables {
    fn default() -> Self {
        Self {
            doppler: true,
            carrier: false,
        }
    }
}

/// The reduced-dynamic extended Kalman filter on pseudoranges, Doppler and carrier phase.
#[derive(Debug, Clone, PartialEq, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ReducedDynamicConfig {
    /// The deterministic force model the orbit is integrated with.
    /// # assumed: J2..J6 and the exponential drag of the default spacecraft, as the
    /// position filter's (docs/orbit-determination.md: without J3..J6 a LEO's model is
    /// off by 1e-4 m/s^2).
    #[serde(default = "default_forces")]
    pub forces: ForceModelConfig,
    /// Which observables are used.
    #[serde(default)]
    pub observables: Observables,
    /// One signal with no ionosphere correction (a receiver in orbit is above the ground
    /// model's reach), or the ionosphere-free combination of two carriers.
    #[serde(default)]
    pub ionosphere: IonosphereCorrection,
    /// 1-sigma of one pseudorange's noise (m), white.
    /// # assumed: 1 m: the code noise (0.4 m at 45 dB-Hz) with a margin for what else is
    /// white (the first run's value, kept when the satellite errors got states).
    #[serde(default = "default_code_sigma_m")]
    pub code_sigma_m: f64,
    /// Steady-state 1-sigma of each satellite's range error, its broadcast orbit and
    /// clock against the truth: a first-order Gauss-Markov state per satellite, in the
    /// code and the carrier alike (m).
    /// # assumed: 0.6 m, the published global-average GPS SISRE of broadcast ephemerides
    /// (0.59 m, Liu et al. 2022); a user with precise orbits sets centimetres.
    #[serde(default = "default_satellite_sigma_m")]
    pub satellite_sigma_m: f64,
    /// Correlation time of the satellites' range errors (s).
    /// # assumed: 2 h: broadcast ephemerides are fitted over 4 h and replaced every 2 h,
    /// so their errors change over hours.
    #[serde(default = "default_satellite_tau_s")]
    pub satellite_tau_s: f64,
    /// 1-sigma of one range rate from the Doppler (m/s).
    /// # assumed: 0.2 m/s, the observation level's Doppler noise at 45 dB-Hz (0.8 Hz on
    /// L1, docs/orbit-determination.md) and a little more.
    #[serde(default = "default_doppler_sigma_mps")]
    pub doppler_sigma_mps: f64,
    /// 1-sigma of one carrier phase (m).
    /// # assumed: 5 mm, the book's and the smoother's phase noise.
    #[serde(default = "default_phase_sigma_m")]
    pub phase_sigma_m: f64,
    /// Steady-state 1-sigma of each empirical acceleration (radial, along-track,
    /// cross-track), a first-order Gauss-Markov process (m/s^2).
    /// # assumed: 1e-7 m/s^2 (100 nm/s^2), the order of a LEO's unmodelled forces once
    /// J2..J6 are in (drag's density error, solar pressure); reduced-dynamic filters of
    /// flight receivers use 5-100 nm/s^2.
    #[serde(default = "default_empirical_sigma_mps2")]
    pub empirical_sigma_mps2: f64,
    /// Correlation time of the empirical accelerations (s).
    /// # assumed: 600 s, a sixth of an orbit, as flight reduced-dynamic filters choose.
    #[serde(default = "default_empirical_tau_s")]
    pub empirical_tau_s: f64,
    /// Random walk of the receiver clock's offset (m / sqrt(s)).
    /// # assumed: 1 m/sqrt(s): the clock is re-estimated at every epoch (a free clock;
    /// a TCXO is not worth modelling tighter).
    #[serde(default = "default_clock_walk")]
    pub clock_walk_m_sqrt_s: f64,
    /// Random walk of the receiver clock's drift (m/s / sqrt(s)).
    /// # assumed: 0.1 m/s/sqrt(s), a TCXO's frequency wander with margin.
    #[serde(default = "default_drift_walk")]
    pub drift_walk_mps_sqrt_s: f64,
    /// Innovations larger than this many of their own sigma are rejected (a reset
    /// ambiguity for a carrier, the measurement dropped otherwise).
    /// # assumed: 5, far beyond Gaussian noise (5.7e-7 per measurement).
    #[serde(default = "default_gate_sigma")]
    pub gate_sigma: f64,
}

fn default_forces() -> ForceModelConfig {
    ForceModelConfig {
        higher_zonals: true,
        ..ForceModelConfig::default()
    }
}
fn default_code_sigma_m() -> f64 {
    1.0
}
fn default_satellite_sigma_m() -> f64 {
    0.6
}
fn default_satellite_tau_s() -> f64 {
    7200.0
}
fn default_doppler_sigma_mps() -> f64 {
    0.2
}
fn default_phase_sigma_m() -> f64 {
    0.005
}
fn default_empirical_sigma_mps2() -> f64 {
    1e-7
}
fn default_empirical_tau_s() -> f64 {
    600.0
}
fn default_clock_walk() -> f64 {
    1.0
}
fn default_drift_walk() -> f64 {
    0.1
}
fn default_gate_sigma() -> f64 {
    5.0
}

impl Default for ReducedDynamicConfig {
    fn default() -> Self {
        Self {
            forces: default_forces(),
            observables: Observables::default(),
            ionosphere: IonosphereCorrection::default(),
            code_sigma_m: default_code_sigma_m(),
            satellite_sigma_m: default_satellite_sigma_m(),
            satellite_tau_s: default_satellite_tau_s(),
            doppler_sigma_mps: default_doppler_sigma_mps(),
            phase_sigma_m: default_phase_sigma_m(),
            empirical_sigma_mps2: default_empirical_sigma_mps2(),
            empirical_tau_s: default_empirical_tau_s(),
            clock_walk_m_sqrt_s: default_clock_walk(),
            drift_walk_mps_sqrt_s: default_drift_walk(),
            gate_sigma: default_gate_sigma(),
        }
    }
}

impl ReducedDynamicConfig {
    /// Whether the values are usable: each error names the field, its value and what is
    /// allowed.
    pub fn check(&self) -> Result<(), String> {
        crate::config_file::check_positive(&[
            ("code_sigma_m", self.code_sigma_m, 1e4),
            ("satellite_sigma_m", self.satellite_sigma_m, 1e3),
            ("satellite_tau_s", self.satellite_tau_s, 1e7),
            ("doppler_sigma_mps", self.doppler_sigma_mps, 1e3),
            ("phase_sigma_m", self.phase_sigma_m, 10.0),
            ("empirical_sigma_mps2", self.empirical_sigma_mps2, 1.0),
            ("empirical_tau_s", self.empirical_tau_s, 1e7),
            ("clock_walk_m_sqrt_s", self.clock_walk_m_sqrt_s, 1e6),
            ("drift_walk_mps_sqrt_s", self.drift_walk_mps_sqrt_s, 1e4),
            ("gate_sigma", self.gate_sigma, 1e3),
        ])?;
        crate::orbit_determination::position_filter::check_forces(&self.forces)
    }
}
