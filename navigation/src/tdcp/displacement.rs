//! The antenna's position at `t2` (hence its displacement from `t1`) from the single or
//! double differences, by Gauss-Newton iterations of weighted least squares.

use super::double_difference::DoubleDifferences;
use super::error::TdcpError;
use super::least_squares::{Fit, weighted_least_squares};
use super::single_difference::TdcpEpoch;
use hifitime::Epoch;
use nalgebra::{DMatrix, DVector};
use skyforge_orbits::ephemeris::SatId;
use skyforge_orbits::{Mat3, Vec3};

/// Most Gauss-Newton iterations: from tens of metres the second leaves 1e-5 m, the third
/// nothing.
const MAX_ITERATIONS: usize = 8;
/// A step below this ends the iteration (m).
const CONVERGED_M: f64 = 1e-6;
/// Satellites a solution needs: 3 position components and the clock change (single
/// differences), or 3 double differences (4 satellites).
const NEEDED_SATELLITES: usize = 4;

/// The antenna's position at `t2` from one pair of epochs.
#[derive(Debug, Clone)]
pub struct Displacement {
    /// The first epoch's time tag.
    pub t1: Epoch,
    /// The second epoch's time tag.
    pub t2: Epoch,
    /// The antenna at `t1`, as given (ECEF, m).
    pub r1_m: Vec3,
    /// The antenna at `t2`, solved (ECEF, m).
    pub r2_m: Vec3,
    /// `r2 - r2_hat`, the correction to the a-priori position given (m).
    pub delta_r_m: Vec3,
    /// `c ddt_r`, the receiver clock's change times c (m), from single differences.
    pub clock_change_m: Option<f64>,
    /// Covariance of `delta_r` (ECEF, m^2) then, from single differences, `c ddt_r`:
    /// 3 x 3 or 4 x 4.
    pub covariance: DMatrix<f64>,
    /// Post-fit residual of each satellite (single differences) or of each satellite
    /// against the reference (double differences) (m).
    pub residuals_m: Vec<(SatId, f64)>,
    /// A-posteriori chi-square `v^T C^-1 v` (chi-square distributed with `dof` degrees
    /// of freedom when the noise model holds).
    pub chi2: f64,
    /// Rows less unknowns.
    pub dof: usize,
    /// Gauss-Newton iterations made.
    pub iterations: usize,
}

impl Displacement {
    /// `r2 - r1` (ECEF, m): what TDCP measures.
    pub fn displacement_m(&self) -> Vec3 {
        self.r2_m - self.r1_m
    }

    /// The covariance of the position (and displacement) at `t2` (ECEF, m^2).
    pub fn position_covariance(&self) -> Mat3 {
        self.covariance.fixed_view::<3, 3>(0, 0).into_owned()
    }
}

/// Which differences a solution uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Solver {
    /// Single differences: position and the receiver clock's change ([`solve_single`]).
    SingleDifferences,
    /// Double differences: position alone ([`solve_double`]).
    #[default]
    DoubleDifferences,
}

/// The solution of `epoch` with `solver`.
pub fn solve(epoch: &TdcpEpoch, solver: Solver) -> Result<Displacement, TdcpError> {
    match solver {
        Solver::SingleDifferences => solve_single(epoch),
        Solver::DoubleDifferences => match epoch.double_differences() {
            Some(dd) => solve_double(&dd),
            None => Err(too_few(epoch)),
        },
    }
}

/// Position change and receiver clock change from the single differences (rows
/// `[-e_i^T, 1]`, covariance `diag(sigma_i^2)`); at least 4 satellites.
pub fn solve_single(epoch: &TdcpEpoch) -> Result<Displacement, TdcpError> {
    iterate(epoch)
}

/// Position change from the double differences (rows `-(e_i - e_ref)^T`, their full
/// covariance); at least 3 double differences (4 satellites).
pub fn solve_double(dd: &DoubleDifferences) -> Result<Displacement, TdcpError> {
    iterate(dd)
}

/// The error of too few satellites in `epoch`.
fn too_few(epoch: &TdcpEpoch) -> TdcpError {
    TdcpError::TooFewSatellites {
        needed: NEEDED_SATELLITES,
        have: epoch.sats.len(),
        t: epoch.t2,
    }
}

/// A set of differences linearised about `r2_hat`.
trait Linearised: Sized {
    /// The single differences underneath.
    fn epoch(&self) -> &TdcpEpoch;
    /// Design matrix, prefit residuals, their covariance, the satellite of each row.
    fn system(&self) -> (DMatrix<f64>, DVector<f64>, DMatrix<f64>, Vec<SatId>);
    /// The same differences about another `r2_hat`.
    fn relinearised(&self, r2_hat_m: Vec3) -> Result<Self, TdcpError>;
    /// Whether the last unknown is the clock change.
    const CLOCK: bool;
}

impl Linearised for TdcpEpoch {
    fn epoch(&self) -> &TdcpEpoch {
        self
    }

    fn system(&self) -> (DMatrix<f64>, DVector<f64>, DMatrix<f64>, Vec<SatId>) {
        let n = self.sats.len();
        let h = DMatrix::from_fn(n, 4, |i, k| if k < 3 { -self.sats[i].los[k] } else { 1.0 });
        let z = DVector::from_fn(n, |i, _| self.sats[i].z_m);
        let sigmas = DVector::from_fn(n, |i, _| self.sats[i].sigma_m.powi(2));
        let sats = self.sats.iter().map(|s| s.sat).collect();
        (h, z, DMatrix::from_diagonal(&sigmas), sats)
    }

    fn relinearised(&self, r2_hat_m: Vec3) -> Result<Self, TdcpError> {
        Ok(TdcpEpoch::relinearised(self, r2_hat_m))
    }

    const CLOCK: bool = true;
}

impl Linearised for DoubleDifferences {
    fn epoch(&self) -> &TdcpEpoch {
        DoubleDifferences::epoch(self)
    }

    fn system(&self) -> (DMatrix<f64>, DVector<f64>, DMatrix<f64>, Vec<SatId>) {
        let (h, z, c) = (self.h.clone(), self.z_m.clone(), self.covariance.clone());
        (h, z, c, self.sats.clone())
    }

    fn relinearised(&self, r2_hat_m: Vec3) -> Result<Self, TdcpError> {
        DoubleDifferences::relinearised(self, r2_hat_m).ok_or_else(|| too_few(self.epoch()))
    }

    const CLOCK: bool = false;
}

/// Gauss-Newton from `start`'s `r2_hat` until the step is below [`CONVERGED_M`].
fn iterate<L: Linearised + Clone>(start: &L) -> Result<Displacement, TdcpError> {
    let first = start.epoch();
    if first.sats.len() < NEEDED_SATELLITES {
        return Err(too_few(first));
    }
    let t = first.t2;
    let mut current = start.clone();
    let mut step_m = f64::INFINITY;
    for iteration in 1..=MAX_ITERATIONS {
        let (h, z, covariance, sats) = current.system();
        let fit = weighted_least_squares(&h, &z, &covariance).ok_or(TdcpError::Singular { t })?;
        let step = Vec3::new(fit.x[0], fit.x[1], fit.x[2]);
        let r2_m = current.epoch().r2_hat_m + step;
        step_m = step.norm();
        if step_m <= CONVERGED_M {
            return Ok(displacement::<L>(first, r2_m, fit, sats, iteration));
        }
        current = current.relinearised(r2_m)?;
    }
    Err(TdcpError::NoConvergence { t, step_m })
}

/// The solution at `r2_m` of the last fit, for the pair `first` was made of.
fn displacement<L: Linearised>(
    first: &TdcpEpoch,
    r2_m: Vec3,
    fit: Fit,
    sats: Vec<SatId>,
    iterations: usize,
) -> Displacement {
    let unknowns = fit.x.len();
    Displacement {
        t1: first.t1,
        t2: first.t2,
        r1_m: first.r1_m,
        r2_m,
        delta_r_m: r2_m - first.r2_hat_m,
        clock_change_m: L::CLOCK.then(|| fit.x[3]),
        covariance: fit.covariance,
        residuals_m: sats
            .into_iter()
            .zip(fit.residuals.iter().copied())
            .collect(),
        chi2: fit.chi2,
        dof: fit.residuals.len().saturating_sub(unknowns),
        iterations,
    }
}
