//! Carrier tracking stages behind one interface ([`CarrierTracker`]), chosen by the
//! receiver configuration (`[stages] carrier`, [`CarrierMethod`]) through [`build`]: the
//! FLL-assisted PLL (`pll_fll.rs`, the default) or the unscented Kalman filter of thesis
//! section 3.3.4 (`ukf_stage.rs` over [`super::ukf_carrier::UkfCarrier`]). Their settings
//! are in [`super::config`].
//!
//! A channel closes each coherent integration by handing the stage the prompt and the NCO
//! it was correlated with; the stage answers with the carrier NCO of the next integration
//! (its Doppler, and a phase step applied at its start).

mod pll_fll;
mod ukf_stage;

use super::TrackingError;
use super::config::{CarrierMethod, TrackingConfig};
use num_complex::Complex;
use pll_fll::PllFll;
use ukf_stage::UkfTracker;

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
pub trait CarrierTracker: std::fmt::Debug + Send {
    /// Close an integration; returns the next integration's NCO.
    fn close(&mut self, end: &IntegrationEnd) -> CarrierStep;
    /// The loop noise bandwidth that limits the coherent integration (`Bn T`), if the stage
    /// has one.
    fn loop_bandwidth_hz(&self) -> Option<f64>;
    /// Estimated Doppler rate (Hz/s).
    fn rate_hzps(&self) -> f64;
}

/// The configured stage, started at the hand-over Doppler and rate.
pub fn build(
    config: &TrackingConfig,
    doppler_hz: f64,
    rate_hzps: f64,
) -> Result<Box<dyn CarrierTracker>, TrackingError> {
    Ok(match config.carrier {
        CarrierMethod::FllPll => Box::new(PllFll::new(config, doppler_hz, rate_hzps)?),
        CarrierMethod::Ukf => Box::new(UkfTracker::new(config, rate_hzps)),
    })
}
