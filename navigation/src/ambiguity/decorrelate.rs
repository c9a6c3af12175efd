//! The decorrelating Z-transformation: integer Gauss transformations and swaps of
//! adjacent ambiguities on `Q = L^T D L` (de Jonge & Tiberius 1996 §3.5-3.7), in the
//! order of the MLAMBDA reduction (Chang, Yang & Zhou 2005 §3: after symmetric pivoting,
//! `L_{k+1,k}` is reduced only when a swap follows, the rest of `L` once at the end).
//!
//! After it, `|L_ij| <= 1/2` below the diagonal and `d_k + L_{k+1,k}^2 d_{k+1} >= d_{k+1}`
//! for every `k` (no swap would lower `d_{k+1}`).

use super::int_matrix::IntMatrix;
use super::ldl::Ldl;
use super::{AmbiguityError, round_fast};
use nalgebra::{DMatrix, DVector};

/// A swap must lower `d_{k+1}` by more than this fraction (guards against cycling on
/// rounding errors).
pub(crate) const SWAP_MARGIN: f64 = 1e-12;
/// Swaps after which the reduction gives up.
const MAX_SWAPS: u64 = 10_000_000;

/// The reduced problem: `Z^T Q Z = L^T D L`, `z_hat = Z^T a_hat`.
#[derive(Debug, Clone)]
pub(crate) struct Reduced {
    pub l: DMatrix<f64>,
    pub d: Vec<f64>,
    pub z: IntMatrix,
    /// `Z^{-T}`, mapping integer `z` back to `a = Z^{-T} z`.
    pub z_inv_t: IntMatrix,
    pub z_hat: DVector<f64>,
}

/// Reduce the factors `f` of `P^T Q P` (`Z` starts as `P`) and transform `a_hat` along.
pub(crate) fn reduce(f: Ldl, a_hat: &DVector<f64>) -> Result<Reduced, AmbiguityError> {
    let n = f.d.len();
    let mut r = Reduced {
        l: f.l,
        d: f.d,
        z: IntMatrix::permutation(&f.perm),
        z_inv_t: IntMatrix::permutation(&f.perm),
        z_hat: DVector::from_fn(n, |k, _| a_hat[f.perm[k]]),
    };
    if n < 2 {
        return Ok(r);
    }
    let mut k = n - 2;
    let mut swaps = 0u64;
    loop {
        // The swap test with L_{k+1,k} reduced; the transformation itself only when a
        // swap follows (otherwise the final pass applies it).
        let lk = r.l[(k + 1, k)];
        let reduced = lk - round_fast(lk);
        let delta = r.d[k] + reduced * reduced * r.d[k + 1];
        if delta < r.d[k + 1] * (1.0 - SWAP_MARGIN) {
            r.gauss(k + 1, k)?;
            r.swap(k, delta);
            swaps += 1;
            if swaps > MAX_SWAPS {
                return Err(AmbiguityError::Overflow);
            }
            // Only the tests at k - 1 and k + 1 can have changed.
            k = (k + 1).min(n - 2);
        } else if k == 0 {
            break;
        } else {
            k -= 1;
        }
    }
    for j in 0..n - 1 {
        for i in j + 1..n {
            r.gauss(i, j)?;
        }
    }
    let finite =
        r.l.iter()
            .chain(&r.d)
            .chain(r.z_hat.iter())
            .all(|v| v.is_finite());
    if !finite || r.d.iter().any(|&v| v <= 0.0) {
        return Err(AmbiguityError::Degenerate);
    }
    Ok(r)
}

impl Reduced {
    /// de Jonge & Tiberius 1996 §3.5: integer Gauss transformation of columns `i > j`,
    /// `Z_ij = I - mu e_i e_j^T` with `mu = round(L_ij)`.
    fn gauss(&mut self, i: usize, j: usize) -> Result<(), AmbiguityError> {
        let lij = self.l[(i, j)];
        if lij.abs() <= 0.5 {
            return Ok(());
        }
        let mu = round_fast(lij);
        if mu.is_nan() || mu.abs() >= 9.0e15 {
            return Err(AmbiguityError::Overflow);
        }
        let n = self.d.len();
        // Column j of L minus mu times column i (rows i..n; column i is zero above i).
        let (left, right) = self.l.as_mut_slice().split_at_mut(i * n);
        let col_j = &mut left[j * n + i..j * n + n];
        let col_i = &right[i..n];
        for (x, y) in col_j.iter_mut().zip(col_i) {
            *x -= mu * y;
        }
        self.z.sub_col(j, i, mu)?;
        // Z^{-1} gains mu times row j in row i: Z^{-T} gains mu times column j in column i.
        self.z_inv_t.sub_col(i, j, -mu)?;
        self.z_hat[j] -= mu * self.z_hat[i];
        Ok(())
    }

    /// de Jonge & Tiberius 1996 §3.6: swap ambiguities `k` and `k + 1`; `delta` is the new
    /// `d_{k+1} = d_k + L_{k+1,k}^2 d_{k+1}`.
    fn swap(&mut self, k: usize, delta: f64) {
        let n = self.d.len();
        let lk = self.l[(k + 1, k)];
        let eta = self.d[k] / delta;
        let lam = self.d[k + 1] * lk / delta;
        self.d[k] = eta * self.d[k + 1];
        self.d[k + 1] = delta;
        let lv = self.l.as_mut_slice();
        for j in 0..k {
            let (a0, a1) = (lv[j * n + k], lv[j * n + k + 1]);
            lv[j * n + k] = a1 - lk * a0;
            lv[j * n + k + 1] = eta * a0 + lam * a1;
        }
        lv[k * n + k + 1] = lam;
        let (left, right) = lv.split_at_mut((k + 1) * n);
        left[k * n + k + 2..k * n + n].swap_with_slice(&mut right[k + 2..n]);
        self.z.swap_cols(k, k + 1);
        self.z_inv_t.swap_cols(k, k + 1);
        self.z_hat.swap_rows(k, k + 1);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ambiguity::ldl::ldl;

    fn ltdl(r: &Reduced) -> DMatrix<f64> {
        r.l.transpose() * DMatrix::from_diagonal(&DVector::from_vec(r.d.clone())) * &r.l
    }

    /// Every step keeps `Z^T Q Z = L^T D L`, `Z Z^{-1} = I` and `z_hat = Z^T a_hat`,
    /// and the result meets the reduction's two conditions.
    #[test]
    fn reduction_keeps_the_invariants() {
        let g = DMatrix::from_fn(7, 5, |i, j| {
            ((i * 7 + j * 3) % 11) as f64 - 4.8 + 0.1 * (i * j) as f64
        });
        let q = g.transpose() * &g * 10.0 + DMatrix::identity(5, 5) * 1e-3;
        let a = DVector::from_fn(5, |i, _| 0.37 * i as f64 - 0.4);
        let r = reduce(ldl(&q, true).unwrap(), &a).unwrap();
        let z = r.z.to_dmatrix();
        let zqz = z.transpose() * &q * &z;
        assert!(
            (ltdl(&r) - &zqz).amax() < 1e-8 * zqz.amax(),
            "Z^T Q Z = L^T D L"
        );
        assert_eq!(
            z.transpose() * r.z_inv_t.to_dmatrix(),
            DMatrix::identity(5, 5)
        );
        assert!((z.transpose() * &a - &r.z_hat).amax() < 1e-9);
        for k in 0..4 {
            assert!(r.l[(k + 1, k)].abs() <= 0.5 + 1e-12);
            let delta = r.d[k] + r.l[(k + 1, k)].powi(2) * r.d[k + 1];
            assert!(delta >= r.d[k + 1] * (1.0 - 2.0 * SWAP_MARGIN));
        }
        for j in 0..5 {
            for i in j + 1..5 {
                assert!(
                    r.l[(i, j)].abs() <= 0.5 + 1e-12,
                    "L[{i}][{j}] = {}",
                    r.l[(i, j)]
                );
            }
        }
    }

    #[test]
    fn swap_alone_matches_the_permuted_factorisation() {
        let q = DMatrix::from_row_slice(3, 3, &[4.0, 1.0, 0.5, 1.0, 3.0, 2.9, 0.5, 2.9, 3.0]);
        let mut r = reduce(ldl(&q, false).unwrap(), &DVector::zeros(3)).unwrap();
        // Swap 1 and 2 by hand (row 0 of L is mixed too) and compare with P^T (L^T D L) P.
        let before = ltdl(&r);
        let lk = r.l[(2, 1)];
        let delta = r.d[1] + lk * lk * r.d[2];
        r.swap(1, delta);
        let mut expected = before.clone();
        expected.swap_rows(1, 2);
        expected.swap_columns(1, 2);
        assert!((ltdl(&r) - expected).amax() < 1e-12);
    }
}
