//! Receiver clock: overlapping Allan deviation of simulated clocks against the value the
//! h-coefficients predict, and determinism of the stream.
//!
//! Estimator spread (measured over 50 seeds while writing this test, 2000 s at 10 ms):
//! the relative standard deviation of OADEV at tau = 100 s is about 20 % where random-walk
//! FM dominates (tcxo, tcxo-low, ocxo, quartz) and about 12 % where white FM dominates
//! (rubidium, cesium); about 30 % resp. 10 % of seeds fall outside +-20 % there. At tau = 1
//! and 10 s the spread is 1.5 % and 4 %. The single-seed acceptance therefore uses the
//! first seed tried (0) and the seed-averaged checks carry the statistical weight.

use skyforge_signals::errors::{
    ClockModel, ClockSample, OscillatorPreset, PowerLaw, overlapping_adev, overlapping_avar,
    predicted_adev, predicted_avar,
};
use skyforge_signals::errors::{Stream, stream_rng};

const DT_S: f64 = 0.01;
const DURATION_S: f64 = 2000.0;
const TAUS_S: [f64; 3] = [1.0, 10.0, 100.0];

/// `n` clock phase samples (s) at `dt_s` of a clock with power law `h`, starting with
/// zero offset and drift, from stream `seed`.
fn phase_series(h: &PowerLaw, dt_s: f64, seed: u64, n: usize) -> Vec<f64> {
    let mut clock = ClockModel::new(
        h,
        0.0,
        0.0,
        dt_s,
        stream_rng(seed, Stream::Named("clock"), 0),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    clock.next_block(n).iter().map(|s| s.phase_s).collect()
}

fn simulate(preset: OscillatorPreset, seed: u64) -> Vec<f64> {
    let n = (DURATION_S / DT_S).round() as usize + 1;
    phase_series(&preset.power_law(), DT_S, seed, n)
}

fn m_of(tau_s: f64) -> usize {
    (tau_s / DT_S).round() as usize
}

/// ACCEPTANCE: OADEV of a 2000 s clock at tau = 1, 10, 100 s within 20 % of the
/// prediction, for every preset (fixed seed 0).
#[test]
fn acceptance_oadev_within_20_percent_of_prediction_for_every_preset() {
    let mut failures = Vec::new();
    println!("preset     tau_s  predicted   measured   ratio");
    for preset in OscillatorPreset::ALL {
        let h = preset.power_law();
        let phase = simulate(preset, 0);
        for tau in TAUS_S {
            let predicted = predicted_adev(&h, tau);
            let measured = overlapping_adev(&phase, DT_S, m_of(tau));
            let ratio = measured / predicted;
            println!(
                "{:9} {:>6} {predicted:10.3e} {measured:10.3e} {ratio:7.3}",
                preset.name(),
                tau
            );
            if (ratio - 1.0).abs() > 0.2 {
                failures.push(format!("{} tau {tau}: ratio {ratio:.3}", preset.name()));
            }
        }
    }
    assert!(failures.is_empty(), "outside 20 %: {failures:?}");
}

/// Over 20 seeds the mean Allan variance (unbiased) and the mean Allan deviation (biased
/// low by a few % at small edf) are within 10 % of the prediction.
#[test]
fn seed_averaged_oadev_within_10_percent_of_prediction() {
    const SEEDS: u64 = 20;
    let mut failures = Vec::new();
    for preset in OscillatorPreset::ALL {
        let h = preset.power_law();
        let mut sum_avar = [0.0; 3];
        let mut sum_adev = [0.0; 3];
        for seed in 1..=SEEDS {
            let phase = simulate(preset, seed);
            for (j, tau) in TAUS_S.into_iter().enumerate() {
                let ratio = overlapping_avar(&phase, DT_S, m_of(tau)) / predicted_avar(&h, tau);
                sum_avar[j] += ratio;
                sum_adev[j] += ratio.sqrt();
            }
        }
        for (j, tau) in TAUS_S.into_iter().enumerate() {
            let rms = (sum_avar[j] / SEEDS as f64).sqrt();
            let mean = sum_adev[j] / SEEDS as f64;
            println!(
                "{:9} tau {tau:>5}: rms ratio {rms:.3}, mean ratio {mean:.3}",
                preset.name()
            );
            if (rms - 1.0).abs() > 0.1 || (mean - 1.0).abs() > 0.1 {
                failures.push(format!(
                    "{} tau {tau}: rms {rms:.3} mean {mean:.3}",
                    preset.name()
                ));
            }
        }
    }
    assert!(failures.is_empty(), "seed means outside 10 %: {failures:?}");
}

/// White FM alone: OADEV from phase is exact for every tau (no model approximation), so
/// 2000 s at tau = 1 s must match sqrt(h0 / 2) within the 1.5 % estimator spread (x3).
#[test]
fn pure_white_fm_matches_closed_form() {
    let h = PowerLaw {
        h0: 4e-20,
        h_minus1: 0.0,
        h_minus2: 0.0,
    };
    let phase = phase_series(&h, DT_S, 11, 200_001);
    let measured = overlapping_adev(&phase, DT_S, 100);
    let expected = (4e-20_f64 / 2.0).sqrt();
    assert!(
        (measured / expected - 1.0).abs() < 0.05,
        "{measured} vs {expected}"
    );
}

/// Flicker FM alone (the Gauss-Markov-sum approximation): the Allan floor
/// `sqrt(2 ln2 h_minus1)` over 10 dt .. 1e4 s. 20 seeds of 2e5 s at dt = 1 s; the
/// tolerances are about three standard errors of the seed-averaged estimate plus the
/// model's own 2.5 % shortfall at 10 dt.
#[test]
fn pure_flicker_fm_floor_holds_from_10_dt_to_1e4_s() {
    const SEEDS: u64 = 20;
    let h = PowerLaw {
        h0: 0.0,
        h_minus1: 1e-20,
        h_minus2: 0.0,
    };
    let checks = [(10.0, 0.05), (100.0, 0.03), (1000.0, 0.05), (1e4, 0.10)];
    let mut sums = [0.0; 4];
    for seed in 0..SEEDS {
        let phase = phase_series(&h, 1.0, seed, 200_001);
        for (sum, (tau, _)) in sums.iter_mut().zip(checks) {
            *sum += overlapping_avar(&phase, 1.0, tau as usize) / predicted_avar(&h, tau);
        }
    }
    for (sum, (tau, tolerance)) in sums.into_iter().zip(checks) {
        let rms = (sum / SEEDS as f64).sqrt();
        println!("flicker tau {tau:>7}: rms ratio {rms:.3}");
        assert!((rms - 1.0).abs() < tolerance, "tau {tau}: {rms:.3}");
    }
}

/// Same key -> identical samples whether pulled as one block of 20000 or in blocks of 137.
#[test]
fn stream_is_identical_for_any_block_size() {
    let h = OscillatorPreset::Quartz.power_law();
    let make = |index| {
        ClockModel::new(
            &h,
            1e-4,
            3e-8,
            0.001,
            stream_rng(42, Stream::Named("clock"), index),
        )
        .unwrap_or_else(|e| panic!("{e}"))
    };
    let whole = make(3).next_block(20_000);
    let mut chunked = Vec::with_capacity(20_000);
    let mut clock = make(3);
    let mut buf = [ClockSample {
        t_s: 0.0,
        phase_s: 0.0,
        freq: 0.0,
    }; 137];
    while chunked.len() < 20_000 {
        let take = buf.len().min(20_000 - chunked.len());
        clock.fill(&mut buf[..take]);
        chunked.extend_from_slice(&buf[..take]);
    }
    assert!(whole.iter().zip(&chunked).all(|(a, b)| {
        a.phase_s.to_bits() == b.phase_s.to_bits()
            && a.freq.to_bits() == b.freq.to_bits()
            && a.t_s.to_bits() == b.t_s.to_bits()
    }));
    let other = make(4).next_block(10);
    assert_ne!(other[9].phase_s, whole[9].phase_s);
}
