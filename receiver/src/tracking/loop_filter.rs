//! Loop filters: the FLL-assisted PLL of 2nd and 3rd order and the carrier-aided DLL.
//!
//! Coefficients from Kaplan & Hegarty, "Understanding GPS: Principles and Applications",
//! 2nd ed., section 5.6, the loop-filter table ("Loop filter characteristics"):
//! - 1st order: `w0 = Bn / 0.25`, filter `w0`;
//! - 2nd order: `w0 = Bn / 0.53`, filter `w0^2`, `a2 w0` with `a2 = 1.414`;
//! - 3rd order: `w0 = Bn / 0.7845`, filter `w0^3`, `a3 w0^2`, `b3 w0` with `a3 = 1.1`,
//!   `b3 = 2.4`;
//!
//! and the FLL-assisted PLL block diagram of the same section: the FLL error enters one
//! integrator earlier than the PLL error (a 1st-order FLL assists a 2nd-order PLL, a
//! 2nd-order FLL a 3rd-order PLL); integrators are the bilinear (trapezoidal) form, output
//! the mean of the accumulator before and after the update. Phases are in cycles and
//! frequencies in Hz, so `w0` (1/s) multiplies them unchanged.

use super::TrackingError;
use super::error_budget::LoopOrder;

/// `Bn / w0` of a 1st-order loop.
const K1: f64 = 0.25;
/// `Bn / w0` of a 2nd-order loop.
const K2: f64 = 0.53;
/// 2nd-order damping coefficient `a2`.
const A2: f64 = 1.414;
/// `Bn / w0` of a 3rd-order loop.
const K3: f64 = 0.7845;
/// 3rd-order coefficients `a3`, `b3`.
const A3: f64 = 1.1;
const B3: f64 = 2.4;

/// `Bn / w0` of a PLL of `order`.
fn bn_per_w0(order: LoopOrder) -> f64 {
    match order {
        LoopOrder::Second => K2,
        LoopOrder::Third => K3,
    }
}

/// Natural frequency `w0` (1/s) of a loop of `order` with noise bandwidth `bn_hz`.
pub fn natural_frequency(order: LoopOrder, bn_hz: f64) -> f64 {
    bn_hz / bn_per_w0(order)
}

/// FLL-assisted PLL loop filter; its state is the carrier Doppler estimate (Hz) and, for
/// the 3rd order, the Doppler rate (Hz/s).
#[derive(Debug, Clone, PartialEq)]
pub struct CarrierLoopFilter {
    order: LoopOrder,
    w_pll: f64,
    w_fll: f64,
    /// Velocity accumulator: Doppler (Hz).
    doppler_hz: f64,
    /// Acceleration accumulator: Doppler rate (Hz/s), 3rd order only.
    rate_hzps: f64,
}

impl CarrierLoopFilter {
    /// A filter of `order` with PLL noise bandwidth `pll_bn_hz` and FLL-assist bandwidth
    /// `fll_bn_hz` (0 turns the assistance off), starting at `doppler_hz`.
    pub fn new(
        order: LoopOrder,
        pll_bn_hz: f64,
        fll_bn_hz: f64,
        doppler_hz: f64,
    ) -> Result<Self, TrackingError> {
        if !(pll_bn_hz.is_finite() && pll_bn_hz > 0.0 && doppler_hz.is_finite()) {
            return Err(TrackingError::InvalidConfig(format!(
                "PLL bandwidth must be positive (got {pll_bn_hz} Hz), Doppler finite \
                 (got {doppler_hz} Hz)"
            )));
        }
        let mut filter = Self {
            order,
            w_pll: natural_frequency(order, pll_bn_hz),
            w_fll: 0.0,
            doppler_hz,
            rate_hzps: 0.0,
        };
        filter.set_fll_bandwidth(fll_bn_hz)?;
        Ok(filter)
    }

    /// Change the FLL-assist noise bandwidth (Hz; 0 = pure PLL). The FLL is one order
    /// below the PLL.
    ///
    /// The FLL natural frequency `wf` is capped at the PLL's `w0`. With both loops closed
    /// (the FLL error being the derivative of the phase error) the characteristic
    /// polynomial is `s^3 + (a2 wf + b3 w0) s^2 + (wf^2 + a3 w0^2) s + w0^3` (3rd order)
    /// or `s^2 + (wf + a2 w0) s + w0^2` (2nd order): a stiffer FLL leaves a slow root
    /// near `-w0^3 / (wf^2 + a3 w0^2)` in which the phase error hardly decays.
    pub fn set_fll_bandwidth(&mut self, fll_bn_hz: f64) -> Result<(), TrackingError> {
        if !(fll_bn_hz.is_finite() && fll_bn_hz >= 0.0) {
            return Err(TrackingError::InvalidConfig(format!(
                "FLL bandwidth must be >= 0 Hz (got {fll_bn_hz})"
            )));
        }
        let w_fll = match self.order {
            LoopOrder::Second => fll_bn_hz / K1,
            LoopOrder::Third => fll_bn_hz / K2,
        };
        self.w_fll = w_fll.min(self.w_pll);
        Ok(())
    }

    /// Change the PLL noise bandwidth (Hz), keeping the Doppler and rate estimates (e.g.
    /// narrowing after pull-in). The FLL cap follows the new PLL natural frequency.
    pub fn set_pll_bandwidth(&mut self, pll_bn_hz: f64) -> Result<(), TrackingError> {
        if !(pll_bn_hz.is_finite() && pll_bn_hz > 0.0) {
            return Err(TrackingError::InvalidConfig(format!(
                "PLL bandwidth must be positive (got {pll_bn_hz} Hz)"
            )));
        }
        self.w_pll = natural_frequency(self.order, pll_bn_hz);
        self.w_fll = self.w_fll.min(self.w_pll);
        Ok(())
    }

    /// PLL noise bandwidth (Hz) in use.
    pub fn pll_bandwidth_hz(&self) -> f64 {
        self.w_pll * bn_per_w0(self.order)
    }

    /// Turn the FLL assistance off (pure PLL from now on).
    pub fn disable_fll(&mut self) {
        self.w_fll = 0.0;
    }

    /// Current Doppler-rate estimate (Hz/s); 0 for the 2nd order.
    pub fn rate_hzps(&self) -> f64 {
        self.rate_hzps
    }

    /// Preset the Doppler rate (Hz/s), e.g. from assistance; ignored by the 2nd order.
    pub fn set_rate_hzps(&mut self, rate_hzps: f64) {
        if self.order == LoopOrder::Third && rate_hzps.is_finite() {
            self.rate_hzps = rate_hzps;
        }
    }

    /// One update with the phase error (cycles) and frequency error (Hz) measured over the
    /// last `dt_s` seconds: returns the carrier NCO Doppler (Hz) for the next interval.
    pub fn update(&mut self, phase_err_cycles: f64, freq_err_hz: f64, dt_s: f64) -> f64 {
        let (wp, wf) = (self.w_pll, self.w_fll);
        match self.order {
            LoopOrder::Second => {
                let old = self.doppler_hz;
                self.doppler_hz += dt_s * (wp * wp * phase_err_cycles + wf * freq_err_hz);
                0.5 * (old + self.doppler_hz) + A2 * wp * phase_err_cycles
            }
            LoopOrder::Third => {
                let old_rate = self.rate_hzps;
                self.rate_hzps += dt_s * (wp * wp * wp * phase_err_cycles + wf * wf * freq_err_hz);
                let rate = 0.5 * (old_rate + self.rate_hzps);
                let old = self.doppler_hz;
                self.doppler_hz +=
                    dt_s * (rate + A3 * wp * wp * phase_err_cycles + A2 * wf * freq_err_hz);
                0.5 * (old + self.doppler_hz) + B3 * wp * phase_err_cycles
            }
        }
    }
}

/// Code NCO rate correction (chips/s) of a 1st-order DLL of noise bandwidth `bn_hz`
/// (`w0 = Bn / 0.25`, Kaplan & Hegarty loop-filter table) for a code error `err_chips`.
pub fn dll_rate_correction(bn_hz: f64, err_chips: f64) -> f64 {
    bn_hz / K1 * err_chips
}

/// Carrier-aided code rate (chips/s): the nominal chip rate scaled by the carrier Doppler,
/// `Rc (1 + fd / fc)` (code and carrier share one Doppler factor).
pub fn aided_code_rate(chip_rate_hz: f64, doppler_hz: f64, carrier_hz: f64) -> f64 {
    chip_rate_hz * (1.0 + doppler_hz / carrier_hz)
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;
    use rand_distr::{Distribution, Normal};

    /// Closed loop with an ideal linear phase detector: the signal phase follows
    /// `truth(t)`, the NCO integrates the filter output. Returns the mean phase error
    /// (cycles) of every update interval (what the detector sees), the filter, and the
    /// last NCO frequency (Hz).
    fn run(
        order: LoopOrder,
        bn: f64,
        dt: f64,
        steps: usize,
        truth: impl Fn(f64) -> f64,
        noise_cycles: f64,
        seed: u64,
    ) -> (Vec<f64>, CarrierLoopFilter, f64) {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
        let normal = Normal::new(0.0, noise_cycles.max(1e-300)).unwrap();
        let mut filter = CarrierLoopFilter::new(order, bn, 0.0, 0.0).unwrap();
        let mut nco = 0.0;
        let mut freq = 0.0;
        let mut errors = Vec::with_capacity(steps);
        for k in 0..steps {
            // Phase error averaged over the interval (the correlator's view), NCO linear.
            let t0 = k as f64 * dt;
            let mid = truth(t0 + dt / 2.0) - (nco + freq * dt / 2.0);
            nco += freq * dt;
            errors.push(mid);
            let measured = mid
                + if noise_cycles > 0.0 {
                    normal.sample(&mut rng)
                } else {
                    0.0
                };
            freq = filter.update(measured, 0.0, dt);
        }
        (errors, filter, freq)
    }

    #[test]
    fn second_order_lags_a_frequency_ramp_by_rate_over_w0_squared() {
        let (bn, rate) = (10.0, 5.0);
        let (err, _, freq) = run(
            LoopOrder::Second,
            bn,
            1e-3,
            5000,
            |t| 0.5 * rate * t * t,
            0.0,
            0,
        );
        let w0 = natural_frequency(LoopOrder::Second, bn);
        let expected = rate / (w0 * w0);
        let last = err[err.len() - 1];
        assert!(
            (last - expected).abs() < 0.01 * expected,
            "{last} vs {expected}"
        );
        // The NCO runs at the signal's frequency in the middle of the next interval.
        assert!((freq - rate * 5.0005).abs() < 1e-3, "{freq}");
    }

    #[test]
    fn third_order_follows_a_ramp_and_lags_a_jerk_by_jerk_over_w0_cubed() {
        let (bn, rate) = (18.0, 80.0);
        let (err, filter, _) = run(
            LoopOrder::Third,
            bn,
            1e-3,
            5000,
            |t| 0.5 * rate * t * t,
            0.0,
            0,
        );
        assert!(err[err.len() - 1].abs() < 1e-6, "{}", err[err.len() - 1]);
        assert!((filter.rate_hzps() - rate).abs() < 1e-3);
        let jerk = 10.0;
        let (err, _, _) = run(
            LoopOrder::Third,
            bn,
            1e-3,
            5000,
            |t| jerk * t * t * t / 6.0,
            0.0,
            0,
        );
        let w0 = natural_frequency(LoopOrder::Third, bn);
        let expected = jerk / w0.powi(3);
        let last = err[err.len() - 1];
        assert!(
            (last - expected).abs() < 0.03 * expected,
            "{last} vs {expected}"
        );
    }

    #[test]
    fn output_phase_noise_matches_the_noise_bandwidth() {
        // White phase noise of variance s^2 per update of length T has a one-sided
        // density 2 s^2 T; through a loop of noise bandwidth Bn the NCO phase variance is
        // 2 Bn T s^2 (Kaplan & Hegarty: Bn = integral of |H(f)|^2 over f >= 0).
        for (order, bn) in [(LoopOrder::Second, 10.0), (LoopOrder::Third, 15.0)] {
            let dt = 1e-3;
            let s = 0.01;
            let (err, _, _) = run(order, bn, dt, 200_000, |_| 0.0, s, 7);
            let tail = &err[1000..];
            let var = tail.iter().map(|e| e * e).sum::<f64>() / tail.len() as f64;
            let expected = 2.0 * bn * dt * s * s;
            assert!(
                (var / expected - 1.0).abs() < 0.1,
                "{order:?}: {var} vs {expected}"
            );
        }
    }

    #[test]
    fn fll_assistance_pulls_in_a_frequency_offset() {
        // FLL alone (phase error held at zero): the Doppler estimate converges on the
        // frequency error it is fed, at the FLL's rate.
        let mut f = CarrierLoopFilter::new(LoopOrder::Third, 15.0, 10.0, 0.0).unwrap();
        let truth = 40.0;
        let mut nco = 0.0;
        for _ in 0..2000 {
            nco = f.update(0.0, truth - nco, 1e-3);
        }
        assert!((nco - truth).abs() < 0.05, "{nco}");
        assert!(CarrierLoopFilter::new(LoopOrder::Second, 0.0, 1.0, 0.0).is_err());
        assert!(CarrierLoopFilter::new(LoopOrder::Second, 1.0, -1.0, 0.0).is_err());
    }

    #[test]
    fn carrier_aiding_scales_the_chip_rate() {
        let r = aided_code_rate(1.023e6, 1575.42, 1575.42e6);
        assert!((r - 1.023e6 * (1.0 + 1e-6)).abs() < 1e-9);
        assert!((dll_rate_correction(2.0, 0.1) - 0.8).abs() < 1e-12);
    }
}
