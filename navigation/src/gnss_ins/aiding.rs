//! Measurement updates of the INS filter beyond fixes, as paper 001 integrates BeiDou with
//! its SINS: time-differenced carrier phase double differences between two epochs
//! (`crate::tdcp`; paper 001 eqs. (6), (7), (9)-(14) as `BOOK_PAPER001_TARGETS.md`
//! reconstructs them), a height constraint (its "altitude aiding") and code differences
//! between satellites (its absolute position from three pseudoranges: the receiver clock
//! cancels, the height constraint supplies what three satellites cannot).
//!
//! A double difference over `[t1, t2]` measures the change of the antenna's position, so
//! it observes the integral of the velocity error over the interval, approximated as
//! `dv(t2) dt` (the paper's `H1 int X dt` to first order; `dt` is an epoch interval, short
//! against the error's dynamics), plus the lever arm turned by the attitude error,
//! `-[((C2 - C1) l) x] psi` (its eq. (5)). Consecutive pairs share an epoch (lag-1
//! correlation -1/2), which the filter, like the paper's, does not model.

use super::config::IntegrationError;
use super::error_state::{ATT, POS, VEL, skew};
use super::filter::{InsFilter, Rows, Update};
use crate::pvt::{CodeResidual, Measurement, PvtConfig, code_residuals};
use crate::tdcp::{ImuPose, LeverArm, TdcpConfig, time_differences_imu};
use nalgebra::{DMatrix, DVector};
use skyforge_gnss::observation::ObsEpoch;
use skyforge_orbits::Vec3;
use skyforge_orbits::ephemeris::EphemerisStore;
use skyforge_orbits::frames::{c_ecef_ned, ecef_to_geodetic};
use skyforge_orbits::time::TimeOrigin;

impl<const N: usize> InsFilter<N> {
    /// Updates with the TDCP double differences between `prev` (whose IMU pose the filter
    /// had, `pose1`) and `cur`, whose time must lie within one IMU interval of the INS's;
    /// `Ok(None)` when fewer than two satellites kept lock.
    pub fn update_tdcp(
        &mut self,
        (prev, cur): (&ObsEpoch, &ObsEpoch),
        pose1: &ImuPose,
        store: &EphemerisStore,
        origin: &TimeOrigin,
        config: &TdcpConfig,
    ) -> Result<Option<Update>, IntegrationError> {
        let state = *self.state();
        let offset_s = self.offset_s(cur.time)?;
        let pose2 = ImuPose {
            r_ecef_m: state.r_ecef_m + state.v_ecef_mps * offset_s,
            c_body_ecef: state.c_body_ecef,
        };
        let lever = LeverArm {
            body_m: self.lever_arm(),
        };
        let epoch =
            time_differences_imu((prev, cur), (pose1, &pose2), &lever, store, origin, config)
                .map_err(|e| IntegrationError::Tdcp(e.to_string()))?;
        let Some(dd) = epoch.double_differences() else {
            return Ok(None);
        };
        let dt = (cur.time - prev.time).to_seconds();
        let turned = skew(&((pose2.c_body_ecef - pose1.c_body_ecef) * lever.body_m));
        let n = dd.z_m.len();
        let mut h = DMatrix::zeros(n, N);
        h.view_mut((0, VEL), (n, 3)).copy_from(&(&dd.h * dt));
        h.view_mut((0, ATT), (n, 3))
            .copy_from(&(-&dd.h * to_dynamic3(&turned)));
        let rows = Rows {
            h,
            y: -&dd.z_m,
            r: dd.covariance.clone(),
        };
        self.apply(rows, cur.time).map(Some)
    }

    /// Updates with the code of `epoch` (within one IMU interval of the INS's time),
    /// differenced between satellites so the receiver clock cancels, each pseudorange with
    /// the error `sigma_m` (`pvt`'s models for the satellite clock, ionosphere and
    /// troposphere of `pvt_config`); `Ok(None)` with fewer than two satellites.
    pub fn update_code(
        &mut self,
        epoch: &ObsEpoch,
        store: &EphemerisStore,
        origin: &TimeOrigin,
        pvt_config: &PvtConfig,
        sigma_m: f64,
    ) -> Result<Option<Update>, IntegrationError> {
        let state = *self.state();
        let offset_s = self
            .offset_s(epoch.time)
            .map_err(|_| IntegrationError::BadFix {
                t: epoch.time,
                what: "code epoch more than an IMU interval from the INS, or a bad sigma",
            })?;
        if !(sigma_m.is_finite() && sigma_m > 0.0) {
            return Err(IntegrationError::BadFix {
                t: epoch.time,
                what: "code epoch more than an IMU interval from the INS, or a bad sigma",
            });
        }
        let c_l = state.c_body_ecef * self.lever_arm();
        let antenna = state.r_ecef_m + state.v_ecef_mps * offset_s + c_l;
        let meas = Measurement::of_records(&epoch.sats);
        let tag_s = origin.seconds_since_start(epoch.time);
        let residuals = code_residuals(&meas, tag_s, store, origin, pvt_config, &antenna);
        let Some((g, y, r)) = code_differences(&residuals, sigma_m) else {
            return Ok(None);
        };
        let n = y.len();
        let mut h = DMatrix::zeros(n, N);
        h.view_mut((0, POS), (n, 3)).copy_from(&g);
        h.view_mut((0, ATT), (n, 3))
            .copy_from(&(-&g * to_dynamic3(&skew(&c_l))));
        self.apply(Rows { h, y, r }, epoch.time).map(Some)
    }

    /// Updates with the antenna's height above the ellipsoid known to `sigma_m` (a
    /// surveyed site, a lake's surface, a road map).
    pub fn update_height(
        &mut self,
        height_m: f64,
        sigma_m: f64,
    ) -> Result<Update, IntegrationError> {
        let state = *self.state();
        if !(height_m.is_finite() && sigma_m.is_finite() && sigma_m > 0.0) {
            return Err(IntegrationError::BadFix {
                t: state.t,
                what: "height or its sigma not finite, or the sigma not positive",
            });
        }
        let c_l = state.c_body_ecef * self.lever_arm();
        let antenna = state.r_ecef_m + c_l;
        let g = ecef_to_geodetic(&antenna);
        let up: Vec3 = -c_ecef_ned(g.lat_rad, g.lon_rad).row(2).transpose();
        let mut h = DMatrix::zeros(1, N);
        h.view_mut((0, POS), (1, 3)).copy_from(&up.transpose());
        h.view_mut((0, ATT), (1, 3))
            .copy_from(&(-up.transpose() * skew(&c_l)));
        let rows = Rows {
            h,
            y: DVector::from_element(1, g.h_m - height_m),
            r: DMatrix::from_element(1, 1, sigma_m * sigma_m),
        };
        self.apply(rows, state.t)
    }
}

/// The code residuals of `epoch` differenced against the highest satellite: `y = -(omc_i -
/// omc_ref)` with rows `-(e_i - e_ref)^T` on the antenna's position error, covariance
/// `sigma^2 (I + 1 1^T)`. `None` with fewer than two satellites.
fn code_differences(
    residuals: &[CodeResidual],
    sigma_m: f64,
) -> Option<(DMatrix<f64>, DVector<f64>, DMatrix<f64>)> {
    let reference = residuals
        .iter()
        .max_by(|a, b| a.el_rad.total_cmp(&b.el_rad))?;
    let others: Vec<&CodeResidual> = (residuals.iter())
        .filter(|c| c.sat != reference.sat)
        .collect();
    let n = others.len();
    if n == 0 {
        return None;
    }
    let g = DMatrix::from_fn(n, 3, |i, k| -(others[i].los[k] - reference.los[k]));
    let y = DVector::from_fn(n, |i, _| -(others[i].omc_m - reference.omc_m));
    let r = DMatrix::from_fn(n, n, |i, j| {
        sigma_m.powi(2) * if i == j { 2.0 } else { 1.0 }
    });
    Some((g, y, r))
}

fn to_dynamic3(m: &skyforge_orbits::Mat3) -> DMatrix<f64> {
    DMatrix::from_fn(3, 3, |i, j| m[(i, j)])
}
