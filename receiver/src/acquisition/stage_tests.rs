//! The acquisition stages against their theory: PCPS detection, the PMF-FFT fine Doppler.

use super::pmf_fft_stage::{PMF_FILTER_CHIPS, PMF_PERIODS};
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
    let pcps = build(Signal::GpsL1Ca, FS, 0.0, &settings).unwrap();
    let pmf = build(
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
