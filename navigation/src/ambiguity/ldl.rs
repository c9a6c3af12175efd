//! `Q = L^T D L` with unit lower-triangular `L` and diagonal `D` (de Jonge & Tiberius 1996
//! §3.3): `d_i` is the variance of ambiguity `i` conditioned on ambiguities `i+1..n`.

use super::AmbiguityError;
use nalgebra::DMatrix;

/// A conditional variance below this fraction of its diagonal entry counts as singular.
const SINGULAR_FRACTION: f64 = 1e-14;

/// The factors of `P^T Q P = L^T D L`.
#[derive(Debug, Clone)]
pub(crate) struct Ldl {
    /// Unit lower-triangular.
    pub l: DMatrix<f64>,
    /// The diagonal of `D` (conditional variances).
    pub d: Vec<f64>,
    /// `perm[k]`: the ambiguity of `Q` at position `k` (identity without pivoting).
    pub perm: Vec<usize>,
}

/// Factor a symmetric `q` (its two triangles averaged); error when it is not positive
/// definite. The caller has checked that `q` is square, finite and symmetric.
///
/// With `pivot`, each step moves the smallest remaining (conditional) variance to the
/// end, the symmetric pivoting of Chang, Yang & Zhou 2005 §3, so that `D` starts close
/// to the order the reduction wants and fewer swaps are needed.
pub(crate) fn ldl(q: &DMatrix<f64>, pivot: bool) -> Result<Ldl, AmbiguityError> {
    let n = q.nrows();
    // Column-major working copy of the symmetrised matrix; the leading block holds the
    // Schur complement.
    let mut a = vec![0.0; n * n];
    let qv = q.as_slice();
    for j in 0..n {
        for i in 0..n {
            a[j * n + i] = 0.5 * (qv[j * n + i] + qv[i * n + j]);
        }
    }
    let mut l = DMatrix::identity(n, n);
    let lv = l.as_mut_slice();
    let mut d = vec![0.0; n];
    let mut perm: Vec<usize> = (0..n).collect();
    // Peel off the last ambiguity: Q_kk = d_k, Q_kj = d_k L_kj, then recurse on the
    // Schur complement Q[..k, ..k] - d_k l l^T.
    for k in (0..n).rev() {
        if pivot {
            let p = (0..=k)
                .min_by(|&x, &y| a[x * n + x].total_cmp(&a[y * n + y]))
                .unwrap_or(k);
            if p != k {
                for j in 0..=k {
                    a.swap(j * n + p, j * n + k);
                }
                for i in 0..=k {
                    a.swap(p * n + i, k * n + i);
                }
                for r in k + 1..n {
                    lv.swap(p * n + r, k * n + r);
                }
                perm.swap(p, k);
            }
        }
        let dk = a[k * n + k];
        let qkk = q[(perm[k], perm[k])].abs();
        if !(dk > SINGULAR_FRACTION * qkk && dk > 0.0) {
            return Err(AmbiguityError::NotPositiveDefinite {
                index: perm[k],
                value: dk,
            });
        }
        d[k] = dk;
        for j in 0..k {
            lv[j * n + k] = a[j * n + k] / dk;
        }
        for j in 0..k {
            let lkj = lv[j * n + k] * dk;
            let col = &mut a[j * n..j * n + k];
            for (i, x) in col.iter_mut().enumerate() {
                *x -= lv[i * n + k] * lkj;
            }
        }
    }
    Ok(Ldl { l, d, perm })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn factors_reproduce_q() {
        let q = DMatrix::from_row_slice(
            3,
            3,
            &[
                6.290, 5.978, 0.544, 5.978, 6.292, 2.340, 0.544, 2.340, 6.288,
            ],
        );
        let f = ldl(&q, false).unwrap();
        let back = f.l.transpose()
            * DMatrix::from_diagonal(&nalgebra::DVector::from_vec(f.d.clone()))
            * &f.l;
        assert!((back - &q).amax() < 1e-12);
        assert_eq!(
            f.d[2], 6.288,
            "d_n is the unconditioned variance of the last"
        );
        for i in 0..3 {
            assert_eq!(f.l[(i, i)], 1.0);
            for j in i + 1..3 {
                assert_eq!(f.l[(i, j)], 0.0);
            }
        }
    }

    #[test]
    fn pivoting_puts_the_smallest_conditional_variances_last() {
        let q = DMatrix::from_row_slice(3, 3, &[1.0, 0.3, 0.1, 0.3, 5.0, 1.0, 0.1, 1.0, 3.0]);
        let f = ldl(&q, true).unwrap();
        assert_eq!(f.perm[2], 0, "Q_00 = 1 is the smallest variance");
        let p = DMatrix::from_fn(3, 3, |i, j| f64::from(u8::from(f.perm[j] == i)));
        let back = f.l.transpose()
            * DMatrix::from_diagonal(&nalgebra::DVector::from_vec(f.d.clone()))
            * &f.l;
        assert!((back - p.transpose() * &q * &p).amax() < 1e-12);
        // Conditioned on ambiguity 0: 5 - 0.09 and 3 - 0.01; the smaller (2.99) goes next.
        assert_eq!(f.perm[1], 2);
        assert!((f.d[1] - 2.99).abs() < 1e-12);
    }

    #[test]
    fn indefinite_and_singular_are_rejected() {
        let q = DMatrix::from_row_slice(2, 2, &[1.0, 2.0, 2.0, 1.0]);
        assert!(matches!(
            ldl(&q, false),
            Err(AmbiguityError::NotPositiveDefinite { index: 0, .. })
        ));
        let q = DMatrix::from_row_slice(2, 2, &[1.0, 1.0, 1.0, 1.0]);
        assert!(matches!(
            ldl(&q, false),
            Err(AmbiguityError::NotPositiveDefinite { index: 0, .. })
        ));
        let q = DMatrix::from_row_slice(1, 1, &[-1.0]);
        assert!(matches!(
            ldl(&q, false),
            Err(AmbiguityError::NotPositiveDefinite { index: 0, .. })
        ));
    }
}
