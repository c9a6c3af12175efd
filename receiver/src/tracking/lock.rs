//! Lock detectors: the PLL phase-lock indicator, the C/N0 estimator and the loss-of-lock
//! timer.

use std::collections::VecDeque;

use num_complex::Complex;

/// Narrow-band PLL lock indicator: the estimate of `cos 2 phi` (phi = carrier phase error)
/// `(I^2 - Q^2) / (I^2 + Q^2)` of each prompt (Van Dierendonck's narrow-band difference
/// over narrow-band power; Kaplan & Hegarty, 2nd ed., section 5.11 "phase lock detector"),
/// smoothed by a first-order low-pass filter of time constant `tau_s`.
///
/// Near 1 in lock, near 0 when the phase is uniform, -1 at a quarter-cycle error; noise
/// pulls it towards `S / (S + N)` of one prompt even in perfect lock.
#[derive(Debug, Clone, PartialEq)]
pub struct PllLockIndicator {
    tau_s: f64,
    value: f64,
}

impl PllLockIndicator {
    /// Indicator with smoothing time constant `tau_s` (s), starting at 0 (not locked).
    pub fn new(tau_s: f64) -> Self {
        Self { tau_s, value: 0.0 }
    }

    /// Add one prompt of `dt_s` seconds; returns the smoothed indicator.
    pub fn update(&mut self, prompt: Complex<f64>, dt_s: f64) -> f64 {
        let power = prompt.norm_sqr();
        if power > 0.0 {
            let c = (prompt.re * prompt.re - prompt.im * prompt.im) / power;
            let alpha = (dt_s / self.tau_s).clamp(0.0, 1.0);
            self.value += alpha * (c - self.value);
        }
        self.value
    }
}

/// C/N0 estimator by the second- and fourth-order moments (M2M4) of the prompt: for a
/// constant-envelope signal in complex Gaussian noise `E|P|^2 = S + N` and
/// `E|P|^4 = S^2 + 4 S N + 2 N^2`, so `S = sqrt(2 M2^2 - M4)`, `N = M2 - S`
/// (Pauluzzi & Beaulieu, "A comparison of SNR estimation techniques for the AWGN
/// channel", IEEE Trans. Commun. 48(10), 2000, the M2M4 estimator with kw = 2), and
/// `C/N0 = S / (N T)` for prompts of `T` seconds.
///
/// Insensitive to data bit signs and to the carrier phase, so it works before bit sync
/// and during pull-in. Moments over a sliding window of the last `window` prompts.
///
/// The moments are running sums, updated as prompts enter and leave the window: summing
/// the whole window at every estimate took a fifth of the receiver's time. They are summed
/// afresh once per window length, so that rounding cannot accumulate, and whenever the
/// fourth-moment sum has fallen below [`FRESH_AFTER_DROP`] of its largest value since
/// (large powers leaving the window cancel digits of what stays: after a 60 dB fade the
/// estimate was 0.5 dB off).
#[derive(Debug, Clone, PartialEq)]
pub struct Cn0Estimator {
    window: usize,
    powers: VecDeque<f64>,
    t_s: f64,
    /// Sum of the powers and of their squares in the window.
    sums: (f64, f64),
    /// Prompts pushed since the sums were last formed afresh.
    since_fresh: usize,
    /// The largest fourth-moment sum since then.
    peak: f64,
}

/// The fall of the running fourth-moment sum, relative to its peak, that makes
/// [`Cn0Estimator`] sum afresh (about 10 of the 52 bits lost to cancellation at most).
const FRESH_AFTER_DROP: f64 = 1e-3;

impl Cn0Estimator {
    /// Estimator over the last `window` prompts (at least 2) of `t_s` seconds each.
    pub fn new(window: usize, t_s: f64) -> Self {
        let window = window.max(2);
        Self {
            window,
            powers: VecDeque::with_capacity(window),
            t_s,
            sums: (0.0, 0.0),
            since_fresh: 0,
            peak: 0.0,
        }
    }

    /// Add a prompt.
    pub fn push(&mut self, prompt: Complex<f64>) {
        if self.powers.len() == self.window
            && let Some(old) = self.powers.pop_front()
        {
            self.sums.0 -= old;
            self.sums.1 -= old * old;
        }
        let p = prompt.norm_sqr();
        self.powers.push_back(p);
        self.sums.0 += p;
        self.sums.1 += p * p;
        self.since_fresh += 1;
        self.peak = self.peak.max(self.sums.1);
        if self.since_fresh >= self.window || self.sums.1 < FRESH_AFTER_DROP * self.peak {
            self.sums = (
                self.powers.iter().sum(),
                self.powers.iter().map(|p| p * p).sum(),
            );
            self.since_fresh = 0;
            self.peak = self.sums.1;
        }
    }

    /// Prompts needed before the first estimate: the window, at most 200.
    pub fn min_prompts(&self) -> usize {
        self.window.min(200)
    }

    /// True once [`Self::min_prompts`] prompts are in (the window then keeps filling).
    pub fn is_ready(&self) -> bool {
        self.powers.len() >= self.min_prompts()
    }

    /// The estimate (dB-Hz), `None` until [`Self::is_ready`]. A window whose moments
    /// show no signal (`2 M2^2 <= M4`) or no noise gives -inf or +inf dB-Hz.
    pub fn cn0_dbhz(&self) -> Option<f64> {
        if !self.is_ready() {
            return None;
        }
        let n = self.powers.len() as f64;
        let m2 = self.sums.0 / n;
        let m4 = self.sums.1 / n;
        let s = (2.0 * m2 * m2 - m4).max(0.0).sqrt();
        let noise = m2 - s;
        Some(10.0 * (s / (noise.max(0.0) * self.t_s)).log10())
    }
}

/// Loss-of-lock timer: the channel is lost after `loss_after_s` seconds without lock.
#[derive(Debug, Clone, PartialEq)]
pub struct LossOfLockTimer {
    loss_after_s: f64,
    unlocked_s: f64,
}

impl LossOfLockTimer {
    /// Timer declaring loss after `loss_after_s` seconds continuously out of lock.
    pub fn new(loss_after_s: f64) -> Self {
        Self {
            loss_after_s,
            unlocked_s: 0.0,
        }
    }

    /// Advance by `dt_s` with the current lock state; true once lock is lost.
    pub fn update(&mut self, locked: bool, dt_s: f64) -> bool {
        if locked {
            self.unlocked_s = 0.0;
        } else {
            self.unlocked_s += dt_s;
        }
        self.unlocked_s >= self.loss_after_s
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;
    use rand_distr::{Distribution, Normal};

    /// Prompts of a constant-envelope signal of power `s` with random data signs and
    /// complex noise of power `n`.
    fn prompts(s: f64, n: f64, phase: f64, count: usize, seed: u64) -> Vec<Complex<f64>> {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
        let normal = Normal::new(0.0, (n / 2.0).sqrt()).unwrap();
        (0..count)
            .map(|k| {
                let sign = if (k * 7 + 3) % 5 < 2 { -1.0 } else { 1.0 };
                Complex::from_polar(sign * s.sqrt(), phase)
                    + Complex::new(normal.sample(&mut rng), normal.sample(&mut rng))
            })
            .collect()
    }

    #[test]
    fn m2m4_recovers_cn0_from_known_snr() {
        // 45 dB-Hz with 1 ms prompts: SNR 10^4.5 * 1e-3 = 31.6; 35 dB-Hz: 3.16.
        for (cn0, t) in [(45.0, 1e-3), (35.0, 1e-3), (35.0, 20e-3)] {
            let snr = 10f64.powf(cn0 / 10.0) * t;
            let mut est = Cn0Estimator::new(2000, t);
            for p in prompts(snr * 4.0, 4.0, 0.7, 2000, 1) {
                est.push(p);
            }
            let got = est.cn0_dbhz().unwrap();
            assert!((got - cn0).abs() < 0.3, "{cn0}: {got}");
        }
    }

    #[test]
    fn running_moments_match_the_window_summed_afresh() {
        // A strong signal that fades by 60 dB: the running sums subtract large powers
        // from a window of small ones, where rounding would show if it accumulated. The
        // fade falls at several places relative to the once-per-window fresh sums (one
        // that coincides with them hid a 0.5 dB error).
        let window = 300;
        for offset in [0, 1, 100, 299] {
            let mut est = Cn0Estimator::new(window, 1e-3);
            let strong = prompts(1e6, 1e3, 0.2, 2 * window + offset, 5);
            let weak = prompts(1.0, 1e-3, 0.2, 5 * window, 6);
            let mut all: Vec<f64> = Vec::new();
            for p in strong.into_iter().chain(weak) {
                est.push(p);
                all.push(p.norm_sqr());
                let last = &all[all.len().saturating_sub(window)..];
                if last.len() < est.min_prompts() {
                    continue;
                }
                let n = last.len() as f64;
                let m2 = last.iter().sum::<f64>() / n;
                let m4 = last.iter().map(|p| p * p).sum::<f64>() / n;
                let s = (2.0 * m2 * m2 - m4).max(0.0).sqrt();
                let direct = 10.0 * (s / ((m2 - s).max(0.0) * 1e-3)).log10();
                let got = est.cn0_dbhz().unwrap();
                assert!(
                    got == direct || (got - direct).abs() < 1e-6,
                    "offset {offset}, prompt {}: {got} vs {direct}",
                    all.len()
                );
            }
        }
    }

    #[test]
    fn m2m4_needs_a_full_window_up_to_200_prompts() {
        let mut est = Cn0Estimator::new(1000, 1e-3);
        for p in prompts(30.0, 1.0, 0.0, 199, 4) {
            est.push(p);
        }
        assert!(est.cn0_dbhz().is_none());
        est.push(Complex::new(5.0, 0.0));
        assert!(est.cn0_dbhz().is_some());
        let mut est = Cn0Estimator::new(10, 1e-3);
        for p in prompts(30.0, 1.0, 0.0, 9, 2) {
            est.push(p);
        }
        assert!(est.cn0_dbhz().is_none());
        est.push(Complex::new(5.0, 0.0));
        assert!(est.cn0_dbhz().is_some());
        // Noise-free constant prompts: no noise, infinite C/N0.
        let mut est = Cn0Estimator::new(3, 1e-3);
        for _ in 0..3 {
            est.push(Complex::new(5.0, 0.0));
        }
        assert_eq!(est.cn0_dbhz(), Some(f64::INFINITY));
    }

    #[test]
    fn lock_indicator_is_cos_two_phi() {
        for phi in [0.0, 0.3, 0.6] {
            let mut ind = PllLockIndicator::new(0.05);
            let mut last = 0.0;
            for (k, p) in prompts(1e6, 1e-6, phi, 1000, 3).into_iter().enumerate() {
                last = ind.update(p * if k % 3 == 0 { -1.0 } else { 1.0 }, 1e-3);
            }
            assert!((last - (2.0 * phi).cos()).abs() < 1e-3, "{phi}: {last}");
        }
    }

    #[test]
    fn loss_of_lock_needs_the_full_time_out_of_lock() {
        let mut timer = LossOfLockTimer::new(0.1);
        for _ in 0..99 {
            assert!(!timer.update(false, 1e-3));
        }
        assert!(!timer.update(true, 1e-3));
        for _ in 0..99 {
            assert!(!timer.update(false, 1e-3));
        }
        assert!(timer.update(false, 1e-3 + 1e-12));
    }
}
