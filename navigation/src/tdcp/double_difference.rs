//! Double differences between satellites of the single differences in time: the
//! receiver clock's change cancels (module docs; paper 001 eq. (7)).

use super::single_difference::TdcpEpoch;
use nalgebra::{DMatrix, DVector};
use skyforge_orbits::ephemeris::SatId;

/// One pair of epochs' double differences against the reference satellite, the highest
/// at `t2`: `z_i - z_ref` with rows `-(e_i - e_ref)^T` and their covariance
/// `diag(s_i^2) + s_ref^2 1 1^T` (`s` the single differences' sigmas; `2 sigma_phi^2
/// (I + 1 1^T)` without elevation weighting).
#[derive(Debug, Clone)]
pub struct DoubleDifferences {
    /// The reference satellite.
    pub reference: SatId,
    /// The other satellites, in row order.
    pub sats: Vec<SatId>,
    /// Prefit double differences (m).
    pub z_m: DVector<f64>,
    /// Design matrix, n x 3: the rows `-(e_i - e_ref)^T` for `delta_r2` (ECEF).
    pub h: DMatrix<f64>,
    /// Covariance of `z_m` (m^2), n x n.
    pub covariance: DMatrix<f64>,
    /// The single differences they come from.
    epoch: TdcpEpoch,
}

impl TdcpEpoch {
    /// The double differences against the highest satellite at `t2`; `None` with fewer
    /// than two satellites.
    pub fn double_differences(&self) -> Option<DoubleDifferences> {
        let reference = (self.sats.iter())
            .max_by(|a, b| a.elevation_rad.total_cmp(&b.elevation_rad))?
            .sat;
        DoubleDifferences::against(self.clone(), reference)
    }
}

impl DoubleDifferences {
    /// The double differences of `epoch` against `reference`; `None` when it is not
    /// among the satellites or no other satellite is.
    fn against(epoch: TdcpEpoch, reference: SatId) -> Option<Self> {
        let r = epoch.sats.iter().find(|s| s.sat == reference)?;
        let others: Vec<_> = epoch.sats.iter().filter(|s| s.sat != reference).collect();
        if others.is_empty() {
            return None;
        }
        let n = others.len();
        let z_m = DVector::from_fn(n, |i, _| others[i].z_m - r.z_m);
        let h = DMatrix::from_fn(n, 3, |i, k| -(others[i].los[k] - r.los[k]));
        let common = r.sigma_m.powi(2);
        let covariance = DMatrix::from_fn(n, n, |i, j| {
            common
                + if i == j {
                    others[i].sigma_m.powi(2)
                } else {
                    0.0
                }
        });
        let sats = others.iter().map(|s| s.sat).collect();
        Some(Self {
            reference,
            sats,
            z_m,
            h,
            covariance,
            epoch,
        })
    }

    /// The single differences these come from.
    pub fn epoch(&self) -> &TdcpEpoch {
        &self.epoch
    }

    /// The same double differences (same reference) linearised about another
    /// `r2_hat_m` ([`TdcpEpoch::relinearised`]).
    pub fn relinearised(&self, r2_hat_m: skyforge_orbits::Vec3) -> Option<Self> {
        Self::against(self.epoch.relinearised(r2_hat_m), self.reference)
    }
}
