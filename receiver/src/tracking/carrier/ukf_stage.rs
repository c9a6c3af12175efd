//! The unscented Kalman filter carrier stage of thesis section 3.3.4 (`[stages] carrier =
//! "ukf"`, settings `[tracking.ukf]`).

use super::{CarrierStep, CarrierTracker, IntegrationEnd};
use crate::tracking::config::{TrackingConfig, UkfSettings};
use crate::tracking::ukf_carrier::{UkfCarrier, UkfConfig};
use nalgebra::{Matrix4, Vector4};
use num_complex::{Complex, Complex64};
use std::f64::consts::TAU;

/// Initial phase uncertainty of the UKF (rad): from the first prompt's angle.
const SIGMA0_PHASE_RAD: f64 = 0.3;
/// Initial uncertainty of the Doppler's second derivative (Hz/s^2): LEO-sized, as T-3.3-S.
const SIGMA0_ACCEL_HZPS2: f64 = 1000.0;
/// C/N0 assumed for the measurement noise before the channel has an estimate (dB-Hz).
const DEFAULT_CN0_DBHZ: f64 = 40.0;
/// Time constant of the prompt amplitude average that normalises the measurement (in
/// integrations).
const AMPLITUDE_INTEGRATIONS: f64 = 20.0;

/// The UKF carrier stage. Its state is kept at the middle of the integration being
/// closed: on closing, it is propagated there from the end of the previous one, updated
/// with the prompt (normalised by the running prompt amplitude; measurement noise from
/// the C/N0 estimate, `1 / (2 C/N0 T)` per component), and propagated to the end, where it
/// sets the next integration's NCO. The first integration only sets the initial phase.
#[derive(Debug)]
pub(super) struct UkfTracker {
    settings: UkfSettings,
    rate0_hzps: f64,
    ukf: Option<Box<UkfCarrier>>,
    /// Average prompt amplitude per second of integration.
    amplitude_per_s: Option<f64>,
    phase_error_cycles: f64,
}

impl UkfTracker {
    pub(super) fn new(config: &TrackingConfig, rate_hzps: f64) -> Self {
        Self {
            settings: config.ukf,
            rate0_hzps: rate_hzps,
            ukf: None,
            amplitude_per_s: None,
            phase_error_cycles: 0.0,
        }
    }

    /// The prompt normalised to unit signal amplitude.
    fn normalised(&mut self, prompt: Complex<f64>, t: f64) -> Complex64 {
        let a = prompt.norm() / t;
        let avg = match self.amplitude_per_s {
            Some(avg) => avg + (a - avg) / AMPLITUDE_INTEGRATIONS,
            None => a,
        };
        self.amplitude_per_s = Some(avg);
        let scale = if avg > 0.0 { 1.0 / (avg * t) } else { 0.0 };
        Complex64::new(prompt.re * scale, prompt.im * scale)
    }
}

impl CarrierTracker for UkfTracker {
    fn close(&mut self, end: &IntegrationEnd) -> CarrierStep {
        let t = end.integration_s;
        let prompt = self.normalised(end.prompt, t);
        let omega_nco = TAU * end.nco_doppler_hz;
        let theta_nco = TAU * end.nco_start_phase_cycles + omega_nco * t / 2.0;
        // Two-quadrant angle: the data sign is unknown.
        let angle = if prompt.re != 0.0 {
            (prompt.im / prompt.re).atan()
        } else {
            0.0
        };
        self.phase_error_cycles = angle / TAU;
        let s = self.settings;
        let ukf = match &mut self.ukf {
            Some(ukf) => {
                ukf.propagate(t / 2.0);
                let cn0 = 10f64.powf(end.cn0_dbhz.unwrap_or(DEFAULT_CN0_DBHZ) / 10.0);
                let r = 1.0 / (2.0 * cn0 * t);
                ukf.set_measurement(t, [r, r]);
                ukf.update_with_nco(prompt, theta_nco, omega_nco);
                ukf
            }
            empty => {
                let cfg = UkfConfig {
                    period_s: t,
                    coherent_s: t,
                    q: s.q,
                    r: [0.0; 2],
                    kappa: s.kappa,
                };
                let p0 = Matrix4::from_diagonal(&Vector4::new(
                    SIGMA0_PHASE_RAD.powi(2),
                    (TAU * s.initial_doppler_sigma_hz).powi(2),
                    (TAU * s.initial_rate_sigma_hzps).powi(2),
                    (TAU * SIGMA0_ACCEL_HZPS2).powi(2),
                ));
                let x0 = [theta_nco + angle, omega_nco, TAU * self.rate0_hzps, 0.0];
                empty.insert(Box::new(UkfCarrier::new(cfg, x0, p0)))
            }
        };
        ukf.propagate(t / 2.0);
        let [theta, omega, alpha, _] = ukf.state();
        let phase_end_cycles = end.nco_start_phase_cycles + end.nco_doppler_hz * t;
        CarrierStep {
            // The frequency at the middle of a next integration as long as this one.
            doppler_hz: (omega + alpha * t / 2.0) / TAU,
            phase_step_cycles: theta / TAU - phase_end_cycles,
            phase_error_cycles: self.phase_error_cycles,
        }
    }

    fn loop_bandwidth_hz(&self) -> Option<f64> {
        None
    }

    fn rate_hzps(&self) -> f64 {
        self.ukf
            .as_ref()
            .map_or(self.rate0_hzps, |u| u.state()[2] / TAU)
    }
}
