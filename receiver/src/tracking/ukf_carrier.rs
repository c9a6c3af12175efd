//! UKF carrier tracking, thesis section 3.3.4, eqs. 3.3-57..3.3-73: the carrier loop of
//! the thesis's fast synchronisation scheme (section 3.3, figure 3.3-6), in which a fine
//! Doppler estimate from the PMF-FFT acquisition hands over to a loop whose phase
//! discriminator and loop filter an unscented Kalman filter replaces.
//!
//! State `X = [theta, omega, alpha, alpha_t]`: carrier phase (rad), angular frequency
//! (rad/s), its first and second rates (rad/s^2, rad/s^3), at the middle of the current
//! integration interval. Each interval the numerically controlled oscillator (NCO) runs at
//! the predicted state; the prompt correlator output of that interval is the measurement.
//! For a state hypothesis `X^j` the expected normalised prompt is (eqs. 3.3-60, 3.3-61)
//! `D sinc(f_e T_coh) exp(j phi_e)`, `f_e = (omega^j - omega_nco) / 2 pi`,
//! `phi_e = theta^j - theta_nco` (the thesis writes `Q = -D sinc sin(phi_e)` with the
//! opposite sign convention of `phi_e`; with this crate's complex correlator,
//! `prompt = sum(samples * conj(replica))`, the phase error enters with a plus sign).
//!
//! The data bit `D` is decided from the prompt's in-phase sign before the update
//! (decision-directed; the thesis does not say how it treats `D`. # assumed: the usual
//! choice for a data channel).

use nalgebra::{Matrix2, Matrix4, Matrix4x2, SMatrix, Vector2, Vector4};
use num_complex::Complex64;
use std::f64::consts::{PI, TAU};

/// State dimension.
const N: usize = 4;

/// Settings of the filter.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct UkfConfig {
    /// Update period T (s), eq. 3.3-58.
    pub period_s: f64,
    /// Coherent integration time of the prompt (s).
    pub coherent_s: f64,
    /// Power spectral densities (Q_theta, Q_omega, Q_alpha, Q_alpha_t), eq. 3.3-59.
    pub q: [f64; 4],
    /// Measurement noise variances of the normalised I and Q, R = diag(r).
    pub r: [f64; 2],
    /// Sigma-point spread kappa, eqs. 3.3-65..3.3-67 (the thesis uses 0.5).
    pub kappa: f64,
}

/// The UKF carrier tracker.
#[derive(Debug, Clone)]
pub struct UkfCarrier {
    cfg: UkfConfig,
    phi: Matrix4<f64>,
    q: Matrix4<f64>,
    x: Vector4<f64>,
    p: Matrix4<f64>,
}

/// State transition of eq. 3.3-58.
fn transition(t: f64) -> Matrix4<f64> {
    Matrix4::new(
        1.0,
        t,
        t * t / 2.0,
        t.powi(3) / 6.0,
        0.0,
        1.0,
        t,
        t * t / 2.0,
        0.0,
        0.0,
        1.0,
        t,
        0.0,
        0.0,
        0.0,
        1.0,
    )
}

/// Process noise covariance of eq. 3.3-59.
fn process_noise(t: f64, q: [f64; 4]) -> Matrix4<f64> {
    let mut m = Matrix4::zeros();
    m[(0, 0)] += q[0] * t;
    let omega = [[t.powi(3) / 3.0, t * t / 2.0], [t * t / 2.0, t]];
    let alpha = [
        [t.powi(5) / 20.0, t.powi(4) / 8.0, t.powi(3) / 6.0],
        [t.powi(4) / 8.0, t.powi(3) / 3.0, t * t / 2.0],
        [t.powi(3) / 6.0, t * t / 2.0, t],
    ];
    let jerk = [
        [
            t.powi(7) / 252.0,
            t.powi(6) / 72.0,
            t.powi(5) / 30.0,
            t.powi(4) / 24.0,
        ],
        [
            t.powi(6) / 72.0,
            t.powi(5) / 20.0,
            t.powi(4) / 8.0,
            t.powi(3) / 6.0,
        ],
        [
            t.powi(5) / 30.0,
            t.powi(4) / 8.0,
            t.powi(3) / 3.0,
            t * t / 2.0,
        ],
        [t.powi(4) / 24.0, t.powi(3) / 6.0, t * t / 2.0, t],
    ];
    for i in 0..4 {
        for j in 0..4 {
            if i < 2 && j < 2 {
                m[(i, j)] += q[1] * omega[i][j];
            }
            if i < 3 && j < 3 {
                m[(i, j)] += q[2] * alpha[i][j];
            }
            m[(i, j)] += q[3] * jerk[i][j];
        }
    }
    m
}

/// sinc(x) = sin(pi x) / (pi x).
fn sinc(x: f64) -> f64 {
    if x.abs() < 1e-12 {
        1.0
    } else {
        (PI * x).sin() / (PI * x)
    }
}

impl UkfCarrier {
    /// A filter started at state `x0` (theta rad, omega rad/s, alpha, alpha_t) with
    /// covariance `p0`.
    pub fn new(cfg: UkfConfig, x0: [f64; 4], p0: Matrix4<f64>) -> Self {
        Self {
            phi: transition(cfg.period_s),
            q: process_noise(cfg.period_s, cfg.q),
            cfg,
            x: Vector4::from(x0),
            p: p0,
        }
    }

    /// The current state estimate.
    pub fn state(&self) -> [f64; 4] {
        self.x.into()
    }

    /// Its covariance.
    pub fn covariance(&self) -> Matrix4<f64> {
        self.p
    }

    /// Eqs. 3.3-63, 3.3-64: propagate to the middle of the next interval and return the
    /// NCO setting for it, (theta, omega, alpha) at that instant.
    pub fn predict(&mut self) -> [f64; 3] {
        self.x = self.phi * self.x;
        self.p = self.phi * self.p * self.phi.transpose() + self.q;
        [self.x[0], self.x[1], self.x[2]]
    }

    /// Propagate the state by `dt_s` (eqs. 3.3-58, 3.3-59 with T = `dt_s`): for update
    /// intervals that change length, as a receiver's integrations do after bit sync.
    pub fn propagate(&mut self, dt_s: f64) {
        let phi = transition(dt_s);
        self.x = phi * self.x;
        self.p = phi * self.p * phi.transpose() + process_noise(dt_s, self.cfg.q);
    }

    /// Set the coherent integration time of the next prompts (s) and their measurement
    /// noise variances (normalised I and Q).
    pub fn set_measurement(&mut self, coherent_s: f64, r: [f64; 2]) {
        self.cfg.coherent_s = coherent_s;
        self.cfg.r = r;
    }

    /// Eqs. 3.3-65..3.3-73: update with the normalised prompt (signal amplitude 1) of the
    /// interval the NCO of [`Self::predict`] produced. Returns the decided data bit.
    pub fn update(&mut self, prompt: Complex64) -> f64 {
        let (theta_nco, omega_nco) = (self.x[0], self.x[1]);
        self.update_with_nco(prompt, theta_nco, omega_nco)
    }

    /// [`Self::update`] for a prompt whose replica ran at phase `theta_nco` (rad) and
    /// angular frequency `omega_nco` (rad/s) at the middle of the interval, when the NCO
    /// did not follow the prediction exactly.
    pub fn update_with_nco(&mut self, prompt: Complex64, theta_nco: f64, omega_nco: f64) -> f64 {
        let data = if prompt.re < 0.0 { -1.0 } else { 1.0 };
        // Sigma points from the Cholesky factor of (n + kappa) P (its columns).
        let n_k = N as f64 + self.cfg.kappa;
        let scaled = self.p * n_k;
        let l = scaled.cholesky().map(|c| c.l()).unwrap_or_else(|| {
            Matrix4::from_diagonal(&scaled.diagonal().map(|d| d.max(0.0).sqrt()))
        });
        let mut points = SMatrix::<f64, 4, 9>::zeros();
        points.set_column(0, &self.x);
        for i in 0..N {
            points.set_column(1 + i, &(self.x + l.column(i)));
            points.set_column(1 + N + i, &(self.x - l.column(i)));
        }
        let w0 = self.cfg.kappa / n_k;
        let wi = 1.0 / (2.0 * n_k);
        let weight = |j: usize| if j == 0 { w0 } else { wi };
        // Eq. 3.3-68: expected prompt of each hypothesis.
        let h = |x: &Vector4<f64>| {
            let f_e = (x[1] - omega_nco) / TAU;
            let phi_e = x[0] - theta_nco;
            let a = data * sinc(f_e * self.cfg.coherent_s);
            Vector2::new(a * phi_e.cos(), a * phi_e.sin())
        };
        let ys: Vec<Vector2<f64>> = (0..2 * N + 1)
            .map(|j| h(&points.column(j).into()))
            .collect();
        // Eqs. 3.3-69..3.3-71.
        let y_mean: Vector2<f64> = (0..2 * N + 1).map(|j| ys[j] * weight(j)).sum();
        let mut p_yy = Matrix2::zeros();
        let mut p_xy = Matrix4x2::zeros();
        for (j, y) in ys.iter().enumerate() {
            let dy = y - y_mean;
            let dx = points.column(j) - self.x;
            p_yy += weight(j) * dy * dy.transpose();
            p_xy += weight(j) * dx * dy.transpose();
        }
        let s = p_yy + Matrix2::from_diagonal(&Vector2::new(self.cfg.r[0], self.cfg.r[1]));
        // Eqs. 3.3-72, 3.3-73.
        if let Some(s_inv) = s.try_inverse() {
            let gain = p_xy * s_inv;
            let innovation = Vector2::new(prompt.re, prompt.im) - y_mean;
            self.x += gain * innovation;
            self.p -= gain * s * gain.transpose();
            self.p = 0.5 * (self.p + self.p.transpose());
        }
        data
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;
    use rand_distr::{Distribution, Normal};

    #[test]
    fn process_noise_is_the_integral_of_the_continuous_model() {
        // Q = int_0^T Phi(s) diag(q) Phi(s)^T ds for white noise on each state derivative
        // (Brown & Hwang): check by numerical integration.
        let (t, q) = (1e-3, [1e-5, 10.0, 1e7, 1e13]);
        let steps = 20_000;
        let mut num = Matrix4::zeros();
        for k in 0..steps {
            let s = (k as f64 + 0.5) * t / steps as f64;
            let f = transition(s);
            num +=
                f * Matrix4::from_diagonal(&Vector4::from(q)) * f.transpose() * (t / steps as f64);
        }
        let m = process_noise(t, q);
        for i in 0..4 {
            for j in 0..4 {
                let scale = m[(i, j)].abs().max(1e-30);
                assert!(
                    (num[(i, j)] - m[(i, j)]).abs() / scale < 1e-6,
                    "{i}{j}: {} vs {}",
                    num[(i, j)],
                    m[(i, j)]
                );
            }
        }
    }

    /// Simulated normalised prompts of a carrier with a Doppler ramp at 45 dB-Hz, 1 ms.
    #[test]
    fn tracks_a_doppler_ramp_from_a_fine_initial_estimate() {
        let t = 1e-3;
        let cn0 = 10f64.powf(4.5);
        let sigma2 = 1.0 / (2.0 * cn0 * t);
        let cfg = UkfConfig {
            period_s: t,
            coherent_s: t,
            q: [1e-10, 1e-4, 1e2, 1e8],
            r: [sigma2, sigma2],
            kappa: 0.5,
        };
        // True carrier: phase 0, -3.73 kHz, 2 kHz/s, 500 Hz/s^2 (thesis 3.3.5 setup).
        let (f0, f1, f2) = (-3730.0, 2000.0, 500.0);
        let mid_phase = |k: usize| {
            let s = (k as f64 + 0.5) * t;
            TAU * (f0 * s + f1 * s * s / 2.0 + f2 * s.powi(3) / 6.0)
        };
        let p0 = Matrix4::from_diagonal(&Vector4::new(
            1.0,
            (TAU * 5.0).powi(2),
            (TAU * 100.0).powi(2),
            (TAU * 100.0).powi(2),
        ));
        // Start 3 Hz off (a fine estimate) and with the rates unknown.
        let mut ukf = UkfCarrier::new(
            cfg,
            [
                mid_phase(0) - TAU * (f0 + 3.0) * t,
                TAU * (f0 + 3.0),
                0.0,
                0.0,
            ],
            p0,
        );
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(3);
        let noise = Normal::new(0.0, sigma2.sqrt()).unwrap();
        let mut errors = Vec::new();
        for k in 0..2000 {
            let [theta_nco, omega_nco, _] = ukf.predict();
            let true_phase = mid_phase(k);
            let s = (k as f64 + 0.5) * t;
            let true_f = f0 + f1 * s + f2 * s * s / 2.0;
            let f_e = true_f - omega_nco / TAU;
            let bit = if (k / 7) % 2 == 0 { 1.0 } else { -1.0 };
            let amp = bit * sinc(f_e * t);
            let e = true_phase - theta_nco;
            let prompt = Complex64::new(
                amp * e.cos() + noise.sample(&mut rng),
                amp * e.sin() + noise.sample(&mut rng),
            );
            ukf.update(prompt);
            if k >= 1000 {
                let x = ukf.state();
                let de = (x[0] - true_phase + PI).rem_euclid(TAU) - PI;
                errors.push((de, x[1] / TAU - true_f));
            }
        }
        let rms = |v: Vec<f64>| (v.iter().map(|x| x * x).sum::<f64>() / v.len() as f64).sqrt();
        let phase = rms(errors.iter().map(|e| e.0).collect());
        let freq = rms(errors.iter().map(|e| e.1).collect());
        // Measured 0.037 rad and 0.32 Hz RMS; the thesis reports 0.025 rad and 0.23 Hz std
        // for this setting (table 3.3-1, sample level).
        assert!(
            phase < 0.1 && freq < 1.0,
            "phase {phase} rad, frequency {freq} Hz"
        );
    }
}
