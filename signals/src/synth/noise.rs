//! Thermal noise of one antenna's front end: white complex Gaussian samples that depend
//! only on (scenario seed, antenna index, absolute sample index).
//!
//! Samples come in frames of [`NOISE_FRAME`]; frame `f` is drawn from ChaCha8 keyed by
//! `errors::seed::stream_seed(seed, Stream::Thermal, antenna)` on stream `f`, so any block
//! split, thread count or processing order yields the same samples. (ChaCha8 instead of
//! ChaCha20: noise needs statistical quality, not cryptographic margin, and it is 2x
//! cheaper.) Each component takes one 32-bit word of the stream (the frame's I words
//! first, then its Q words) and becomes a normal deviate by table inversion of the
//! normal distribution ([`normal_table`]).

mod normal_table;

use crate::errors::seed::{Stream, stream_seed};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// Complex samples per independently seeded noise frame.
pub const NOISE_FRAME: usize = 1024;

/// The noise source of one antenna.
#[derive(Debug, Clone)]
pub struct ThermalNoise {
    key: [u8; 32],
    sigma: f32,
    words: Vec<u32>,
    frame: Vec<f32>,
    frame_index: Option<u64>,
}

impl ThermalNoise {
    /// Noise with standard deviation `sigma` per component for antenna `antenna`.
    pub fn new(seed: u64, antenna: u32, sigma: f32) -> Self {
        Self::of_stream(seed, Stream::Thermal, antenna, sigma)
    }

    /// White complex Gaussian noise of `sigma` per component drawn from `stream`'s
    /// `index` (a noise jammer's waveform: `Stream::JammerNoise`).
    pub fn of_stream(seed: u64, stream: Stream, index: u32, sigma: f32) -> Self {
        normal_table::init();
        Self {
            key: stream_seed(seed, stream, index),
            sigma,
            words: Vec::new(),
            frame: Vec::new(),
            frame_index: None,
        }
    }

    /// Standard deviation per component.
    pub fn sigma(&self) -> f32 {
        self.sigma
    }

    fn load_frame(&mut self, f: u64) {
        if self.frame_index == Some(f) {
            return;
        }
        let mut rng = ChaCha8Rng::from_seed(self.key);
        rng.set_stream(f);
        self.words.resize(2 * NOISE_FRAME, 0);
        rng.fill(&mut self.words[..]);
        self.frame.resize(2 * NOISE_FRAME, 0.0);
        normal_table::fill_normal(&self.words, self.sigma, &mut self.frame);
        self.frame_index = Some(f);
    }

    /// Add the noise of absolute samples `first_sample ..` to `i` and `q`.
    pub fn add(&mut self, first_sample: u64, i: &mut [f32], q: &mut [f32]) {
        let n = i.len().min(q.len());
        let mut done = 0;
        while done < n {
            let k = first_sample + done as u64;
            let (f, off) = (k / NOISE_FRAME as u64, (k % NOISE_FRAME as u64) as usize);
            self.load_frame(f);
            let take = (NOISE_FRAME - off).min(n - done);
            let (fi, fq) = self.frame.split_at(NOISE_FRAME);
            for (o, &x) in i[done..done + take].iter_mut().zip(&fi[off..off + take]) {
                *o += x;
            }
            for (o, &x) in q[done..done + take].iter_mut().zip(&fq[off..off + take]) {
                *o += x;
            }
            done += take;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn noise(seed: u64, antenna: u32, first: u64, n: usize, block: usize) -> (Vec<f32>, Vec<f32>) {
        let mut src = ThermalNoise::new(seed, antenna, 2.0);
        let (mut i, mut q) = (vec![0f32; n], vec![0f32; n]);
        for start in (0..n).step_by(block) {
            let end = (start + block).min(n);
            src.add(first + start as u64, &mut i[start..end], &mut q[start..end]);
        }
        (i, q)
    }

    #[test]
    fn samples_do_not_depend_on_block_size() {
        let whole = noise(9, 1, 5000, 10_000, 10_000);
        for block in [1, 7, 1000, 1024, 4092] {
            assert_eq!(noise(9, 1, 5000, 10_000, block), whole, "block {block}");
        }
        // A later window of the same stream is the same samples.
        let tail = noise(9, 1, 9000, 6000, 333);
        assert_eq!(tail.0[..], whole.0[4000..]);
    }

    #[test]
    fn white_gaussian_with_the_requested_sigma_and_independent_antennas() {
        let n = 200_000;
        let (i, q) = noise(1, 0, 0, n, 4092);
        let (i2, _) = noise(1, 1, 0, n, 4092);
        let mean = |v: &[f32]| v.iter().map(|&x| f64::from(x)).sum::<f64>() / v.len() as f64;
        let var = |v: &[f32]| v.iter().map(|&x| f64::from(x).powi(2)).sum::<f64>() / v.len() as f64;
        let dot = |a: &[f32], b: &[f32]| {
            a.iter()
                .zip(b)
                .map(|(&x, &y)| f64::from(x) * f64::from(y))
                .sum::<f64>()
                / a.len() as f64
        };
        // sigma 2: the variance estimate has a standard deviation of 4 sqrt(2/n) = 0.013.
        for v in [&i, &q] {
            assert!(mean(v).abs() < 0.02);
            assert!((var(v) - 4.0).abs() < 0.06, "{}", var(v));
        }
        // Normalised correlations (I/Q, antennas, lag 1, across a frame edge) ~ N(0, 1/n).
        for (a, b) in [(&i[..], &q[..]), (&i[..], &i2[..]), (&i[1..], &i[..n - 1])] {
            assert!(dot(a, b).abs() / 4.0 < 0.01);
        }
        // Fourth moment of a Gaussian: 3 sigma^4.
        let m4 = i.iter().map(|&x| f64::from(x).powi(4)).sum::<f64>() / n as f64;
        assert!((m4 / 48.0 - 1.0).abs() < 0.05, "{m4}");
    }
}
