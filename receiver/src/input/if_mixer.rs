//! Real IF samples to complex baseband: `y[k] = 2 x[k] exp(-j 2 pi f_IF k / fs)`.
//!
//! A real signal `A s(t) cos(2 pi f_IF t + phi)` becomes `A s(t) exp(j phi)` (the factor 2
//! makes a full-scale real carrier a unit phasor) plus its image
//! `A s(t) exp(-j (4 pi f_IF t + phi))` at -2 IF. No filter removes the image: it lies
//! 2 IF (several MHz) away from the wanted signal, so the code and carrier correlation of
//! acquisition and tracking reject it like any out-of-band interference (over a 1 ms
//! integration its residual is attenuated by the code's cross-spectrum at 2 IF and
//! `sinc(2 IF x 1 ms)`); it only adds to the noise-like power. C/N0 is preserved: the
//! wanted component keeps the real signal's C/N0, the real noise's two halves of the
//! spectrum both land in the complex band.
//!
//! The NCO phase is accumulated in f64 cycles per block (exact to ~1e-16 cycles per block);
//! within a block the phasor is the block-start phasor times a precomputed f32 table
//! `2 exp(-j 2 pi k f_IF / fs)`, so no trigonometry runs per sample.

use num_complex::Complex32;
use std::f64::consts::TAU;

/// The real-to-complex mixing NCO of one antenna.
#[derive(Debug, Clone)]
pub struct IfMixer {
    /// IF in cycles per sample.
    cycles_per_sample: f64,
    /// NCO phase at the next sample (cycles, in [0, 1)).
    phase_cycles: f64,
    /// `2 exp(-j 2 pi k f_IF / fs)` for k in 0..len.
    table: Vec<Complex32>,
}

impl IfMixer {
    /// A mixer for IF `if_hz` at `sample_rate_hz`, for blocks of up to `block_len`
    /// samples (longer blocks grow the table once).
    pub fn new(if_hz: f64, sample_rate_hz: f64, block_len: usize) -> Self {
        let mut mixer = Self {
            cycles_per_sample: if_hz / sample_rate_hz,
            phase_cycles: 0.0,
            table: Vec::new(),
        };
        mixer.grow(block_len);
        mixer
    }

    /// Extends the table to `len` samples.
    fn grow(&mut self, len: usize) {
        let step = self.cycles_per_sample;
        let start = self.table.len();
        self.table.extend((start..len).map(|k| {
            let (s, c) = (-TAU * (k as f64 * step).rem_euclid(1.0)).sin_cos();
            Complex32::new((2.0 * c) as f32, (2.0 * s) as f32)
        }));
    }

    /// Mixes the next `x.len()` real samples (continuing the stream) into `out[..x.len()]`.
    pub fn mix(&mut self, x: &[f32], out: &mut [Complex32]) {
        let n = x.len().min(out.len());
        if n > self.table.len() {
            self.grow(n);
        }
        let (s, c) = (-TAU * self.phase_cycles).sin_cos();
        let start = Complex32::new(c as f32, s as f32);
        for ((o, &v), &t) in out[..n].iter_mut().zip(x).zip(&self.table) {
            *o = start * t * v;
        }
        self.phase_cycles = (self.phase_cycles
            + (n as f64 * self.cycles_per_sample).rem_euclid(1.0))
        .rem_euclid(1.0);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `cos(2 pi f k / fs + phi)` for k in k0..k0 + n.
    fn tone(f_over_fs: f64, phi: f64, k0: usize, n: usize) -> Vec<f32> {
        (k0..k0 + n)
            .map(|k| (TAU * f_over_fs * k as f64 + phi).cos() as f32)
            .collect()
    }

    #[test]
    fn a_carrier_at_the_if_becomes_a_unit_phasor_plus_its_image() {
        // fs = 4 MHz, IF = 1.25 MHz, carrier at IF + 1 kHz with phase 0.3 rad.
        let (fs, f_if, df, phi) = (4e6, 1.25e6, 1e3, 0.3);
        let n = 40_000;
        let x = tone((f_if + df) / fs, phi, 0, n);
        let mut m = IfMixer::new(f_if, fs, 4000);
        let mut y = vec![Complex32::new(0.0, 0.0); n];
        for (xs, ys) in x.chunks(4000).zip(y.chunks_mut(4000)) {
            m.mix(xs, ys);
        }
        // Wipe the expected baseband phasor exp(j (2 pi df k / fs + phi)) and average: the
        // image (at -2 IF - df relative) averages out over whole periods.
        let mean: num_complex::Complex64 = y
            .iter()
            .enumerate()
            .map(|(k, v)| {
                let w = num_complex::Complex64::from_polar(1.0, -(TAU * df * k as f64 / fs + phi));
                num_complex::Complex64::new(f64::from(v.re), f64::from(v.im)) * w
            })
            .sum::<num_complex::Complex64>()
            / n as f64;
        assert!((mean.re - 1.0).abs() < 1e-3, "{mean}");
        assert!(mean.im.abs() < 1e-3, "{mean}");
        // Sample by sample: y = exp(j a) + exp(-j b) with the analytical a, b.
        for (k, v) in y.iter().enumerate().step_by(997) {
            let t = k as f64 / fs;
            let a = TAU * df * t + phi;
            let b = TAU * (2.0 * f_if + df) * t + phi;
            let want = num_complex::Complex64::from_polar(1.0, a)
                + num_complex::Complex64::from_polar(1.0, -b);
            assert!((f64::from(v.re) - want.re).abs() < 2e-5, "k {k}");
            assert!((f64::from(v.im) - want.im).abs() < 2e-5, "k {k}");
        }
    }

    #[test]
    fn block_length_does_not_change_the_output() {
        let (fs, f_if) = (16.368e6, 4.092e6 + 0.3);
        let x = tone(0.2371, 1.0, 0, 10_000);
        let run = |sizes: &[usize]| {
            let mut m = IfMixer::new(f_if, fs, 16);
            let mut y = vec![Complex32::new(0.0, 0.0); x.len()];
            let mut k = 0;
            for &len in sizes.iter().cycle() {
                if k >= x.len() {
                    break;
                }
                let e = (k + len).min(x.len());
                m.mix(&x[k..e], &mut y[k..e]);
                k = e;
            }
            y
        };
        let a = run(&[10_000]);
        let b = run(&[1, 7, 333, 4096]);
        for (p, q) in a.iter().zip(&b) {
            assert!((p - q).norm() < 1e-5);
        }
    }
}
