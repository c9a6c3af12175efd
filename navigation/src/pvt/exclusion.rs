//! Which satellite fault detection and exclusion removes: the one with the largest
//! normalised (standardised) residual (Brown 1992; Parkinson & Axelrad 1988; Yuan 2000
//! eqs. 5-1..5-12 written for weighted least squares).
//!
//! With the weighted least-squares estimate x = A z, A = (H^T W H)^-1 H^T W (eqs. 5-1, 5-2),
//! the post-fit residuals are v = S z, S = I - H A (eq. 5-3's I - H H*). With
//! Cov(z) = W^-1 = diag(sigma_i^2) the residuals have the covariance
//!
//!   Cov(v) = S W^-1 S^T = S W^-1    (S W^-1 = W^-1 - H (H^T W H)^-1 H^T is symmetric, S S = S)
//!
//! so residual i has the standard deviation sigma_i sqrt(S_ii), with
//! S_ii = 1 - w_i h_i (H^T W H)^-1 h_i^T (h_i the i-th row of H, w_i = 1 / sigma_i^2) the
//! diagonal of eq. 5-10's (I - H H*)_ii. The normalised residual
//!
//!   w_i = v_i / (sigma_i sqrt(S_ii))
//!
//! is standard normal without a fault. A bias b on satellite k alone gives E[v] = b S e_k,
//! and with the symmetric idempotent P = W^{1/2} S W^{-1/2} (P_ii = S_ii):
//! |E[w_i]| = |b| |P_ik| / (sigma_k sqrt(P_ii)) <= |b| sqrt(P_kk) / sigma_k = |E[w_k]|
//! (Cauchy-Schwarz, P_ik^2 <= P_ii P_kk): the faulty satellite has the largest expected
//! normalised residual. The weighted residual v_i / sigma_i lacks the 1 / sqrt(S_ii) and
//! points at a well-redundant satellite when the faulty one has little redundancy (its
//! bias is mostly absorbed by the estimate and shows in the others' residuals).

use nalgebra::{DMatrix, DVector};

/// Diagonal of S below which a residual carries no information (the satellite has no
/// redundancy: its residual is zero whatever its error).
pub const UNOBSERVABLE_S_II: f64 = 1e-12;

/// The diagonal of S = I - H (H^T W H)^-1 H^T W: each residual's variance over its
/// measurement's variance. `None` when H^T W H is singular or the sizes disagree.
pub fn residual_redundancy(h: &DMatrix<f64>, weights: &DVector<f64>) -> Option<DVector<f64>> {
    let (n, m) = h.shape();
    if weights.len() != n || n < m {
        return None;
    }
    let n_inv = (h.transpose() * DMatrix::from_diagonal(weights) * h).try_inverse()?;
    Some(DVector::from_iterator(
        n,
        (0..n).map(|i| {
            let row = h.row(i);
            1.0 - weights[i] * (row * &n_inv * row.transpose())[(0, 0)]
        }),
    ))
}

/// The normalised residuals |v_i| / (sigma_i sqrt(S_ii)) of `residuals` (m) with design
/// matrix `h` and `weights` (1 / sigma_i^2); 0 for a residual without redundancy
/// (S_ii below [`UNOBSERVABLE_S_II`]). `None` as [`residual_redundancy`], or when the
/// residuals' length disagrees.
pub fn normalised_residuals(
    h: &DMatrix<f64>,
    weights: &DVector<f64>,
    residuals: &DVector<f64>,
) -> Option<Vec<f64>> {
    if residuals.len() != h.nrows() {
        return None;
    }
    let s = residual_redundancy(h, weights)?;
    Some(
        (0..h.nrows())
            .map(|i| {
                if s[i] < UNOBSERVABLE_S_II {
                    0.0
                } else {
                    residuals[i].abs() * weights[i].sqrt() / s[i].sqrt()
                }
            })
            .collect(),
    )
}

/// The index of the largest of `normalised` (the satellite to exclude); `None` when empty
/// or all are zero (no residual carries information).
pub fn most_suspect(normalised: &[f64]) -> Option<usize> {
    normalised
        .iter()
        .enumerate()
        .filter(|(_, w)| **w > 0.0)
        .max_by(|a, b| a.1.total_cmp(b.1))
        .map(|(i, _)| i)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pvt::test_geometry::six_satellites;

    /// Post-fit residuals of `z` by QR of the whitened system (not the normal equations
    /// the functions under test use).
    fn residuals(h: &DMatrix<f64>, w: &DVector<f64>, z: &DVector<f64>) -> DVector<f64> {
        let root_w = DMatrix::from_diagonal(&w.map(f64::sqrt));
        let (hw, zw) = (&root_w * h, &root_w * z);
        let qr = hw.clone().qr();
        let x = qr
            .r()
            .solve_upper_triangular(&(qr.q().transpose() * &zw))
            .unwrap();
        z - h * x
    }

    /// The bias on satellite `k` alone: residuals, and the index the largest weighted
    /// residual |v_i| / sigma_i picks.
    fn biased(h: &DMatrix<f64>, w: &DVector<f64>, k: usize) -> (DVector<f64>, usize) {
        let mut z = DVector::zeros(h.nrows());
        z[k] = 100.0;
        let v = residuals(h, w, &z);
        let weighted: Vec<f64> = v
            .iter()
            .zip(w.iter())
            .map(|(v, w)| v.abs() * w.sqrt())
            .collect();
        let pick = (0..weighted.len())
            .max_by(|&a, &b| weighted[a].total_cmp(&weighted[b]))
            .unwrap();
        (v, pick)
    }

    #[test]
    fn the_normalised_residual_picks_a_low_redundancy_fault_the_weighted_one_misses() {
        let (h, w) = six_satellites();
        // A bias on satellite 0 (near the zenith, little redundancy): the estimate absorbs
        // most of it, and the largest weighted residual is satellite 3's.
        let (v, weighted_pick) = biased(&h, &w, 0);
        assert_eq!(weighted_pick, 3);
        let normalised = normalised_residuals(&h, &w, &v).unwrap();
        assert_eq!(most_suspect(&normalised), Some(0), "{normalised:?}");
        // Likewise satellite 5 (weighted picks 1). For every satellite the normalised rule
        // picks the biased one (the Cauchy-Schwarz bound of the module doc).
        assert_eq!(biased(&h, &w, 5).1, 1);
        for k in 0..h.nrows() {
            let (v, _) = biased(&h, &w, k);
            let normalised = normalised_residuals(&h, &w, &v).unwrap();
            assert_eq!(most_suspect(&normalised), Some(k), "{normalised:?}");
        }
    }

    #[test]
    fn residual_variance_is_sigma_squared_times_the_redundancy() {
        // Oracle: residuals of 20000 noise draws of the weights' sigmas (QR route); the
        // sample variance of residual i over sigma_i^2 must be S_ii within 4 standard
        // errors (the variance of a sample variance is 2 s^4 / (n - 1) for Gaussians).
        use rand::SeedableRng;
        use rand_chacha::ChaCha20Rng;
        use rand_distr::{Distribution, StandardNormal};
        let (h, w) = six_satellites();
        let s = residual_redundancy(&h, &w).unwrap();
        let mut rng = ChaCha20Rng::seed_from_u64(1992);
        let draws = 20_000;
        let mut sum_sq = DVector::<f64>::zeros(h.nrows());
        for _ in 0..draws {
            let z = DVector::from_iterator(
                h.nrows(),
                w.iter().map(|w| {
                    <StandardNormal as Distribution<f64>>::sample(&StandardNormal, &mut rng)
                        / w.sqrt()
                }),
            );
            let v = residuals(&h, &w, &z);
            sum_sq += v.component_mul(&v);
        }
        for i in 0..h.nrows() {
            let ratio = sum_sq[i] / draws as f64 * w[i];
            let se = s[i] * (2.0 / draws as f64).sqrt();
            assert!(
                (ratio - s[i]).abs() < 4.0 * se,
                "sat {i}: {ratio} vs {}",
                s[i]
            );
        }
        // The trace of S is the degrees of freedom n - m.
        assert!((s.sum() - 2.0).abs() < 1e-12);
    }

    #[test]
    fn no_redundancy_gives_no_suspect() {
        // As many measurements as unknowns: every S_ii is 0, every residual uninformative.
        let (h, w) = six_satellites();
        let (h4, w4) = (h.rows(0, 4).into_owned(), w.rows(0, 4).into_owned());
        let v = DVector::from_element(4, 1.0);
        let normalised = normalised_residuals(&h4, &w4, &v).unwrap();
        assert!(normalised.iter().all(|x| *x == 0.0));
        assert_eq!(most_suspect(&normalised), None);
        assert_eq!(normalised_residuals(&h, &w4, &v), None);
        assert_eq!(most_suspect(&[]), None);
    }
}
