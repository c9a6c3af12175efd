//! The relative dynamics of the book's relative filters (section 5.6.4): the chaser's
//! position and rate relative to the target in the target's orbit frame, propagated by
//! the Hill / Clohessy-Wiltshire equations (eq. 5-34 with the target's orbit as the
//! reference, eq. 5-53) with the difference of the two vehicles' perturbing accelerations
//! as the input `U`. Shared by [`super::HillFilter`] (eqs. 5-57/5-58) and the
//! single-difference filter (eq. 5-59).
//!
//! The book gives `U` as the difference of the J2 accelerations in a linearised form
//! (`Jeff (X_c - X_t) / R`) and of drag (`-k rho V dV`). Here `U` is everything the Hill
//! equations leave out, evaluated exactly: the force model's acceleration difference at
//! the two vehicles (which holds the book's J2 and drag terms and the point mass's
//! gradient beyond the linear one: at 32 km that curvature is 5e-4 m/s^2, a metre a
//! minute) and the frame's true rotation on an eccentric orbit, less the Hill terms;
//! held over a step at the mean of its values at the two ends (as the position
//! filter's, `orbit_determination::position_filter`). The Hill equations then carry the
//! covariance.
//!
//! The state is the convention of `orbits::frames::relative_in_frame_of`: position and
//! its rate in a frame turning about the orbit normal alone.

use crate::orbit_determination::{input, transition};
use nalgebra::{Matrix3, Matrix6, Matrix6x3, Vector3, Vector6};
use skyforge_orbits::Vec3;
use skyforge_orbits::frames::c_orbital_eci;
use skyforge_orbits::propagate::{ForceModel, ForceModelConfig};

/// The target's absolute state (ECI) at an epoch: the reference orbit of the frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TargetState {
    pub t_s: f64,
    pub r_eci_m: Vec3,
    pub v_eci_mps: Vec3,
}

/// Eq. 5-34 about the target's orbit with the exact `U` (module docs).
#[derive(Debug, Clone)]
pub(crate) struct HillDynamics {
    forces: ForceModel,
}

/// One step of [`HillDynamics`]: the state carried and what carries its covariance.
#[derive(Debug, Clone)]
pub(crate) struct HillStep {
    /// The relative state at the step's end (the convention's, module docs).
    pub state: Vector6<f64>,
    phi: Matrix6<f64>,
    gamma: Matrix6x3<f64>,
    /// The convention's state to the frame's own at the start.
    in0: Matrix6<f64>,
    /// The frame's own state to the convention's at the end.
    out1: Matrix6<f64>,
}

impl HillStep {
    /// The covariance `p` of the start carried to the end, with white relative
    /// acceleration of `acceleration_sigma_mps2` per axis (`Q`).
    pub(crate) fn covariance(
        &self,
        p: &Matrix6<f64>,
        acceleration_sigma_mps2: f64,
    ) -> Matrix6<f64> {
        let (phi, gamma) = (self.phi, self.gamma);
        let q = Matrix3::identity() * acceleration_sigma_mps2.powi(2);
        let p_own = phi * self.in0 * p * self.in0.transpose() * phi.transpose()
            + gamma * q * gamma.transpose();
        self.out1 * p_own * self.out1.transpose()
    }

    /// The step's linear map of the relative state (the cross-covariances of other
    /// states).
    pub(crate) fn transition(&self) -> Matrix6<f64> {
        self.out1 * self.phi * self.in0
    }
}

impl HillDynamics {
    /// The dynamics with the perturbations `forces` (whose difference is `U`) for a run
    /// starting at `start` (the force model's date).
    pub(crate) fn new(forces: &ForceModelConfig, start: hifitime::Epoch) -> Self {
        Self {
            forces: ForceModel::new(forces, start, 0.0),
        }
    }

    /// The target frame's angular velocity in its own axes: `w = |r x v| / r^2` about
    /// the orbit normal (`-y`) and, where the target's acceleration has a part `a_n`
    /// along the normal (J2 turns the orbit plane), `a_n r / |r x v|` about the radial
    /// axis (`-z`): what turns `r x v`.
    fn frame_rate(&self, t_s: f64, r: &Vec3, v: &Vec3) -> Vec3 {
        let h = r.cross(v);
        let a_n = self.forces.acceleration_eci(t_s, r, v).dot(&h) / h.norm();
        Vec3::new(
            0.0,
            -h.norm() / r.norm_squared(),
            -a_n * r.norm() / h.norm(),
        )
    }

    /// The part of the frame's rate the relative velocity's convention leaves out
    /// (`orbits::frames::relative_in_frame_of` turns the frame about the normal alone).
    fn rate_beyond_convention(&self, target: &TargetState) -> Vec3 {
        let w = self.frame_rate(target.t_s, &target.r_eci_m, &target.v_eci_mps);
        Vec3::new(w.x, 0.0, w.z)
    }

    /// `U`: what the Hill equations leave out of the chaser's acceleration relative to
    /// the target, in the target's orbit frame, for a relative state `rel` (position and
    /// its time derivative in the frame) about `target`: the force model's exact
    /// acceleration difference (the perturbations' difference of the book's `U`, and the
    /// point mass's beyond its linear gradient) with the frame's true rotation
    /// ([`Self::frame_rate`] and its change, by central differences over a second), less
    /// the Hill equations' own terms at the step's rate `n`.
    fn input_acceleration(&self, target: &TargetState, rel: &Vector6<f64>, n: f64) -> Vector3<f64> {
        let (r, v, t) = (target.r_eci_m, target.v_eci_mps, target.t_s);
        let c = c_orbital_eci(&r, &v);
        let omega = self.frame_rate(t, &r, &v);
        let a = self.forces.acceleration_eci(t, &r, &v);
        let omega_at = |d: f64| self.frame_rate(t + d, &(r + v * d), &(v + a * d));
        let omega_dot = (omega_at(1.0) - omega_at(-1.0)) / 2.0;
        let rho = Vec3::new(rel[0], rel[1], rel[2]);
        let rho_dot = Vec3::new(rel[3], rel[4], rel[5]);
        let rho_eci = c * rho;
        let rho_dot_eci = c * (rho_dot + omega.cross(&rho));
        let da = c.transpose()
            * (self
                .forces
                .acceleration_eci(t, &(r + rho_eci), &(v + rho_dot_eci))
                - a);
        let relative = da
            - omega.cross(&rho_dot) * 2.0
            - omega.cross(&omega.cross(&rho))
            - omega_dot.cross(&rho);
        let hill = Vec3::new(
            2.0 * n * rho_dot.z,
            -n * n * rho.y,
            3.0 * n * n * rho.z - 2.0 * n * rho_dot.x,
        );
        relative - hill
    }

    /// The Jacobian from the convention's state (position, rate as
    /// `relative_in_frame_of` gives it) to the frame's own (position, time derivative):
    /// `rho' = rate - w_extra x rho` ([`Self::rate_beyond_convention`]).
    fn to_own(&self, target: &TargetState) -> Matrix6<f64> {
        let w = self.rate_beyond_convention(target);
        let mut j = Matrix6::identity();
        j.fixed_view_mut::<3, 3>(3, 0).copy_from(
            &-crate::orbit_determination::position_filter::cross_matrix(&w),
        );
        j
    }

    /// The relative state `x` at `from` carried `dt_s` to `target`'s epoch (eq. 5-34
    /// about the target's orbit; `U` at the mean of its two ends).
    pub(crate) fn step(
        &self,
        from: &TargetState,
        x: &Vector6<f64>,
        target: &TargetState,
        dt_s: f64,
    ) -> HillStep {
        let n = from.r_eci_m.cross(&from.v_eci_mps).norm() / from.r_eci_m.norm_squared();
        let (phi, gamma) = (transition(n, dt_s), input(n, dt_s));
        let (in0, in1) = (self.to_own(from), self.to_own(target));
        let out1 = in1.try_inverse().unwrap_or_else(Matrix6::identity);
        let x0 = in0 * x;
        let u0 = self.input_acceleration(from, &x0, n);
        let first = phi * x0 + gamma * u0;
        let u1 = self.input_acceleration(target, &first, n);
        let state = out1 * (phi * x0 + gamma * ((u0 + u1) * 0.5));
        HillStep {
            state,
            phi,
            gamma,
            in0,
            out1,
        }
    }
}
