//! Receiver settings: acquisition, tracking, observation rate, PVT, and the approximate
//! state a receiver can be told (assistance).

pub use crate::acquisition::config::{AcquisitionMethod, AcquisitionSettings};
use crate::tracking::config::CarrierMethod;
use crate::tracking::config::TrackingConfig;
use skyforge_navigation::pvt::PvtConfig;
use skyforge_orbits::Vec3;

/// The stage after observables, at every epoch.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum EpochStageKind {
    /// Single-point position, velocity and time per antenna with RAIM (default).
    #[default]
    Pvt,
}

/// `[stages]`: which implementation runs each receiver stage, as GNSS-SDR's
/// `implementation` keys choose its blocks.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct StagesFile {
    pub acquisition: AcquisitionMethod,
    pub carrier: CarrierMethod,
    pub epoch: EpochStageKind,
}

/// The receiver's approximate position and velocity at the start of the recording (for
/// assisted acquisition, e.g. from an orbit prediction), with uncertainties.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ApproximateState {
    pub r_ecef_m: Vec3,
    pub v_ecef_mps: Vec3,
    pub position_uncertainty_m: f64,
    pub velocity_uncertainty_mps: f64,
    /// Uncertainty of the recording's start time (s).
    pub time_uncertainty_s: f64,
    /// Oscillator frequency uncertainty (dimensionless).
    pub oscillator_uncertainty: f64,
}

/// Everything the receiver is set up with.
#[derive(Debug, Clone, PartialEq)]
pub struct ReceiverConfig {
    pub acquisition: AcquisitionSettings,
    pub tracking: TrackingConfig,
    /// Observation epochs per second (1 to 100), at whole multiples of the period in the
    /// receiver's time.
    pub observation_rate_hz: f64,
    /// The stage after observables.
    pub epoch_stage: EpochStageKind,
    pub pvt: PvtConfig,
}

impl Default for ReceiverConfig {
    fn default() -> Self {
        Self {
            acquisition: AcquisitionSettings::default(),
            tracking: TrackingConfig::default(),
            observation_rate_hz: 1.0,
            epoch_stage: EpochStageKind::Pvt,
            pvt: PvtConfig::default(),
        }
    }
}

/// The receiver configuration file (TOML): every table and field optional, defaults as
/// in [`ReceiverConfig::default`]; degrees and ppm at this edge, SI inside.
#[derive(Debug, Clone, Default, PartialEq, serde::Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ReceiverFile {
    pub stages: StagesFile,
    pub acquisition: AcquisitionFile,
    pub tracking: TrackingConfig,
    pub observables: ObservablesFile,
    pub pvt: PvtFile,
    pub assist: Option<AssistFile>,
}

/// `[acquisition]`.
#[derive(Debug, Clone, Copy, PartialEq, serde::Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct AcquisitionFile {
    pub coherent_ms: usize,
    pub noncoherent: usize,
    pub pfa: f64,
    pub doppler_half_width_hz: f64,
    pub reacquire_interval_s: f64,
}

impl Default for AcquisitionFile {
    fn default() -> Self {
        let d = AcquisitionSettings::default();
        Self {
            coherent_ms: d.coherent_ms,
            noncoherent: d.noncoherent,
            pfa: d.pfa,
            doppler_half_width_hz: d.cold_half_width_hz,
            reacquire_interval_s: d.reacquire_interval_s,
        }
    }
}

/// `[observables]`.
#[derive(Debug, Clone, Copy, PartialEq, serde::Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ObservablesFile {
    pub rate_hz: f64,
}

impl Default for ObservablesFile {
    fn default() -> Self {
        Self { rate_hz: 1.0 }
    }
}

/// `[pvt]`.
#[derive(Debug, Clone, Copy, PartialEq, serde::Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct PvtFile {
    pub elevation_mask_deg: f64,
    pub troposphere: bool,
    pub raim_pfa: f64,
    /// Missed-detection probability of the protection levels (docs/raim.md).
    pub raim_pmd: f64,
    /// Horizontal alarm limit (m).
    pub raim_hal_m: f64,
    /// Vertical alarm limit (m), none by default.
    pub raim_val_m: Option<f64>,
}

impl Default for PvtFile {
    fn default() -> Self {
        let d = PvtConfig::default();
        Self {
            elevation_mask_deg: d.elevation_mask_rad.to_degrees(),
            troposphere: d.troposphere,
            raim_pfa: d.raim_pfa,
            raim_pmd: d.raim_pmd,
            raim_hal_m: d.raim_hal_m,
            raim_val_m: d.raim_val_m,
        }
    }
}

/// `[assist]`: the approximate state at the recording's start.
#[derive(Debug, Clone, Copy, PartialEq, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AssistFile {
    pub position_ecef_m: [f64; 3],
    #[serde(default)]
    pub velocity_ecef_mps: [f64; 3],
    #[serde(default = "default_position_uncertainty")]
    pub position_uncertainty_m: f64,
    #[serde(default = "default_velocity_uncertainty")]
    pub velocity_uncertainty_mps: f64,
    #[serde(default = "default_time_uncertainty")]
    pub time_uncertainty_s: f64,
    #[serde(default = "default_oscillator_ppm")]
    pub oscillator_ppm: f64,
}

fn default_position_uncertainty() -> f64 {
    10e3
}
fn default_velocity_uncertainty() -> f64 {
    10.0
}
fn default_time_uncertainty() -> f64 {
    1.0
}
fn default_oscillator_ppm() -> f64 {
    1.0
}

/// A value of the configuration file outside its range.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{field} = {value}: allowed {allowed}")]
pub struct ConfigValueError {
    pub field: &'static str,
    pub value: String,
    pub allowed: &'static str,
}

impl ReceiverFile {
    /// The settings, with every value checked.
    pub fn resolve(&self) -> Result<(ReceiverConfig, Option<ApproximateState>), ConfigValueError> {
        let a = &self.acquisition;
        let bad = |field, value: String, allowed| ConfigValueError {
            field,
            value,
            allowed,
        };
        if !(1..=20).contains(&a.coherent_ms) {
            return Err(bad(
                "acquisition.coherent_ms",
                a.coherent_ms.to_string(),
                "1 to 20",
            ));
        }
        if !(1..=100).contains(&a.noncoherent) {
            return Err(bad(
                "acquisition.noncoherent",
                a.noncoherent.to_string(),
                "1 to 100",
            ));
        }
        if !(a.pfa > 0.0 && a.pfa < 1.0) {
            return Err(bad("acquisition.pfa", a.pfa.to_string(), "between 0 and 1"));
        }
        if !(a.doppler_half_width_hz > 0.0 && a.doppler_half_width_hz <= 60e3) {
            return Err(bad(
                "acquisition.doppler_half_width_hz",
                a.doppler_half_width_hz.to_string(),
                "above 0, at most 60000",
            ));
        }
        if !(a.reacquire_interval_s.is_finite() && a.reacquire_interval_s > 0.0) {
            return Err(bad(
                "acquisition.reacquire_interval_s",
                a.reacquire_interval_s.to_string(),
                "positive",
            ));
        }
        if !(1.0..=100.0).contains(&self.observables.rate_hz) {
            return Err(bad(
                "observables.rate_hz",
                self.observables.rate_hz.to_string(),
                "1 to 100",
            ));
        }
        let p = &self.pvt;
        if !(0.0..90.0).contains(&p.elevation_mask_deg) {
            return Err(bad(
                "pvt.elevation_mask_deg",
                p.elevation_mask_deg.to_string(),
                "0 to below 90",
            ));
        }
        for (key, v) in [("pvt.raim_pfa", p.raim_pfa), ("pvt.raim_pmd", p.raim_pmd)] {
            if !(0.0..1.0).contains(&v) {
                return Err(bad(key, v.to_string(), "0 (off) to below 1"));
            }
        }
        for (key, v) in [
            ("pvt.raim_hal_m", Some(p.raim_hal_m)),
            ("pvt.raim_val_m", p.raim_val_m),
        ] {
            if let Some(v) = v.filter(|v| !(v.is_finite() && *v > 0.0)) {
                return Err(bad(key, v.to_string(), "a positive number of metres"));
            }
        }
        let approximate = match self.assist {
            None => None,
            Some(s) => {
                let finite = s
                    .position_ecef_m
                    .iter()
                    .chain(&s.velocity_ecef_mps)
                    .all(|x| x.is_finite());
                if !finite {
                    return Err(bad(
                        "assist.position_ecef_m/velocity_ecef_mps",
                        format!("{:?} {:?}", s.position_ecef_m, s.velocity_ecef_mps),
                        "finite numbers",
                    ));
                }
                let positive = [
                    ("assist.position_uncertainty_m", s.position_uncertainty_m),
                    (
                        "assist.velocity_uncertainty_mps",
                        s.velocity_uncertainty_mps,
                    ),
                    ("assist.time_uncertainty_s", s.time_uncertainty_s),
                    ("assist.oscillator_ppm", s.oscillator_ppm),
                ];
                for (field, v) in positive {
                    if !(v.is_finite() && v >= 0.0) {
                        return Err(bad(field, v.to_string(), "finite and >= 0"));
                    }
                }
                Some(ApproximateState {
                    r_ecef_m: Vec3::from(s.position_ecef_m),
                    v_ecef_mps: Vec3::from(s.velocity_ecef_mps),
                    position_uncertainty_m: s.position_uncertainty_m,
                    velocity_uncertainty_mps: s.velocity_uncertainty_mps,
                    time_uncertainty_s: s.time_uncertainty_s,
                    oscillator_uncertainty: s.oscillator_ppm * 1e-6,
                })
            }
        };
        let config = ReceiverConfig {
            acquisition: AcquisitionSettings {
                method: self.stages.acquisition,
                coherent_ms: a.coherent_ms,
                noncoherent: a.noncoherent,
                pfa: a.pfa,
                cold_half_width_hz: a.doppler_half_width_hz,
                reacquire_interval_s: a.reacquire_interval_s,
            },
            tracking: TrackingConfig {
                carrier: self.stages.carrier,
                ..self.tracking
            },
            observation_rate_hz: self.observables.rate_hz,
            epoch_stage: self.stages.epoch,
            pvt: PvtConfig {
                elevation_mask_rad: p.elevation_mask_deg.to_radians(),
                troposphere: p.troposphere,
                raim_pfa: p.raim_pfa,
                raim_pmd: p.raim_pmd,
                raim_hal_m: p.raim_hal_m,
                raim_val_m: p.raim_val_m,
                ..PvtConfig::default()
            },
        };
        Ok((config, approximate))
    }
}

/// Position rounding of the assistance file (m): what an orbit prediction or a rough
/// position fix would tell a receiver, not the truth.
const ASSIST_POSITION_ROUNDING_M: f64 = 1000.0;
/// Velocity rounding of the assistance file (m/s).
const ASSIST_VELOCITY_ROUNDING_MPS: f64 = 1.0;

/// `receiver.toml` for `skyforge receive --config` (what `synth` writes beside its
/// recordings): the approximate state at the start, rounded, with uncertainties that cover
/// the rounding many times over.
pub fn assistance_toml(r_ecef_m: &Vec3, v_ecef_mps: &Vec3) -> String {
    let round = |x: f64, step: f64| (x / step).round() * step;
    let r = r_ecef_m.map(|x| round(x, ASSIST_POSITION_ROUNDING_M));
    let v = v_ecef_mps.map(|x| round(x, ASSIST_VELOCITY_ROUNDING_MPS));
    format!(
        "# Settings for `skyforge receive --config receiver.toml` on these recordings.\n\
         # [assist]: the approximate state at the first sample a receiver could be told\n\
         # (an orbit prediction, a last fix), rounded to {} m and {} m/s.\n\
         [assist]\n\
         position_ecef_m = [{:.1}, {:.1}, {:.1}]\n\
         velocity_ecef_mps = [{:.1}, {:.1}, {:.1}]\n\
         position_uncertainty_m = 10000.0\n\
         velocity_uncertainty_mps = 10.0\n",
        ASSIST_POSITION_ROUNDING_M, ASSIST_VELOCITY_ROUNDING_MPS, r.x, r.y, r.z, v.x, v.y, v.z
    )
}
