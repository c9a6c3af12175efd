//! The book's relative filter (section 5.6.4): the chaser's state relative to the target
//! in the target's orbit frame, propagated by the Hill / Clohessy-Wiltshire equations
//! (eq. 5-34 with the target's orbit as the reference, eq. 5-53) with the difference of
//! the two vehicles' perturbing accelerations as the input `U` (evaluated exactly:
//! [`super::hill_dynamics`]), and updated by the relative measurements of eq. 5-57 (the
//! difference of the two fixes, whose noise is the sum of the two receivers', eq. 5-58).

use super::hill_dynamics::{HillDynamics, TargetState};
use nalgebra::{Matrix6, Vector6};
use skyforge_orbits::Vec3;
use skyforge_orbits::propagate::ForceModelConfig;

/// The relative filter's settings; every default is an assumption a user can change.
#[derive(Debug, Clone, PartialEq, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct HillFilterConfig {
    /// 1-sigma of one relative position coordinate (m), the difference of two fixes on
    /// the same satellites (eq. 5-58: twice one receiver's noise variance).
    /// # assumed: 1.5 m, the position-difference mode's measured 3-D RMS on B-5.6
    /// (1.49 m, docs/orbit-determination.md) taken per axis with a margin.
    #[serde(default = "default_position_sigma_m")]
    pub position_sigma_m: f64,
    /// 1-sigma of one relative velocity coordinate (m/s).
    /// # assumed: 0.5 m/s, two Doppler velocities' difference at 45 dB-Hz (0.39 m/s on
    /// the nadir axis, docs/orbit-determination.md) with a margin.
    #[serde(default = "default_velocity_sigma_mps")]
    pub velocity_sigma_mps: f64,
    /// 1-sigma of the unmodelled relative acceleration per axis (m/s^2): `Q`.
    /// # assumed: 1e-5 m/s^2, the position filter's (B-5.5): the Hill equations' neglect
    /// of the orbit's eccentricity (0.01 gives n e rho-dot terms of this order at tens of
    /// kilometres) dominates.
    #[serde(default = "default_acceleration_sigma_mps2")]
    pub acceleration_sigma_mps2: f64,
    /// The perturbations whose difference is `U` (the book: J2 and drag).
    #[serde(default)]
    pub forces: ForceModelConfig,
}

fn default_position_sigma_m() -> f64 {
    1.5
}
fn default_velocity_sigma_mps() -> f64 {
    0.5
}
fn default_acceleration_sigma_mps2() -> f64 {
    1e-5
}

impl Default for HillFilterConfig {
    fn default() -> Self {
        Self {
            position_sigma_m: default_position_sigma_m(),
            velocity_sigma_mps: default_velocity_sigma_mps(),
            acceleration_sigma_mps2: default_acceleration_sigma_mps2(),
            forces: ForceModelConfig::default(),
        }
    }
}

impl HillFilterConfig {
    /// Whether the values are usable: each error names the field, its value and what is
    /// allowed.
    pub fn check(&self) -> Result<(), String> {
        crate::config_file::check_positive(&[
            ("position_sigma_m", self.position_sigma_m, 1e6),
            ("velocity_sigma_mps", self.velocity_sigma_mps, 1e4),
            ("acceleration_sigma_mps2", self.acceleration_sigma_mps2, 1.0),
        ])?;
        crate::orbit_determination::position_filter::check_forces(&self.forces)
    }
}

/// The relative filter's estimate: position and rate in the target's orbit frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HillEstimate {
    pub t_s: f64,
    pub position_m: Vec3,
    pub velocity_mps: Vec3,
    pub covariance: Matrix6<f64>,
}

/// The book's relative filter.
#[derive(Debug, Clone)]
pub struct HillFilter {
    config: HillFilterConfig,
    dynamics: HillDynamics,
    last: Option<(TargetState, HillEstimate)>,
}

fn state(e: &HillEstimate) -> Vector6<f64> {
    Vector6::from_iterator(e.position_m.iter().chain(e.velocity_mps.iter()).copied())
}

impl HillFilter {
    /// A filter for a run starting at `start` (the force model's date).
    pub fn new(config: HillFilterConfig, start: hifitime::Epoch) -> Self {
        Self {
            dynamics: HillDynamics::new(&config.forces, start),
            config,
            last: None,
        }
    }

    /// The estimate of the last epoch carried to `target`'s epoch (eq. 5-34 about the
    /// target's orbit; `U` at the mean of its two ends).
    pub fn predict(
        &self,
        from: &TargetState,
        e: &HillEstimate,
        target: &TargetState,
    ) -> HillEstimate {
        let step = self
            .dynamics
            .step(from, &state(e), target, target.t_s - e.t_s);
        let x1 = step.state;
        HillEstimate {
            t_s: target.t_s,
            position_m: Vec3::new(x1[0], x1[1], x1[2]),
            velocity_mps: Vec3::new(x1[3], x1[4], x1[5]),
            covariance: step.covariance(&e.covariance, self.config.acceleration_sigma_mps2),
        }
    }

    /// Take the relative measurement at `target`'s epoch (`position_m`, and the rate
    /// `velocity_mps` where both vehicles had one; eq. 5-57); the estimate after it. The
    /// first measurement starts the filter.
    pub fn update(
        &mut self,
        target: TargetState,
        position_m: Vec3,
        velocity_mps: Option<Vec3>,
    ) -> HillEstimate {
        let (sp, sv) = (self.config.position_sigma_m, self.config.velocity_sigma_mps);
        let r_diag = Vector6::new(sp, sp, sp, sv, sv, sv).map(|s| s * s);
        let measured = Vector6::from_iterator(
            (position_m.iter())
                .chain(velocity_mps.unwrap_or_else(Vec3::zeros).iter())
                .copied(),
        );
        let rows: Vec<usize> = if velocity_mps.is_some() {
            (0..6).collect()
        } else {
            (0..3).collect()
        };
        let predicted = match &self.last {
            Some((from, e)) => self.predict(from, e, &target),
            None => {
                let mut p = Matrix6::from_diagonal(&r_diag);
                if velocity_mps.is_none() {
                    for k in 3..6 {
                        // No rate measured: uninformative (100 m/s).
                        p[(k, k)] = 1e4;
                    }
                }
                let e = HillEstimate {
                    t_s: target.t_s,
                    position_m,
                    velocity_mps: velocity_mps.unwrap_or_else(Vec3::zeros),
                    covariance: p,
                };
                self.last = Some((target, e));
                return e;
            }
        };
        let x = state(&predicted);
        let m = rows.len();
        let h = nalgebra::DMatrix::from_fn(m, 6, |i, j| f64::from(u8::from(rows[i] == j)));
        let p = nalgebra::DMatrix::from_iterator(6, 6, predicted.covariance.iter().copied());
        let r = nalgebra::DMatrix::from_fn(m, m, |i, j| if i == j { r_diag[rows[i]] } else { 0.0 });
        let innovation = nalgebra::DVector::from_fn(m, |i, _| measured[rows[i]] - x[rows[i]]);
        let s = &h * &p * h.transpose() + &r;
        let estimate = match s.cholesky() {
            Some(chol) => {
                let k = &p * h.transpose() * chol.inverse();
                let x1 = nalgebra::DVector::from_iterator(6, x.iter().copied()) + &k * innovation;
                let i_kh = nalgebra::DMatrix::<f64>::identity(6, 6) - &k * &h;
                let p1 = &i_kh * p * i_kh.transpose() + &k * r * k.transpose();
                HillEstimate {
                    t_s: target.t_s,
                    position_m: Vec3::new(x1[0], x1[1], x1[2]),
                    velocity_mps: Vec3::new(x1[3], x1[4], x1[5]),
                    covariance: Matrix6::from_iterator(p1.iter().copied()),
                }
            }
            None => predicted,
        };
        self.last = Some((target, estimate));
        estimate
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::orbit_determination::transition;
    use skyforge_orbits::frames::relative_in_target_frame;
    use skyforge_orbits::propagate::{ForceModel, KeplerianElements};

    /// Two orbits integrated with the force model by small Runge-Kutta steps.
    fn propagate(forces: &ForceModel, r: Vec3, v: Vec3, t_s: f64) -> (Vec3, Vec3) {
        let h = 1.0;
        let (mut r, mut v) = (r, v);
        let acc = |r: &Vec3, v: &Vec3| forces.acceleration_eci(0.0, r, v);
        for _ in 0..(t_s / h) as usize {
            let (k1r, k1v) = (v, acc(&r, &v));
            let (k2r, k2v) = (
                v + k1v * h / 2.0,
                acc(&(r + k1r * h / 2.0), &(v + k1v * h / 2.0)),
            );
            let (k3r, k3v) = (
                v + k2v * h / 2.0,
                acc(&(r + k2r * h / 2.0), &(v + k2v * h / 2.0)),
            );
            let (k4r, k4v) = (v + k3v * h, acc(&(r + k3r * h), &(v + k3v * h)));
            r += (k1r + k2r * 2.0 + k3r * 2.0 + k4r) * (h / 6.0);
            v += (k1v + k2v * 2.0 + k3v * 2.0 + k4v) * (h / 6.0);
        }
        (r, v)
    }

    /// A chaser 32 km behind a target on the book's 500 km orbit with e = 0.01 (book
    /// 5.6.4), both under J2 and drag: the filter's prediction over 60 s lands within 0.1
    /// m and 5 mm/s of the two orbits' relative state (# assumed bars: far below the
    /// measurements' metres), where the Hill equations alone miss by metres.
    #[test]
    fn the_prediction_follows_two_perturbed_orbits() {
        let start = hifitime::Epoch::from_gpst_seconds(1.0e9);
        let mu = 3.986_004_418e14;
        let elements = |m_deg: f64| KeplerianElements {
            a_m: 6_878_137.0,
            e: 0.01,
            i_rad: 98f64.to_radians(),
            raan_rad: 0.0,
            argp_rad: 0.0,
            mean_anomaly_rad: (30.0 + m_deg).to_radians(),
        };
        let (rt, vt) = elements(0.0).to_cartesian(mu);
        let (rc, vc) = elements(-0.2667).to_cartesian(mu);
        let config = HillFilterConfig::default();
        let forces = ForceModel::new(&config.forces, start, 0.0);
        let dt = 60.0;
        let (rt1, vt1) = propagate(&forces, rt, vt, dt);
        let (rc1, vc1) = propagate(&forces, rc, vc, dt);
        let (p0, v0) = relative_in_target_frame(&rt, &vt, &rc, &vc);
        let (p1, v1) = relative_in_target_frame(&rt1, &vt1, &rc1, &vc1);
        let from = TargetState {
            t_s: 0.0,
            r_eci_m: rt,
            v_eci_mps: vt,
        };
        let to = TargetState {
            t_s: dt,
            r_eci_m: rt1,
            v_eci_mps: vt1,
        };
        let e = HillEstimate {
            t_s: 0.0,
            position_m: p0,
            velocity_mps: v0,
            covariance: Matrix6::identity(),
        };
        let predicted = HillFilter::new(config, start).predict(&from, &e, &to);
        let n = rt.cross(&vt).norm() / rt.norm_squared();
        let x0 = Vector6::from_iterator(p0.iter().chain(v0.iter()).copied());
        let hill_alone = transition(n, dt) * x0;
        let miss = (predicted.position_m - p1).norm();
        let hill_miss = (Vec3::new(hill_alone[0], hill_alone[1], hill_alone[2]) - p1).norm();
        eprintln!("filter {miss:.4} m, Hill alone {hill_miss:.3} m");
        assert!(miss < 0.1, "{miss}");
        assert!((predicted.velocity_mps - v1).norm() < 0.005);
        assert!(hill_miss > 1.0, "{hill_miss}");
    }

    /// On measurements without noise the estimate stays on them and its covariance
    /// shrinks below the measurement's.
    #[test]
    fn exact_measurements_are_followed() {
        let start = hifitime::Epoch::from_gpst_seconds(1.0e9);
        let mu = 3.986_004_418e14_f64;
        let r = 6_878_137.0_f64;
        let v = (mu / r).sqrt();
        let n = v / r;
        let mut f = HillFilter::new(HillFilterConfig::default(), start);
        let mut last = None;
        for k in 0..120 {
            let t = k as f64;
            let angle = n * t;
            let target = TargetState {
                t_s: t,
                r_eci_m: Vec3::new(r * angle.cos(), r * angle.sin(), 0.0),
                v_eci_mps: Vec3::new(-v * angle.sin(), v * angle.cos(), 0.0),
            };
            // At rest 1 km behind on the same circle.
            last = Some(f.update(target, Vec3::new(-1000.0, 0.0, 0.0), Some(Vec3::zeros())));
        }
        let e = last.unwrap();
        assert!(
            (e.position_m - Vec3::new(-1000.0, 0.0, 0.0)).norm() < 0.1,
            "{:?}",
            e.position_m
        );
        assert!(e.covariance[(0, 0)] < 1.5f64.powi(2) / 4.0);
    }
}
