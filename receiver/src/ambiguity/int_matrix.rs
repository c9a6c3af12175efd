//! Square integer matrices for `Z` and `Z^{-1}`, with overflow-checked updates.

use super::AmbiguityError;
use nalgebra::DMatrix;

/// An `n x n` matrix of `i64`, column-major.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct IntMatrix {
    n: usize,
    data: Vec<i64>,
}

impl IntMatrix {
    pub(crate) fn identity(n: usize) -> Self {
        let mut data = vec![0; n * n];
        for i in 0..n {
            data[i * n + i] = 1;
        }
        Self { n, data }
    }

    pub(crate) fn get(&self, row: usize, col: usize) -> i64 {
        self.data[col * self.n + row]
    }

    /// Column `dst` -= `mu` * column `src`.
    pub(crate) fn sub_col(
        &mut self,
        dst: usize,
        src: usize,
        mu: i64,
    ) -> Result<(), AmbiguityError> {
        let n = self.n;
        for r in 0..n {
            let v = mu
                .checked_mul(self.data[src * n + r])
                .and_then(|p| self.data[dst * n + r].checked_sub(p))
                .ok_or(AmbiguityError::Overflow)?;
            self.data[dst * n + r] = v;
        }
        Ok(())
    }

    /// Row `dst` += `mu` * row `src`.
    pub(crate) fn add_row(
        &mut self,
        dst: usize,
        src: usize,
        mu: i64,
    ) -> Result<(), AmbiguityError> {
        let n = self.n;
        for c in 0..n {
            let v = mu
                .checked_mul(self.data[c * n + src])
                .and_then(|p| self.data[c * n + dst].checked_add(p))
                .ok_or(AmbiguityError::Overflow)?;
            self.data[c * n + dst] = v;
        }
        Ok(())
    }

    pub(crate) fn swap_cols(&mut self, a: usize, b: usize) {
        let n = self.n;
        for r in 0..n {
            self.data.swap(a * n + r, b * n + r);
        }
    }

    pub(crate) fn swap_rows(&mut self, a: usize, b: usize) {
        let n = self.n;
        for c in 0..n {
            self.data.swap(c * n + a, c * n + b);
        }
    }

    /// `self^T v`, overflow-checked.
    pub(crate) fn transpose_mul(&self, v: &[i64]) -> Result<Vec<i64>, AmbiguityError> {
        (0..self.n)
            .map(|c| {
                (0..self.n).try_fold(0i64, |acc, r| {
                    self.get(r, c)
                        .checked_mul(v[r])
                        .and_then(|p| acc.checked_add(p))
                        .ok_or(AmbiguityError::Overflow)
                })
            })
            .collect()
    }

    pub(crate) fn to_dmatrix(&self) -> DMatrix<f64> {
        DMatrix::from_fn(self.n, self.n, |r, c| self.get(r, c) as f64)
    }
}
