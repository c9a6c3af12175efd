//! The `pmf-fft` acquisition stage: PCPS, then the PMF-FFT fine Doppler of thesis sections
//! 3.3.1-3.3.2.

use super::pcps::{Acquisition, DopplerWindow};
use super::pcps_stage::PcpsStage;
use super::pmf_fft::{ChipTiming, PmfFft, despread_to_chips};
use super::{AcquisitionError, AcquisitionStage, Candidate};
use crate::replica::{replica_chips, subchips};
use num_complex::Complex32;
use rayon::prelude::*;
use skyforge_gnss::signal::Signal;

/// Chips per partial matched filter (thesis section 3.3.5: L = 64).
pub(super) const PMF_FILTER_CHIPS: usize = 64;
/// Code periods whose fine Doppler estimates are averaged. # assumed: 10 (10 ms, inside
/// one search block; the estimates of separate periods are independent, so the average
/// has a third of one period's standard deviation).
pub(super) const PMF_PERIODS: usize = 10;
/// Galileo E1's 4 ms periods averaged: 4 (16 ms of 8184 half-chips each), so that a search
/// (one period more) fits the receiver's 20 ms blocks.
const PMF_E1_PERIODS: usize = 4;

/// BeiDou B1C's 10 ms periods averaged: 2 (20 ms of 20460 half-chips each), so that a
/// search (one period more) fits the 30 ms a B1C block holds.
const PMF_B1C_PERIODS: usize = 2;

/// Code periods averaged for `signal`.
fn pmf_periods(signal: Signal) -> usize {
    match signal {
        Signal::GalE1 => PMF_E1_PERIODS,
        Signal::BdsB1C => PMF_B1C_PERIODS,
        _ => PMF_PERIODS,
    }
}

/// PCPS for detection and code phase, then the Doppler from the PMF-FFT fine estimator
/// (thesis eqs. 3.3-13, 3.3-14) on the despread chips of [`PMF_PERIODS`] code periods,
/// with the carrier wiped at the PCPS Doppler: the refined Doppler is the PCPS one plus
/// the mean fine offset.
pub(super) struct PmfFftStage {
    pcps: PcpsStage,
    pmf: PmfFft,
    signal: Signal,
    sample_rate_hz: f64,
    if_hz: f64,
}

impl PmfFftStage {
    pub(super) fn new(
        pcps: PcpsStage,
        signal: Signal,
        sample_rate_hz: f64,
        if_hz: f64,
    ) -> Result<Self, AcquisitionError> {
        // M: the code padded with zero chips to a power of two (1023 -> 1024, 2046 -> 2048;
        // Galileo E1's 8184 BOC(1,1) half-chips -> 8192).
        let m = (signal.code_length() * subchips(signal)).next_power_of_two();
        Ok(Self {
            pcps,
            pmf: PmfFft::new(m, PMF_FILTER_CHIPS)?,
            signal,
            sample_rate_hz,
            if_hz,
        })
    }

    /// Samples of one code period at Doppler `doppler_hz` (code Doppler included).
    fn period_samples(&self, doppler_hz: f64) -> f64 {
        let chip_rate = self.signal.chip_rate_hz() * (1.0 + doppler_hz / self.signal.carrier_hz());
        self.signal.code_length() as f64 * self.sample_rate_hz / chip_rate
    }

    /// The PCPS Doppler refined by the mean PMF-FFT fine offset over the whole code
    /// periods after the code phase.
    fn refine(&self, samples: &[Complex32], acq: &Acquisition) -> Result<f64, AcquisitionError> {
        let code = replica_chips(self.signal, &self.signal.code(acq.prn)?);
        let period = self.period_samples(acq.doppler_hz);
        // Replica chips per second (BOC(1,1) half-chips for Galileo E1).
        let chip_rate = self.signal.chip_rate_hz()
            * subchips(self.signal) as f64
            * (1.0 + acq.doppler_hz / self.signal.carrier_hz());
        let mut scratch = self.pmf.scratch();
        let mut sum = 0.0;
        let mut count = 0;
        for k in 0..pmf_periods(self.signal) {
            let timing = ChipTiming {
                sample_rate_hz: self.sample_rate_hz,
                carrier_hz: self.if_hz + acq.doppler_hz,
                chip_rate_hz: chip_rate,
                code_start_sample: acq.code_phase_samples + k as f64 * period,
            };
            match despread_to_chips(samples, timing, &code, self.pmf.m()) {
                Ok(chips) => {
                    sum += self.pmf.estimate(&chips, &mut scratch)?.fine_fd_tc;
                    count += 1;
                }
                Err(AcquisitionError::TooFewSamples { .. }) => break,
                Err(e) => return Err(e),
            }
        }
        Ok(if count == 0 {
            acq.doppler_hz
        } else {
            acq.doppler_hz + sum / f64::from(count) * chip_rate
        })
    }
}

impl AcquisitionStage for PmfFftStage {
    fn samples_needed(&self) -> usize {
        let periods = (pmf_periods(self.signal) + 1) as f64 * self.period_samples(0.0);
        self.pcps.samples_needed().max(periods.ceil() as usize)
    }

    fn doppler_step_hz(&self) -> f64 {
        self.pcps.doppler_step_hz()
    }

    fn cold_window(&self) -> DopplerWindow {
        self.pcps.cold_window()
    }

    fn run(
        &self,
        samples: &[Complex32],
        candidates: &[Candidate],
    ) -> Result<Vec<(Candidate, Acquisition)>, AcquisitionError> {
        self.pcps
            .run(samples, candidates)?
            .into_par_iter()
            .map(|(c, acq)| {
                let doppler_hz = self.refine(samples, &acq)?;
                Ok((c, Acquisition { doppler_hz, ..acq }))
            })
            .collect()
    }
}
