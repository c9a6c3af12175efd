//! The receiver's states of the tightly coupled filter (book 3.2.2's 18-state filter):
//! after the INS's 15, the receiver clock's bias and drift (m, m/s) and the barometric
//! altimeter's bias (m).
//!
//! Models (book 3.2.2, Table 3-4 and the digest's 2.14): the clock bias integrates the
//! drift plus white phase noise; the drift is a first-order Gauss-Markov process
//! `df' = -df / tau + w` (or a random constant); the barometer's bias is first-order
//! Gauss-Markov in distance travelled, `db' = -(v / D) db + w`, its driving noise
//! `2 sigma^2 v / D`. Error convention as the INS's position: estimate minus truth,
//! removed from the estimates after each update.

use super::config::IntegrationError;
use nalgebra::{SMatrix, SVector};

/// The tightly coupled filter's number of states.
pub const TIGHT_STATES: usize = 18;
/// Indices of the receiver's states.
pub(crate) const CLOCK: usize = 15;
pub(crate) const DRIFT: usize = 16;
pub(crate) const BARO: usize = 17;

/// A barometric altimeter as the filter models it (book 3.2.2: bias 50 m, white 5 m,
/// correlation distance 450 km).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BarometerNoise {
    /// The bias's stationary 1 sigma (m), also its initial uncertainty.
    pub bias_m: f64,
    /// Its correlation distance (m).
    pub correlation_distance_m: f64,
    /// A reading's white noise (m).
    pub white_m: f64,
}

/// What the tightly coupled filter assumes of the receiver (1 sigma, SI units).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ReceiverNoise {
    /// Initial error of the clock bias (m).
    pub clock_bias_m: f64,
    /// Initial error of the clock drift (m/s), and its stationary sigma when it is a
    /// Gauss-Markov process.
    pub clock_drift_mps: f64,
    /// The drift's correlation time (s); `None`: a random constant.
    pub clock_drift_tau_s: Option<f64>,
    /// White phase noise on the clock bias, as a density (m^2/s).
    pub clock_phase_psd_m2_s: f64,
    /// A pseudorange's white error (m).
    pub code_sigma_m: f64,
    /// A pseudorange rate's white error (m/s).
    pub range_rate_sigma_mps: f64,
    /// The barometer, when one aids the height.
    pub barometer: Option<BarometerNoise>,
}

impl ReceiverNoise {
    /// Every sigma finite and positive (the phase density not negative), every
    /// correlation time and distance positive and finite.
    pub fn check(&self) -> Result<(), IntegrationError> {
        let mut positive = vec![
            ("receiver.clock_bias_m", self.clock_bias_m),
            ("receiver.clock_drift_mps", self.clock_drift_mps),
            ("receiver.code_sigma_m", self.code_sigma_m),
            ("receiver.range_rate_sigma_mps", self.range_rate_sigma_mps),
        ];
        if let Some(tau) = self.clock_drift_tau_s {
            positive.push(("receiver.clock_drift_tau_s", tau));
        }
        if let Some(b) = &self.barometer {
            positive.extend([
                ("receiver.barometer.bias_m", b.bias_m),
                (
                    "receiver.barometer.correlation_distance_m",
                    b.correlation_distance_m,
                ),
                ("receiver.barometer.white_m", b.white_m),
            ]);
        }
        for (field, value) in positive {
            if !(value.is_finite() && value > 0.0) {
                return Err(IntegrationError::Config {
                    field,
                    value,
                    allowed: "finite and positive",
                });
            }
        }
        let psd = self.clock_phase_psd_m2_s;
        if !(psd.is_finite() && psd >= 0.0) {
            return Err(IntegrationError::Config {
                field: "receiver.clock_phase_psd_m2_s",
                value: psd,
                allowed: "finite and not negative",
            });
        }
        Ok(())
    }
}

/// The receiver's estimates beside the INS's, and their models.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct ReceiverStates {
    pub noise: ReceiverNoise,
    /// Clock bias (m) and drift (m/s).
    pub clock_m: f64,
    pub drift_mps: f64,
    /// The barometer's bias (m).
    pub baro_bias_m: f64,
}

impl ReceiverStates {
    /// The initial variances (the barometer's zero, and so never moved, without one).
    pub fn initial_covariance<const N: usize>(&self, p: &mut SMatrix<f64, N, N>) {
        p[(CLOCK, CLOCK)] = self.noise.clock_bias_m.powi(2);
        p[(DRIFT, DRIFT)] = self.noise.clock_drift_mps.powi(2);
        p[(BARO, BARO)] = self.noise.barometer.map_or(0.0, |b| b.bias_m.powi(2));
    }

    /// Advances the estimates over `dt` and writes their transition into `phi` and process
    /// noise into `q`: book 3.2.2's F block `[0 1; 0 -1/tau]` (exactly), the barometer's
    /// decay at `speed_mps`.
    pub fn propagate<const N: usize>(
        &mut self,
        phi: &mut SMatrix<f64, N, N>,
        q: &mut SVector<f64, N>,
        dt: f64,
        speed_mps: f64,
    ) {
        let n = &self.noise;
        let (decay, gain, driving) = match n.clock_drift_tau_s {
            Some(tau) => {
                let e = (-dt / tau).exp();
                (e, tau * (1.0 - e), 2.0 * n.clock_drift_mps.powi(2) / tau)
            }
            None => (1.0, dt, 0.0),
        };
        self.clock_m += gain * self.drift_mps;
        self.drift_mps *= decay;
        phi[(CLOCK, DRIFT)] = gain;
        phi[(DRIFT, DRIFT)] = decay;
        q[CLOCK] = n.clock_phase_psd_m2_s * dt;
        q[DRIFT] = driving * dt;
        if let Some(b) = &n.barometer {
            let rate = speed_mps / b.correlation_distance_m;
            phi[(BARO, BARO)] = (-rate * dt).exp();
            self.baro_bias_m *= phi[(BARO, BARO)];
            q[BARO] = 2.0 * b.bias_m.powi(2) * rate * dt;
        }
    }

    /// Removes the estimated errors `x` (the filter's whole state) from the estimates.
    pub fn feed_back(&mut self, x: &[f64]) {
        self.clock_m -= x[CLOCK];
        self.drift_mps -= x[DRIFT];
        self.baro_bias_m -= x[BARO];
    }
}
