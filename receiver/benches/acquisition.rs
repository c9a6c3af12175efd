//! Acquisition speed (issue #4 speed bar): a cold PCPS search of 32 GPS PRNs over
//! +/-10 kHz at 4.092 Msps with 1 ms coherent integration (replica FFTs included), and
//! one PMF-FFT fine Doppler estimate (M = 1024, L = 64); a cold search of 8 GPS L5 PRNs
//! (data and pilot, aligned windows) at 20.46 Msps; and the forward FFT at one code
//! period's length (4092 and 20 460 samples: 1 ms at 4.092 and 20.46 Msps), twice it, and
//! the nearest lengths without the factor 31 (4096, 8192, 20 480, 40 960), which the search
//! now uses (`Pcps::fft_len`).

use criterion::{Criterion, criterion_group, criterion_main};
use num_complex::Complex32;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, StandardNormal};
use skyforge_gnss::signal::Signal;
use skyforge_receiver::acquisition::pmf_fft::PmfFft;
use skyforge_receiver::acquisition::{BitTransition, Pcps, PcpsConfig};
use std::hint::black_box;

/// One code period of PRN 7 at 45 dB-Hz, 2.7 kHz Doppler, in unit noise.
fn samples(fs: f64, n: usize) -> Vec<Complex32> {
    let mut rng = ChaCha8Rng::seed_from_u64(42);
    let code = Signal::GpsL1Ca.code(7).unwrap_or_default();
    let amp = (2.0 * 10f64.powf(4.5) / fs).sqrt();
    (0..n)
        .map(|i| {
            let t = i as f64 / fs;
            let chip = ((t * 1.023e6 + 300.0) as usize) % 1023;
            let ph = std::f64::consts::TAU * 2700.0 * t;
            let s = amp * f64::from(code.get(chip).copied().unwrap_or(1));
            let (nre, nim): (f64, f64) = (
                StandardNormal.sample(&mut rng),
                StandardNormal.sample(&mut rng),
            );
            Complex32::new((s * ph.cos() + nre) as f32, (s * ph.sin() + nim) as f32)
        })
        .collect()
}

fn pcps_cold(c: &mut Criterion) {
    let fs = 4.092e6;
    let Ok(pcps) = Pcps::new(PcpsConfig::cold(Signal::GpsL1Ca, fs)) else {
        panic!("cold PCPS configuration refused");
    };
    let x = samples(fs, pcps.samples_needed());
    let prns: Vec<u8> = (1..=32).collect();
    let mut group = c.benchmark_group("acquisition");
    group.sample_size(10);
    group.bench_function("pcps_cold_32prn_pm10khz_4092ksps_1ms", |b| {
        b.iter(|| black_box(pcps.search_prns(black_box(&x), &prns)))
    });
    let Ok(pmf) = PmfFft::new(1024, 64) else {
        panic!("PMF-FFT M = 1024, L = 64 refused");
    };
    let chips: Vec<Complex32> = samples(1.023e6, 1024);
    let mut scratch = pmf.scratch();
    group.bench_function("pmf_fft_estimate_m1024_l64", |b| {
        b.iter(|| black_box(pmf.estimate(black_box(&chips), &mut scratch)))
    });
    let fs = 20.46e6;
    let Ok(l5) = Pcps::new(PcpsConfig {
        bit_transition: BitTransition::AlignedWindows,
        ..PcpsConfig::cold(Signal::GpsL5, fs)
    }) else {
        panic!("cold L5 PCPS configuration refused");
    };
    let x = samples(fs, l5.samples_needed());
    group.bench_function("pcps_cold_8prn_l5_pm10khz_20460ksps_1ms", |b| {
        b.iter(|| black_box(l5.search_prns(black_box(&x), &prns[..8])))
    });
    group.finish();
}

/// rustfft's forward transform of one code period's length and of the nearest length
/// without a large prime factor.
fn fft_lengths(c: &mut Criterion) {
    let mut planner = rustfft::FftPlanner::<f32>::new();
    let mut group = c.benchmark_group("fft_forward");
    for n in [4092, 4096, 8184, 8192, 20_460, 20_480, 40_920, 40_960] {
        let fft = planner.plan_fft_forward(n);
        let mut buf = samples(4.092e6, n);
        let mut scratch = vec![Complex32::default(); fft.get_inplace_scratch_len()];
        group.bench_function(format!("{n}"), |b| {
            b.iter(|| fft.process_with_scratch(black_box(&mut buf), &mut scratch))
        });
    }
    group.finish();
}

criterion_group!(benches, pcps_cold, fft_lengths);
criterion_main!(benches);
