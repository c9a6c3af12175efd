//! Local replicas for acquisition: a ranging code sampled at any sample rate, and the
//! carrier wipe-off of a block of samples by a phase-continuous NCO.

use num_complex::Complex32;
use skyforge_gnss::nco::{LanePhasors, turn};

/// The code `chips` (one period, +1/-1) sampled at `sample_rate_hz` for `n` samples:
/// sample `i` holds the chip active at `t = i / fs` of a code whose chip 0 starts at
/// `t = 0`, i.e. chip `floor(i Rc / fs) mod len` (nearest-preceding-chip sampling, no
/// code Doppler).
pub fn sample_code(chips: &[i8], chip_rate_hz: f64, sample_rate_hz: f64, n: usize) -> Vec<f32> {
    let len = chips.len().max(1);
    let chips_per_sample = chip_rate_hz / sample_rate_hz;
    (0..n)
        .map(|i| {
            let chip = (i as f64 * chips_per_sample).floor() as usize % len;
            chips.get(chip).map_or(0.0, |&c| f32::from(c))
        })
        .collect()
}

/// Mean delay (samples) of the chip edges of [`sample_code`]'s replica behind the
/// continuous edges: chip `k` starts at `k fs / Rc` but in the replica at the first sample
/// at or after it. 0 when `fs / Rc` is an integer, about 0.5 otherwise.
pub fn mean_edge_delay_samples(chip_rate_hz: f64, sample_rate_hz: f64, n: usize) -> f64 {
    let chips_per_sample = chip_rate_hz / sample_rate_hz;
    let (mut sum, mut edges) = (0.0, 0usize);
    let mut prev = 0.0;
    for i in 1..n {
        let chip = (i as f64 * chips_per_sample).floor();
        if chip > prev {
            sum += i as f64 - chip / chips_per_sample;
            edges += 1;
            prev = chip;
        }
    }
    if edges == 0 { 0.0 } else { sum / edges as f64 }
}

/// `out[i] = samples[i] * exp(-j 2 pi freq_hz (first_sample + i) / fs)`: removes a carrier
/// of `freq_hz` whose phase is zero at absolute sample 0, so blocks cut anywhere from
/// one recording stay phase-continuous. The NCO is [`LANES`] interleaved `f32` phasor
/// recurrences started from the exact (`f64`) phases of the block's first samples
/// (independent chains the compiler vectorises; over a 20 460-sample block each lane
/// takes 1279 steps, a drift of about 1e-4 rad).
pub fn wipe_carrier(
    samples: &[Complex32],
    first_sample: u64,
    sample_rate_hz: f64,
    freq_hz: f64,
    out: &mut [Complex32],
) {
    let cycles_per_sample = freq_hz / sample_rate_hz;
    let start_cycles = (cycles_per_sample * first_sample as f64).fract();
    let LanePhasors {
        mut re,
        mut im,
        step_re,
        step_im,
    } = LanePhasors::<LANES>::new(-start_cycles, -cycles_per_sample);
    let n = samples.len().min(out.len());
    let (chunks, tail) = samples[..n].as_chunks::<LANES>();
    let (outs, out_tail) = out[..n].as_chunks_mut::<LANES>();
    for (o, x) in outs.iter_mut().zip(chunks) {
        for l in 0..LANES {
            o[l] = Complex32::new(
                x[l].re * re[l] - x[l].im * im[l],
                x[l].re * im[l] + x[l].im * re[l],
            );
        }
        (re, im) = turn(&re, &im, step_re, step_im);
    }
    for (l, (o, x)) in out_tail.iter_mut().zip(tail).enumerate() {
        *o = x * Complex32::new(re[l], im[l]);
    }
}

/// Phasor lanes of [`wipe_carrier`].
const LANES: usize = 16;

#[cfg(test)]
mod tests {
    use super::*;
    use num_complex::Complex64;

    #[test]
    fn code_at_two_samples_per_chip_repeats_each_chip() {
        let chips = [1i8, -1, -1, 1];
        let s = sample_code(&chips, 1.0e6, 2.0e6, 10);
        assert_eq!(s, [1.0, 1.0, -1.0, -1.0, -1.0, -1.0, 1.0, 1.0, 1.0, 1.0]);
    }

    #[test]
    fn code_at_a_non_integer_rate_keeps_the_chip_boundaries() {
        // 2.6 Msps for a 1.023 Mchip/s code: sample i is in chip floor(i * 1.023 / 2.6).
        let chips: Vec<i8> = (0..1023).map(|k| if k % 3 == 0 { 1 } else { -1 }).collect();
        let s = sample_code(&chips, 1.023e6, 2.6e6, 2600);
        for (i, &v) in s.iter().enumerate() {
            let k = (i as f64 * 1.023 / 2.6).floor() as usize;
            assert_eq!(v, f32::from(chips[k % 1023]), "sample {i}");
        }
    }

    #[test]
    fn edge_delay_is_zero_at_integer_rates_and_half_a_sample_otherwise() {
        assert_eq!(mean_edge_delay_samples(1.023e6, 4.092e6, 4092), 0.0);
        assert_eq!(mean_edge_delay_samples(2.046e6, 4.092e6, 4092), 0.0);
        let d = mean_edge_delay_samples(1.023e6, 2.6e6, 2600);
        assert!((d - 0.5).abs() < 0.02, "{d}");
    }

    #[test]
    fn wipe_off_is_phase_continuous_across_blocks_and_matches_direct_evaluation() {
        let fs = 4.092e6;
        let f = -3456.7;
        let x: Vec<Complex32> = (0..5000)
            .map(|i| Complex32::new(1.0 + 0.001 * i as f32, -0.5))
            .collect();
        let mut whole = vec![Complex32::default(); x.len()];
        wipe_carrier(&x, 1_000_000, fs, f, &mut whole);
        let mut second = vec![Complex32::default(); 3000];
        wipe_carrier(&x[2000..], 1_002_000, fs, f, &mut second);
        // f32 phasor lanes: rounding grows by about 1e-7 per step (312 steps here).
        for i in 0..3000 {
            let tol = 1e-4 * x[2000 + i].norm();
            assert!((whole[2000 + i] - second[i]).norm() < tol);
        }
        for i in [0usize, 1234, 4999, 4993] {
            let phase = -std::f64::consts::TAU * f * (1_000_000 + i) as f64 / fs;
            let direct = Complex64::new(f64::from(x[i].re), f64::from(x[i].im))
                * Complex64::from_polar(1.0, phase);
            let tol = 1e-4 * direct.norm();
            assert!((f64::from(whole[i].re) - direct.re).abs() < tol);
            assert!((f64::from(whole[i].im) - direct.im).abs() < tol);
        }
    }
}
