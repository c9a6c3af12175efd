//! Fine alignment of a stationary IMU (Groves 2013 sec. 5.6.3, and the zero-velocity
//! update of sec. 15.3): the INS navigates through the static period from a coarse
//! attitude while a six-state Kalman filter of its attitude and velocity errors takes the
//! velocity it computes as the measurement of its velocity error (the true velocity is
//! zero) and corrects the INS after every update (closed loop).
//!
//! Error model, NED-resolved at the fixed position (Groves 2013 sec. 14.2, the ECEF
//! error equations rotated to the stationary local frame, position errors dropped since
//! the surveyed position is restored at every update): with the attitude error `psi`
//! defined by `C_b^n(computed) = (I + [psi x]) C_b^n(true)` (so `psi_D` is the heading
//! error, computed minus true) and the velocity error `dv`,
//! `psi' = -w_ie x psi + (gyro noise)`, `dv' = -f x psi - 2 w_ie x dv + (accel noise)`,
//! `f = -g` the specific force at rest. Heading is observed through the east tilt it
//! makes (`psi_E' = w_ie cos L psi_D`), which drives a north velocity; a gyro bias along
//! east is indistinguishable from that heading error and stays in the result
//! ([`super::heading_error_from_east_gyro_bias_rad`]).

use super::error::InsError;
use super::rotation::{orthonormalise, rodrigues};
use super::state::{InsState, attitude_ned};
use nalgebra::{Matrix3, Matrix6, Matrix6x3, Vector6};
use skyforge_gnss::imu::ImuIncrement;
use skyforge_orbits::frames::Geodetic;
use skyforge_orbits::frames::c_ecef_ned;
use skyforge_orbits::gravity::{earth_rate_ecef, normal_gravity_ned};
use skyforge_orbits::{Mat3, Vec3};
use std::f64::consts::{PI, TAU};

/// Settings of the fine-alignment filter.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FineAlignmentConfig {
    /// Gyro angle random walk (rad/sqrt(s)): the attitude process noise.
    pub gyro_arw_rad_per_sqrt_s: f64,
    /// Accelerometer velocity random walk (m/s/sqrt(s)): the velocity process noise.
    pub accel_vrw_mps_per_sqrt_s: f64,
    /// Standard deviation of a zero-velocity measurement (m/s): vibration of the vehicle
    /// at rest.
    pub zupt_sigma_mps: f64,
    /// Initial standard deviation of each tilt error (rad).
    pub level_sigma_rad: f64,
    /// Initial standard deviation of the heading error (rad).
    pub heading_sigma_rad: f64,
    /// Increments between two zero-velocity updates (at least 1).
    pub update_every: usize,
}

impl Default for FineAlignmentConfig {
    /// A navigation-grade IMU (0.002 deg/sqrt(h), 0.003 m/s/sqrt(h)) after a coarse
    /// alignment good to 1 mrad of level and 1 deg of heading, a zero-velocity update
    /// every 10 increments (10 Hz at 100 Hz) with 1 mm/s of vibration. Gyrocompassing
    /// needs such gyros: the angle random walk alone leaves a heading error of about
    /// `ARW / (w_ie cos L sqrt(T))`, 0.03 deg after 300 s at 30 deg latitude (a
    /// tactical-grade 0.1 deg/sqrt(h) gyro would leave 1.5 deg).
    fn default() -> Self {
        Self {
            gyro_arw_rad_per_sqrt_s: 0.002_f64.to_radians() / 60.0,
            accel_vrw_mps_per_sqrt_s: 0.003 / 60.0,
            zupt_sigma_mps: 1e-3,
            level_sigma_rad: 1e-3,
            heading_sigma_rad: 1.0_f64.to_radians(),
            update_every: 10,
        }
    }
}

impl FineAlignmentConfig {
    /// Every noise setting positive and finite, `update_every` at least 1.
    fn check(&self) -> Result<(), InsError> {
        let settings = [
            ("gyro_arw_rad_per_sqrt_s", self.gyro_arw_rad_per_sqrt_s),
            ("accel_vrw_mps_per_sqrt_s", self.accel_vrw_mps_per_sqrt_s),
            ("zupt_sigma_mps", self.zupt_sigma_mps),
            ("level_sigma_rad", self.level_sigma_rad),
            ("heading_sigma_rad", self.heading_sigma_rad),
            ("update_every", self.update_every as f64),
        ];
        for (name, value) in settings {
            if !(value.is_finite() && value > 0.0) {
                return Err(InsError::BadSetting { name, value });
            }
        }
        Ok(())
    }
}

/// The aligned state and the filter's diagnostics of its heading.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FineAlignment {
    /// The state at the end of the static period, corrected by the last update.
    pub state: InsState,
    /// The filter's standard deviation of the heading error at the end (rad). It does not
    /// include the heading error of an east gyro bias, which a static period cannot see.
    pub heading_sigma_rad: f64,
    /// The larger of the filter's two tilt standard deviations at the end (rad).
    pub level_sigma_rad: f64,
    /// Final heading minus initial heading (rad, in (-pi, pi]): the correction the fine
    /// alignment made to the coarse heading.
    pub heading_correction_rad: f64,
    /// Root-mean-square of the zero-velocity innovations (m/s).
    pub innovation_rms_mps: f64,
    /// Number of zero-velocity updates.
    pub updates: usize,
}

/// Fine alignment over `increments`, a static period that begins at `initial.t`, from the
/// coarse attitude and surveyed position of `initial`.
pub fn fine_alignment(
    initial: &InsState,
    increments: &[ImuIncrement],
    cfg: &FineAlignmentConfig,
) -> Result<FineAlignment, InsError> {
    cfg.check()?;
    if increments.is_empty() {
        return Err(InsError::Empty);
    }
    let position = initial.geodetic();
    let mut filter = ZuptFilter::new(cfg, &position);
    let mut state = *initial;
    let (mut prev, mut since_s, mut sum_sq) = (None, 0.0, 0.0);
    for (k, inc) in increments.iter().enumerate() {
        state.propagate(prev, inc)?;
        prev = Some(inc);
        since_s += inc.dt_s;
        if (k + 1) % cfg.update_every == 0 {
            filter.predict(since_s);
            since_s = 0.0;
            let z = filter.c_ecef_ned * state.v_ecef_mps;
            sum_sq += z.norm_squared();
            let dx = filter.update(&z)?;
            filter.correct(&mut state, &dx, &initial.r_ecef_m);
        }
    }
    Ok(filter.diagnostics(initial, state, sum_sq))
}

/// The six-state error filter: covariance, noise and the fixed local frame.
#[derive(Debug)]
struct ZuptFilter {
    p: Matrix6<f64>,
    q_psi: f64,
    q_v: f64,
    r: f64,
    f_ned: Vec3,
    w_ned: Vec3,
    c_ecef_ned: Mat3,
    updates: usize,
}

impl ZuptFilter {
    fn new(cfg: &FineAlignmentConfig, position: &Geodetic) -> Self {
        let c_ecef_ned = c_ecef_ned(position.lat_rad, position.lon_rad);
        let (l, h) = (cfg.level_sigma_rad.powi(2), cfg.heading_sigma_rad.powi(2));
        let zupt_var = cfg.zupt_sigma_mps.powi(2);
        let p0 = Vector6::new(l, l, h, zupt_var, zupt_var, zupt_var);
        Self {
            p: Matrix6::from_diagonal(&p0),
            q_psi: cfg.gyro_arw_rad_per_sqrt_s.powi(2),
            q_v: cfg.accel_vrw_mps_per_sqrt_s.powi(2),
            r: zupt_var,
            f_ned: -normal_gravity_ned(position),
            w_ned: c_ecef_ned * earth_rate_ecef(),
            c_ecef_ned,
            updates: 0,
        }
    }

    /// `P <- Phi P Phi^T + Q` over `tau` seconds, `Phi = I + F tau + (F tau)^2 / 2`.
    fn predict(&mut self, tau: f64) {
        let mut f = Matrix6::zeros();
        let w = self.w_ned.cross_matrix();
        f.fixed_view_mut::<3, 3>(0, 0).copy_from(&-w);
        f.fixed_view_mut::<3, 3>(3, 0)
            .copy_from(&-self.f_ned.cross_matrix());
        f.fixed_view_mut::<3, 3>(3, 3).copy_from(&(w * -2.0));
        let ft = f * tau;
        let phi = Matrix6::identity() + ft + ft * ft * 0.5;
        let q = Vector6::new(
            self.q_psi, self.q_psi, self.q_psi, self.q_v, self.q_v, self.q_v,
        );
        self.p = phi * self.p * phi.transpose() + Matrix6::from_diagonal(&(q * tau));
    }

    /// The zero-velocity update with measurement `z` (the computed NED velocity); returns
    /// the error estimate (the prior estimate is zero: the filter runs closed loop). The
    /// covariance by Joseph's form.
    fn update(&mut self, z: &Vec3) -> Result<Vector6<f64>, InsError> {
        let s = self.p.fixed_view::<3, 3>(3, 3) + Matrix3::identity() * self.r;
        let s_inv = s.try_inverse().ok_or(InsError::Degenerate(
            "zero-velocity innovation covariance singular",
        ))?;
        let k: Matrix6x3<f64> = self.p.fixed_view::<6, 3>(0, 3) * s_inv;
        let mut kh = Matrix6::zeros();
        kh.fixed_view_mut::<6, 3>(0, 3).copy_from(&k);
        let i_kh = Matrix6::identity() - kh;
        self.p = i_kh * self.p * i_kh.transpose() + k * k.transpose() * self.r;
        self.updates += 1;
        Ok(k * z)
    }

    /// Removes the estimated errors from `state` (`C_true = (I + [psi x])^-1 C`) and
    /// restores the surveyed position.
    fn correct(&self, state: &mut InsState, dx: &Vector6<f64>, r_survey: &Vec3) {
        let c_ned_ecef = self.c_ecef_ned.transpose();
        let psi_ecef = c_ned_ecef * Vec3::new(dx[0], dx[1], dx[2]);
        let dv_ecef = c_ned_ecef * Vec3::new(dx[3], dx[4], dx[5]);
        state.c_body_ecef = orthonormalise(&(rodrigues(&-psi_ecef) * state.c_body_ecef));
        state.v_ecef_mps -= dv_ecef;
        state.r_ecef_m = *r_survey;
    }

    fn diagnostics(&self, initial: &InsState, state: InsState, sum_sq: f64) -> FineAlignment {
        let position = initial.geodetic();
        let heading0 = attitude_ned(&initial.c_body_ecef, &position).yaw_rad;
        let heading1 = attitude_ned(&state.c_body_ecef, &position).yaw_rad;
        let rms = if self.updates == 0 {
            0.0
        } else {
            (sum_sq / self.updates as f64).sqrt()
        };
        FineAlignment {
            state,
            heading_sigma_rad: self.p[(2, 2)].sqrt(),
            level_sigma_rad: self.p[(0, 0)].max(self.p[(1, 1)]).sqrt(),
            heading_correction_rad: wrap_pi(heading1 - heading0),
            innovation_rms_mps: rms,
            updates: self.updates,
        }
    }
}

/// `x` wrapped into (-pi, pi].
pub(crate) fn wrap_pi(x: f64) -> f64 {
    let w = (x + PI).rem_euclid(TAU) - PI;
    if w <= -PI { w + TAU } else { w }
}
