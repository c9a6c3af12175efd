//! The residual (RAIM-style) test: with weights equal to the inverse measurement
//! variances, the sum of squared weighted post-fit residuals of a fault-free fix follows a
//! chi-square distribution with n - m degrees of freedom (Parkinson & Axelrad 1988, Brown
//! 1992). A fix whose sum exceeds the (1 - pfa) quantile is declared faulty; the solver then
//! excludes the satellite with the largest standardised residual.

use crate::continued_fraction;

/// Iterations of the series and the continued fraction of the incomplete gamma function.
const GAMMA_ITERATIONS: usize = 500;
const GAMMA_EPS: f64 = 1e-15;

/// ln Gamma(x) for x > 0 (Lanczos approximation, g = 7, 9 terms; relative error ~1e-15).
fn ln_gamma(x: f64) -> f64 {
    const G: f64 = 7.0;
    const C: [f64; 9] = [
        0.999_999_999_999_809_9,
        676.520_368_121_885_1,
        -1_259.139_216_722_402_8,
        771.323_428_777_653_1,
        -176.615_029_162_140_6,
        12.507_343_278_686_905,
        -0.138_571_095_265_720_12,
        9.984_369_578_019_572e-6,
        1.505_632_735_149_311_6e-7,
    ];
    if x < 0.5 {
        // Reflection: Gamma(x) Gamma(1 - x) = pi / sin(pi x).
        let pi = std::f64::consts::PI;
        return (pi / (pi * x).sin()).ln() - ln_gamma(1.0 - x);
    }
    let x = x - 1.0;
    let t = x + G + 0.5;
    let sum = C[0] + (1..9).map(|i| C[i] / (x + i as f64)).sum::<f64>();
    0.5 * (2.0 * std::f64::consts::PI).ln() + (x + 0.5) * t.ln() - t + sum.ln()
}

/// Upper regularised incomplete gamma Q(a, x) = Gamma(a, x) / Gamma(a): the power series
/// of P for x < a + 1, the continued fraction of Q (evaluated by the modified Lentz method)
/// otherwise.
fn gamma_q(a: f64, x: f64) -> f64 {
    if x <= 0.0 {
        return 1.0;
    }
    let prefactor = (a * x.ln() - x - ln_gamma(a)).exp();
    if x < a + 1.0 {
        // P(a, x) = x^a e^-x / Gamma(a) * sum_n x^n / (a (a+1) ... (a+n)).
        let (mut term, mut sum) = (1.0 / a, 1.0 / a);
        for n in 1..GAMMA_ITERATIONS {
            term *= x / (a + n as f64);
            sum += term;
            if term.abs() < sum.abs() * GAMMA_EPS {
                break;
            }
        }
        1.0 - prefactor * sum
    } else {
        // Q(a, x) = x^a e^-x / Gamma(a) * 1 / (x + 1 - a - 1 (1 - a) / (x + 3 - a - ...)).
        let b1 = x + 1.0 - a;
        let term = |n: usize| (-(n as f64) * (n as f64 - a), b1 + 2.0 * n as f64);
        prefactor / continued_fraction::evaluate(b1, term, GAMMA_EPS, GAMMA_ITERATIONS - 1)
    }
}

/// Probability that a chi-square variable with `dof` degrees of freedom exceeds `x`.
pub fn chi2_survival(dof: usize, x: f64) -> f64 {
    gamma_q(dof as f64 / 2.0, x / 2.0)
}

/// The value a chi-square variable with `dof` degrees of freedom exceeds with probability
/// `pfa` (bisection on [`chi2_survival`]).
pub fn chi2_threshold(dof: usize, pfa: f64) -> f64 {
    let (mut lo, mut hi) = (0.0, dof as f64 + 10.0);
    while chi2_survival(dof, hi) > pfa {
        hi *= 2.0;
    }
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if chi2_survival(dof, mid) > pfa {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn chi_square_quantiles_match_the_tables() {
        // Published upper-tail critical values (NIST/SEMATECH e-Handbook, table 1.3.6.7.4).
        for (dof, p, x) in [
            (1, 0.05, 3.841),
            (1, 0.001, 10.828),
            (2, 0.01, 9.210),
            (4, 0.001, 18.467),
            (10, 0.05, 18.307),
            (30, 0.001, 59.703),
        ] {
            let t = chi2_threshold(dof, p);
            assert!((t - x).abs() < 2e-3, "dof {dof} p {p}: {t} vs {x}");
        }
    }

    #[test]
    fn survival_of_two_degrees_of_freedom_is_exponential() {
        // chi2(2) is exponential with mean 2: P(X > x) = exp(-x / 2).
        for x in [0.1, 1.0, 3.0, 10.0, 40.0] {
            assert!(
                (chi2_survival(2, x) - (-x / 2.0f64).exp()).abs() < 1e-12,
                "{x}"
            );
        }
    }
}
