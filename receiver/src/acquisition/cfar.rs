//! CFAR detection threshold of a square-law acquisition detector.
//!
//! The normalised statistic of one search cell is `S = sum_{k=1..K} |R_k|^2 / sigma^2`,
//! `R_k` the k-th of `K` non-coherently summed complex correlations and `sigma^2` the
//! noise power of one of them (`E|R_k|^2` without signal). Without signal each
//! `2 |R_k|^2 / sigma^2` is chi-square with 2 degrees of freedom, so `2 S` is chi-square
//! with `2 K` degrees of freedom (Kaplan & Hegarty, *Understanding GPS: Principles and
//! Applications*, 2nd ed., ch. 5, the acquisition threshold for `2 N` degrees of freedom
//! around eq. 5.53). For an even number of degrees of freedom the tail is the Erlang sum
//! (Abramowitz & Stegun 26.4.21):
//! `P(S > g) = Q(2 g | 2 K) = exp(-g) sum_{i=0}^{K-1} g^i / i!`.
//! A search of `n` cells with an overall false-alarm probability `P_fa` uses the per-cell
//! probability `1 - (1 - P_fa)^(1/n)`; by the union bound the overall false-alarm rate
//! stays at or below `P_fa` whatever the correlation between neighbouring cells.

use super::AcquisitionError;

/// `P(S > g)` for `S ~ Gamma(k, 1)` (`2 S` chi-square with `2 k` degrees of freedom):
/// `exp(-g) sum_{i<k} g^i / i!`, summed in the log domain so large `k` and `g` do not
/// overflow. `k = 0` is treated as 1.
pub fn erlang_tail(k: usize, g: f64) -> f64 {
    if g <= 0.0 {
        return 1.0;
    }
    let k = k.max(1);
    // Terms t_i = g^i / i! grow until i ~ g: scale by the largest term.
    let log_terms = (0..k).scan(0.0_f64, |log_t, i| {
        if i > 0 {
            *log_t += g.ln() - (i as f64).ln();
        }
        Some(*log_t)
    });
    let logs: Vec<f64> = log_terms.collect();
    let max = logs.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let sum: f64 = logs.iter().map(|l| (l - max).exp()).sum();
    (max + sum.ln() - g).exp()
}

/// Checks `0 < p < 1`; the error names the probability.
fn open_probability(name: &'static str, p: f64) -> Result<(), AcquisitionError> {
    if p > 0.0 && p < 1.0 {
        Ok(())
    } else {
        Err(AcquisitionError::BadParameter {
            name,
            value: p,
            allowed: "0 < p < 1",
        })
    }
}

/// The threshold `g` with `P(S > g) = pfa_cell` for `K = k` non-coherent sums.
pub fn cell_threshold(k: usize, pfa_cell: f64) -> Result<f64, AcquisitionError> {
    open_probability("per-cell false-alarm probability", pfa_cell)?;
    // The tail falls monotonically in g; bracket then bisect on log P.
    let target = pfa_cell.ln();
    let log_tail = |g: f64| erlang_tail(k, g).ln();
    let (mut lo, mut hi) = (0.0_f64, k.max(1) as f64);
    while log_tail(hi) > target {
        lo = hi;
        hi *= 2.0;
    }
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if log_tail(mid) > target {
            lo = mid;
        } else {
            hi = mid;
        }
        if hi - lo <= 1e-12 * hi {
            break;
        }
    }
    Ok(0.5 * (lo + hi))
}

/// The per-cell false-alarm probability that gives `pfa_total` over `cells` cells:
/// `1 - (1 - pfa_total)^(1/cells)`.
pub fn per_cell_pfa(pfa_total: f64, cells: usize) -> Result<f64, AcquisitionError> {
    open_probability("false-alarm probability", pfa_total)?;
    let n = cells.max(1) as f64;
    Ok(-((-pfa_total).ln_1p() / n).exp_m1())
}

/// The threshold on the normalised statistic for `k` non-coherent sums, `cells` searched
/// cells and an overall false-alarm probability `pfa_total`.
pub fn search_threshold(k: usize, cells: usize, pfa_total: f64) -> Result<f64, AcquisitionError> {
    cell_threshold(k, per_cell_pfa(pfa_total, cells)?)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Upper-tail chi-square critical values from the standard printed tables
    /// (e.g. NIST/SEMATECH e-Handbook 1.3.6.7.4): (degrees of freedom, p, value).
    const CHI2_TABLE: [(usize, f64, f64); 6] = [
        (2, 0.05, 5.991),
        (2, 0.01, 9.210),
        (4, 0.05, 9.488),
        (4, 0.01, 13.277),
        (10, 0.05, 18.307),
        (20, 0.01, 37.566),
    ];

    #[test]
    fn thresholds_match_printed_chi_square_tables() {
        for (dof, p, value) in CHI2_TABLE {
            let g = cell_threshold(dof / 2, p).unwrap();
            assert!(
                (2.0 * g - value).abs() < 2e-3,
                "dof {dof} p {p}: {}",
                2.0 * g
            );
        }
    }

    #[test]
    fn erlang_tail_matches_numeric_integration_of_the_gamma_density() {
        for k in [1usize, 2, 5, 20] {
            for g in [0.5, 3.0, 12.0, 40.0] {
                // Simpson integration of x^(k-1) e^-x / (k-1)! from g to g + 200.
                let log_fact: f64 = (1..k).map(|i| (i as f64).ln()).sum();
                let pdf = |x: f64| ((k as f64 - 1.0) * x.ln() - x - log_fact).exp();
                let (a, b, n) = (g, g + 200.0, 20_000);
                let h = (b - a) / n as f64;
                let mut s = pdf(a) + pdf(b);
                for i in 1..n {
                    s += if i % 2 == 1 { 4.0 } else { 2.0 } * pdf(a + h * i as f64);
                }
                let integral = s * h / 3.0;
                let tail = erlang_tail(k, g);
                assert!(
                    (tail / integral - 1.0).abs() < 1e-6,
                    "k {k} g {g}: {tail} vs {integral}"
                );
            }
        }
    }

    #[test]
    fn exponential_case_is_closed_form() {
        // K = 1: P(S > g) = exp(-g).
        let g = cell_threshold(1, 1e-9).unwrap();
        assert!((g - 1e9_f64.ln()).abs() < 1e-9);
    }

    #[test]
    fn per_cell_probability_composes_back_to_the_total() {
        let pc = per_cell_pfa(1e-3, 126_852).unwrap();
        let total = 1.0 - (1.0 - pc).powf(126_852.0);
        // (1 - pc) rounds at 1e-16 of a pc near 1e-8: 1e-8 relative error.
        assert!((total / 1e-3 - 1.0).abs() < 1e-6);
        assert!(per_cell_pfa(0.0, 10).is_err());
        assert!(cell_threshold(3, 1.0).is_err());
    }
}
