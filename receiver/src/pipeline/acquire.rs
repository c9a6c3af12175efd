//! Searching one antenna's block for satellites: cold (every PRN over the configured
//! Doppler window) or assisted (predicted satellites around their predicted Doppler), by
//! the acquisition stage the configuration names: PCPS, or PCPS with the PMF-FFT fine
//! Doppler.

use super::config::{AcquisitionMethod, AcquisitionSettings};
use crate::acquisition::AcquisitionError;
use crate::acquisition::pcps::{Acquisition, BitTransition, DopplerWindow, Pcps, PcpsConfig};
use crate::acquisition::pmf_fft::{ChipTiming, PmfFft, despread_to_chips};
use num_complex::Complex32;
use rayon::prelude::*;
use skyforge_gnss::signal::Signal;

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
pub(crate) fn acquisition_stage(
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

/// Parallel code-phase search over Doppler bins.
struct PcpsStage {
    pcps: Pcps,
}

impl PcpsStage {
    fn new(
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
            // The observed-only signals are refused by `Pcps::new` (no code).
            Signal::GpsL1Ca | Signal::GpsL2 | Signal::GpsL5 | Signal::BdsB2I | Signal::BdsB3I => {
                BitTransition::Ignore
            }
        };
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

/// Chips per partial matched filter (thesis section 3.3.5: L = 64).
const PMF_FILTER_CHIPS: usize = 64;
/// Code periods whose fine Doppler estimates are averaged. # assumed: 10 (10 ms, inside
/// one search block; the estimates of separate periods are independent, so the average
/// has a third of one period's standard deviation).
const PMF_PERIODS: usize = 10;

/// PCPS for detection and code phase, then the Doppler from the PMF-FFT fine estimator
/// (thesis eqs. 3.3-13, 3.3-14) on the despread chips of [`PMF_PERIODS`] code periods,
/// with the carrier wiped at the PCPS Doppler: the refined Doppler is the PCPS one plus
/// the mean fine offset.
struct PmfFftStage {
    pcps: PcpsStage,
    pmf: PmfFft,
    signal: Signal,
    sample_rate_hz: f64,
    if_hz: f64,
}

impl PmfFftStage {
    fn new(
        pcps: PcpsStage,
        signal: Signal,
        sample_rate_hz: f64,
        if_hz: f64,
    ) -> Result<Self, AcquisitionError> {
        // M: the code padded with zero chips to a power of two (1023 -> 1024, 2046 -> 2048).
        let m = signal.code_length().next_power_of_two();
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
        let code = self.signal.code(acq.prn)?;
        let period = self.period_samples(acq.doppler_hz);
        let chip_rate =
            self.signal.chip_rate_hz() * (1.0 + acq.doppler_hz / self.signal.carrier_hz());
        let mut scratch = self.pmf.scratch();
        let mut sum = 0.0;
        let mut count = 0;
        for k in 0..PMF_PERIODS {
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
        let periods = (PMF_PERIODS + 1) as f64 * self.period_samples(0.0);
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::acquisition::pmf_fft::theory::nmse_fd_tc;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;
    use rand_distr::{Distribution, StandardNormal};

    const FS: f64 = 4.0e6;
    const CN0_DBHZ: f64 = 45.0;
    const PRN: u8 = 7;

    /// 20 ms of GPS C/A (no data transition) at `doppler_hz` from sample `start` on, in
    /// unit-variance complex noise at [`CN0_DBHZ`] (`C/N0 = A^2 fs / 2`).
    fn signal(rng: &mut ChaCha8Rng, doppler_hz: f64, start: f64) -> Vec<Complex32> {
        let s = Signal::GpsL1Ca;
        let code = s.code(PRN).unwrap();
        let rc = s.chip_rate_hz() * (1.0 + doppler_hz / s.carrier_hz());
        let amp = (2.0 * 10f64.powf(CN0_DBHZ / 10.0) / FS).sqrt();
        let phase0: f64 = rng.random_range(0.0..std::f64::consts::TAU);
        (0..(0.02 * FS) as usize)
            .map(|i| {
                let chip = ((i as f64 - start) / FS * rc).floor() as i64;
                let c = f64::from(code[chip.rem_euclid(code.len() as i64) as usize]);
                let ph = phase0 + std::f64::consts::TAU * doppler_hz * i as f64 / FS;
                let n: [f64; 2] = [StandardNormal.sample(rng), StandardNormal.sample(rng)];
                Complex32::new(
                    (amp * c * ph.cos() + n[0]) as f32,
                    (amp * c * ph.sin() + n[1]) as f32,
                )
            })
            .collect()
    }

    /// The PMF-FFT stage's Doppler error (RMS over trials) is below the PCPS stage's on the
    /// same samples and within a factor 1.5 of the thesis's theory for the average of
    /// [`PMF_PERIODS`] independent estimates (eq. 3.3-74: variance plus squared bias).
    #[test]
    fn pmf_fft_refines_the_pcps_doppler_as_its_theory_predicts() {
        let settings = AcquisitionSettings::default();
        let pcps = acquisition_stage(Signal::GpsL1Ca, FS, 0.0, &settings).unwrap();
        let pmf = acquisition_stage(
            Signal::GpsL1Ca,
            FS,
            0.0,
            &AcquisitionSettings {
                method: AcquisitionMethod::PmfFft,
                ..settings
            },
        )
        .unwrap();
        let candidate = Candidate {
            prn: PRN,
            window: pcps.cold_window(),
            doppler_rate_hzps: 0.0,
            cold: true,
        };
        let mut rng = ChaCha8Rng::seed_from_u64(17);
        let (mut se_pcps, mut se_pmf, mut nmse) = (0.0, 0.0, 0.0);
        let trials = 40;
        for _ in 0..trials {
            let doppler: f64 = rng.random_range(-5000.0..5000.0);
            let start: f64 = rng.random_range(0.0..3900.0);
            let x = signal(&mut rng, doppler, start);
            let found = |stage: &dyn AcquisitionStage| {
                let hits = stage.run(&x, &[candidate]).unwrap();
                assert_eq!(hits.len(), 1, "PRN {PRN} at 45 dB-Hz is detected");
                hits[0].1.doppler_hz - doppler
            };
            se_pcps += found(pcps.as_ref()).powi(2);
            let e = found(pmf.as_ref());
            se_pmf += e * e;
            // The residual the fine estimator sees: the PCPS error.
            let rc = Signal::GpsL1Ca.chip_rate_hz();
            let snr_chip = 10f64.powf(CN0_DBHZ / 10.0) / rc;
            let residual_tc = found(pcps.as_ref()) / rc;
            nmse += nmse_fd_tc(1024, PMF_FILTER_CHIPS, residual_tc, snr_chip) * rc * rc
                / PMF_PERIODS as f64;
        }
        let rms = |se: f64| (se / f64::from(trials)).sqrt();
        let theory = (nmse / f64::from(trials)).sqrt();
        let (pcps_rms, pmf_rms) = (rms(se_pcps), rms(se_pmf));
        assert!(
            pmf_rms < pcps_rms,
            "PMF-FFT {pmf_rms:.1} Hz vs PCPS {pcps_rms:.1} Hz"
        );
        assert!(
            pmf_rms < 1.5 * theory && pmf_rms > theory / 1.5,
            "PMF-FFT {pmf_rms:.1} Hz RMS, theory {theory:.1} Hz"
        );
    }
}
