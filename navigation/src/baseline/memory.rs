//! Float ambiguities carried from epoch to epoch: the memory of a kinematic filter whose
//! ambiguities are constant and whose baselines are new at every epoch (RTKLIB's
//! kinematic mode keeps the same in its Kalman filter; the thesis's single-epoch chain
//! does without).
//!
//! The memory is the last float solution's ambiguities `N_hat` (n x m) and their shared
//! cofactor `P_NN` (the covariance of each baseline's ambiguities is `Q_M` times it, as in
//! [`super::float`]). At the next epoch each double difference `N(s) - N(r')` of the new
//! layout is the old `N(s) - N(r)` minus the old `N(r') - N(r)` (the old reference's own
//! entry zero): a matrix `C` of +1 and -1, so the prior is `C N_hat` with cofactor
//! `C P_NN C^T`, joining the epoch's normal equations in information form. A double
//! difference whose satellites the memory does not have enters without a prior; one that
//! loses lock is forgotten (marginalising a Gaussian in covariance form is deleting its
//! rows and columns), and a reference satellite that loses lock takes its signal's whole
//! block.

use super::differences::DdLayout;
use super::float::{AmbiguityPrior, FloatBaselines};
use nalgebra::DMatrix;
use skyforge_gnss::signal::Signal;
use skyforge_orbits::ephemeris::SatId;

/// What earlier epochs know of the ambiguities.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct FloatMemory {
    /// (signal, satellite, reference satellite) of each remembered ambiguity.
    ids: Vec<(Signal, SatId, SatId)>,
    /// `N_hat` (ambiguities x baselines, cycles).
    mean: DMatrix<f64>,
    /// `P_NN` (ambiguities x ambiguities).
    cofactor: DMatrix<f64>,
}

impl FloatMemory {
    /// Nothing remembered.
    pub fn new() -> Self {
        Self::default()
    }

    /// Remember `float`'s ambiguities (replacing what was remembered: they already hold
    /// it as their prior).
    pub fn remember(&mut self, float: &FloatBaselines) {
        let n = float.model.ambiguity_count();
        self.ids = float.model.layout.ambiguity_ids().collect();
        self.mean = float.ambiguities.clone();
        self.cofactor = float.cofactor.view((0, 0), (n, n)).into_owned();
    }

    /// A loss of lock of `sat` on `signal` at any antenna: its ambiguities are forgotten,
    /// and the whole signal's when `sat` is its reference.
    pub fn slip(&mut self, sat: SatId, signal: Signal) {
        let keep: Vec<usize> = (0..self.ids.len())
            .filter(|&i| {
                let (s, other, reference) = self.ids[i];
                s != signal || (other != sat && reference != sat)
            })
            .collect();
        if keep.len() == self.ids.len() {
            return;
        }
        self.ids = keep.iter().map(|&i| self.ids[i]).collect();
        self.mean = self.mean.select_rows(&keep);
        self.cofactor = self.cofactor.select_rows(&keep).select_columns(&keep);
    }

    /// The remembered row of `sat` relative to the reference of `signal`: `Some(None)`
    /// for the reference itself (zero), `None` when not remembered.
    fn row(&self, signal: Signal, sat: SatId) -> Option<Option<usize>> {
        if let Some(i) = self
            .ids
            .iter()
            .position(|&(s, other, _)| s == signal && other == sat)
        {
            return Some(Some(i));
        }
        self.ids
            .iter()
            .any(|&(s, _, reference)| s == signal && reference == sat)
            .then_some(None)
    }

    /// The prior of `layout`'s ambiguities for `baselines` baselines; `None` when nothing
    /// of them is remembered (or the remembered cofactor is unusable).
    pub fn prior(&self, layout: &DdLayout, baselines: usize) -> Option<AmbiguityPrior> {
        if self.ids.is_empty() || self.mean.ncols() != baselines {
            return None;
        }
        // Rows of C: (new index, +1 row, -1 row) with None for the old reference's zero.
        let mut rows: Vec<(usize, Option<usize>, Option<usize>)> = Vec::new();
        for (i, (signal, sat, reference)) in layout.ambiguity_ids().enumerate() {
            if let (Some(plus), Some(minus)) = (self.row(signal, sat), self.row(signal, reference))
            {
                rows.push((i, plus, minus));
            }
        }
        if rows.is_empty() {
            return None;
        }
        let c = DMatrix::from_fn(rows.len(), self.ids.len(), |r, j| {
            let (_, plus, minus) = rows[r];
            f64::from(i8::from(plus == Some(j)) - i8::from(minus == Some(j)))
        });
        let cofactor = &c * &self.cofactor * c.transpose();
        let mean = &c * &self.mean;
        // A prior that is not positive definite (rounding in an extreme case) is dropped:
        // the epoch solves on its own and is remembered in its place, where an error
        // would fail every later epoch on the same memory.
        let factor = cofactor.cholesky()?;
        let information = factor.inverse();
        let n = layout.ambiguity_count();
        let mut full_information = DMatrix::zeros(n, n);
        let mut full_mean = DMatrix::zeros(n, baselines);
        for (a, &(i, _, _)) in rows.iter().enumerate() {
            full_mean.set_row(i, &mean.row(a));
            for (b, &(j, _, _)) in rows.iter().enumerate() {
                full_information[(i, j)] = information[(a, b)];
            }
        }
        Some(AmbiguityPrior {
            information: full_information,
            mean: full_mean,
        })
    }
}
