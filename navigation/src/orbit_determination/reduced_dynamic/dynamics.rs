//! The reduced-dynamic filter's orbit model: the deterministic force model plus three
//! empirical accelerations (radial, along-track, cross-track) that follow first-order
//! Gauss-Markov processes (Montenbruck and Gill, *Satellite Orbits*, 2000, section 8.2.2,
//! eq. 8.46; Wu, Yunck and Thornton 1991 name the method). Position and velocity are
//! integrated with the classical fourth-order Runge-Kutta method in steps of at most
//! [`MAX_STEP_S`]; the transition matrix of `[r, v, a]` is the series of the linearised
//! dynamics over each step, and the process noise the integral of the accelerations'
//! driving noise through it.

use nalgebra::{SMatrix, SVector};
use skyforge_orbits::Vec3;
use skyforge_orbits::frames::c_rac_eci;
use skyforge_orbits::propagate::ForceModel;

/// The orbit part of the state: `[r, v, a]` (ECI position, inertial velocity, empirical
/// acceleration in the radial, along-track, cross-track axes of the current orbit).
pub(crate) type Orbit9 = SVector<f64, 9>;
/// A 9 x 9 block (transition matrix, covariance, process noise) of the orbit part.
pub(crate) type Block9 = SMatrix<f64, 9, 9>;

/// Longest integration step (s): at 10 s the Runge-Kutta error of a LEO orbit is under
/// a millimetre and the truncated series of the transition matrix exact to 1e-9.
pub(crate) const MAX_STEP_S: f64 = 10.0;
/// The finite-difference step of the gravity gradient (m).
const GRADIENT_STEP_M: f64 = 10.0;

/// The force model with the empirical accelerations' process.
#[derive(Debug, Clone)]
pub(crate) struct OrbitModel {
    pub forces: ForceModel,
    /// Correlation time of the empirical accelerations (s).
    pub tau_s: f64,
    /// Their steady-state 1-sigma (m/s^2).
    pub sigma_mps2: f64,
}

/// `r`, `v` and `a` of an orbit state.
fn parts(x: &Orbit9) -> (Vec3, Vec3, Vec3) {
    (
        x.fixed_rows::<3>(0).into(),
        x.fixed_rows::<3>(3).into(),
        x.fixed_rows::<3>(6).into(),
    )
}

fn join(r: &Vec3, v: &Vec3, a: &Vec3) -> Orbit9 {
    Orbit9::from_iterator(r.iter().chain(v.iter()).chain(a.iter()).copied())
}

impl OrbitModel {
    /// The acceleration at `t_s` for position `r`, velocity `v` and empirical
    /// acceleration `a_rac` (radial, along, cross), ECI.
    fn acceleration(&self, t_s: f64, r: &Vec3, v: &Vec3, a_rac: &Vec3) -> Vec3 {
        self.forces.acceleration_eci(t_s, r, v) + c_rac_eci(r, v) * a_rac
    }

    /// The Jacobian of the dynamics `d[r, v, a]/dt` at a state: the gravity gradient by
    /// central differences, the empirical accelerations' rotation into ECI and their
    /// decay; drag's dependence on the state (1e-8 m/s^2 over a metre) is left out.
    fn jacobian(&self, r: &Vec3, v: &Vec3) -> Block9 {
        let mut f = Block9::zeros();
        f.fixed_view_mut::<3, 3>(0, 3)
            .copy_from(&nalgebra::Matrix3::identity());
        for k in 0..3 {
            let mut d = Vec3::zeros();
            d[k] = GRADIENT_STEP_M;
            let g = (self.forces.gravity_eci(&(r + d)) - self.forces.gravity_eci(&(r - d)))
                / (2.0 * GRADIENT_STEP_M);
            f.fixed_view_mut::<3, 1>(3, k).copy_from(&g);
        }
        f.fixed_view_mut::<3, 3>(3, 6).copy_from(&c_rac_eci(r, v));
        for k in 6..9 {
            f[(k, k)] = -1.0 / self.tau_s;
        }
        f
    }

    /// One Runge-Kutta step of `h` seconds from `t_s`; the empirical acceleration decays
    /// exponentially over it.
    fn rk4(&self, t_s: f64, x: &Orbit9, h: f64) -> Orbit9 {
        let (r, v, a0) = parts(x);
        let a_at = |dt: f64| a0 * (-dt / self.tau_s).exp();
        let deriv =
            |dt: f64, r: &Vec3, v: &Vec3| (*v, self.acceleration(t_s + dt, r, v, &a_at(dt)));
        let (k1r, k1v) = deriv(0.0, &r, &v);
        let (k2r, k2v) = deriv(h / 2.0, &(r + k1r * (h / 2.0)), &(v + k1v * (h / 2.0)));
        let (k3r, k3v) = deriv(h / 2.0, &(r + k2r * (h / 2.0)), &(v + k2v * (h / 2.0)));
        let (k4r, k4v) = deriv(h, &(r + k3r * h), &(v + k3v * h));
        let r1 = r + (k1r + k2r * 2.0 + k3r * 2.0 + k4r) * (h / 6.0);
        let v1 = v + (k1v + k2v * 2.0 + k3v * 2.0 + k4v) * (h / 6.0);
        join(&r1, &v1, &a_at(h))
    }

    /// The state `dt_s` after `t_s`, its transition matrix and the process noise gathered
    /// on the way (the empirical accelerations' driving noise, spectral density
    /// `2 sigma^2 / tau`, integrated through the transition by the trapezoid rule).
    pub fn propagate(&self, t_s: f64, x: &Orbit9, dt_s: f64) -> (Orbit9, Block9, Block9) {
        let steps = (dt_s.abs() / MAX_STEP_S).ceil().max(1.0);
        let h = dt_s / steps;
        let mut phi = Block9::identity();
        let mut q = Block9::zeros();
        let mut g_q_g = Block9::zeros();
        let qc = 2.0 * self.sigma_mps2.powi(2) / self.tau_s;
        for k in 6..9 {
            g_q_g[(k, k)] = qc;
        }
        let mut x = *x;
        let mut t = t_s;
        for _ in 0..steps as usize {
            let next = self.rk4(t, &x, h);
            // The Jacobian at the step's midpoint: second order in the step.
            let ((r0, v0, _), (r1, v1, _)) = (parts(&x), parts(&next));
            let fh = self.jacobian(&((r0 + r1) / 2.0), &((v0 + v1) / 2.0)) * h;
            // exp(F h) to fourth order: |F h| is about n h (1e-2 at 10 s).
            let fh2 = fh * fh;
            let step_phi = Block9::identity() + fh + fh2 / 2.0 + fh2 * fh / 6.0 + fh2 * fh2 / 24.0;
            let q_step = (step_phi * g_q_g * step_phi.transpose() + g_q_g) * (h.abs() / 2.0);
            q = step_phi * q * step_phi.transpose() + q_step;
            phi = step_phi * phi;
            x = next;
            t += h;
        }
        (x, phi, q)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use skyforge_orbits::propagate::ForceModelConfig;

    fn model() -> OrbitModel {
        let cfg = ForceModelConfig {
            higher_zonals: true,
            ..ForceModelConfig::default()
        };
        OrbitModel {
            forces: ForceModel::new(&cfg, hifitime::Epoch::from_gpst_seconds(1.0e9), 0.0),
            tau_s: 600.0,
            sigma_mps2: 1e-7,
        }
    }

    /// A LEO at 893 km, inclined.
    fn leo() -> Orbit9 {
        let r = Vec3::new(7.271e6, 0.0, 0.0);
        let v = Vec3::new(0.0, 7404.0 * 0.6, 7404.0 * 0.8);
        join(&r, &v, &Vec3::new(0.0, 2e-7, 0.0))
    }

    /// Ten 10 s steps against one hundred 1 s steps: the integration converged.
    #[test]
    fn the_integration_converges_with_the_step() {
        let m = model();
        let (coarse, _, _) = m.propagate(0.0, &leo(), 100.0);
        let mut fine = leo();
        for k in 0..100 {
            fine = m.propagate(k as f64, &fine, 1.0).0;
        }
        let (rc, vc, ac) = parts(&coarse);
        let (rf, vf, af) = parts(&fine);
        assert!((rc - rf).norm() < 1e-4, "{}", (rc - rf).norm());
        assert!((vc - vf).norm() < 1e-7, "{}", (vc - vf).norm());
        assert!((ac - af).norm() < 1e-18);
    }

    /// The transition matrix maps a small change of the start state to the change of the
    /// end state, as a second propagation from the changed state gives it.
    #[test]
    fn the_transition_matrix_matches_perturbed_propagations() {
        let m = model();
        let x0 = leo();
        let dt = 60.0;
        let (x1, phi, _) = m.propagate(0.0, &x0, dt);
        let deltas = [1.0, 1.0, 1.0, 1e-3, 1e-3, 1e-3, 1e-6, 1e-6, 1e-6];
        for (k, d) in deltas.iter().enumerate() {
            let mut xp = x0;
            xp[k] += d;
            let (x1p, _, _) = m.propagate(0.0, &xp, dt);
            let numeric = (x1p - x1) / *d;
            let analytic = phi.column(k);
            // Within 1e-3 of the column's own size in position and in velocity (the
            // series holds each 10 s step's Jacobian at its midpoint; the empirical
            // accelerations' axes turn by 0.01 rad over a step): a covariance mapped
            // through it is as good as the filter needs.
            let size = |i: usize| analytic.rows(i / 3 * 3, 3).norm();
            for i in 0..9 {
                let tol = 1e-3 * size(i);
                assert!(
                    (numeric[i] - analytic[i]).abs() <= tol,
                    "d x{i} / d x{k}: numeric {} analytic {}",
                    numeric[i],
                    analytic[i]
                );
            }
        }
    }

    /// The empirical accelerations' process noise reaches its steady state: after many
    /// correlation times the acceleration's variance is sigma^2.
    #[test]
    fn the_empirical_process_noise_reaches_sigma_squared() {
        let m = model();
        let (_, phi, q) = m.propagate(0.0, &leo(), 20.0 * m.tau_s);
        let p = phi * Block9::zeros() * phi.transpose() + q;
        for k in 6..9 {
            let ratio = p[(k, k)] / m.sigma_mps2.powi(2);
            assert!((ratio - 1.0).abs() < 1e-2, "{ratio}");
        }
    }
}
