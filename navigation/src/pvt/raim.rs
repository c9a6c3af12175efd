//! The residual (RAIM-style) test: with weights equal to the inverse measurement
//! variances, the sum of squared weighted post-fit residuals of a fault-free fix follows a
//! chi-square distribution with n - m degrees of freedom (Parkinson & Axelrad 1988, Brown
//! 1992; Yuan 2000 eqs. 5-1..5-4). A fix whose sum exceeds the (1 - pfa) quantile is
//! declared faulty; the solver then excludes the satellite with the largest standardised
//! (normalised) residual, [`super::exclusion`].
//!
//! With a bias on one satellite the sum follows the noncentral chi-square distribution
//! (Yuan 2000 eq. 5-5); [`lambda_det`] is the noncentrality a fault must reach to be
//! detected with probability 1 - P_md at the test's threshold, the input of the protection
//! levels of [`super::protection`].

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

/// Regularised incomplete gamma functions (P(a, x), Q(a, x)), P + Q = 1: the power series
/// of P for x < a + 1, the continued fraction of Q (evaluated by the modified Lentz method)
/// otherwise; the small one of the two is computed directly, so it keeps its relative
/// precision.
fn gamma_pq(a: f64, x: f64) -> (f64, f64) {
    if x <= 0.0 {
        return (0.0, 1.0);
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
        let p = prefactor * sum;
        (p, 1.0 - p)
    } else {
        // Q(a, x) = x^a e^-x / Gamma(a) * 1 / (x + 1 - a - 1 (1 - a) / (x + 3 - a - ...)).
        let b1 = x + 1.0 - a;
        let term = |n: usize| (-(n as f64) * (n as f64 - a), b1 + 2.0 * n as f64);
        let q = prefactor / continued_fraction::evaluate(b1, term, GAMMA_EPS, GAMMA_ITERATIONS - 1);
        (1.0 - q, q)
    }
}

/// Upper regularised incomplete gamma Q(a, x) = Gamma(a, x) / Gamma(a).
fn gamma_q(a: f64, x: f64) -> f64 {
    gamma_pq(a, x).1
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

/// Poisson weights below this fraction of the largest one end the noncentral sums.
const POISSON_TAIL: f64 = 1e-18;
/// Most terms either side of the Poisson mode (enough for a noncentrality of ~1e5).
const POISSON_TERMS: usize = 5_000;

/// Yuan 2000 eq. 5-5, the density of a noncentral chi-square variable with `dof` degrees of
/// freedom and noncentrality `lambda` at `x`:
/// f(x) = e^{-(x+lambda)/2} / 2^{n/2} sum_j x^{n/2+j-1} lambda^j / (2^{2j} Gamma(n/2+j) j!),
/// n = `dof` (the digest's corrected exponent 2^{2j}: each term is the Poisson weight
/// e^{-lambda/2} (lambda/2)^j / j! times the central chi-square(n + 2j) density). The sum
/// is taken in logarithms about its largest term.
#[cfg(test)]
pub fn ncx2_pdf(dof: usize, lambda: f64, x: f64) -> f64 {
    if x <= 0.0 || dof == 0 {
        return 0.0;
    }
    let half_n = dof as f64 / 2.0;
    let ln2 = std::f64::consts::LN_2;
    // ln of the j-th term of the sum, without the common factor.
    let ln_term = |j: usize| {
        let jf = j as f64;
        let lam = if j == 0 { 0.0 } else { jf * lambda.ln() };
        (half_n + jf - 1.0) * x.ln() + lam
            - 2.0 * jf * ln2
            - ln_gamma(half_n + jf)
            - ln_gamma(jf + 1.0)
    };
    if lambda <= 0.0 {
        return (-(x / 2.0) - half_n * ln2 + ln_term(0)).exp();
    }
    // The terms peak near j ~ sqrt(lambda x) / 2; sum outwards from there.
    let mode = ((lambda * x).sqrt() / 2.0).floor() as usize;
    let peak = ln_term(mode);
    let mut sum = 1.0;
    for j in (mode + 1)..(mode + 1 + POISSON_TERMS) {
        let t = (ln_term(j) - peak).exp();
        sum += t;
        if t < POISSON_TAIL {
            break;
        }
    }
    for j in (0..mode).rev() {
        let t = (ln_term(j) - peak).exp();
        sum += t;
        if t < POISSON_TAIL {
            break;
        }
    }
    (-(x + lambda) / 2.0 - half_n * ln2 + peak + sum.ln()).exp()
}

/// Probability that a noncentral chi-square variable (`dof` degrees of freedom,
/// noncentrality `lambda`) does not exceed `x`: the Poisson mixture of central
/// chi-square distributions, sum_j e^{-lambda/2} (lambda/2)^j / j! P(n/2 + j, x/2), the
/// integral of eq. 5-5 term by term. With `lambda` = 0 it is the central distribution.
/// Yuan 2000 eq. 5-11 reads P_MD = P(T / sigma^2, lambda, n) with this function.
pub fn ncx2_cdf(dof: usize, lambda: f64, x: f64) -> f64 {
    if x <= 0.0 {
        return 0.0;
    }
    let half_n = dof as f64 / 2.0;
    if lambda <= 0.0 {
        return gamma_pq(half_n, x / 2.0).0;
    }
    let mu = lambda / 2.0;
    let ln_weight = |j: usize| -mu + j as f64 * mu.ln() - ln_gamma(j as f64 + 1.0);
    let mode = mu.floor() as usize;
    let term = |j: usize| ln_weight(j).exp() * gamma_pq(half_n + j as f64, x / 2.0).0;
    let mut sum = term(mode);
    for j in (mode + 1)..(mode + 1 + POISSON_TERMS) {
        let t = term(j);
        sum += t;
        if ln_weight(j).exp() < POISSON_TAIL {
            break;
        }
    }
    for j in (0..mode).rev() {
        let t = term(j);
        sum += t;
        if ln_weight(j).exp() < POISSON_TAIL {
            break;
        }
    }
    sum.clamp(0.0, 1.0)
}

/// The noncentrality a fault must give the test statistic so that a test at false-alarm
/// probability `pfa` (threshold T = [`chi2_threshold`], the inverse of Yuan 2000 eq. 5-9)
/// misses it with probability `pmd`: the lambda with P(T, lambda, dof) = pmd (eq. 5-11
/// solved for lambda,
/// by bisection; the distribution function falls as lambda grows). `None` for
/// probabilities outside (0, 1) or no degrees of freedom.
pub fn lambda_det(dof: usize, pfa: f64, pmd: f64) -> Option<f64> {
    if dof == 0 || !(pfa > 0.0 && pfa < 1.0) || !(pmd > 0.0 && pmd < 1.0) {
        return None;
    }
    let t = chi2_threshold(dof, pfa);
    if ncx2_cdf(dof, 0.0, t) <= pmd {
        // Even a fault-free statistic exceeds T with probability 1 - pmd or more.
        return Some(0.0);
    }
    let (mut lo, mut hi) = (0.0, 1.0);
    while ncx2_cdf(dof, hi, t) > pmd {
        hi *= 2.0;
        if hi > 1e6 {
            return None;
        }
    }
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if ncx2_cdf(dof, mid, t) > pmd {
            lo = mid;
        } else {
            hi = mid;
        }
        if hi - lo < 1e-10 * hi {
            break;
        }
    }
    Some(0.5 * (lo + hi))
}

/// Remembered values: (dof, pfa bits, pmd bits or 0 for the threshold) -> value.
type CacheKey = (usize, u64, u64);
static CACHE: std::sync::Mutex<Vec<(CacheKey, f64)>> = std::sync::Mutex::new(Vec::new());
/// Entries the cache keeps (configurations seldom change; degrees of freedom up to ~40).
const CACHE_MAX: usize = 1024;

/// `compute()` once per process for `key`, remembered (a poisoned lock only skips the
/// cache).
fn cached(key: CacheKey, compute: impl FnOnce() -> Option<f64>) -> Option<f64> {
    if let Ok(cache) = CACHE.lock()
        && let Some((_, v)) = cache.iter().find(|(k, _)| *k == key)
    {
        return Some(*v);
    }
    let value = compute()?;
    if let Ok(mut cache) = CACHE.lock()
        && cache.len() < CACHE_MAX
    {
        cache.push((key, value));
    }
    Some(value)
}

/// [`chi2_threshold`] remembered per (dof, pfa): the test's threshold T of Yuan 2000 eq.
/// 5-9 inverted, T = P^-1(1 - P_FA | n), step (1) of the book's algorithm (a bisection of 200
/// steps, costlier than a fix).
pub fn test_threshold(dof: usize, pfa: f64) -> f64 {
    cached((dof, pfa.to_bits(), 0), || Some(chi2_threshold(dof, pfa)))
        .unwrap_or_else(|| chi2_threshold(dof, pfa))
}

/// ([`chi2_threshold`], [`lambda_det`]) of (`dof`, `pfa`, `pmd`), computed once per
/// process and remembered.
pub fn detection_parameters(dof: usize, pfa: f64, pmd: f64) -> Option<(f64, f64)> {
    let lambda = cached((dof, pfa.to_bits(), pmd.to_bits()), || {
        lambda_det(dof, pfa, pmd)
    })?;
    Some((test_threshold(dof, pfa), lambda))
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
    /// Simpson's rule of `f` over [a, b] with `n` (even) intervals.
    fn simpson(f: impl Fn(f64) -> f64, a: f64, b: f64, n: usize) -> f64 {
        let h = (b - a) / n as f64;
        let mut s = f(a) + f(b);
        for k in 1..n {
            s += f(a + k as f64 * h) * if k % 2 == 1 { 4.0 } else { 2.0 };
        }
        s * h / 3.0
    }

    #[test]
    fn noncentral_cdf_is_the_integral_of_the_eq_5_5_density() {
        // Two independent routes: eq. 5-5's series integrated numerically against the
        // Poisson mixture of central distribution functions. x = u^2 removes the x^{n/2-1}
        // singularity of one degree of freedom.
        for dof in [1, 2, 3, 5, 8] {
            for lambda in [0.0, 0.7, 6.0, 35.0, 90.0] {
                for x in [0.5f64, 4.0, 15.0, 60.0, 140.0] {
                    let integral = simpson(
                        |u| 2.0 * u * ncx2_pdf(dof, lambda, u * u),
                        // From 1e-9: the integrand's limit at 0 is finite, its value there
                        // (x = 0) is not computed; the piece left out is below 1e-9.
                        1e-9,
                        x.sqrt(),
                        4000,
                    );
                    let cdf = ncx2_cdf(dof, lambda, x);
                    assert!(
                        (integral - cdf).abs() < 1e-7,
                        "dof {dof} lambda {lambda} x {x}: {integral} vs {cdf}"
                    );
                }
            }
        }
    }

    #[test]
    fn noncentral_density_integrates_to_one_with_mean_n_plus_lambda() {
        for (dof, lambda) in [(2, 10.0), (4, 40.0), (7, 3.0)] {
            let f = |u: f64| 2.0 * u * ncx2_pdf(dof, lambda, u * u);
            let mass = simpson(f, 0.0, 30.0, 20_000);
            let mean = simpson(|u| u * u * f(u), 0.0, 30.0, 20_000);
            assert!((mass - 1.0).abs() < 1e-9, "{mass}");
            let want = dof as f64 + lambda;
            assert!((mean - want).abs() < 1e-6 * want, "{mean} vs {want}");
        }
    }

    #[test]
    fn central_case_and_one_degree_of_freedom_closed_form() {
        for dof in [1, 3, 6] {
            for x in [0.3, 2.0, 9.0, 30.0] {
                let a = ncx2_cdf(dof, 0.0, x);
                assert!((a - (1.0 - chi2_survival(dof, x))).abs() < 1e-13);
                assert!((ncx2_pdf(dof, 0.0, x) - ncx2_pdf(dof, 1e-300, x)).abs() < 1e-12);
            }
        }
        // One degree of freedom: X = (Z + sqrt(lambda))^2, so
        // P(X <= x) = Phi(sqrt(x) - sqrt(lambda)) - Phi(-sqrt(x) - sqrt(lambda)), the
        // normal integral taken here by Simpson's rule of the normal density.
        let phi = |z: f64| {
            let density = |t: f64| (-t * t / 2.0).exp() / (2.0 * std::f64::consts::PI).sqrt();
            0.5 + if z >= 0.0 {
                simpson(density, 0.0, z, 4000)
            } else {
                -simpson(density, z, 0.0, 4000)
            }
        };
        for lambda in [1.0, 9.0, 25.0] {
            for x in [1.0f64, 10.0, 40.0] {
                let s = f64::sqrt(lambda);
                let want = phi(x.sqrt() - s) - phi(-x.sqrt() - s);
                let got = ncx2_cdf(1, lambda, x);
                assert!(
                    (got - want).abs() < 1e-10,
                    "lambda {lambda} x {x}: {got} vs {want}"
                );
            }
        }
    }

    #[test]
    fn lambda_det_meets_its_missed_detection_probability() {
        for dof in [1, 2, 4, 8] {
            for (pfa, pmd) in [(1e-3, 1e-3), (5.6e-7, 1e-3), (1e-5, 0.05)] {
                let l = lambda_det(dof, pfa, pmd).unwrap();
                let t = chi2_threshold(dof, pfa);
                assert!((ncx2_cdf(dof, l, t) / pmd - 1.0).abs() < 1e-6);
                assert!(l > 0.0);
                // More degrees of freedom need a larger bias at the same probabilities.
                if dof > 1 {
                    assert!(l > lambda_det(dof - 1, pfa, pmd).unwrap());
                }
                assert_eq!(detection_parameters(dof, pfa, pmd), Some((t, l)));
                assert_eq!(test_threshold(dof, pfa), t);
            }
        }
        assert_eq!(lambda_det(0, 1e-3, 1e-3), None);
        assert_eq!(lambda_det(3, 0.0, 1e-3), None);
    }
}
