//! Receiver settings: acquisition, tracking, observation rate, PVT, and the approximate
//! state a receiver can be told (assistance).

pub use crate::acquisition::config::{AcquisitionMethod, AcquisitionSettings};
use crate::tracking::config::CarrierMethod;
use crate::tracking::config::TrackingConfig;
use skyforge_navigation::pvt::{IonosphereCorrection, PvtConfig, SmoothingConfig};
use skyforge_orbits::Vec3;
use skyforge_orbits::check::{Invalid, NEAR_EARTH_RADIUS_M, check_position, check_table};

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
    /// `"broadcast"` (one signal per satellite, Klobuchar) or `"dual-frequency"` (the
    /// ionosphere-free combination of two signals per satellite).
    pub ionosphere: IonosphereCorrection,
    pub troposphere: bool,
    pub raim_pfa: f64,
    /// Missed-detection probability of the protection levels (docs/raim.md).
    pub raim_pmd: f64,
    /// Horizontal alarm limit (m).
    pub raim_hal_m: f64,
    /// Vertical alarm limit (m), none by default.
    pub raim_val_m: Option<f64>,
    /// `[pvt.carrier_smoothing]`: smooth each signal's code with its carrier before the
    /// fix (absent: raw code).
    pub carrier_smoothing: Option<SmoothingConfig>,
}

impl Default for PvtFile {
    fn default() -> Self {
        let d = PvtConfig::default();
        Self {
            elevation_mask_deg: d.elevation_mask_rad.to_degrees(),
            ionosphere: d.ionosphere,
            troposphere: d.troposphere,
            raim_pfa: d.raim_pfa,
            raim_pmd: d.raim_pmd,
            raim_hal_m: d.raim_hal_m,
            raim_val_m: d.raim_val_m,
            carrier_smoothing: d.carrier_smoothing,
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

/// The range of every `[acquisition]`, `[observables]`, `[pvt]` and `[assist]` value
/// (docs/limits.md lists them; `[tracking]`'s are beside its settings).
mod limits {
    use skyforge_orbits::check::Allowed;

    pub(super) const ACQUISITION_COHERENT_MS: Allowed = Allowed::closed(1.0, 20.0, "ms");
    pub(super) const NONCOHERENT: Allowed = Allowed::closed(1.0, 100.0, "sums");
    /// assumed: a search that false-alarms more often than not is no search; 1e-12 is
    /// below any threshold the CFAR tables give.
    pub(super) const ACQUISITION_PFA: Allowed = Allowed::closed(1e-12, 0.5, "");
    pub(super) const DOPPLER_HALF_WIDTH_HZ: Allowed = Allowed::above(0.0, 60e3, "Hz");
    /// assumed: an hour between searches is longer than any recording worth a search.
    pub(super) const REACQUIRE_INTERVAL_S: Allowed = Allowed::above(0.0, 3600.0, "s");
    pub(super) const OBSERVATION_RATE_HZ: Allowed = Allowed::closed(1.0, 100.0, "Hz");
    /// Below the zenith: a mask of 90 deg leaves no satellite.
    pub(super) const ELEVATION_MASK_DEG: Allowed = Allowed::closed(0.0, 89.0, "deg");
    /// Probabilities of the residual test and of the protection levels (0 turns them
    /// off): assumed from 1e-12 (below any integrity requirement, 1e-7 per hour for
    /// aviation) to 0.5.
    pub(super) const RAIM_PROBABILITY: Allowed = Allowed::closed(1e-12, 0.5, "(or 0: off)");
    /// assumed: 100 km, beyond any alarm limit in use (556 m for en-route aviation).
    pub(super) const ALARM_LIMIT_M: Allowed = Allowed::above(0.0, 100e3, "m");
    /// assumed: 1000 km/s, far beyond a LEO's 8 km/s (the receiver is near the Earth).
    pub(super) const VELOCITY_MPS: Allowed = Allowed::closed(-1e6, 1e6, "m/s");
    /// assumed: the whole Earth's diameter and more says nothing about the position.
    pub(super) const POSITION_UNCERTAINTY_M: Allowed = Allowed::closed(0.0, 1e8, "m");
    pub(super) const VELOCITY_UNCERTAINTY_MPS: Allowed = Allowed::closed(0.0, 1e4, "m/s");
    /// assumed: a day of time uncertainty is a cold start, not an assistance.
    pub(super) const TIME_UNCERTAINTY_S: Allowed = Allowed::closed(0.0, 86_400.0, "s");
    /// assumed: 1000 ppm (0.1 %) is beyond the worst crystal oscillator.
    pub(super) const OSCILLATOR_PPM: Allowed = Allowed::closed(0.0, 1000.0, "ppm");
    /// Noise sigmas of carrier smoothing: assumed up to 1 km, beyond any code noise.
    pub(super) const SMOOTHING_SIGMA_M: Allowed = Allowed::above(0.0, 1000.0, "m");
    /// Restart gap of carrier smoothing: assumed up to an hour.
    pub(super) const SMOOTHING_GAP_S: Allowed = Allowed::above(0.0, 3600.0, "s");
    /// Memory cap of carrier smoothing: from 1 (no smoothing) to a day at 1 Hz.
    pub(super) const SMOOTHING_EPOCHS: Allowed = Allowed::closed(1.0, 86_400.0, "epochs");
}

impl ReceiverFile {
    /// The settings, with every value checked against its range: the error names the
    /// field (`tracking.pll_bandwidth_hz`), its value and the range.
    pub fn resolve(&self) -> Result<(ReceiverConfig, Option<ApproximateState>), Invalid> {
        use limits::*;
        let (a, p) = (&self.acquisition, &self.pvt);
        let values = [
            (
                "acquisition.coherent_ms",
                a.coherent_ms as f64,
                ACQUISITION_COHERENT_MS,
            ),
            ("acquisition.noncoherent", a.noncoherent as f64, NONCOHERENT),
            ("acquisition.pfa", a.pfa, ACQUISITION_PFA),
            (
                "acquisition.doppler_half_width_hz",
                a.doppler_half_width_hz,
                DOPPLER_HALF_WIDTH_HZ,
            ),
            (
                "acquisition.reacquire_interval_s",
                a.reacquire_interval_s,
                REACQUIRE_INTERVAL_S,
            ),
            (
                "observables.rate_hz",
                self.observables.rate_hz,
                OBSERVATION_RATE_HZ,
            ),
            (
                "pvt.elevation_mask_deg",
                p.elevation_mask_deg,
                ELEVATION_MASK_DEG,
            ),
            ("pvt.raim_hal_m", p.raim_hal_m, ALARM_LIMIT_M),
        ];
        check_table(&values)?;
        for (field, v) in [("pvt.raim_pfa", p.raim_pfa), ("pvt.raim_pmd", p.raim_pmd)] {
            if v != 0.0 {
                RAIM_PROBABILITY.check(field, v)?;
            }
        }
        if let Some(v) = p.raim_val_m {
            ALARM_LIMIT_M.check("pvt.raim_val_m", v)?;
        }
        if let Some(c) = &p.carrier_smoothing {
            check_table(&[
                (
                    "pvt.carrier_smoothing.code_sigma_m",
                    c.code_sigma_m,
                    SMOOTHING_SIGMA_M,
                ),
                (
                    "pvt.carrier_smoothing.phase_sigma_m",
                    c.phase_sigma_m,
                    SMOOTHING_SIGMA_M,
                ),
                (
                    "pvt.carrier_smoothing.max_gap_s",
                    c.max_gap_s,
                    SMOOTHING_GAP_S,
                ),
            ])?;
            if let Some(n) = c.max_epochs {
                SMOOTHING_EPOCHS.check("pvt.carrier_smoothing.max_epochs", f64::from(n))?;
            }
        }
        self.tracking.check().map_err(|e| e.within("tracking"))?;
        let approximate = self.assist.as_ref().map(AssistFile::resolve).transpose()?;
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
                ionosphere: p.ionosphere,
                troposphere: p.troposphere,
                raim_pfa: p.raim_pfa,
                raim_pmd: p.raim_pmd,
                raim_hal_m: p.raim_hal_m,
                raim_val_m: p.raim_val_m,
                carrier_smoothing: p.carrier_smoothing,
                ..PvtConfig::default()
            },
        };
        Ok((config, approximate))
    }
}

impl AssistFile {
    /// The approximate state, with every value checked against its range.
    fn resolve(&self) -> Result<ApproximateState, Invalid> {
        use limits::*;
        check_position(
            "assist.position_ecef_m",
            &self.position_ecef_m,
            NEAR_EARTH_RADIUS_M,
        )?;
        for (i, v) in self.velocity_ecef_mps.iter().enumerate() {
            VELOCITY_MPS.check(&format!("assist.velocity_ecef_mps[{i}]"), *v)?;
        }
        let values = [
            (
                "assist.position_uncertainty_m",
                self.position_uncertainty_m,
                POSITION_UNCERTAINTY_M,
            ),
            (
                "assist.velocity_uncertainty_mps",
                self.velocity_uncertainty_mps,
                VELOCITY_UNCERTAINTY_MPS,
            ),
            (
                "assist.time_uncertainty_s",
                self.time_uncertainty_s,
                TIME_UNCERTAINTY_S,
            ),
            ("assist.oscillator_ppm", self.oscillator_ppm, OSCILLATOR_PPM),
        ];
        check_table(&values)?;
        Ok(ApproximateState {
            r_ecef_m: Vec3::from(self.position_ecef_m),
            v_ecef_mps: Vec3::from(self.velocity_ecef_mps),
            position_uncertainty_m: self.position_uncertainty_m,
            velocity_uncertainty_mps: self.velocity_uncertainty_mps,
            time_uncertainty_s: self.time_uncertainty_s,
            oscillator_uncertainty: self.oscillator_ppm * 1e-6,
        })
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
