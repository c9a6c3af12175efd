//! `Q = L^T D L` with unit lower-triangular `L` and diagonal `D` (de Jonge & Tiberius 1996
//! §3.3): `d_i` is the variance of ambiguity `i` conditioned on ambiguities `i+1..n`.

use super::AmbiguityError;
use nalgebra::DMatrix;

/// A conditional variance below this fraction of its diagonal entry counts as singular.
const SINGULAR_FRACTION: f64 = 1e-14;

/// The factors of `Q = L^T D L`.
#[derive(Debug, Clone)]
pub(crate) struct Ldl {
    /// Unit lower-triangular.
    pub l: DMatrix<f64>,
    /// The diagonal of `D` (conditional variances).
    pub d: Vec<f64>,
}

/// Factor a symmetric `q` (its two triangles averaged); error when it is not positive
/// definite. The caller has checked that `q` is square, finite and symmetric.
pub(crate) fn ldl(q: &DMatrix<f64>) -> Result<Ldl, AmbiguityError> {
    let n = q.nrows();
    // Lower triangle of the symmetrised matrix; the Schur complements overwrite it.
    let mut a = DMatrix::from_fn(n, n, |i, j| {
        if i >= j {
            0.5 * (q[(i, j)] + q[(j, i)])
        } else {
            0.0
        }
    });
    let mut l = DMatrix::identity(n, n);
    let mut d = vec![0.0; n];
    // Peel off the last ambiguity: Q_kk = d_k, Q_kj = d_k L_kj, then recurse on the
    // Schur complement Q[..k, ..k] - d_k l l^T.
    for k in (0..n).rev() {
        let dk = a[(k, k)];
        if !(dk > SINGULAR_FRACTION * q[(k, k)].abs() && dk > 0.0) {
            return Err(AmbiguityError::NotPositiveDefinite {
                index: k,
                value: dk,
            });
        }
        d[k] = dk;
        for j in 0..k {
            l[(k, j)] = a[(k, j)] / dk;
        }
        for j in 0..k {
            let lkj = l[(k, j)] * dk;
            for i in j..k {
                a[(i, j)] -= l[(k, i)] * lkj;
            }
        }
    }
    Ok(Ldl { l, d })
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
        let f = ldl(&q).unwrap();
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
    fn indefinite_and_singular_are_rejected() {
        let q = DMatrix::from_row_slice(2, 2, &[1.0, 2.0, 2.0, 1.0]);
        assert!(matches!(
            ldl(&q),
            Err(AmbiguityError::NotPositiveDefinite { index: 0, .. })
        ));
        let q = DMatrix::from_row_slice(2, 2, &[1.0, 1.0, 1.0, 1.0]);
        assert!(matches!(
            ldl(&q),
            Err(AmbiguityError::NotPositiveDefinite { index: 0, .. })
        ));
        let q = DMatrix::from_row_slice(1, 1, &[-1.0]);
        assert!(matches!(
            ldl(&q),
            Err(AmbiguityError::NotPositiveDefinite { index: 0, .. })
        ));
    }
}
