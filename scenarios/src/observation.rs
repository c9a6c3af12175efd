//! The observation-level noise a scenario asks for, with its calibration file read.

use crate::Scenario;
use crate::error::ScenarioError;
use crate::parse::SCENARIO_MAX_BYTES;
use skyforge_orbits::bounded_read::read_text;
use skyforge_orbits::check::Invalid;
use skyforge_signals::obs_model::{Calibration, ObsNoise, ObsNoiseConfig, ObservationModel};

/// The calibration bundled with SkyForge (`scenarios/calibration/default.toml`), measured by
/// `skyforge calibrate scenarios/calibration/leo-gps-bds.toml` (see that file).
pub const BUNDLED_CALIBRATION: &str = include_str!("../calibration/default.toml");

/// The integrity monitor's configuration bundled with SkyForge
/// (`scenarios/calibration/monitor-lab.toml`), written by `skyforge monitor calibrate
/// integrity-lab --seed 1 --seeds 8` (see that file).
pub const BUNDLED_MONITOR_CONFIG: &str = include_str!("../calibration/monitor-lab.toml");

impl Scenario {
    /// The observation-level model of this scenario for `antennas` antennas observed every
    /// `step_s`: its noise resolved ([`Self::observation_noise`]), with Doppler noise
    /// where `[observation] doppler_noise` asks for it (located errors for a noise model
    /// or a calibration that cannot give it).
    pub fn observation_model(
        &self,
        antennas: usize,
        step_s: f64,
    ) -> Result<ObservationModel, ScenarioError> {
        let model = ObservationModel::new(
            self.observation_noise()?,
            self.receiver_seed(),
            antennas,
            step_s,
        );
        if !self.observation.doppler_noise {
            return Ok(model);
        }
        model
            .with_doppler_noise(self.receiver_seed())
            .map_err(|e| self.located(Invalid::new("observation.doppler_noise", true, e)))
    }

    /// `[observation.noise]` resolved: a calibration file named relative to the scenario
    /// (the bundled one when none is named) read and checked.
    pub fn observation_noise(&self) -> Result<ObsNoise, ScenarioError> {
        match &self.observation.noise {
            ObsNoiseConfig::Constant {
                phase_m,
                code_m,
                doppler_mps,
            } => Ok(ObsNoise::Constant {
                phase_m: *phase_m,
                code_m: *code_m,
                doppler_mps: *doppler_mps,
            }),
            ObsNoiseConfig::Elevation { phase, code } => Ok(ObsNoise::Elevation {
                phase: *phase,
                code: *code,
            }),
            ObsNoiseConfig::Calibrated { file } => {
                let field = "observation.noise.file";
                let (text, shown) = match file {
                    None => (BUNDLED_CALIBRATION.to_string(), "(bundled)".to_string()),
                    Some(f) => {
                        let path = self.base_dir.join(f);
                        let text = read_text(&path, SCENARIO_MAX_BYTES, "calibration file")
                            .map_err(|e| {
                                self.located(Invalid::new(
                                    field,
                                    f.display(),
                                    format!("cannot read {}: {e}", path.display()),
                                ))
                            })?;
                        (text, f.display().to_string())
                    }
                };
                let bad = |message: String| self.located(Invalid::new(field, &shown, message));
                let calibration: Calibration = toml::from_str(&text)
                    .map_err(|e| bad(format!("not a calibration file: {e}")))?;
                calibration
                    .check()
                    .map_err(|e| bad(format!("invalid calibration: {e}")))?;
                Ok(ObsNoise::Calibrated(calibration))
            }
        }
    }
}
