//! The Hatch carrier-smoothing filter of one station's track of one satellite.

/// Hatch (1982) filter, the standard form the paper's missing equation stands for:
/// `rho_bar_k = rho_k / n + (n - 1) / n (rho_bar_{k-1} + lambda (phi_k - phi_{k-1}))`,
/// with `n` the epochs since the track began, at most `window` (the smoothing time
/// constant over the epoch spacing: 100 s at 1 Hz in paper 002).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hatch {
    window: f64,
    epochs: f64,
    smoothed_m: f64,
    last_phase_m: f64,
}

impl Hatch {
    /// A filter started on the pseudorange `code_m` and carrier phase `phase_m` (both m)
    /// of the track's first epoch; `window` epochs make the time constant.
    pub fn start(window: f64, code_m: f64, phase_m: f64) -> Self {
        Self {
            window: window.max(1.0),
            epochs: 1.0,
            smoothed_m: code_m,
            last_phase_m: phase_m,
        }
    }

    /// The smoothed pseudorange (m).
    pub fn smoothed_m(&self) -> f64 {
        self.smoothed_m
    }

    /// Take the next epoch's pseudorange and carrier phase (m) and return the smoothed
    /// pseudorange.
    pub fn update(&mut self, code_m: f64, phase_m: f64) -> f64 {
        self.epochs = (self.epochs + 1.0).min(self.window);
        let n = self.epochs;
        let predicted = self.smoothed_m + (phase_m - self.last_phase_m);
        self.smoothed_m = code_m / n + (n - 1.0) / n * predicted;
        self.last_phase_m = phase_m;
        self.smoothed_m
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A code step `step_m` held for `epochs` epochs on a flat track: the smoothed change
    /// after each epoch (the paper's multipath case).
    fn code_step(step_m: f64, epochs: usize) -> Vec<f64> {
        let mut h = Hatch::start(100.0, 0.0, 0.0);
        (0..200).for_each(|_| {
            h.update(0.0, 0.0);
        });
        (0..epochs).map(|_| h.update(step_m, 0.0)).collect()
    }

    #[test]
    fn a_code_step_enters_at_one_part_in_the_window_per_epoch() {
        // Papers digest 2.4: 30 m over 100 epochs accumulates 0.30, 0.60, 0.89, 1.18,
        // 1.47, 1.76 m: 30 (1 - 0.99^k).
        let got = code_step(30.0, 6);
        for (k, g) in got.iter().enumerate() {
            let want = 30.0 * (1.0 - 0.99f64.powi(k as i32 + 1));
            assert!((g - want).abs() < 1e-12, "epoch {k}: {g} vs {want}");
        }
        assert!((got[1] - 0.597).abs() < 1e-3 && (got[5] - 1.76).abs() < 5e-3);
    }

    #[test]
    fn a_carrier_step_shifts_the_smoothed_code_by_its_size_times_the_decay() {
        // Papers digest 2.4: a 100-cycle slip on B1I (lambda = c / 1561.098 MHz) shifts
        // the smoothed code by 19.20 m x 0.99 = 19.01 m, then decays by 0.99 per epoch.
        let lambda = 299_792_458.0 / 1561.098e6;
        let mut h = Hatch::start(100.0, 0.0, 0.0);
        (0..500).for_each(|_| {
            h.update(0.0, 0.0);
        });
        let jump = h.update(0.0, 100.0 * lambda);
        assert!((jump - 19.01).abs() < 0.01, "{jump}");
        let after: Vec<f64> = (0..500).map(|_| h.update(0.0, 100.0 * lambda)).collect();
        assert!((after[0] / jump - 0.99).abs() < 1e-12);
        // 0.99^500 of it is left after 500 epochs: about 0.12 m.
        assert!((after[499] - jump * 0.99f64.powi(500)).abs() < 1e-9);
        assert!(after[499] < 0.13);
    }

    #[test]
    fn the_window_grows_from_one_epoch() {
        // Before `window` epochs, the filter averages what it has: constant code and
        // phase give the code exactly; a code alternating +-1 averages towards 0.
        let mut h = Hatch::start(100.0, 1.0, 0.0);
        assert_eq!(h.update(-1.0, 0.0), 0.0);
        assert!((h.update(1.0, 0.0) - 1.0 / 3.0).abs() < 1e-15);
    }
}
