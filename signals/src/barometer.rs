//! A barometric altimeter: the platform's height plus a bias and white noise (book 3.2.2
//! and Table 3-9: bias 50 m, first-order Gauss-Markov in the distance travelled with a
//! correlation distance of 450 km, `db' = -(v / D) db + w`; white 5 m), from a random
//! stream keyed like the other receiver-side sources.

use crate::errors::seed::{Stream, stream_rng};
use rand_chacha::ChaCha20Rng;
use rand_distr::{Distribution, StandardNormal};

/// A barometer's errors (1 sigma).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BarometerConfig {
    /// The bias's stationary sigma (m); its value at the start is drawn from it.
    pub bias_m: f64,
    /// The bias's correlation distance (m).
    pub correlation_distance_m: f64,
    /// A reading's white noise (m).
    pub white_m: f64,
}

/// The book's barometer (3.2.2): bias 50 m over 450 km, white 5 m.
pub const BOOK_BAROMETER: BarometerConfig = BarometerConfig {
    bias_m: 50.0,
    correlation_distance_m: 450e3,
    white_m: 5.0,
};

/// A barometer's readings along a path.
#[derive(Debug, Clone)]
pub struct Barometer {
    config: BarometerConfig,
    bias_m: f64,
    rng: ChaCha20Rng,
}

fn normal(rng: &mut ChaCha20Rng) -> f64 {
    StandardNormal.sample(rng)
}

impl Barometer {
    /// Barometer `index` of the run seeded `seed`, its bias drawn.
    pub fn new(config: BarometerConfig, seed: u64, index: u32) -> Self {
        let mut rng = stream_rng(seed, Stream::Barometer, index);
        let bias_m = config.bias_m * normal(&mut rng);
        Self {
            config,
            bias_m,
            rng,
        }
    }

    /// The reading at the true height `height_m` after `distance_m` travelled since the
    /// previous reading: the bias moved over the distance (exact discrete Gauss-Markov),
    /// then the height plus bias plus white noise.
    pub fn read(&mut self, height_m: f64, distance_m: f64) -> f64 {
        let c = &self.config;
        let decay = (-distance_m.abs() / c.correlation_distance_m).exp();
        let step = c.bias_m * (1.0 - decay * decay).sqrt();
        self.bias_m = decay * self.bias_m + step * normal(&mut self.rng);
        height_m + self.bias_m + c.white_m * normal(&mut self.rng)
    }

    /// The bias now (m): truth, for validation.
    pub fn bias(&self) -> f64 {
        self.bias_m
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Over many barometers, the bias's sigma is the configured one at the start and
    /// after travelling; its correlation over one correlation distance is 1/e; the
    /// white noise's sigma is the configured one (each within 5 %: 4000 draws give a
    /// sigma to 1.1 % and a correlation to 0.015).
    #[test]
    fn bias_and_noise_have_the_configured_statistics() {
        let config = BOOK_BAROMETER;
        let n = 4000;
        let (mut start, mut later, mut product, mut white) = (0.0, 0.0, 0.0, 0.0);
        for k in 0..n {
            let mut b = Barometer::new(config, 7, k);
            let b0 = b.bias();
            // 45 readings 10 km apart: one correlation distance.
            let mut last = 0.0;
            for _ in 0..45 {
                last = b.read(100.0, 10e3);
            }
            let b1 = b.bias();
            start += b0 * b0;
            later += b1 * b1;
            product += b0 * b1;
            white += (last - 100.0 - b1).powi(2);
        }
        let n = f64::from(n);
        let sigma0 = (start / n).sqrt();
        let sigma1 = (later / n).sqrt();
        let rho = product / (start * later).sqrt();
        let white = (white / n).sqrt();
        assert!((sigma0 / 50.0 - 1.0).abs() < 0.05, "start sigma {sigma0}");
        assert!((sigma1 / 50.0 - 1.0).abs() < 0.05, "later sigma {sigma1}");
        assert!((rho - (-1.0f64).exp()).abs() < 0.05, "correlation {rho}");
        assert!((white / 5.0 - 1.0).abs() < 0.05, "white sigma {white}");
    }
}
