//! The relative dynamics of two spacecraft 200 km apart: the difference of two orbits
//! under one gravity field, not the Hill/Clohessy-Wiltshire equations. CW linearises the
//! gravity difference about the target (book eq. 5-34): a follower 200 km behind on the
//! same circle sits 2.9 km "below" the target's along-track axis
//! (`r (1 - cos theta)`), where the linear equations see an acceleration of
//! `3 n^2 z`, 0.01 m/s^2, that is not there: 5 mm after one second. Here both orbits are
//! integrated and differenced:
//!
//! `d2 b / dt2 = g(r_t + b) - g(r_t)`  (ECI, `g` the point mass and the zonal terms of
//! the target orbit filter's force model, `[target_orbit.forces]`),
//!
//! with the target's state `r_t, v_t` from its own orbit filter. The gravity difference
//! depends on the target's position only through the gravity gradient's change over the
//! baseline, `3 n^2 |b| / r` per metre, 1e-7 m/s^2 for a metre of error: its error is
//! negligible. Drag differences of like spacecraft are left to the process noise. The
//! zonal terms matter: J3..J6 differ by about 5e-6 m/s^2 across 200 km (J2 by 1e-3), so
//! the field must be the world's: the filter's is the target orbit filter's, which a
//! user sets to their world's (a simulated one's `[platform.leo.forces]`).
//!
//! Covariance: `Phi = [[I + G dt^2/2, I dt + G dt^3/6], [G dt, I + G dt^2/2]]` with `G`
//! the point-mass gravity gradient `mu / r^3 (3 u u^T - I)` at the chaser, and a white
//! acceleration held over the step, `Q = Gamma sigma^2 Gamma^T`,
//! `Gamma = [dt^2/2 I; dt I]` (as the target's orbit filter's eq. 5-40d).

use nalgebra::{Matrix3, Matrix6, SVector};
use skyforge_orbits::Vec3;
use skyforge_orbits::propagate::{ForceModel, ForceModelConfig};

/// Longest integration step (s): RK4's error at 5 s of a LEO is far below a micrometre.
const MAX_STEP_S: f64 = 5.0;

/// Two absolute states `[r_t, v_t, r_c, v_c]` (ECI).
type Pair = SVector<f64, 12>;

fn derivative(forces: &ForceModel, y: &Pair) -> Pair {
    let mut d = Pair::zeros();
    for k in 0..2 {
        let r = Vec3::new(y[6 * k], y[6 * k + 1], y[6 * k + 2]);
        let a = forces.gravity_eci(&r);
        for i in 0..3 {
            d[6 * k + i] = y[6 * k + 3 + i];
            d[6 * k + 3 + i] = a[i];
        }
    }
    d
}

/// Two absolute states (ECI) `dt_s` later, integrated together by RK4.
pub(crate) fn propagate_pair(
    forces: &ForceModel,
    states: [(Vec3, Vec3); 2],
    dt_s: f64,
) -> [(Vec3, Vec3); 2] {
    let mut y = Pair::zeros();
    for (k, (r, v)) in states.iter().enumerate() {
        y.fixed_rows_mut::<3>(6 * k).copy_from(r);
        y.fixed_rows_mut::<3>(6 * k + 3).copy_from(v);
    }
    let steps = (dt_s.abs() / MAX_STEP_S).ceil().max(1.0);
    let h = dt_s / steps;
    for _ in 0..steps as usize {
        let k1 = derivative(forces, &y);
        let k2 = derivative(forces, &(y + k1 * (h / 2.0)));
        let k3 = derivative(forces, &(y + k2 * (h / 2.0)));
        let k4 = derivative(forces, &(y + k3 * h));
        y += (k1 + k2 * 2.0 + k3 * 2.0 + k4) * (h / 6.0);
    }
    let part = |k: usize| Vec3::new(y[3 * k], y[3 * k + 1], y[3 * k + 2]);
    [(part(0), part(1)), (part(2), part(3))]
}

/// The relative state `b, b_dot` (ECI) of a chaser relative to the target at `r_t, v_t`
/// (ECI), `dt_s` later: both orbits integrated and differenced.
pub(crate) fn propagate(
    forces: &ForceModel,
    (r_t, v_t): (Vec3, Vec3),
    (b, b_dot): (Vec3, Vec3),
    dt_s: f64,
) -> (Vec3, Vec3) {
    let [(r_t1, v_t1), (r_c1, v_c1)] =
        propagate_pair(forces, [(r_t, v_t), (r_t + b, v_t + b_dot)], dt_s);
    (r_c1 - r_t1, v_c1 - v_t1)
}

/// The transition matrix of `[b, b_dot]` over `dt_s` at the chaser's position `r_c`
/// (module docs).
pub(crate) fn transition(mu: f64, r_c: &Vec3, dt_s: f64) -> Matrix6<f64> {
    let r = r_c.norm();
    let u = r_c / r;
    let g = (u * u.transpose() * 3.0 - Matrix3::identity()) * (mu / r.powi(3));
    let i = Matrix3::identity();
    let mut phi = Matrix6::zeros();
    let diag = i + g * (dt_s * dt_s / 2.0);
    phi.fixed_view_mut::<3, 3>(0, 0).copy_from(&diag);
    phi.fixed_view_mut::<3, 3>(0, 3)
        .copy_from(&(i * dt_s + g * (dt_s.powi(3) / 6.0)));
    phi.fixed_view_mut::<3, 3>(3, 0).copy_from(&(g * dt_s));
    phi.fixed_view_mut::<3, 3>(3, 3).copy_from(&diag);
    phi
}

/// The process noise of `[b, b_dot]` over `dt_s` for a white acceleration of
/// `sigma_mps2` per axis held over the step.
pub(crate) fn process_noise(sigma_mps2: f64, dt_s: f64) -> Matrix6<f64> {
    let (a, b, c) = (dt_s.powi(4) / 4.0, dt_s.powi(3) / 2.0, dt_s * dt_s);
    let s2 = sigma_mps2 * sigma_mps2;
    let mut q = Matrix6::zeros();
    for i in 0..3 {
        q[(i, i)] = a * s2;
        q[(i, i + 3)] = b * s2;
        q[(i + 3, i)] = b * s2;
        q[(i + 3, i + 3)] = c * s2;
    }
    q
}

/// The gravity field of the relative dynamics: that of `forces` (the target's orbit
/// filter's: J2, and J3..J6 where set), without drag.
pub(crate) fn gravity_field(forces: &ForceModelConfig, start: hifitime::Epoch) -> ForceModel {
    let config = ForceModelConfig {
        drag: false,
        ..forces.clone()
    };
    ForceModel::new(&config, start, 0.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A follower on the target's circle (point mass) stays on it: the propagated
    /// baseline keeps its length, 200 km, to a micrometre over 100 s, and the transition
    /// matrix predicts a small change of the initial state as the integration does.
    #[test]
    fn a_follower_on_the_same_circle_keeps_its_distance() {
        let forces = ForceModel::new(
            &skyforge_orbits::propagate::ForceModelConfig {
                j2: false,
                higher_zonals: false,
                drag: false,
                ..Default::default()
            },
            hifitime::Epoch::from_gregorian_utc_at_midnight(2023, 3, 12),
            0.0,
        );
        let mu = forces.gm();
        let r = 6.878e6_f64;
        let (v, theta) = ((mu / r).sqrt(), 200e3 / r);
        let r_t = Vec3::new(r, 0.0, 0.0);
        let v_t = Vec3::new(0.0, v, 0.0);
        let r_c = Vec3::new(r * theta.cos(), -r * theta.sin(), 0.0);
        let v_c = Vec3::new(v * theta.sin(), v * theta.cos(), 0.0);
        let (b, b_dot) = (r_c - r_t, v_c - v_t);
        let (b1, _) = propagate(&forces, (r_t, v_t), (b, b_dot), 100.0);
        assert!(
            (b1.norm() - b.norm()).abs() < 1e-6,
            "{}",
            b1.norm() - b.norm()
        );
        let db = Vec3::new(0.3, -0.2, 0.1);
        let (b2, v2) = propagate(&forces, (r_t, v_t), (b + db, b_dot), 10.0);
        let (b0, v0) = propagate(&forces, (r_t, v_t), (b, b_dot), 10.0);
        let phi = transition(mu, &r_c, 10.0);
        let mut dx = nalgebra::Vector6::zeros();
        dx.fixed_rows_mut::<3>(0).copy_from(&db);
        let predicted = phi * dx;
        assert!((b2 - b0 - predicted.fixed_rows::<3>(0)).norm() < 1e-5);
        assert!((v2 - v0 - predicted.fixed_rows::<3>(3)).norm() < 1e-5);
    }
}
