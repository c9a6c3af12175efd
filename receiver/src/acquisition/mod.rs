//! Acquisition: parallel code-phase search (PCPS) and the PMF-FFT of thesis section 3.3.1.
//!
//! - [`pcps`]: FFT circular correlation over a Doppler grid, coherent and non-coherent
//!   integration, a CFAR decision ([`cfar`]), optional bit-transition-safe windows.
//! - [`pmf_fft`]: partial matched filters + FFT with the fine Doppler estimator of thesis
//!   eq. 3.3-13/3.3-14, and its noise theory (eq. 3.3-45..3.3-55) in [`pmf_fft::theory`].
//! - [`replica`]: ranging-code replicas at any sample rate and the carrier wipe-off.

pub mod cfar;
pub mod pcps;
pub mod pmf_fft;
pub mod replica;

/// The complex `f32` sample type the acquisition functions take.
pub use num_complex::Complex32;

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
    #[error("{0} is read from observation files only; SkyForge does not acquire or track it")]
    NotTracked(skyforge_gnss::signal::Signal),
}
