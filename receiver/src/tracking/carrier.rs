//! Carrier tracking stages behind one interface ([`CarrierTracker`]), chosen by the
//! receiver configuration (`[stages] carrier`): the FLL-assisted PLL
//! ([`PllFll`], the default) or the unscented Kalman filter of thesis section 3.3.4
//! ([`UkfTracker`] over [`super::ukf_carrier::UkfCarrier`]).
//!
//! A channel closes each coherent integration by handing the stage the prompt and the NCO
//! it was correlated with; the stage answers with the carrier NCO of the next integration
//! (its Doppler, and a phase step applied at its start).

use super::TrackingError;
use super::config::{CarrierMethod, TrackingConfig, UkfSettings};
use super::discriminators::{FllDiscriminator, PllDiscriminator};
use super::loop_filter::CarrierLoopFilter;
use super::ukf_carrier::{UkfCarrier, UkfConfig};
use nalgebra::{Matrix4, Vector4};
use num_complex::{Complex, Complex64};
use std::f64::consts::TAU;

/// What a channel knows when it closes a coherent integration.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct IntegrationEnd {
    /// Prompt correlation of the integration.
    pub prompt: Complex<f64>,
    /// Its length (s).
    pub integration_s: f64,
    /// Time since the hand-over at the end of the integration (s).
    pub time_s: f64,
    /// When bit synchronisation was reached (s since the hand-over).
    pub synced_at_s: Option<f64>,
    /// Latest C/N0 estimate (dB-Hz).
    pub cn0_dbhz: Option<f64>,
    /// Carrier NCO of the integration: Doppler (Hz) and phase at its start (cycles,
    /// without the IF).
    pub nco_doppler_hz: f64,
    pub nco_start_phase_cycles: f64,
}

/// The carrier NCO of the next integration.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CarrierStep {
    pub doppler_hz: f64,
    /// Added to the NCO phase at the start of the next integration (cycles).
    pub phase_step_cycles: f64,
    /// The stage's phase error estimate of the closed integration (cycles), for records.
    pub phase_error_cycles: f64,
}

/// A carrier tracking stage.
pub trait CarrierTracker {
    /// Close an integration; returns the next integration's NCO.
    fn close(&mut self, end: &IntegrationEnd) -> CarrierStep;
    /// The loop noise bandwidth that limits the coherent integration (`Bn T`), if the stage
    /// has one.
    fn loop_bandwidth_hz(&self) -> Option<f64>;
    /// Estimated Doppler rate (Hz/s).
    fn rate_hzps(&self) -> f64;
}

/// The stage a channel runs, as configured.
#[derive(Debug, Clone)]
pub enum Carrier {
    FllPll(PllFll),
    Ukf(UkfTracker),
}

impl Carrier {
    /// The configured stage, started at the hand-over Doppler and rate.
    pub fn new(
        config: &TrackingConfig,
        doppler_hz: f64,
        rate_hzps: f64,
    ) -> Result<Self, TrackingError> {
        Ok(match config.carrier {
            CarrierMethod::FllPll => Carrier::FllPll(PllFll::new(config, doppler_hz, rate_hzps)?),
            CarrierMethod::Ukf => Carrier::Ukf(UkfTracker::new(config, rate_hzps)),
        })
    }

    fn stage(&mut self) -> &mut dyn CarrierTracker {
        match self {
            Carrier::FllPll(s) => s,
            Carrier::Ukf(s) => s,
        }
    }

    fn stage_ref(&self) -> &dyn CarrierTracker {
        match self {
            Carrier::FllPll(s) => s,
            Carrier::Ukf(s) => s,
        }
    }
}

impl CarrierTracker for Carrier {
    fn close(&mut self, end: &IntegrationEnd) -> CarrierStep {
        self.stage().close(end)
    }
    fn loop_bandwidth_hz(&self) -> Option<f64> {
        self.stage_ref().loop_bandwidth_hz()
    }
    fn rate_hzps(&self) -> f64 {
        self.stage_ref().rate_hzps()
    }
}

/// The FLL-assisted PLL: discriminators, the loop filter, FLL assist for
/// `fll_assist_s` after the hand-over, and the narrowing of the PLL after bit sync.
#[derive(Debug, Clone)]
pub struct PllFll {
    config: PllFllSettings,
    filter: CarrierLoopFilter,
    previous_prompt: Option<(Complex<f64>, f64)>,
}

/// The part of [`TrackingConfig`] the PLL/FLL stage reads (field meanings there).
#[derive(Debug, Clone, Copy, PartialEq)]
struct PllFllSettings {
    pll_bandwidth_hz: f64,
    pll_narrow_bandwidth_hz: Option<f64>,
    pll_narrowing_s: f64,
    pll_discriminator: PllDiscriminator,
    fll_bandwidth_hz: f64,
    fll_discriminator: FllDiscriminator,
    fll_assist_s: f64,
}

impl PllFll {
    fn new(
        config: &TrackingConfig,
        doppler_hz: f64,
        rate_hzps: f64,
    ) -> Result<Self, TrackingError> {
        let mut filter = CarrierLoopFilter::new(
            config.pll_order,
            config.pll_bandwidth_hz,
            if config.fll_assist_s > 0.0 {
                config.fll_bandwidth_hz
            } else {
                0.0
            },
            doppler_hz,
        )?;
        filter.set_rate_hzps(rate_hzps);
        Ok(Self {
            config: PllFllSettings {
                pll_bandwidth_hz: config.pll_bandwidth_hz,
                pll_narrow_bandwidth_hz: config.pll_narrow_bandwidth_hz,
                pll_narrowing_s: config.pll_narrowing_s,
                pll_discriminator: config.pll_discriminator,
                fll_bandwidth_hz: config.fll_bandwidth_hz,
                fll_discriminator: config.fll_discriminator,
                fll_assist_s: config.fll_assist_s,
            },
            filter,
            previous_prompt: None,
        })
    }

    /// After bit sync: move the PLL bandwidth towards the narrow one, if configured.
    fn narrow(&mut self, time_s: f64, synced_at_s: Option<f64>) {
        if let (Some(narrow), Some(t0)) = (self.config.pll_narrow_bandwidth_hz, synced_at_s) {
            let wide = self.config.pll_bandwidth_hz;
            let x = ((time_s - t0) / self.config.pll_narrowing_s).clamp(0.0, 1.0);
            // Positive and finite: both bandwidths checked in `TrackingConfig::check`.
            let _ = self
                .filter
                .set_pll_bandwidth(wide * (narrow / wide).powf(x));
        }
    }
}

impl CarrierTracker for PllFll {
    fn close(&mut self, end: &IntegrationEnd) -> CarrierStep {
        let (prompt, t) = (end.prompt, end.integration_s);
        let phase_error = self.config.pll_discriminator.phase_error_cycles(prompt);
        let fll_on = end.time_s <= self.config.fll_assist_s && self.config.fll_bandwidth_hz > 0.0;
        let freq_error = match self.previous_prompt {
            Some((previous, t_prev)) if fll_on => self.config.fll_discriminator.frequency_error_hz(
                previous,
                prompt,
                0.5 * (t_prev + t),
            ),
            _ => 0.0,
        };
        if !fll_on {
            self.filter.disable_fll();
        }
        self.previous_prompt = Some((prompt, t));
        self.narrow(end.time_s, end.synced_at_s);
        let doppler_hz = self.filter.update(phase_error, freq_error, t);
        // Zero-delay carrier NCO: the next integration starts at the phase the new
        // Doppler would have reached over this one. With the plain frequency NCO the
        // correction acts one integration late, and the digital loop realises more than its
        // design noise bandwidth (+8 % at 25 Hz and 1 ms, +40 % at 5 Hz and 20 ms); with
        // this phase step it realises the design value within a few per cent at any
        // `Bn T` up to 0.1 (`tests/tracking_loops.rs` measures it).
        CarrierStep {
            doppler_hz,
            phase_step_cycles: (doppler_hz - end.nco_doppler_hz) * t,
            phase_error_cycles: phase_error,
        }
    }

    fn loop_bandwidth_hz(&self) -> Option<f64> {
        Some(self.filter.pll_bandwidth_hz())
    }

    fn rate_hzps(&self) -> f64 {
        self.filter.rate_hzps()
    }
}

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
#[derive(Debug, Clone)]
pub struct UkfTracker {
    settings: UkfSettings,
    rate0_hzps: f64,
    ukf: Option<Box<UkfCarrier>>,
    /// Average prompt amplitude per second of integration.
    amplitude_per_s: Option<f64>,
    phase_error_cycles: f64,
}

impl UkfTracker {
    fn new(config: &TrackingConfig, rate_hzps: f64) -> Self {
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
