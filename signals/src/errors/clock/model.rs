//! The streaming receiver-clock generator.
//!
//! Each step of length `dt` adds three independent parts to the clock phase `x` (s):
//!
//! - **White FM** (`h0`): the step's mean frequency is Gaussian with variance
//!   `h0 / (2 dt)`, so `x` gains `N(0, h0 dt / 2)`. Exact for every `tau = m dt`.
//! - **Random-walk FM** (`h_minus2`): the frequency is a Wiener process with diffusion
//!   `q = 2 pi^2 h_minus2` (so that `S_y = q / (2 pi^2 f^2)`); frequency and phase are
//!   advanced by the exact integrated-Wiener transition (covariance `q [dt, dt^2/2;
//!   dt^2/2, dt^3/3]`). Exact at the sample times.
//! - **Flicker FM** (`h_minus1`): approximated by a sum of first-order Gauss-Markov
//!   processes with time constants `T_i = dt * r^i`, `r = sqrt(10)` (two per decade), from
//!   `dt` up to [`FLICKER_MAX_TIME_CONSTANT_S`]. Each has variance `h_minus1 ln r` and PSD
//!   `4 var T / (1 + (2 pi f T)^2)`; summed over log-spaced corners this is
//!   `h_minus1 / f` for `1/(2 pi T_max) << f << 1/(2 pi dt)`. Numerical integration of
//!   the Allan kernel over the continuous-time sum gives the flicker floor
//!   `2 ln2 h_minus1` within 1 % for `30 T_min <= tau <= 1e4 s` and within 5 % up to
//!   `6e4 s`; simulated, the Allan deviation is 2.5 % low at `tau = 10 dt`, 6 % low at
//!   `3 dt`, and within 1 % from `100 dt` to `1e4 s`. Outside that range the floor falls
//!   off. Components are started in their stationary distribution. A component with
//!   `T_i >= 16 dt` is updated only every `M_i` steps (`M_i` the largest power of two
//!   `<= T_i / (8 dt)`, exact Gauss-Markov transition over `M_i dt`) and held in between,
//!   which moves its PSD only at `f > 8 / T_i`, where it is negligible.
//!
//! All draws come from one `ChaCha20Rng` in a fixed per-step order, so the output depends
//! only on the configuration and the key, never on how it is pulled (block sizes, threads).
//! Memory is fixed at construction (about 20 components).

use super::PowerLaw;
use rand::Rng;
use rand_chacha::ChaCha20Rng;
use rand_distr::StandardNormal;
use skyforge_orbits::check::Invalid;
use std::f64::consts::PI;

/// Longest flicker-component time constant (s): the flicker floor holds to `tau ~ 1e4 s`.
pub const FLICKER_MAX_TIME_CONSTANT_S: f64 = 2e5;
/// Ratio of successive flicker time constants (two per decade).
const FLICKER_RATIO: f64 = 3.162_277_660_168_379_5;
/// Largest accepted step (s).
const MAX_DT_S: f64 = 1.0;

/// One clock sample.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ClockSample {
    /// Time since the start of the clock stream, `k * dt` (s).
    pub t_s: f64,
    /// Clock offset at `t_s`: receiver clock minus true time (s). A positive value makes
    /// every pseudorange longer by `c * phase_s`.
    pub phase_s: f64,
    /// Mean fractional frequency over `[t_s, t_s + dt)`: the next sample's phase is
    /// `phase_s + freq * dt`.
    pub freq: f64,
}

#[derive(Debug, Clone)]
struct FlickerComponent {
    y: f64,
    phi: f64,
    innovation_sd: f64,
    /// Update period in steps (a power of two).
    every: u64,
}

/// Streaming generator of clock phase and frequency at a fixed step (see module docs).
#[derive(Debug, Clone)]
pub struct ClockModel {
    dt_s: f64,
    k: u64,
    x_s: f64,
    y_rw: f64,
    white_sd_s: f64,
    rw_dy_sd: f64,
    rw_dx_sd_s: f64,
    flicker: Vec<FlickerComponent>,
    rng: ChaCha20Rng,
}

impl ClockModel {
    /// A clock with coefficients `h`, initial `bias_s` and `drift` (s/s), step `dt_s`
    /// (0 < dt <= 1 s), drawing from `rng` (see
    /// [`stream_rng`](crate::errors::seed::stream_rng)).
    pub fn new(
        h: &PowerLaw,
        bias_s: f64,
        drift: f64,
        dt_s: f64,
        mut rng: ChaCha20Rng,
    ) -> Result<Self, Invalid> {
        if !(dt_s.is_finite() && dt_s > 0.0 && dt_s <= MAX_DT_S) {
            return Err(Invalid::new("dt_s", dt_s, "must be in (0, 1] s"));
        }
        let coefficients = [
            ("h0", h.h0),
            ("h_minus1", h.h_minus1),
            ("h_minus2", h.h_minus2),
        ];
        for (name, value) in coefficients {
            super::H_COEFFICIENT.check(name, value)?;
        }
        if !(bias_s.is_finite() && drift.is_finite()) {
            return Err(Invalid::new(
                "bias_s",
                format!("{bias_s} (drift {drift})"),
                "initial bias and drift must be finite",
            ));
        }
        let q = 2.0 * PI * PI * h.h_minus2;
        let flicker = if h.h_minus1 > 0.0 {
            flicker_components(h.h_minus1, dt_s, &mut rng)
        } else {
            Vec::new()
        };
        Ok(Self {
            dt_s,
            k: 0,
            x_s: bias_s,
            y_rw: drift,
            white_sd_s: (h.h0 * dt_s / 2.0).sqrt(),
            rw_dy_sd: (q * dt_s).sqrt(),
            rw_dx_sd_s: (q * dt_s * dt_s * dt_s).sqrt(),
            flicker,
            rng,
        })
    }

    /// The step (s).
    pub fn dt_s(&self) -> f64 {
        self.dt_s
    }

    /// The next sample.
    pub fn step(&mut self) -> ClockSample {
        let dt = self.dt_s;
        let k = self.k;
        if k > 0 {
            for c in &mut self.flicker {
                if k & (c.every - 1) == 0 {
                    let n: f64 = self.rng.sample(StandardNormal);
                    c.y = c.phi * c.y + c.innovation_sd * n;
                }
            }
        }
        let y_flicker: f64 = self.flicker.iter().map(|c| c.y).sum();
        let mut dx = (self.y_rw + y_flicker) * dt;
        if self.white_sd_s > 0.0 {
            let n: f64 = self.rng.sample(StandardNormal);
            dx += self.white_sd_s * n;
        }
        if self.rw_dy_sd > 0.0 {
            let n1: f64 = self.rng.sample(StandardNormal);
            let n2: f64 = self.rng.sample(StandardNormal);
            // Integrated Wiener process: corr(dy, dx) = sqrt(3)/2.
            dx += self.rw_dx_sd_s * (0.5 * n1 + n2 / (2.0 * 3f64.sqrt()));
            self.y_rw += self.rw_dy_sd * n1;
        }
        let sample = ClockSample {
            t_s: k as f64 * dt,
            phase_s: self.x_s,
            freq: dx / dt,
        };
        self.x_s += dx;
        self.k += 1;
        sample
    }

    /// Fills `out` with the next `out.len()` samples (no allocation).
    pub fn fill(&mut self, out: &mut [ClockSample]) {
        for s in out {
            *s = self.step();
        }
    }

    /// The next `n` samples.
    pub fn next_block(&mut self, n: usize) -> Vec<ClockSample> {
        (0..n).map(|_| self.step()).collect()
    }
}

/// The flicker components for `h_minus1` at step `dt_s`, in stationary initial states.
fn flicker_components(h_minus1: f64, dt_s: f64, rng: &mut ChaCha20Rng) -> Vec<FlickerComponent> {
    let variance = h_minus1 * FLICKER_RATIO.ln();
    let count = ((FLICKER_MAX_TIME_CONSTANT_S / dt_s).ln() / FLICKER_RATIO.ln()).ceil() as i32 + 1;
    (0..count.max(1))
        .map(|i| {
            let tau_c_s = dt_s * FLICKER_RATIO.powi(i);
            let every = hold_steps(tau_c_s / dt_s);
            let phi = (-(every as f64) * dt_s / tau_c_s).exp();
            let n: f64 = rng.sample(StandardNormal);
            FlickerComponent {
                y: variance.sqrt() * n,
                phi,
                innovation_sd: (variance * (1.0 - phi * phi)).sqrt(),
                every,
            }
        })
        .collect()
}

/// Update period (steps) of a component whose time constant is `tc_steps` steps: the
/// largest power of two `<= tc_steps / 8`, at least 1.
fn hold_steps(tc_steps: f64) -> u64 {
    let mut every = 1_u64;
    while (2 * every) as f64 <= tc_steps / 8.0 {
        every *= 2;
    }
    every
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::errors::clock::OscillatorPreset;
    use rand::SeedableRng;

    fn rng() -> ChaCha20Rng {
        ChaCha20Rng::from_seed([3; 32])
    }

    #[test]
    fn noise_free_clock_is_bias_plus_drift() {
        let h = PowerLaw {
            h0: 0.0,
            h_minus1: 0.0,
            h_minus2: 0.0,
        };
        let mut m = ClockModel::new(&h, 1e-4, 2e-7, 0.01, rng()).unwrap_or_else(|e| panic!("{e}"));
        let s = m.next_block(1001);
        let last = s[1000];
        assert!((last.t_s - 10.0).abs() < 1e-12);
        assert!((last.phase_s - (1e-4 + 2e-7 * 10.0)).abs() < 1e-15);
        assert!(s.iter().all(|x| (x.freq - 2e-7).abs() < 1e-20));
    }

    #[test]
    fn phase_is_the_running_sum_of_mean_frequency() {
        let h = OscillatorPreset::Quartz.power_law();
        let mut m = ClockModel::new(&h, 0.0, 0.0, 0.01, rng()).unwrap_or_else(|e| panic!("{e}"));
        let s = m.next_block(500);
        for w in s.windows(2) {
            let predicted = w[0].phase_s + w[0].freq * 0.01;
            assert!((w[1].phase_s - predicted).abs() < 1e-20);
        }
    }

    #[test]
    fn flicker_set_spans_dt_to_the_longest_time_constant() {
        let comps = flicker_components(1e-20, 1e-3, &mut rng());
        // 1 ms .. 2e5 s at two per decade: ceil(2 * 8.301) + 1 = 18 components.
        assert_eq!(comps.len(), 18);
        assert_eq!(comps[0].every, 1);
        let last = FLICKER_RATIO.powi(17) * 1e-3;
        assert!((FLICKER_MAX_TIME_CONSTANT_S..1e6).contains(&last));
        assert!(comps.iter().all(|c| c.phi > 0.0 && c.phi < 1.0));
        assert_eq!(hold_steps(15.9), 1);
        assert_eq!(hold_steps(16.0), 2);
        assert_eq!(hold_steps(1000.0), 64);
    }

    #[test]
    fn bad_step_or_coefficients_are_rejected() {
        let h = OscillatorPreset::Quartz.power_law();
        for dt in [0.0, -1.0, 2.0, f64::NAN] {
            assert!(ClockModel::new(&h, 0.0, 0.0, dt, rng()).is_err());
        }
        let bad = PowerLaw { h0: -1.0, ..h };
        let err = ClockModel::new(&bad, 0.0, 0.0, 0.01, rng()).err();
        assert_eq!(err.map(|e| e.field), Some("h0".to_string()));
    }
}
