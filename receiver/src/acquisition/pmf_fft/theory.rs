//! Noise theory of the PMF-FFT fine Doppler estimator (thesis section 3.3.3): the
//! expectation of `delta` (eq. 3.3-45), the variance ratio to the modified Cramer-Rao
//! bound `R_f` (eq. 3.3-48..3.3-55), the MCRB itself (eq. 3.3-54/3.3-75) and the NMSE
//! it implies. All frequencies are normalised by the chip period: `fd Tc`.
//!
//! The signal model is eq. 3.3-15, `x'[n] = exp(j(2 pi fd n Tc + phi)) + z[n]`, `z` complex
//! white Gaussian of total variance `sigma_z^2`, `SNR = Es/N0 = 1/sigma_z^2`.

use std::f64::consts::PI;

/// Below this `|delta|` the closed-form limit at `delta = 0` is used (the general
/// expressions are 0/0 there; the neglected terms are O(delta^2)).
const DELTA_LIMIT: f64 = 1e-6;

/// Thesis eq. 3.3-21 (definition of `lambda_0`): the common amplitude of the three
/// spectral lines, `sin(pi (p+delta) / (2P)) / (pi L sin(pi (p+delta) / (2M)))`,
/// `P = M / L`; `1/pi` at `p + delta = 0`.
pub fn lambda0(m: usize, l: usize, p: i64, delta: f64) -> f64 {
    let (mf, lf) = (m as f64, l as f64);
    let pf = mf / lf;
    let x = p as f64 + delta;
    if x.abs() < 1e-12 {
        return mf / (PI * lf * pf);
    }
    (PI / (2.0 * pf) * x).sin() / (PI * lf * (PI / (2.0 * mf) * x).sin())
}

/// Thesis eq. 3.3-45: `E[delta_hat] = delta (pi^2/4 + 8/pi^2) / (8/pi^2 + 8 delta^2/pi^2
/// + tan^2(pi delta / 2) (delta^2 - 1)^2 / delta^2)`, asymptotically `delta` (eq. 3.3-46).
pub fn expected_delta(delta: f64) -> f64 {
    if delta == 0.0 {
        return 0.0;
    }
    let c = 8.0 / (PI * PI);
    let t = (PI * delta / 2.0).tan() / delta;
    let d2 = delta * delta;
    delta * (PI * PI / 4.0 + c) / (c + c * d2 + t * t * (d2 - 1.0).powi(2))
}

/// Thesis eq. 3.3-55: `R_f = D(fd_hat) / MCRB(fd) = (pi^2 / 12)(mu6 + mu7 + mu8)` with
/// `mu1..mu8` of eq. 3.3-36..3.3-41 and 3.3-49..3.3-51, for `M` chips, filters of `L`
/// chips, peak bin `p` and fractional offset `delta`. At `delta -> 0` it tends to
/// `pi^2 / (96 lambda0^2)` (`pi^4 / 96 = 1.0147` at `p = 0`).
pub fn rf_ratio(m: usize, l: usize, p: i64, delta: f64) -> f64 {
    let a2 = lambda0(m, l, p, delta).powi(2);
    if delta.abs() < DELTA_LIMIT {
        return PI * PI / (96.0 * a2);
    }
    let d = delta;
    let c1 = (PI.powi(4) + 32.0) / (16.0 * PI * PI);
    let c2 = 4.0 / (PI * PI);
    // Eq. 3.3-24, 3.3-25 (squared).
    let l1 = a2 * (2.0 * (PI * d / 2.0).sin() / d).powi(2);
    let l2 = a2 * (2.0 * (PI * d / 2.0).cos() / d).powi(2);
    let (dm, dp) = (d / (d - 1.0), d / (d + 1.0));
    // Eq. 3.3-35..3.3-41.
    let y = c1 * l2 * (dm * dm - dp * dp);
    let mu1 = c1 * l2 * 2.0 * dm;
    let mu2 = c1 * l2 * 2.0 * dp;
    let x = c2 * l2 * (dm * dm + dp * dp) + l1;
    let mu3 = c2 * l2 * 2.0 * dm;
    let mu4 = c2 * l2 * 2.0 * dp;
    let mu5 = 2.0 * l1;
    // Eq. 3.3-49..3.3-51.
    let r = (y / x).powi(2);
    let mu6 = r * (mu1 / y - mu3 / x).powi(2) / l2;
    let mu7 = r * (mu2 / y + mu4 / x).powi(2) / l2;
    let mu8 = r * (mu5 / x).powi(2) / l1;
    PI * PI / 12.0 * (mu6 + mu7 + mu8)
}

/// Thesis eq. 3.3-54 / 3.3-75: `MCRB(fd Tc) = 3 / (2 pi^2 M^3 SNR)` with `SNR = Es/N0`
/// of `x'[n]` (linear).
pub fn mcrb_fd_tc(m: usize, snr: f64) -> f64 {
    3.0 / (2.0 * PI * PI * (m as f64).powi(3) * snr)
}

/// Thesis eq. 3.3-53 in `Tc` units: `D(fd_hat Tc) = R_f MCRB(fd Tc)`.
pub fn variance_fd_tc(m: usize, l: usize, p: i64, delta: f64, snr: f64) -> f64 {
    rf_ratio(m, l, p, delta) * mcrb_fd_tc(m, snr)
}

/// Splits `fd Tc` into the nearest bin `p` and the offset `delta` in `[-0.5, 0.5]`
/// (eq. 3.3-8: `fd = (p + delta) / (2 M Tc)`).
pub fn bin_and_offset(m: usize, fd_tc: f64) -> (i64, f64) {
    let bins = 2.0 * m as f64 * fd_tc;
    let p = bins.round();
    (p as i64, bins - p)
}

/// The NMSE of `fd_hat Tc` (thesis eq. 3.3-74) the theory predicts: the variance of
/// eq. 3.3-53 plus the squared bias of eq. 3.3-45, `((E[delta_hat] - delta) / 2M)^2`.
pub fn nmse_fd_tc(m: usize, l: usize, fd_tc: f64, snr: f64) -> f64 {
    let (p, delta) = bin_and_offset(m, fd_tc);
    let bias = (expected_delta(delta) - delta) / (2.0 * m as f64);
    variance_fd_tc(m, l, p, delta, snr) + bias * bias
}

#[cfg(test)]
mod tests {
    use super::super::fine_offset;
    use super::*;

    #[test]
    fn rf_reproduces_the_printed_extremes() {
        // Thesis section 3.3.3: R_f^min = 1.0147 at delta = 0, R_f^max = 1.4444 at
        // |delta| = 0.5 (M = 1024, L = 64).
        assert!((rf_ratio(1024, 64, 0, 0.0) - 1.0147).abs() < 1e-4);
        assert!((rf_ratio(1024, 64, 0, 0.5) - 1.4444).abs() < 1e-4);
        assert!((rf_ratio(1024, 64, 0, -0.5) - 1.4444).abs() < 1e-4);
        // The closed-form limit pi^4 / 96 (derived from eq. 3.3-49..3.3-51 by hand).
        assert!((rf_ratio(1024, 64, 0, 0.0) - PI.powi(4) / 96.0).abs() < 1e-6);
        // Continuity through the limit switch.
        let near = rf_ratio(1024, 64, 0, 2.0 * DELTA_LIMIT);
        assert!((near - rf_ratio(1024, 64, 0, 0.0)).abs() < 1e-9);
    }

    /// An independent route to R_f: linearise the estimator (eq. 3.3-13) numerically.
    /// With the line model of eq. 3.3-26/3.3-27, `Y_D = s_D + Z_D`, to first order
    /// `|Y_D|^2 = |s_D|^2 + 2 |s_D| n_D`, `n_D` the in-phase noise of variance
    /// `sigma_z^2 / 2M` (eq. 3.3-17). So `D(delta_hat) = sum_D (d delta / d E_D)^2 4 |s_D|^2
    /// sigma_z^2 / 2M` and, with eq. 3.3-53/3.3-54, `R_f = (pi^2/3) sum_D (d delta/d E_D)^2
    /// |s_D|^2` (SNR and M cancel).
    fn rf_by_numeric_linearisation(m: usize, l: usize, delta: f64) -> f64 {
        let a = lambda0(m, l, 0, delta);
        let amp = |dd: f64| -> f64 {
            // |lambda_1| (D = 0) or |lambda_2| (D = +/-1) times |delta / (delta - D)|.
            let lam = if dd == 0.0 {
                2.0 * a * (PI * delta / 2.0).sin() / delta
            } else {
                2.0 * a * (PI * delta / 2.0).cos() / delta
            };
            (lam * delta / (delta - dd)).abs()
        };
        let e = [amp(-1.0).powi(2), amp(0.0).powi(2), amp(1.0).powi(2)];
        let mut sum = 0.0;
        for (i, dd) in [-1.0, 0.0, 1.0].into_iter().enumerate() {
            let h = 1e-6 * e[1];
            let (mut up, mut down) = (e, e);
            up[i] += h;
            down[i] -= h;
            let grad = (fine_offset(up[0], up[1], up[2]) - fine_offset(down[0], down[1], down[2]))
                / (2.0 * h);
            sum += grad * grad * amp(dd).powi(2);
        }
        PI * PI / 3.0 * sum
    }

    #[test]
    fn rf_agrees_with_a_numeric_linearisation_of_the_estimator() {
        for l in [64usize, 128, 256, 512] {
            for delta in [-0.45, -0.2, 0.05, 0.3, 0.5] {
                let theory = rf_ratio(1024, l, 0, delta);
                let numeric = rf_by_numeric_linearisation(1024, l, delta);
                assert!(
                    (theory / numeric - 1.0).abs() < 1e-5,
                    "L {l} delta {delta}: {theory} vs {numeric}"
                );
            }
        }
    }

    #[test]
    fn expectation_is_the_noiseless_estimator_on_the_line_model() {
        // Eq. 3.3-45 is y/x: the estimator applied to the noiseless line energies of
        // eq. 3.3-10 in its large-P form (sin(pi x / 2P) -> pi x / 2P).
        for delta in [-0.5, -0.31, -0.1, 0.02, 0.25, 0.44] {
            let e = |dd: f64| {
                let x: f64 = delta - dd;
                ((PI / 2.0 * x).sin() / x).powi(2)
            };
            let direct = fine_offset(e(-1.0), e(0.0), e(1.0));
            assert!(
                (expected_delta(delta) - direct).abs() < 1e-12,
                "delta {delta}: {} vs {direct}",
                expected_delta(delta)
            );
        }
        assert_eq!(expected_delta(0.0), 0.0);
        assert!((expected_delta(0.5) - 0.5).abs() < 0.01);
    }

    #[test]
    fn mcrb_and_nmse_scale_as_the_formulas_say() {
        let m0 = mcrb_fd_tc(1024, 1.0);
        assert!((m0 - 3.0 / (2.0 * PI * PI * 1024f64.powi(3))).abs() < 1e-24);
        assert!((mcrb_fd_tc(1024, 10.0) - m0 / 10.0).abs() < 1e-24);
        // At a bin centre the NMSE is the variance: R_f(0) MCRB.
        let at_zero = nmse_fd_tc(1024, 64, 0.0, 1.0);
        assert!((at_zero / m0 - PI.powi(4) / 96.0).abs() < 1e-9);
        // At the edge of the PMF range (|fd Tc| = 1/2L, p = P) the line amplitude falls
        // by the PMF's sinc, lambda0 = 2 / pi^2 instead of 1 / pi: variance x (pi/2)^2.
        let edge = nmse_fd_tc(1024, 64, 1.0 / 128.0, 1.0);
        let expect =
            PI.powi(4) / 96.0 * (PI / 2.0).powi(2) * (PI / 128.0 / (PI / 128.0).sin()).powi(-2);
        assert!((edge / m0 / expect - 1.0).abs() < 1e-3, "{}", edge / m0);
        assert_eq!(bin_and_offset(1024, 3.25 / 2048.0), (3, 0.25));
    }
}
