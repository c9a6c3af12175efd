//! Searching one antenna's block for satellites: cold (every PRN over the configured
//! Doppler window) or assisted (predicted satellites around their predicted Doppler).

use super::config::AcquisitionSettings;
use crate::acquisition::AcquisitionError;
use crate::acquisition::pcps::{Acquisition, BitTransition, DopplerWindow, Pcps, PcpsConfig};
use num_complex::Complex32;
use rayon::prelude::*;
use skyforge_signals::signal::Signal;

/// A satellite to search for, with its Doppler window and predicted Doppler rate.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Candidate {
    pub(crate) prn: u8,
    pub(crate) window: DopplerWindow,
    pub(crate) doppler_rate_hzps: f64,
    /// The window is the blind one (no prediction for this satellite).
    pub(crate) cold: bool,
}

/// The search plan of one signal.
pub(crate) struct Search {
    pcps: Pcps,
}

impl Search {
    pub(crate) fn new(
        signal: Signal,
        sample_rate_hz: f64,
        if_hz: f64,
        s: &AcquisitionSettings,
    ) -> Result<Self, AcquisitionError> {
        let mut config = PcpsConfig::cold(signal, sample_rate_hz);
        config.carrier_offset_hz = if_hz;
        config.coherent_periods = s.coherent_ms;
        config.noncoherent = s.noncoherent;
        config.pfa = s.pfa;
        config.window = DopplerWindow {
            centre_hz: 0.0,
            half_width_hz: s.cold_half_width_hz,
        };
        // BeiDou: NH chips (D1) every 1 ms and D2 bits every 2 ms change the sign
        // between code periods; GPS bits change only every 20 ms.
        config.bit_transition = match signal {
            Signal::BdsB1I => BitTransition::AlignedWindows,
            Signal::GpsL1Ca => BitTransition::Ignore,
        };
        Ok(Self {
            pcps: Pcps::new(config)?,
        })
    }

    /// Samples a search reads.
    pub(crate) fn samples_needed(&self) -> usize {
        self.pcps.samples_needed()
    }

    /// Doppler bin spacing of the search (Hz).
    pub(crate) fn doppler_step_hz(&self) -> f64 {
        self.pcps.config().doppler_step()
    }

    /// The cold window.
    pub(crate) fn cold_window(&self) -> DopplerWindow {
        self.pcps.config().window
    }

    /// Search every candidate in `samples` (which start at the hand-over sample); returns
    /// the detections.
    pub(crate) fn run(
        &self,
        samples: &[Complex32],
        candidates: &[Candidate],
    ) -> Result<Vec<(Candidate, Acquisition)>, AcquisitionError> {
        let found: Result<Vec<_>, AcquisitionError> = candidates
            .par_iter()
            .map(|c| {
                let code = self.pcps.prepare(c.prn)?;
                let acq = self.pcps.search_window(samples, &code, c.window)?;
                Ok((*c, acq))
            })
            .collect();
        Ok(found?.into_iter().filter(|(_, a)| a.detected).collect())
    }
}
