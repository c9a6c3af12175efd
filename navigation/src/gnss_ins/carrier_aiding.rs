//! Carrier-phase and height aiding of the INS filter, as paper 001 integrates BeiDou with
//! its SINS: time-differenced carrier phase double differences between two epochs
//! (`crate::tdcp`; paper 001 eqs. (6), (7), (9)-(14) as `BOOK_PAPER001_TARGETS.md`
//! reconstructs them) and a height constraint (its "altitude aiding").
//!
//! A double difference over `[t1, t2]` measures the change of the antenna's position, so
//! it observes the integral of the velocity error over the interval, approximated as
//! `dv(t2) dt` (the paper's `H1 int X dt` to first order; `dt` is an epoch interval, short
//! against the error's dynamics), plus the lever arm turned by the attitude error,
//! `-[((C2 - C1) l) x] psi` (its eq. (5)). Consecutive pairs share an epoch (lag-1
//! correlation -1/2), which the filter, like the paper's, does not model.

use super::config::IntegrationError;
use super::error_state::{ATT, POS, STATES, VEL, skew};
use super::filter::{LooselyCoupled, Rows, Update};
use crate::tdcp::{ImuPose, LeverArm, TdcpConfig, time_differences_imu};
use nalgebra::{DMatrix, DVector};
use skyforge_gnss::observation::ObsEpoch;
use skyforge_orbits::Vec3;
use skyforge_orbits::ephemeris::EphemerisStore;
use skyforge_orbits::frames::ecef_to_geodetic;
use skyforge_orbits::time::TimeOrigin;

impl LooselyCoupled {
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
        let offset_s = (cur.time - state.t).to_seconds();
        if offset_s.abs() > self.step_s() + 1e-6 {
            return Err(IntegrationError::FixOutOfStep {
                t: cur.time,
                ins_t: state.t,
                offset_s,
            });
        }
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
        let mut h = DMatrix::zeros(n, STATES);
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
        let up = Vec3::new(
            g.lat_rad.cos() * g.lon_rad.cos(),
            g.lat_rad.cos() * g.lon_rad.sin(),
            g.lat_rad.sin(),
        );
        let mut h = DMatrix::zeros(1, STATES);
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

fn to_dynamic3(m: &skyforge_orbits::Mat3) -> DMatrix<f64> {
    DMatrix::from_fn(3, 3, |i, j| m[(i, j)])
}
