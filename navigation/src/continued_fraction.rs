//! Continued fractions `b0 + a1 / (b1 + a2 / (b2 + ...))` by the modified Lentz method
//! (Lentz 1976; Thompson & Barnett 1986), as the incomplete gamma function of the residual
//! test and the complementary error function of the success rates use them.

/// Magnitude that stands in for a zero denominator.
const TINY: f64 = 1e-300;

/// The fraction with `b0` and terms `(a_n, b_n)` for n = 1, 2, ..., stopped when a step
/// changes it by less than the relative `tol` or after `max_terms` terms.
pub fn evaluate(b0: f64, terms: impl Fn(usize) -> (f64, f64), tol: f64, max_terms: usize) -> f64 {
    let nonzero = |v: f64| if v.abs() < TINY { TINY } else { v };
    let mut f = nonzero(b0);
    let (mut c, mut d) = (f, 0.0);
    for n in 1..=max_terms {
        let (a, b) = terms(n);
        d = 1.0 / nonzero(b + a * d);
        c = nonzero(b + a / c);
        let delta = c * d;
        f *= delta;
        if (delta - 1.0).abs() < tol {
            break;
        }
    }
    f
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The golden ratio is 1 + 1/(1 + 1/(1 + ...)); sqrt(2) is 1 + 1/(2 + 1/(2 + ...)).
    #[test]
    fn known_fractions() {
        let phi = evaluate(1.0, |_| (1.0, 1.0), 1e-15, 200);
        assert!((phi - (1.0 + 5f64.sqrt()) / 2.0).abs() < 1e-13, "{phi}");
        let root2 = evaluate(1.0, |_| (1.0, 2.0), 1e-15, 200);
        assert!((root2 - 2f64.sqrt()).abs() < 1e-13, "{root2}");
    }
}
