//! Square integer matrices for `Z` and `Z^{-T}`, stored as `f64` for fast (vectorised)
//! column updates and kept exact: every column carries an upper bound of its largest
//! magnitude, and an update that could reach 2^52 is refused (below that, every product
//! and difference of whole numbers is exact).

use super::AmbiguityError;
use nalgebra::DMatrix;

/// Entries stay below this magnitude (2^52), so every update is exact.
const LIMIT: f64 = 4_503_599_627_370_496.0;
/// Column bounds above this (2^40) are replaced by the exact maximum.
const REFRESH: f64 = 1_099_511_627_776.0;

/// An `n x n` integer matrix, column-major.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct IntMatrix {
    n: usize,
    data: Vec<f64>,
    /// Upper bound of `|entry|` per column.
    bound: Vec<f64>,
}

impl IntMatrix {
    /// The permutation matrix with ones at `(perm[k], k)`.
    pub(crate) fn permutation(perm: &[usize]) -> Self {
        let n = perm.len();
        let mut data = vec![0.0; n * n];
        for (k, &p) in perm.iter().enumerate() {
            data[k * n + p] = 1.0;
        }
        Self {
            n,
            data,
            bound: vec![1.0; n],
        }
    }

    pub(crate) fn get(&self, row: usize, col: usize) -> i64 {
        self.data[col * self.n + row] as i64
    }

    /// Column `dst` -= `mu` * column `src` (`dst != src`, `mu` a whole number).
    pub(crate) fn sub_col(
        &mut self,
        dst: usize,
        src: usize,
        mu: f64,
    ) -> Result<(), AmbiguityError> {
        let n = self.n;
        let (d, s) = if dst < src {
            let (a, b) = self.data.split_at_mut(src * n);
            (&mut a[dst * n..dst * n + n], &b[..n])
        } else {
            let (a, b) = self.data.split_at_mut(dst * n);
            (&mut b[..n], &a[src * n..src * n + n])
        };
        let mut bound = self.bound[dst] + mu.abs() * self.bound[src];
        if bound < REFRESH {
            for (x, y) in d.iter_mut().zip(s) {
                *x -= mu * y;
            }
        } else {
            // The bound is loose or large: update with the exact maximum. All entries are
            // below 2^52, so a rounded product `mu y` (>= 2^53) leaves |x - mu y| >= 2^52.
            let mut big = 0.0f64;
            for (x, y) in d.iter_mut().zip(s) {
                *x -= mu * y;
                let ax = x.abs();
                big = if ax > big { ax } else { big };
            }
            if big >= LIMIT {
                return Err(AmbiguityError::Overflow);
            }
            bound = big;
        }
        self.bound[dst] = bound;
        Ok(())
    }

    pub(crate) fn swap_cols(&mut self, a: usize, b: usize) {
        let n = self.n;
        let (lo, hi) = (a.min(b), a.max(b));
        if lo == hi {
            return;
        }
        let (left, right) = self.data.split_at_mut(hi * n);
        left[lo * n..lo * n + n].swap_with_slice(&mut right[..n]);
        self.bound.swap(lo, hi);
    }

    /// `self v`, overflow-checked.
    pub(crate) fn mul_vec(&self, v: &[i64]) -> Result<Vec<i64>, AmbiguityError> {
        // Every partial sum is at most sum_c |v_c| bound_c: below 2^52 the f64 column
        // sums are exact (and vectorise); otherwise checked integer arithmetic.
        let reach: f64 = v
            .iter()
            .zip(&self.bound)
            .map(|(&x, b)| (x as f64).abs() * b)
            .sum();
        if reach < LIMIT {
            let mut out = vec![0.0; self.n];
            for (column, &x) in self.data.chunks_exact(self.n).zip(v) {
                let x = x as f64;
                for (o, c) in out.iter_mut().zip(column) {
                    *o += c * x;
                }
            }
            return Ok(out.into_iter().map(|x| x as i64).collect());
        }
        (0..self.n)
            .map(|r| {
                (0..self.n).try_fold(0i64, |acc, c| {
                    self.get(r, c)
                        .checked_mul(v[c])
                        .and_then(|p| acc.checked_add(p))
                        .ok_or(AmbiguityError::Overflow)
                })
            })
            .collect()
    }

    pub(crate) fn to_dmatrix(&self) -> DMatrix<f64> {
        DMatrix::from_column_slice(self.n, self.n, &self.data)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `m v` in i128, the oracle.
    fn naive(m: &IntMatrix, v: &[i64]) -> Vec<i128> {
        (0..m.n)
            .map(|r| {
                (0..m.n)
                    .map(|c| i128::from(m.get(r, c)) * i128::from(v[c]))
                    .sum()
            })
            .collect()
    }

    /// A 3 x 3 matrix grown by column updates (entries up to about `mu^2`).
    fn grown(mu: f64) -> IntMatrix {
        let mut m = IntMatrix::permutation(&[2, 0, 1]);
        m.sub_col(0, 1, mu).unwrap();
        m.sub_col(1, 2, -mu).unwrap();
        m.sub_col(2, 0, 3.0).unwrap();
        m.sub_col(0, 2, mu).unwrap();
        m
    }

    #[test]
    fn products_match_integer_arithmetic_on_both_paths() {
        // Small: the f64 path; a large vector: the checked path, still exact; beyond
        // i64: an overflow error.
        let m = grown(1000.0);
        for v in [[3, -7, 11], [1 << 40, -(1 << 41), 5], [i64::MAX / 2, 0, 1]] {
            let exact = naive(&m, &v);
            match m.mul_vec(&v) {
                Ok(got) => {
                    let got: Vec<i128> = got.into_iter().map(i128::from).collect();
                    assert_eq!(got, exact, "{v:?}");
                }
                Err(e) => {
                    assert_eq!(e, AmbiguityError::Overflow);
                    assert!(exact.iter().any(|x| i64::try_from(*x).is_err()), "{v:?}");
                }
            }
        }
    }
}
