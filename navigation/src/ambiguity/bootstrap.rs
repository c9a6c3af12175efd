//! Bootstrapped success rate (Teunissen 1998, "Success probability of integer GPS
//! ambiguity rounding and bootstrapping", J. Geodesy 72, eq. for P(a_B = a)):
//! `P = prod_i (2 Phi(1 / (2 sqrt(d_i))) - 1) = prod_i erf(1 / sqrt(8 d_i))`, with `d_i`
//! the conditional variances of `Q = L^T D L` (bootstrapping from the last ambiguity to
//! the first, as the LAMBDA search does).

use super::{AmbiguityError, check_q, ldl};
use crate::continued_fraction;
use nalgebra::DMatrix;

/// Bootstrapped success rate of the problem as given (no decorrelation).
pub fn bootstrapped_success_rate(q: &DMatrix<f64>) -> Result<f64, AmbiguityError> {
    check_q(q)?;
    Ok(success_rate_of(&ldl::ldl(q, false)?.d))
}

/// `prod_i erf(1 / sqrt(8 d_i))`.
pub(crate) fn success_rate_of(d: &[f64]) -> f64 {
    d.iter().map(|&di| erf(1.0 / (8.0 * di).sqrt())).product()
}

/// Above this, erfc comes from its continued fraction, below, erf from its series.
const SWITCH: f64 = 3.0;
/// erf is 1 in double precision from here on (erfc(6) = 2.2e-17, below half an ulp of 1).
const ONE_ABOVE: f64 = 6.0;

/// The error function, to about 1e-15 (Abramowitz & Stegun 7.1.6 series below 3,
/// 7.1.14 continued fraction above).
pub fn erf(x: f64) -> f64 {
    if x.is_nan() {
        return f64::NAN;
    }
    let ax = x.abs();
    let v = if ax >= ONE_ABOVE {
        1.0
    } else if ax < SWITCH {
        erf_series(ax)
    } else {
        1.0 - erfc_fraction(ax, ERF_ABS_TOL)
    };
    v.copysign(x)
}

/// The complementary error function `1 - erf(x)`, without cancellation for large `x`.
pub fn erfc(x: f64) -> f64 {
    if x.is_nan() {
        f64::NAN
    } else if x >= SWITCH {
        erfc_fraction(x, 0.0)
    } else if x > 0.5 {
        1.0 - erf_series(x)
    } else {
        1.0 - erf(x)
    }
}

/// A&S 7.1.6: `erf x = 2/sqrt(pi) e^{-x^2} sum_n 2^n x^{2n+1} / (1 3 ... (2n+1))`, all
/// terms positive.
fn erf_series(x: f64) -> f64 {
    let x2 = 2.0 * x * x;
    let mut term = x;
    let mut sum = x;
    for inv in &INV_ODD {
        term *= x2 * inv;
        sum += term;
        if term <= 1e-17 * sum {
            break;
        }
    }
    std::f64::consts::FRAC_2_SQRT_PI * (-x * x).exp() * sum
}

/// `1 / (2n + 1)` for n = 1..: the series needs about 80 terms at x = 3.
const INV_ODD: [f64; 160] = {
    let mut t = [0.0; 160];
    let mut n = 0;
    while n < 160 {
        t[n] = 1.0 / (2 * n + 3) as f64;
        n += 1;
    }
    t
};

/// Absolute accuracy wanted of erfc inside erf (far below an ulp of 1).
const ERF_ABS_TOL: f64 = 2e-17;

/// A&S 7.1.14: `erfc x = e^{-x^2}/sqrt(pi) * 1/(x + (1/2)/(x + 1/(x + (3/2)/(x + ...))))`,
/// evaluated with the modified Lentz method, `x >= 3`, to 1e-16 relative or `abs_tol`
/// absolute, whichever is reached first.
fn erfc_fraction(x: f64, abs_tol: f64) -> f64 {
    let scale = (-x * x).exp() / std::f64::consts::PI.sqrt();
    // erfc x < scale / x: a relative tolerance abs_tol * x / scale gives abs_tol.
    let tol = (abs_tol * x / scale).max(1e-16);
    scale / continued_fraction::evaluate(x, |n| (0.5 * n as f64, x), tol, 299)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Values of Abramowitz & Stegun Table 7.1 (erf to 15 digits) and erfc(3), erfc(5)
    /// (A&S 7.1.13 tabulated in e.g. DLMF 7.3).
    #[test]
    fn erf_matches_tabulated_values() {
        for (x, v) in [
            (0.5, 0.520_499_877_813_047),
            (1.0, 0.842_700_792_949_715),
            (1.5, 0.966_105_146_475_311),
            (2.0, 0.995_322_265_018_953),
        ] {
            assert!((erf(x) - v).abs() < 2e-15, "erf({x}) = {}", erf(x));
            assert!((erf(-x) + v).abs() < 2e-15);
        }
        assert!((erfc(3.0) / 2.209_049_699_858_544e-5 - 1.0).abs() < 1e-13);
        assert!((erfc(5.0) / 1.537_459_794_428_035e-12 - 1.0).abs() < 1e-13);
        assert_eq!(erf(0.0), 0.0);
        assert!(erf(f64::NAN).is_nan());
        assert_eq!(erf(40.0), 1.0);
        assert_eq!(
            1.0 - erfc_fraction(ONE_ABOVE, 0.0),
            1.0,
            "erf is 1 from ONE_ABOVE on"
        );
        assert!(erf(ONE_ABOVE - 0.3) < 1.0);
    }

    /// erf from the shortened fraction is within 2e-17 of 1 - erfc at full precision.
    #[test]
    fn shortened_fraction_is_accurate_enough_for_erf() {
        for i in 0..=300 {
            let x = SWITCH + f64::from(i) * 0.01;
            let full = erfc_fraction(x, 0.0);
            let short = erfc_fraction(x, ERF_ABS_TOL);
            assert!((full - short).abs() < ERF_ABS_TOL, "{x}: {full} vs {short}");
        }
    }

    #[test]
    fn series_and_fraction_agree_at_the_switch() {
        for x in [2.9, 3.0, 3.1, 3.5] {
            let s = 1.0 - erf_series(x);
            let f = erfc_fraction(x, 0.0);
            assert!((s - f).abs() < 1e-14, "{x}: {s} vs {f}");
        }
    }
}
