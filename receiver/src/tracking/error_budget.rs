//! Carrier-loop (PLL) phase error budget of thesis section 3.2: dynamic stress, thermal
//! jitter, Allan-deviation jitter, vibration, and the 1-sigma total against the 15 deg
//! rule-of-thumb loss-of-lock threshold.

/// Rule-of-thumb 1-sigma PLL loss-of-lock threshold (deg), thesis section 3.2.1 item 5.
pub const LOCK_THRESHOLD_DEG: f64 = 15.0;

/// Vibration-induced oscillator phase jitter assumed by the thesis (deg, 1 sigma).
pub const THESIS_VIBRATION_DEG: f64 = 2.0;

/// Order of a PLL designed for minimum mean square error.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Deserialize, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum LoopOrder {
    Second,
    Third,
}

impl LoopOrder {
    /// Short label, as in reports.
    pub fn label(self) -> &'static str {
        match self {
            LoopOrder::Second => "2nd order",
            LoopOrder::Third => "3rd order",
        }
    }
}

/// Loop and signal parameters of one budget evaluation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LoopSetting {
    pub order: LoopOrder,
    /// Loop noise bandwidth Bn (Hz).
    pub bn_hz: f64,
    /// Carrier-to-noise density ratio (dB-Hz).
    pub cn0_dbhz: f64,
    /// Predetection (coherent) integration time (s).
    pub t_coh_s: f64,
    /// Oscillator Allan deviation at the loop's time scale.
    pub sigma_allan: f64,
    /// Carrier frequency (Hz).
    pub carrier_hz: f64,
    /// Vibration-induced phase jitter (deg, 1 sigma).
    pub sigma_vibration_deg: f64,
}

/// Thesis eq. 3.2-1: 2nd-order MMSE loop dynamic stress error (deg, 3 sigma) from the
/// line-of-sight acceleration expressed as a Doppler rate `fd_rate_hzps` (1 Hz/s = 360 deg/s^2).
pub fn dynamic_stress_2nd_deg(fd_rate_hzps: f64, bn_hz: f64) -> f64 {
    0.53_f64.powi(2) * 360.0 * fd_rate_hzps.abs() / bn_hz.powi(2)
}

/// Thesis eq. 3.2-2: 3rd-order MMSE loop dynamic stress error (deg, 3 sigma) from the
/// line-of-sight jerk expressed as a Doppler acceleration `fd_accel_hzps2` (Hz/s^2).
pub fn dynamic_stress_3rd_deg(fd_accel_hzps2: f64, bn_hz: f64) -> f64 {
    0.7845_f64.powi(3) * 360.0 * fd_accel_hzps2.abs() / bn_hz.powi(3)
}

/// Thesis eq. 3.2-3: PLL thermal-noise jitter (deg, 1 sigma).
pub fn thermal_jitter_deg(bn_hz: f64, cn0_dbhz: f64, t_coh_s: f64) -> f64 {
    360.0 * skyforge_gnss::observation::pll_thermal_cycles(bn_hz, cn0_dbhz, t_coh_s)
}

/// Thesis eq. 3.2-4 (2nd order, factor 144) and 3.2-5 (3rd order, factor 160):
/// Allan-deviation-induced phase jitter (deg, 1 sigma).
pub fn allan_jitter_deg(order: LoopOrder, sigma_allan: f64, carrier_hz: f64, bn_hz: f64) -> f64 {
    let k = match order {
        LoopOrder::Second => 144.0,
        LoopOrder::Third => 160.0,
    };
    k * sigma_allan * carrier_hz / bn_hz
}

/// The line-of-sight dynamics a loop must follow, as Doppler derivatives.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct DopplerDynamics {
    /// |fd'| (Hz/s).
    pub rate_hzps: f64,
    /// |fd''| (Hz/s^2).
    pub accel_hzps2: f64,
}

/// All terms of one budget (deg).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Budget {
    pub thermal_deg: f64,
    pub allan_deg: f64,
    pub vibration_deg: f64,
    /// Dynamic stress (3 sigma).
    pub dynamic_deg: f64,
    /// Thesis eq. 3.2-6: sqrt(thermal^2 + allan^2 + vibration^2) + dynamic / 3.
    pub total_deg: f64,
}

impl Budget {
    /// True when the total stays within [`LOCK_THRESHOLD_DEG`].
    pub fn holds_lock(&self) -> bool {
        self.total_deg <= LOCK_THRESHOLD_DEG
    }
}

impl LoopSetting {
    /// The budget for the given dynamics (thesis eq. 3.2-6).
    pub fn budget(&self, dynamics: DopplerDynamics) -> Budget {
        let thermal_deg = thermal_jitter_deg(self.bn_hz, self.cn0_dbhz, self.t_coh_s);
        let allan_deg = allan_jitter_deg(self.order, self.sigma_allan, self.carrier_hz, self.bn_hz);
        let dynamic_deg = match self.order {
            LoopOrder::Second => dynamic_stress_2nd_deg(dynamics.rate_hzps, self.bn_hz),
            LoopOrder::Third => dynamic_stress_3rd_deg(dynamics.accel_hzps2, self.bn_hz),
        };
        let vibration_deg = self.sigma_vibration_deg;
        let total_deg = (thermal_deg.powi(2) + allan_deg.powi(2) + vibration_deg.powi(2)).sqrt()
            + dynamic_deg / 3.0;
        Budget {
            thermal_deg,
            allan_deg,
            vibration_deg,
            dynamic_deg,
            total_deg,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn thermal_jitter_follows_the_textbook_rule() {
        // Kaplan's rule of thumb: at 1 Hz bandwidth and infinite C/N0 x T the jitter is
        // (180/pi) * sqrt(Bn / CN0); at 30 dB-Hz, Bn = 1000 Hz that is exactly 1 rad.
        let sigma = thermal_jitter_deg(1000.0, 30.0, 1e9);
        assert!((sigma - 180.0 / std::f64::consts::PI).abs() < 1e-6);
        // The squaring-loss term doubles the variance when 2 T CN0 = 1.
        let cn0_dbhz = 10.0 * (500.0f64).log10();
        let with_loss = thermal_jitter_deg(10.0, cn0_dbhz, 1e-3);
        let without = thermal_jitter_deg(10.0, cn0_dbhz, 1e9);
        assert!((with_loss / without - 2f64.sqrt()).abs() < 1e-9);
    }

    #[test]
    fn dynamic_stress_is_the_steady_state_error_of_an_mmse_loop() {
        // 2nd order: theta_e = R'' / w0^2 with w0 = Bn / 0.53. A 1 Hz/s ramp is 360 deg/s^2.
        let bn = 18.0;
        let w0 = bn / 0.53;
        assert!((dynamic_stress_2nd_deg(1.0, bn) - 360.0 / (w0 * w0)).abs() < 1e-12);
        // 3rd order: theta_e = R''' / w0^3 with w0 = Bn / 0.7845.
        let w0 = bn / 0.7845;
        assert!((dynamic_stress_3rd_deg(1.0, bn) - 360.0 / (w0 * w0 * w0)).abs() < 1e-12);
        // The thesis rounds 0.53^2 to 0.2809 and 0.7845^3 to 0.4828.
        assert!((0.53f64.powi(2) - 0.2809).abs() < 1e-12);
        assert!((0.7845f64.powi(3) - 0.4828).abs() < 5e-5);
    }

    #[test]
    fn total_adds_one_third_of_the_dynamic_stress() {
        let setting = LoopSetting {
            order: LoopOrder::Second,
            bn_hz: 18.0,
            cn0_dbhz: 39.0,
            t_coh_s: 1e-3,
            sigma_allan: 0.0,
            carrier_hz: 1575.42e6,
            sigma_vibration_deg: 0.0,
        };
        let quiet = setting.budget(DopplerDynamics::default());
        let moving = setting.budget(DopplerDynamics {
            rate_hzps: 10.0,
            accel_hzps2: 0.0,
        });
        assert!((moving.total_deg - quiet.total_deg - moving.dynamic_deg / 3.0).abs() < 1e-12);
        assert!(quiet.holds_lock());
    }
}
