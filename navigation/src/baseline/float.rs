//! The float solution of all baselines (thesis eqs. 2.4-62, 2.4-63) and the baselines given
//! integer ambiguities (eqs. 2.4-64, 2.4-65).
//!
//! The design of vec(Y) is `I_m (x) X` with `X = [A G]` and its covariance `Q_M (x) Q_t`,
//! so the normal matrix is `Q_M^{-1} (x) X^T W X` and the least-squares solution of every
//! baseline is `P X^T W y_k` with `P = (X^T W X)^{-1}`; the covariance of
//! `[vec(N); vec(B)]` (in the per-baseline order) is `Q_M (x) P`.

use super::BaselineError;
use super::model::DdModel;
use nalgebra::{DMatrix, DVector, Matrix3xX};
use skyforge_gnss::observation::ObsRecord;

/// A prior on one epoch's ambiguities, in the layout's order: its mean and its
/// information (`information` joins the ambiguity block of the normal matrix; the
/// solution is formed as a correction to `mean`, which keeps its digits: ambiguities of
/// real receivers run to 1e8 cycles).
#[derive(Debug, Clone, PartialEq)]
pub struct AmbiguityPrior {
    /// `(C P_NN C^T)^{-1}`, zero rows and columns for ambiguities without a prior.
    pub information: DMatrix<f64>,
    /// `C N_hat` (n x m), zero rows for ambiguities without a prior.
    pub mean: DMatrix<f64>,
}

/// Float ambiguities and baselines of one epoch.
#[derive(Debug, Clone, PartialEq)]
pub struct FloatBaselines {
    pub model: DdModel,
    /// `Y` (2n x m, m): column `k` holds baseline `k`'s double-differenced phase (first n
    /// rows) and code (eq. 2.4-3), the observations the solution was computed from.
    pub observations: DMatrix<f64>,
    /// `N_hat` (n x m, cycles): column `k` holds baseline `k`'s ambiguities.
    pub ambiguities: DMatrix<f64>,
    /// `B_hat` (3 x m, m, ECEF).
    pub baselines: Matrix3xX<f64>,
    /// `P = (X^T W X)^{-1}` ((n + 3) x (n + 3)): ambiguities first, then x, y, z.
    pub cofactor: DMatrix<f64>,
}

/// Baselines after fixing integer ambiguities (or integer combinations of them).
#[derive(Debug, Clone, PartialEq)]
pub struct FixedBaselines {
    /// `B_check` (3 x m, m, ECEF).
    pub baselines: Matrix3xX<f64>,
    /// Covariance of vec(B_check) (3m x 3m, m^2): baseline 1's x, y, z first.
    pub covariance: DMatrix<f64>,
}

/// The float ambiguities left free when some are held at integers: their conditional mean
/// and covariance, and how well the held integers fit the float solution.
#[derive(Debug, Clone, PartialEq)]
pub struct Conditioned {
    /// Indices into vec(N) of the free ambiguities.
    pub free: Vec<usize>,
    /// `a_F - Q_FH Q_HH^{-1} (a_H - v)`.
    pub ambiguities: DVector<f64>,
    /// `Q_FF - Q_FH Q_HH^{-1} Q_HF`.
    pub covariance: DMatrix<f64>,
    /// `(a_H - v)^T Q_HH^{-1} (a_H - v)`: chi-square with as many degrees of freedom as
    /// held integers when they are right.
    pub held_statistic: f64,
}

/// `prior` fits `n` ambiguities of `m` baselines.
fn check_prior(prior: &AmbiguityPrior, n: usize, m: usize) -> Result<(), BaselineError> {
    let (rows, cols) = prior.information.shape();
    if (rows, cols) != (n, n) || prior.mean.shape() != (n, m) {
        return Err(BaselineError::Dimension {
            what: "ambiguity prior rows",
            expected: n,
            found: rows,
        });
    }
    Ok(())
}

/// Vectorised order: baseline 1's entries, then baseline 2's (vec of a column-major matrix).
fn vec_of(m: &DMatrix<f64>) -> DVector<f64> {
    DVector::from_column_slice(m.as_slice())
}

impl FloatBaselines {
    /// Least-squares float solution (eq. 2.4-62) of the baselines from `antennas[0]` to
    /// each other antenna, with the cofactor of eq. 2.4-63; with `prior`, earlier epochs'
    /// information on the ambiguities ([`super::memory`]) joins the normal equations.
    pub fn solve(
        model: DdModel,
        antennas: &[&[ObsRecord]],
        prior: Option<&AmbiguityPrior>,
    ) -> Result<Self, BaselineError> {
        let m = model.baseline_count();
        if antennas.len() != m + 1 {
            return Err(BaselineError::Dimension {
                what: "antennas with observations",
                expected: m + 1,
                found: antennas.len(),
            });
        }
        let n = model.ambiguity_count();
        let xtw = model.design.transpose() * &model.weight;
        let mut normal = &xtw * &model.design;
        if let Some(p) = prior {
            check_prior(p, n, m)?;
            let mut block = normal.view_mut((0, 0), (n, n));
            block += &p.information;
        }
        let cofactor = normal.cholesky().ok_or(BaselineError::Singular)?.inverse();
        let mut ambiguities = DMatrix::zeros(n, m);
        let mut baselines = Matrix3xX::zeros(m);
        let mut observations = DMatrix::zeros(2 * n, m);
        for (k, rover) in antennas[1..].iter().enumerate() {
            let y = model.layout.double_differences(antennas[0], rover)?;
            if y.iter().any(|v| !v.is_finite()) {
                return Err(BaselineError::NotFinite {
                    what: "a double-differenced observation",
                });
            }
            // With a prior, the correction to its mean (whose own term is then zero).
            let x = match prior {
                Some(p) => {
                    let mut start = DVector::zeros(n + 3);
                    start.rows_mut(0, n).copy_from(&p.mean.column(k));
                    let residual = &y - &model.design * &start;
                    start + &cofactor * (&xtw * residual)
                }
                None => &cofactor * (&xtw * &y),
            };
            ambiguities.set_column(k, &x.rows(0, n));
            baselines.set_column(k, &x.rows(n, 3));
            observations.set_column(k, &y);
        }
        Ok(Self {
            model,
            observations,
            ambiguities,
            baselines,
            cofactor,
        })
    }

    /// vec(N_hat): baseline 1's ambiguities, then baseline 2's (length n m).
    pub fn ambiguity_vector(&self) -> DVector<f64> {
        vec_of(&self.ambiguities)
    }

    /// `Q_M (x)` the block of the cofactor at `start` of size `shape`: the covariance of
    /// the corresponding vec() quantities over all baselines.
    fn covariance_block(&self, start: (usize, usize), shape: (usize, usize)) -> DMatrix<f64> {
        self.model
            .q_m
            .kronecker(&self.cofactor.view(start, shape).into_owned())
    }

    /// `Q_NN = Q_M (x) P_NN` (nm x nm), the covariance of [`Self::ambiguity_vector`].
    pub fn ambiguity_covariance(&self) -> DMatrix<f64> {
        let n = self.model.ambiguity_count();
        self.covariance_block((0, 0), (n, n))
    }

    /// `Q_BB = Q_M (x) P_BB` (3m x 3m), the covariance of vec(B_hat).
    pub fn baseline_covariance(&self) -> DMatrix<f64> {
        let n = self.model.ambiguity_count();
        self.covariance_block((n, n), (3, 3))
    }

    /// `Q_BN = Q_M (x) P_BN` (3m x nm), the covariance of vec(B_hat) with vec(N_hat).
    fn baseline_ambiguity_covariance(&self) -> DMatrix<f64> {
        let n = self.model.ambiguity_count();
        self.covariance_block((n, 0), (3, n))
    }

    /// The free ambiguities conditioned on `held` (index into vec(N), integer).
    pub fn conditioned(&self, held: &[(usize, i64)]) -> Result<Conditioned, BaselineError> {
        let a = self.ambiguity_vector();
        let q = self.ambiguity_covariance();
        let nm = a.len();
        if let Some(&(i, _)) = held.iter().find(|(i, _)| *i >= nm) {
            return Err(BaselineError::Dimension {
                what: "held ambiguity index",
                expected: nm,
                found: i,
            });
        }
        let h: Vec<usize> = held.iter().map(|(i, _)| *i).collect();
        let free: Vec<usize> = (0..nm).filter(|i| !h.contains(i)).collect();
        let pick = |rows: &[usize], cols: &[usize]| {
            DMatrix::from_fn(rows.len(), cols.len(), |r, c| q[(rows[r], cols[c])])
        };
        let dh = DVector::from_iterator(h.len(), held.iter().map(|&(i, v)| a[i] - v as f64));
        let a_f = DVector::from_iterator(free.len(), free.iter().map(|&i| a[i]));
        if h.is_empty() {
            return Ok(Conditioned {
                covariance: pick(&free, &free),
                ambiguities: a_f,
                free,
                held_statistic: 0.0,
            });
        }
        let chol = pick(&h, &h).cholesky().ok_or(BaselineError::Singular)?;
        let q_fh = pick(&free, &h);
        let gain = chol.solve(&q_fh.transpose()).transpose();
        Ok(Conditioned {
            ambiguities: a_f - &gain * &dh,
            covariance: pick(&free, &free) - &gain * q_fh.transpose(),
            held_statistic: dh.dot(&chol.solve(&dh)),
            free,
        })
    }

    /// The full fix as a linear map: `vec(B_check) = vec(B_hat) - G (a_hat - N)` for any
    /// integer vector `N` (eq. 2.4-64, `G = Q_BN Q_NN^{-1}`, 3m x nm), and the covariance of
    /// eq. 2.4-65 (3m x 3m), the same for every `N`.
    pub fn fix_gain(&self) -> Result<(DMatrix<f64>, DMatrix<f64>), BaselineError> {
        let q_bn = self.baseline_ambiguity_covariance();
        let chol = self
            .ambiguity_covariance()
            .cholesky()
            .ok_or(BaselineError::Singular)?;
        let gain = chol.solve(&q_bn.transpose()).transpose();
        let covariance = self.baseline_covariance() - &gain * q_bn.transpose();
        Ok((gain, covariance))
    }

    /// vec(B_hat): baseline 1's x, y, z, then baseline 2's.
    pub fn baseline_vector(&self) -> DVector<f64> {
        DVector::from_column_slice(self.baselines.as_slice())
    }

    /// Eqs. 2.4-64/2.4-65 with every ambiguity fixed: `integers` is vec(N_check).
    pub fn fix(&self, integers: &[i64]) -> Result<FixedBaselines, BaselineError> {
        let nm = self.ambiguities.len();
        self.fix_combinations(&DMatrix::identity(nm, nm), integers)
    }

    /// Eqs. 2.4-64/2.4-65 generalised to integer combinations `z = Z^T vec(N)` (rows of
    /// `z_t`, p x nm) fixed to `values`; with `Z^T = I` this is the full fix, with fewer
    /// rows a partial one: `b = b_hat - Q_bz Q_zz^{-1} (z_hat - z)`,
    /// `Q = Q_bb - Q_bz Q_zz^{-1} Q_zb`.
    pub fn fix_combinations(
        &self,
        z_t: &DMatrix<f64>,
        values: &[i64],
    ) -> Result<FixedBaselines, BaselineError> {
        let nm = self.ambiguities.len();
        if z_t.ncols() != nm || z_t.nrows() != values.len() {
            return Err(BaselineError::Dimension {
                what: "integer combinations (rows of Z^T x ambiguities)",
                expected: nm,
                found: z_t.ncols(),
            });
        }
        let q_bz = self.baseline_ambiguity_covariance() * z_t.transpose();
        let q_zz = z_t * self.ambiguity_covariance() * z_t.transpose();
        let z_hat = z_t * self.ambiguity_vector();
        let dz = z_hat - DVector::from_iterator(values.len(), values.iter().map(|&v| v as f64));
        let chol = q_zz.cholesky().ok_or(BaselineError::Singular)?;
        let gain = chol.solve(&q_bz.transpose()).transpose();
        let b = self.baseline_vector() - &gain * dz;
        let covariance = self.baseline_covariance() - &gain * q_bz.transpose();
        Ok(FixedBaselines {
            baselines: Matrix3xX::from_column_slice(b.as_slice()),
            covariance,
        })
    }
}
