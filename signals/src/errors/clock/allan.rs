//! Allan variance: the value power-law coefficients predict, and the overlapping estimator
//! from phase data.

use super::PowerLaw;
use std::f64::consts::{LN_2, PI};

/// Allan variance that `h` predicts at averaging time `tau_s` (s):
/// `h0 / (2 tau) + 2 ln2 h_minus1 + (2 pi^2 / 3) h_minus2 tau`
/// (Barnes et al. 1971, table I; NIST SP 1065 table 3 conversions).
pub fn predicted_avar(h: &PowerLaw, tau_s: f64) -> f64 {
    h.h0 / (2.0 * tau_s) + 2.0 * LN_2 * h.h_minus1 + 2.0 * PI * PI / 3.0 * h.h_minus2 * tau_s
}

/// Allan deviation that `h` predicts at `tau_s`: the square root of [`predicted_avar`].
pub fn predicted_adev(h: &PowerLaw, tau_s: f64) -> f64 {
    predicted_avar(h, tau_s).sqrt()
}

/// Overlapping Allan variance at `tau = m dt` from phase samples `x` (s) spaced `dt_s`
/// (NIST SP 1065 eq. 11):
/// `sum_{i=0}^{N-2m-1} (x[i+2m] - 2 x[i+m] + x[i])^2 / (2 (N - 2m) tau^2)`.
///
/// Returns NaN when `m == 0` or there are fewer than `2m + 1` samples.
pub fn overlapping_avar(phase_s: &[f64], dt_s: f64, m: usize) -> f64 {
    let n = phase_s.len();
    if m == 0 || n < 2 * m + 1 {
        return f64::NAN;
    }
    let terms = n - 2 * m;
    let sum: f64 = (0..terms)
        .map(|i| {
            let d2 = phase_s[i + 2 * m] - 2.0 * phase_s[i + m] + phase_s[i];
            d2 * d2
        })
        .sum();
    let tau_s = m as f64 * dt_s;
    sum / (2.0 * terms as f64 * tau_s * tau_s)
}

/// Overlapping Allan deviation: the square root of [`overlapping_avar`] (NaN when it is).
pub fn overlapping_adev(phase_s: &[f64], dt_s: f64, m: usize) -> f64 {
    overlapping_avar(phase_s, dt_s, m).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn constant_frequency_has_zero_allan_deviation() {
        let x: Vec<f64> = (0..100).map(|k| 1e-3 + 2e-8 * k as f64).collect();
        assert!(overlapping_adev(&x, 1.0, 5) < 1e-18);
    }

    #[test]
    fn linear_frequency_drift_gives_d_tau_over_sqrt2() {
        // x = D t^2 / 2 -> sigma_y(tau) = D tau / sqrt(2) (NIST SP 1065 section 5.6).
        let d = 3e-12;
        let dt = 0.5;
        let x: Vec<f64> = (0..400)
            .map(|k| {
                let t = k as f64 * dt;
                0.5 * d * t * t
            })
            .collect();
        for m in [1, 7, 50] {
            let tau = m as f64 * dt;
            let expected = d * tau / 2f64.sqrt();
            let got = overlapping_adev(&x, dt, m);
            assert!(
                (got / expected - 1.0).abs() < 1e-9,
                "m {m}: {got} vs {expected}"
            );
        }
    }

    #[test]
    fn too_little_data_is_nan() {
        assert!(overlapping_adev(&[0.0; 10], 1.0, 5).is_nan());
        assert!(overlapping_adev(&[0.0; 11], 1.0, 5).is_finite());
        assert!(overlapping_adev(&[0.0; 11], 1.0, 0).is_nan());
    }

    #[test]
    fn predicted_terms_follow_their_power_laws() {
        let white = PowerLaw {
            h0: 2e-20,
            h_minus1: 0.0,
            h_minus2: 0.0,
        };
        assert!((predicted_adev(&white, 4.0) - (2e-20_f64 / 8.0).sqrt()).abs() < 1e-25);
        let flicker = PowerLaw {
            h0: 0.0,
            h_minus1: 1e-20,
            h_minus2: 0.0,
        };
        let floor = (2.0 * 2f64.ln() * 1e-20).sqrt();
        assert!((predicted_adev(&flicker, 1.0) - floor).abs() < 1e-24);
        assert!((predicted_adev(&flicker, 1e4) - floor).abs() < 1e-24);
        let rw = PowerLaw {
            h0: 0.0,
            h_minus1: 0.0,
            h_minus2: 3e-22,
        };
        let ratio = predicted_adev(&rw, 100.0) / predicted_adev(&rw, 1.0);
        assert!((ratio - 10.0).abs() < 1e-12);
    }
}
