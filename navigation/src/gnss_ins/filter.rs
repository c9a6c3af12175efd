//! The GNSS/INS error-state filter: the INS propagated over bias-corrected increments,
//! its error covariance with it, updates, and the estimated errors fed back after each
//! (closed loop, Groves 2013 sec. 14.1.1). One filter for both couplings: the loosely
//! coupled one has the 15 INS error states and takes fixes; the tightly coupled one adds
//! the receiver's states (`super::receiver_states`) and takes ranges.

use super::config::{IntegrationError, LooselyCoupledConfig};
use super::error_state::{ACC, ATT, GYR, POS, STATES, VEL, skew, transition};
use super::fix::GnssFix;
use super::receiver_states::ReceiverStates;
use crate::ins::InsState;
use crate::tdcp::ImuPose;
use hifitime::Epoch;
use nalgebra::{DMatrix, DVector, SMatrix, SVector};
use skyforge_gnss::imu::ImuIncrement;
use skyforge_orbits::gravity::{GravityModel, earth_rate_ecef};
use skyforge_orbits::{Mat3, Vec3};

/// What one update did.
#[derive(Debug, Clone, PartialEq)]
pub struct Update {
    /// Innovations (predicted minus measured): position (m), then velocity (m/s) when
    /// the fix had one.
    pub innovation: DVector<f64>,
    /// Normalised innovation squared `z^T S^-1 z`.
    pub nis: f64,
    /// Its degrees of freedom (3, or 6 with velocity).
    pub dof: usize,
}

/// Measurement rows for the error state: `y = H x + v`, `v ~ N(0, R)`, `y` predicted
/// minus measured.
pub(crate) struct Rows {
    pub h: DMatrix<f64>,
    pub y: DVector<f64>,
    pub r: DMatrix<f64>,
}

/// The error-state filter over `N` states: the INS's 15 first, the receiver's after them
/// (none for [`LooselyCoupled`]).
#[derive(Debug, Clone)]
pub struct InsFilter<const N: usize> {
    config: LooselyCoupledConfig,
    ins: InsState,
    p: SMatrix<f64, N, N>,
    /// The receiver's clock (and barometer) states and estimates, tightly coupled only.
    pub(crate) receiver: Option<ReceiverStates>,
    gyro_bias: Vec3,
    accel_bias: Vec3,
    /// The previous bias-corrected increment (coning and sculling).
    prev: Option<ImuIncrement>,
    /// The last interval's mean angular rate relative to inertial space (rad/s).
    omega_ib_body: Vec3,
    /// The gravity the INS subtracts (normal gravity unless [`Self::in_gravity`]).
    gravity: GravityModel,
}

/// The loosely coupled filter (Groves 2013 sec. 14.3.1): the 15 INS error states.
pub type LooselyCoupled = InsFilter<STATES>;

impl LooselyCoupled {
    /// A filter starting at `initial` with zero bias estimates and the configured
    /// initial uncertainties (heading about the local vertical, tilt about the
    /// horizontal axes).
    pub fn new(initial: InsState, config: LooselyCoupledConfig) -> Result<Self, IntegrationError> {
        Self::with_receiver(initial, config, None)
    }
}

impl<const N: usize> InsFilter<N> {
    /// The filter with the INS's initial covariance; `receiver`'s states (when any) after
    /// the INS's, their covariance set by the caller.
    pub(crate) fn with_receiver(
        initial: InsState,
        config: LooselyCoupledConfig,
        receiver: Option<ReceiverStates>,
    ) -> Result<Self, IntegrationError> {
        config.check()?;
        let up = initial.r_ecef_m.normalize();
        let tilt = config.initial_tilt_rad.powi(2) * (Mat3::identity() - up * up.transpose());
        let heading = config.initial_heading_rad.powi(2) * up * up.transpose();
        let mut p = SMatrix::<f64, N, N>::zeros();
        let diagonal = [
            (POS, config.initial_position_m.powi(2)),
            (VEL, config.initial_velocity_mps.powi(2)),
            (ACC, config.imu.accel_bias.powi(2)),
            (GYR, config.imu.gyro_bias.powi(2)),
        ];
        for (start, variance) in diagonal {
            for k in start..start + 3 {
                p[(k, k)] = variance;
            }
        }
        p.fixed_view_mut::<3, 3>(ATT, ATT)
            .copy_from(&(tilt + heading));
        if let Some(r) = &receiver {
            r.initial_covariance(&mut p);
        }
        Ok(Self {
            config,
            ins: initial,
            p,
            receiver,
            gyro_bias: Vec3::zeros(),
            accel_bias: Vec3::zeros(),
            prev: None,
            omega_ib_body: Vec3::zeros(),
            gravity: GravityModel::Normal,
        })
    }

    /// The INS's state (the IMU's position, velocity, attitude).
    pub fn state(&self) -> &InsState {
        &self.ins
    }

    /// The error covariance, in the order position, velocity, attitude, accelerometer
    /// bias, gyro bias (ECEF; biases in body axes), then the receiver's states.
    pub fn covariance(&self) -> SMatrix<f64, N, N> {
        self.p
    }

    /// The bias estimates: gyro (rad/s), accelerometer (m/s^2), body axes.
    pub fn biases(&self) -> (Vec3, Vec3) {
        (self.gyro_bias, self.accel_bias)
    }

    /// The antenna's position (ECEF, m).
    pub fn antenna_position(&self) -> Vec3 {
        self.ins.r_ecef_m + self.ins.c_body_ecef * self.config.lever_arm_body_m
    }

    /// The filter with its INS subtracting `gravity` (the orbit's zonal field in orbit).
    /// The error dynamics keep the point mass's gravity gradient (error_state.rs), which
    /// the zonal terms change by about a thousandth.
    pub fn in_gravity(mut self, gravity: GravityModel) -> Self {
        self.gravity = gravity;
        self
    }

    /// Moves the INS and its covariance over `inc` (its biases removed).
    pub fn propagate(&mut self, inc: &ImuIncrement) -> Result<(), IntegrationError> {
        let dt = inc.dt_s;
        let corrected = ImuIncrement {
            dtheta_rad: inc.dtheta_rad - self.gyro_bias * dt,
            dv_mps: inc.dv_mps - self.accel_bias * dt,
            ..*inc
        };
        let before = self.ins;
        (self.ins).propagate_in(self.gravity, self.prev.as_ref(), &corrected)?;
        let f_body = corrected.dv_mps / dt;
        let (phi15, q15) = transition(
            &before.r_ecef_m,
            &before.c_body_ecef,
            &f_body,
            &self.config.imu,
            dt,
        );
        let mut phi = SMatrix::<f64, N, N>::identity();
        phi.fixed_view_mut::<STATES, STATES>(0, 0).copy_from(&phi15);
        let mut q = SVector::<f64, N>::zeros();
        q.fixed_rows_mut::<STATES>(0).copy_from(&q15);
        if let Some(r) = &mut self.receiver {
            r.propagate(&mut phi, &mut q, dt, self.ins.v_ecef_mps.norm());
        }
        self.p = phi * self.p * phi.transpose() + SMatrix::<f64, N, N>::from_diagonal(&q);
        self.p = (self.p + self.p.transpose()) * 0.5;
        self.omega_ib_body = corrected.dtheta_rad / dt;
        self.prev = Some(corrected);
        Ok(())
    }

    /// Corrects the INS with `fix` (Groves eqs. 14.110-14.111 with the lever arm), which
    /// must lie within one IMU interval of the INS's time; the INS is extrapolated to it.
    pub fn update(&mut self, fix: &GnssFix) -> Result<Update, IntegrationError> {
        check_fix(fix)?;
        let offset_s = self.offset_s(fix.t)?;
        let (h, z, r) = self.measurement(fix, offset_s);
        self.apply(Rows { h, y: z, r }, fix.t)
    }

    /// The Kalman update on `rows` (Joseph form), then the closed-loop correction;
    /// `t` names the measurement in errors.
    pub(crate) fn apply(&mut self, rows: Rows, t: Epoch) -> Result<Update, IntegrationError> {
        let Rows { h, y, r } = rows;
        let p = DMatrix::from_fn(N, N, |i, j| self.p[(i, j)]);
        let s = &h * &p * h.transpose() + &r;
        let s_inv = s
            .cholesky()
            .ok_or(IntegrationError::BadFix {
                t,
                what: "innovation covariance not positive definite",
            })?
            .inverse();
        let k = &p * h.transpose() * &s_inv;
        let i_kh = DMatrix::identity(N, N) - &k * &h;
        let p_new = &i_kh * p * i_kh.transpose() + &k * r * k.transpose();
        let x = &k * &y;
        self.p = SMatrix::from_fn(|i, j| 0.5 * (p_new[(i, j)] + p_new[(j, i)]));
        self.feed_back(&SVector::<f64, N>::from_iterator(x.iter().copied()));
        Ok(Update {
            nis: (y.transpose() * &s_inv * &y)[(0, 0)],
            dof: y.len(),
            innovation: y,
        })
    }

    /// The IMU's pose now.
    pub fn pose(&self) -> ImuPose {
        ImuPose {
            r_ecef_m: self.ins.r_ecef_m,
            c_body_ecef: self.ins.c_body_ecef,
        }
    }

    /// The lever arm from the IMU to the antenna (body, m).
    pub fn lever_arm(&self) -> Vec3 {
        self.config.lever_arm_body_m
    }

    /// How far `t` lies after the INS's time (s), when within one IMU interval of it.
    pub(crate) fn offset_s(&self, t: Epoch) -> Result<f64, IntegrationError> {
        let offset_s = (t - self.ins.t).to_seconds();
        let step_s = self.prev.map_or(0.0, |p| p.dt_s);
        if offset_s.abs() > step_s + 1e-6 {
            return Err(IntegrationError::FixOutOfStep {
                t,
                ins_t: self.ins.t,
                offset_s,
            });
        }
        Ok(offset_s)
    }

    /// The measurement matrix, innovations and noise covariance of `fix`, `offset_s`
    /// after the INS's time.
    fn measurement(
        &self,
        fix: &GnssFix,
        offset_s: f64,
    ) -> (DMatrix<f64>, DVector<f64>, DMatrix<f64>) {
        let c = self.ins.c_body_ecef;
        let lever = self.config.lever_arm_body_m;
        let c_l = c * lever;
        let rows = if fix.v_ecef_mps.is_some() { 6 } else { 3 };
        let mut h = DMatrix::zeros(rows, N);
        let mut z = DVector::zeros(rows);
        let mut r = DMatrix::zeros(rows, rows);
        let predicted = self.ins.r_ecef_m + self.ins.v_ecef_mps * offset_s + c_l;
        h.view_mut((0, POS), (3, 3)).copy_from(&Mat3::identity());
        h.view_mut((0, ATT), (3, 3)).copy_from(&-skew(&c_l));
        z.rows_mut(0, 3).copy_from(&(predicted - fix.r_ecef_m));
        r.view_mut((0, 0), (3, 3)).copy_from(&fix.r_cov_m2);
        if let Some((v, v_cov)) = fix.v_ecef_mps {
            let (hv, zv) = self.velocity_rows(&v);
            h.rows_mut(3, 3).copy_from(&hv);
            z.rows_mut(3, 3).copy_from(&zv);
            r.view_mut((3, 3), (3, 3)).copy_from(&v_cov);
        }
        (h, z, r)
    }

    /// The rows of the antenna's velocity `v` (Groves eq. 14.111): `H` on the velocity,
    /// attitude and gyro-bias errors, and the innovation (predicted minus measured).
    fn velocity_rows(&self, v: &Vec3) -> (DMatrix<f64>, DVector<f64>) {
        let c = self.ins.c_body_ecef;
        let lever = self.config.lever_arm_body_m;
        let rotating = c * self.omega_ib_body.cross(&lever) - earth_rate_ecef().cross(&(c * lever));
        let mut h = DMatrix::zeros(3, N);
        h.view_mut((0, VEL), (3, 3)).copy_from(&Mat3::identity());
        h.view_mut((0, ATT), (3, 3)).copy_from(&-skew(&rotating));
        h.view_mut((0, GYR), (3, 3)).copy_from(&(-c * skew(&lever)));
        let z = DVector::from_column_slice((self.ins.v_ecef_mps + rotating - v).as_slice());
        (h, z)
    }

    /// Corrects the INS with the antenna's velocity alone (`v_cov` its covariance), valid
    /// at `t` within one IMU interval of the INS's time: a velocity-only aiding, as the
    /// book's velocity sub-filter (3.2.1).
    pub fn update_velocity(
        &mut self,
        t: Epoch,
        v: &Vec3,
        v_cov: &Mat3,
    ) -> Result<Update, IntegrationError> {
        self.offset_s(t)?;
        check_vector(t, v, v_cov, VELOCITY_CHECKS)?;
        let (h, y) = self.velocity_rows(v);
        let r = DMatrix::from_fn(3, 3, |i, j| v_cov[(i, j)]);
        self.apply(Rows { h, y, r }, t)
    }

    /// Closed-loop correction: the estimated errors removed from the INS and added to
    /// the bias estimates (Groves 2013 sec. 14.2.3: `C = (I - [psi x]) C^`, taken as the
    /// exact rotation by `-psi`).
    fn feed_back(&mut self, x: &SVector<f64, N>) {
        let block = |k: usize| Vec3::new(x[k], x[k + 1], x[k + 2]);
        self.ins.r_ecef_m -= block(POS);
        self.ins.v_ecef_mps -= block(VEL);
        let undo = nalgebra::Rotation3::new(-block(ATT));
        self.ins.c_body_ecef = undo.matrix() * self.ins.c_body_ecef;
        self.accel_bias += block(ACC);
        self.gyro_bias += block(GYR);
        if let Some(r) = &mut self.receiver {
            r.feed_back(x.as_slice());
        }
    }

    /// The last IMU interval's mean angular rate relative to inertial space (rad/s).
    pub(crate) fn omega_ib_body(&self) -> Vec3 {
        self.omega_ib_body
    }
}

/// A fix with finite values and symmetric covariances with positive diagonals.
fn check_fix(fix: &GnssFix) -> Result<(), IntegrationError> {
    check_vector(
        fix.t,
        &fix.r_ecef_m,
        &fix.r_cov_m2,
        [
            "position not finite",
            "position covariance not finite, symmetric, with positive variances",
        ],
    )?;
    if let Some((v, cov)) = &fix.v_ecef_mps {
        check_vector(fix.t, v, cov, VELOCITY_CHECKS)?;
    }
    Ok(())
}

/// What a bad velocity is called.
const VELOCITY_CHECKS: [&str; 2] = [
    "velocity not finite",
    "velocity covariance not finite, symmetric, with positive variances",
];

/// A measured vector with finite values and a symmetric covariance with positive
/// diagonals; `what` names the two failures.
fn check_vector(
    t: Epoch,
    x: &Vec3,
    cov: &Mat3,
    what: [&'static str; 2],
) -> Result<(), IntegrationError> {
    let bad = |what| Err(IntegrationError::BadFix { t, what });
    if !x.iter().all(|x| x.is_finite()) {
        return bad(what[0]);
    }
    let usable = cov.iter().all(|x| x.is_finite())
        && (0..3).all(|k| cov[(k, k)] > 0.0)
        && (cov - cov.transpose()).amax() <= 1e-9 * cov.amax();
    if !usable {
        return bad(what[1]);
    }
    Ok(())
}
