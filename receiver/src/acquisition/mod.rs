//! Acquisition: parallel code-phase search (PCPS) and the PMF-FFT of thesis section 3.3.1.
//!
//! - [`pcps`]: FFT circular correlation over a Doppler grid, coherent and non-coherent
//!   integration, a CFAR decision ([`cfar`]), optional bit-transition-safe windows.
//! - [`pmf_fft`]: partial matched filters + FFT with the fine Doppler estimator of thesis
//!   eq. 3.3-13/3.3-14, and its noise theory (eq. 3.3-45..3.3-55) in [`pmf_fft::theory`].
//! - [`replica`]: ranging-code replicas at any sample rate and the carrier wipe-off.

pub mod cfar;
pub(crate) mod config;
pub(crate) mod pcps;
mod pcps_stage;
pub mod pmf_fft;
mod pmf_fft_stage;
pub(crate) mod replica;

/// The complex `f32` sample type the acquisition functions take.
use config::{AcquisitionMethod, AcquisitionSettings};
pub use num_complex::Complex32;
use pcps::Acquisition;
pub use pcps::{BitTransition, DopplerWindow, Pcps, PcpsConfig};
use pcps_stage::PcpsStage;
use pmf_fft_stage::PmfFftStage;
pub use replica::wipe_carrier;
use skyforge_gnss::signal::Signal;

/// Why an acquisition could not run.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum AcquisitionError {
    #[error(transparent)]
    UnknownPrn(#[from] skyforge_gnss::signal::UnknownPrn),
    #[error("{name} = {value} is not allowed: {allowed}")]
    BadParameter {
        name: &'static str,
        value: f64,
        allowed: &'static str,
    },
    #[error("the search needs {needed} samples but only {got} were given")]
    TooFewSamples { needed: usize, got: usize },
    /// A signal SkyForge reads from files but does not track (GPS L2).
    #[error("{0} is not tracked by the bundled receiver; it does not acquire it")]
    NotTracked(skyforge_gnss::signal::Signal),
}

/// A satellite to search for, with its Doppler window and predicted Doppler rate.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Candidate {
    pub(crate) prn: u8,
    pub(crate) window: DopplerWindow,
    pub(crate) doppler_rate_hzps: f64,
    /// The window is the blind one (no prediction for this satellite).
    pub(crate) cold: bool,
}

/// The acquisition stage of one signal, as configured (`[stages] acquisition`).
pub(crate) trait AcquisitionStage: Send + Sync {
    /// Samples a search reads.
    fn samples_needed(&self) -> usize;
    /// Doppler bin spacing of the search (Hz).
    fn doppler_step_hz(&self) -> f64;
    /// The window of a search without a prediction.
    fn cold_window(&self) -> DopplerWindow;
    /// Search every candidate in `samples` (which start at the hand-over sample); returns
    /// the detections.
    fn run(
        &self,
        samples: &[Complex32],
        candidates: &[Candidate],
    ) -> Result<Vec<(Candidate, Acquisition)>, AcquisitionError>;
}

/// The stage `settings` name for `signal` at `sample_rate_hz`, its carrier at `if_hz`.
pub(crate) fn build(
    signal: Signal,
    sample_rate_hz: f64,
    if_hz: f64,
    settings: &AcquisitionSettings,
) -> Result<Box<dyn AcquisitionStage>, AcquisitionError> {
    let pcps = PcpsStage::new(signal, sample_rate_hz, if_hz, settings)?;
    Ok(match settings.method {
        AcquisitionMethod::Pcps => Box::new(pcps),
        AcquisitionMethod::PmfFft => {
            Box::new(PmfFftStage::new(pcps, signal, sample_rate_hz, if_hz)?)
        }
    })
}

#[cfg(test)]
mod stage_tests;
