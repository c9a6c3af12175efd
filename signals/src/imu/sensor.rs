//! One sensor triad's errors applied to its error-free increments.
//!
//! Per axis (Groves 2013 eqs. 4.16-4.17 in increment form): the output over an interval
//! of length `dt` is `(I + S + M) x + b dt + n`, where `x` is the true increment, `S` the
//! diagonal scale-factor errors, `M` the off-diagonal misalignment and non-orthogonality
//! terms, `b` the bias (a turn-on constant plus a first-order Gauss-Markov instability
//! sampled exactly, Gelb Table 4.4-1), and `n` the white-rate noise integrated over the
//! interval, `N sqrt(dt)` with `N` the random-walk density. Quantisation keeps the part
//! below one count for the next interval (an IMU's counters carry it), so the summed
//! output never drifts from the summed input by more than one count.

use super::config::TriadErrors;
use rand::Rng;
use rand_chacha::ChaCha20Rng;
use rand_distr::StandardNormal;
use skyforge_orbits::{Mat3, Vec3};

/// A triad's state: the errors drawn at turn-on and the running bias and remainder.
#[derive(Debug, Clone)]
pub struct Triad {
    errors: TriadErrors,
    rng: ChaCha20Rng,
    /// `I + S + M`.
    gain: Mat3,
    turn_on_bias: Vec3,
    instability: Vec3,
    remainder: Vec3,
}

fn normal3(rng: &mut ChaCha20Rng) -> Vec3 {
    Vec3::new(
        rng.sample(StandardNormal),
        rng.sample(StandardNormal),
        rng.sample(StandardNormal),
    )
}

impl Triad {
    /// A triad whose turn-on errors are drawn from `rng`, which then drives its noise.
    /// Every quantity is drawn whether or not its sigma is zero, so switching one error
    /// off leaves the others' draws as they were.
    pub fn new(errors: TriadErrors, mut rng: ChaCha20Rng) -> Self {
        let turn_on_bias = errors.bias * normal3(&mut rng);
        let scale = errors.scale_factor * normal3(&mut rng);
        let off = errors.misalignment_rad * normal3(&mut rng);
        let off2 = errors.misalignment_rad * normal3(&mut rng);
        let gain = Mat3::new(
            1.0 + scale.x,
            off.x,
            off.y,
            off.z,
            1.0 + scale.y,
            off2.x,
            off2.y,
            off2.z,
            1.0 + scale.z,
        );
        let instability = errors.instability * normal3(&mut rng);
        Self {
            errors,
            rng,
            gain,
            turn_on_bias,
            instability,
            remainder: Vec3::zeros(),
        }
    }

    /// The bias now (rate units): turn-on plus instability.
    pub fn bias(&self) -> Vec3 {
        self.turn_on_bias + self.instability
    }

    /// The scale-factor and misalignment matrix `I + S + M`.
    pub fn gain(&self) -> Mat3 {
        self.gain
    }

    /// The output for the true increment `truth` over `dt_s`; advances the bias and the
    /// noise by one interval.
    pub fn measure(&mut self, truth: Vec3, dt_s: f64) -> Vec3 {
        let bias = self.bias();
        let noise = self.errors.density * dt_s.sqrt() * normal3(&mut self.rng);
        let phi = (-dt_s / self.errors.instability_tau_s).exp();
        let drive = self.errors.instability * (1.0 - phi * phi).sqrt();
        self.instability = phi * self.instability + drive * normal3(&mut self.rng);
        let raw = self.gain * truth + bias * dt_s + noise;
        self.quantised(raw)
    }

    /// `raw` in whole counts, the remainder carried.
    fn quantised(&mut self, raw: Vec3) -> Vec3 {
        let q = self.errors.quantum;
        if q <= 0.0 {
            return raw;
        }
        let total = raw + self.remainder;
        let out = total.map(|v| (v / q).round() * q);
        self.remainder = total - out;
        out
    }
}
