//! The double-difference model of all baselines (thesis eqs. 2.4-3, 2.4-35, 2.4-61):
//! `vec(Y) = [I_m (x) A, I_m (x) G] [vec(N); vec(B)]` with `Q_YY = Q_M (x) Q_t`
//! (eqs. 2.4-15, 2.4-45, 2.4-60).

use super::BaselineError;
use super::differences::DdLayout;
use super::noise::NoiseModel;
use nalgebra::DMatrix;

/// The per-baseline design `X = [A G]`, its weight `W = Q_t^{-1}` and the antenna
/// covariance `Q_M` shared by all baselines.
#[derive(Debug, Clone, PartialEq)]
pub struct DdModel {
    pub layout: DdLayout,
    /// `[A G]` (2n x (n + 3)): phase rows `[lambda I, g]`, code rows `[0, g]` (eq. 2.4-3).
    pub design: DMatrix<f64>,
    /// `Q_t^{-1}` (2n x 2n), block diagonal by signal and observation type.
    pub weight: DMatrix<f64>,
    /// `Q_M = D_m^T Q_m D_m` (m x m): the covariance of the antenna differences (eq. 2.4-11).
    pub q_m: DMatrix<f64>,
}

/// Inverse of `diag(d) + c 1 1^T` (Sherman-Morrison): the covariance of `n` differences
/// against one reference with independent noise `d` and reference noise `c`.
fn dd_weight(d: &[f64], c: f64) -> DMatrix<f64> {
    let n = d.len();
    let inv: Vec<f64> = d.iter().map(|v| 1.0 / v).collect();
    let denom = 1.0 + c * inv.iter().sum::<f64>();
    DMatrix::from_fn(n, n, |i, j| {
        let diag = if i == j { inv[i] } else { 0.0 };
        diag - c * inv[i] * inv[j] / denom
    })
}

impl DdModel {
    /// The model of `layout` for `antennas` antennas (master included) under `noise`.
    pub fn new(
        layout: DdLayout,
        antennas: usize,
        noise: &NoiseModel,
    ) -> Result<Self, BaselineError> {
        if antennas < 2 {
            return Err(BaselineError::TooFewAntennas(antennas));
        }
        let n = layout.ambiguity_count();
        let mut design = DMatrix::zeros(2 * n, n + 3);
        let mut weight = DMatrix::zeros(2 * n, 2 * n);
        let mut row = 0;
        for block in &layout.blocks {
            let lambda = block.signal.wavelength_m();
            let f = noise.signal_factor(block.signal);
            let k = block.others.len();
            for (i, other) in block.others.iter().enumerate() {
                // Eq. 2.3-10: g = -(l_i - l_ref)^T (with a delay gradient, the directions
                // of [`LineOfSight::model_direction`]).
                let g = -(other.model_direction() - block.reference.model_direction());
                for c in 0..3 {
                    design[(row + i, n + c)] = g[c];
                    design[(n + row + i, n + c)] = g[c];
                }
                design[(row + i, row + i)] = lambda;
            }
            for (offset, model) in [(0, &noise.phase), (n, &noise.code)] {
                let var = |e: f64| (f * model.sigma_m(e)).powi(2);
                let d: Vec<f64> = block.others.iter().map(|o| var(o.elevation_rad)).collect();
                let w = dd_weight(&d, var(block.reference.elevation_rad));
                weight
                    .view_mut((offset + row, offset + row), (k, k))
                    .copy_from(&w);
            }
            row += k;
        }
        if design.iter().chain(weight.iter()).any(|v| !v.is_finite()) {
            return Err(BaselineError::NotFinite {
                what: "the double-difference design or weight",
            });
        }
        let m = antennas - 1;
        let s0 = noise.antenna_factor(0).powi(2);
        let q_m = DMatrix::from_fn(m, m, |i, j| {
            s0 + if i == j {
                noise.antenna_factor(i + 1).powi(2)
            } else {
                0.0
            }
        });
        Ok(Self {
            layout,
            design,
            weight,
            q_m,
        })
    }

    /// Ambiguities per baseline.
    pub fn ambiguity_count(&self) -> usize {
        self.layout.ambiguity_count()
    }

    /// Number of baselines.
    pub fn baseline_count(&self) -> usize {
        self.q_m.nrows()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sherman_morrison_weight_inverts_the_dd_covariance() {
        let d = [1.0, 4.0, 0.25, 2.0];
        let c = 3.0;
        let q = DMatrix::from_fn(4, 4, |i, j| c + if i == j { d[i] } else { 0.0 });
        let prod = q * dd_weight(&d, c);
        assert!((prod - DMatrix::<f64>::identity(4, 4)).abs().max() < 1e-12);
    }
}
