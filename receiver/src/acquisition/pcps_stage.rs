//! The `pcps` acquisition stage: the parallel code-phase search over Doppler bins.

use super::config::AcquisitionSettings;
use super::pcps::{Acquisition, BitTransition, DopplerWindow, Pcps, PcpsConfig};
use super::{AcquisitionError, AcquisitionStage, Candidate};
use num_complex::Complex32;
use rayon::prelude::*;
use skyforge_gnss::signal::Signal;

/// Parallel code-phase search over Doppler bins.
pub(super) struct PcpsStage {
    pcps: Pcps,
}

impl PcpsStage {
    pub(super) fn new(
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
        // between code periods, as the secondary codes of L5 and E5a do on both
        // components: a sign change inside a block splits the Doppler peak (on 45 s of
        // interop-l5-static, 7 of 20 detections from one-period blocks never locked, none
        // of 12 from aligned windows; the loops do not pull in from 300 Hz off). GPS L1
        // C/A bits change only every 20 ms.
        // Galileo E1's I/NAV symbols and E1-C's CS25 change sign every 4 ms period.
        config.bit_transition = match signal {
            Signal::BdsB1I | Signal::GpsL5 | Signal::GalE5a | Signal::GalE1 => {
                BitTransition::AlignedWindows
            }
            // B2a: the 5-chip data and 100-chip pilot secondary codes (BDS-SIS-ICD-B2a-1.0
            // §5.2.2) flip signs between 1 ms periods, as E5a's.
            Signal::BdsB2a => BitTransition::AlignedWindows,
            // B1C: the B-CNAV1 symbols on the data and the 1800-chip secondary code on the
            // pilot may each change sign between 10 ms periods (BDS-SIS-ICD-B1C-1.0 §5.2.2,
            // §6.2.1).
            Signal::BdsB1C => BitTransition::AlignedWindows,
            // The observed-only signals are refused by `Pcps::new` (no code).
            Signal::GpsL1Ca | Signal::GpsL2 | Signal::BdsB2I | Signal::BdsB3I => {
                BitTransition::Ignore
            }
        };
        // E1's 4 ms periods: bins 1 / (2 T) apart (125 Hz at one period) lose at most
        // sinc(1/4) = 0.91 dB between bins, where the default 2 / (3 T) would lose 1.65 dB;
        // likewise B1C's 10 ms periods (50 Hz bins).
        if matches!(signal, Signal::GalE1 | Signal::BdsB1C) {
            config.doppler_step_hz = Some(1.0 / (2.0 * config.coherent_s()));
        }
        Ok(Self {
            pcps: Pcps::new(config)?,
        })
    }
}

impl AcquisitionStage for PcpsStage {
    fn samples_needed(&self) -> usize {
        self.pcps.samples_needed()
    }

    fn doppler_step_hz(&self) -> f64 {
        self.pcps.config().doppler_step()
    }

    fn cold_window(&self) -> DopplerWindow {
        self.pcps.config().window
    }

    fn run(
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
