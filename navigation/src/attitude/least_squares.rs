//! The iterated LS attitude of thesis eqs. 2.5-9..2.5-13 (Gauss-Newton).
//!
//! `vec(B_NED) = h vec(R(xi))` with `h = B_0^T (x) I_3` (eq. 2.5-8) is linearised at
//! `xi_0` with `H = h J(xi_0)` (eqs. 2.5-9, 2.5-10) and iterated,
//! `xi = xi_0 + (H^T Q^-1 H)^-1 H^T Q^-1 (vec(B_NED) - h vec(R(xi_0)))`
//! (eqs. 2.5-11, 2.5-12, `Q = Q_BB_NED`), until the step is below
//! [`LsConfig::tolerance_rad`]; the covariance at the solution is
//! `(H^T Q^-1 H)^-1` (eq. 2.5-13).
//!
//! The start value, unless given, is the closed-form Wahba solution
//! ([`super::wahba::wahba_attitude`]), so no prior is needed; from there a few iterations
//! suffice (each one shrinks the error by a factor of order noise / baseline length).
//!
//! One baseline (m = 1) determines only two of the three angles (the rotation about the
//! baseline is unobservable, `H^T Q^-1 H` has rank 2): that is the error
//! [`AttitudeError::SingleBaseline`], never a singular-matrix NaN.

use super::jacobian::design_matrix;
use super::wahba::wahba_attitude;
use super::{AttitudeError, AttitudeEstimate, BodyGeometry, NedBaselines, YawPitchRoll};
use nalgebra::{DMatrix, Matrix3, Vector3};

/// Iteration settings.
#[derive(Debug, Clone, Copy, PartialEq, serde::Deserialize, serde::Serialize)]
#[serde(default, deny_unknown_fields)]
pub struct LsConfig {
    /// Converged when the largest angle step is below this (rad). Default 1e-12 rad
    /// (1e-12 m at 1 m: far below any carrier-phase noise, reached in a few iterations
    /// from the Wahba start).
    pub tolerance_rad: f64,
    /// Iterations allowed before [`AttitudeError::NotConverged`]. Default 50.
    pub max_iterations: usize,
}

impl Default for LsConfig {
    fn default() -> Self {
        Self {
            tolerance_rad: 1e-12,
            max_iterations: 50,
        }
    }
}

impl LsConfig {
    /// Tolerance finite and > 0, at least one iteration.
    pub fn check(&self) -> Result<(), AttitudeError> {
        if self.tolerance_rad.is_finite() && self.tolerance_rad > 0.0 && self.max_iterations > 0 {
            Ok(())
        } else {
            Err(AttitudeError::Config(format!(
                "least squares: tolerance_rad must be finite and > 0 and max_iterations > 0, got {self:?}"
            )))
        }
    }
}

/// The weighted normal equations at `xi`: `(H^T Q^-1 H, H^T Q^-1 r, r)` with
/// `r = vec(B) - vec(R(xi) B_0)`.
fn normal_equations(
    geometry: &BodyGeometry,
    measured: &NedBaselines,
    q_chol: &nalgebra::Cholesky<f64, nalgebra::Dyn>,
    xi: &YawPitchRoll,
) -> (Matrix3<f64>, Vector3<f64>, nalgebra::DVector<f64>) {
    let h = design_matrix(geometry, xi);
    let r = measured.vec() - geometry.predict(xi);
    let w_h: DMatrix<f64> = q_chol.solve(&h);
    let n = h.transpose() * &w_h;
    let u = w_h.transpose() * &r;
    (
        Matrix3::from_iterator(n.iter().copied()),
        Vector3::from_iterator(u.iter().copied()),
        r,
    )
}

/// The Cholesky factor of `Q_BB` after checking the baselines fit the geometry (m >= 2).
pub(crate) fn weight_factor(
    geometry: &BodyGeometry,
    measured: &NedBaselines,
) -> Result<nalgebra::Cholesky<f64, nalgebra::Dyn>, AttitudeError> {
    geometry.check_count(measured)?;
    if geometry.len() < 2 {
        return Err(AttitudeError::SingleBaseline);
    }
    measured
        .covariance()
        .clone()
        .cholesky()
        .ok_or_else(|| AttitudeError::Covariance("Q_BB is not positive definite".into()))
}

/// Steps below this (rad) end [`misfit_upper_bound`]'s iteration: the misfit then changes
/// by far less than any candidate score difference.
const MISFIT_STEP_RAD: f64 = 1e-10;

/// The smallest weighted misfit `r^T Q^-1 r` (eq. 2.5-9's cost) over the Gauss-Newton
/// iterates from the Wahba start, at most `max_iterations` steps: the LS misfit where the
/// iteration converges, an upper bound of it where it does not (a large-residual problem
/// such as a wrong integer candidate's baselines, on which Gauss-Newton converges slowly
/// or oscillates).
pub fn misfit_upper_bound(
    geometry: &BodyGeometry,
    measured: &NedBaselines,
    max_iterations: usize,
) -> Result<f64, AttitudeError> {
    let q_chol = weight_factor(geometry, measured)?;
    misfit_upper_bound_with(geometry, measured, &q_chol, max_iterations)
}

/// [`misfit_upper_bound`] with the Cholesky factor of `measured`'s covariance given (a
/// caller scoring many baselines of one covariance forms it once).
pub fn misfit_upper_bound_with(
    geometry: &BodyGeometry,
    measured: &NedBaselines,
    q_chol: &nalgebra::Cholesky<f64, nalgebra::Dyn>,
    max_iterations: usize,
) -> Result<f64, AttitudeError> {
    geometry.check_count(measured)?;
    let mut xi = wahba_attitude(geometry, measured)?;
    let mut best = f64::INFINITY;
    for iteration in 0..=max_iterations {
        let (n, u, r) = normal_equations(geometry, measured, q_chol, &xi);
        best = best.min(r.dot(&q_chol.solve(&r)));
        if iteration == max_iterations {
            break;
        }
        let Some(step) = n.cholesky().map(|c| c.solve(&u)) else {
            break;
        };
        if !step.iter().all(|v| v.is_finite()) || step.amax() < MISFIT_STEP_RAD {
            break;
        }
        xi = YawPitchRoll::new(
            xi.yaw_rad + step[0],
            xi.pitch_rad + step[1],
            xi.roll_rad + step[2],
        );
    }
    Ok(best)
}

/// The LS attitude of one epoch (eqs. 2.5-9..2.5-13). `start`: the first `xi_0`; `None`
/// starts from the Wahba solution. Needs m >= 2 baselines.
pub fn solve(
    geometry: &BodyGeometry,
    measured: &NedBaselines,
    start: Option<YawPitchRoll>,
    config: &LsConfig,
) -> Result<AttitudeEstimate, AttitudeError> {
    config.check()?;
    let q_chol = weight_factor(geometry, measured)?;
    let mut xi = match start {
        Some(s) => {
            if ![s.yaw_rad, s.pitch_rad, s.roll_rad]
                .iter()
                .all(|v| v.is_finite())
            {
                return Err(AttitudeError::Measurement(format!(
                    "start attitude is not finite: {s:?}"
                )));
            }
            s
        }
        None => wahba_attitude(geometry, measured)?,
    };
    let mut last_step = f64::INFINITY;
    for iteration in 1..=config.max_iterations {
        let (n, u, _) = normal_equations(geometry, measured, &q_chol, &xi);
        let step = n.cholesky().map(|c| c.solve(&u)).ok_or_else(|| {
            AttitudeError::Singular(format!(
                "H^T Q^-1 H is not invertible at {xi:?} (gimbal lock or degenerate baselines)"
            ))
        })?;
        if !step.iter().all(|v| v.is_finite()) {
            return Err(AttitudeError::Singular(format!(
                "the LS step at {xi:?} is not finite"
            )));
        }
        xi = YawPitchRoll::new(
            xi.yaw_rad + step[0],
            xi.pitch_rad + step[1],
            xi.roll_rad + step[2],
        );
        last_step = step.amax();
        if last_step < config.tolerance_rad {
            // Canonical angles of the same rotation (yaw, roll in (-pi, pi], |pitch| <=
            // pi/2); eq. 2.5-13 at the solution.
            let xi = YawPitchRoll::from_c_ref_body(&xi.c_ref_body());
            let (n, _, r) = normal_equations(geometry, measured, &q_chol, &xi);
            let covariance = n.try_inverse().ok_or_else(|| {
                AttitudeError::Singular(format!("H^T Q^-1 H is not invertible at {xi:?}"))
            })?;
            let chi_square = r.dot(&q_chol.solve(&r));
            return Ok(AttitudeEstimate {
                angles: xi,
                covariance: 0.5 * (covariance + covariance.transpose()),
                iterations: iteration,
                residual_m: r,
                chi_square,
            });
        }
    }
    Err(AttitudeError::NotConverged {
        iterations: config.max_iterations,
        last_step_rad: last_step,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use skyforge_orbits::Vec3;

    #[test]
    fn exact_baselines_give_the_angles_from_a_far_start() {
        let g = BodyGeometry::new(&[Vec3::new(1.0, 0.0, 0.0), Vec3::new(0.0, 1.0, 0.0)]).unwrap();
        let truth = YawPitchRoll::new(3.1, 0.3, -0.5);
        let est = solve(
            &g,
            &measured(&g, truth, Vec3::zeros()),
            Some(YawPitchRoll::new(2.8, 0.1, -0.2)),
            &LsConfig::default(),
        )
        .unwrap();
        let e = super::super::angle_error(&est.angles, &truth);
        assert!(e.amax() < 1e-12, "{e:?}");
        assert!(est.chi_square < 1e-15);
    }

    /// Baselines of `truth` on `g` with `error` added to the first (m), covariance 1 mm^2.
    fn measured(g: &BodyGeometry, truth: YawPitchRoll, error: Vec3) -> NedBaselines {
        let mut b = g.in_reference(&truth);
        b[0] += error;
        NedBaselines::new(&b, DMatrix::identity(6, 6) * 1e-6).unwrap()
    }

    #[test]
    fn misfit_upper_bound_is_the_ls_misfit_where_ls_converges() {
        let g = BodyGeometry::new(&[Vec3::new(1.0, 0.0, 0.0), Vec3::new(0.0, 1.0, 0.0)]).unwrap();
        let truth = YawPitchRoll::new(0.4, -0.2, 0.1);
        // Millimetre noise (the right integers) and 19 cm (a wrong integer on one
        // baseline, a large-residual problem).
        for error in [Vec3::new(1e-3, -2e-3, 1.5e-3), Vec3::new(0.19, 0.0, -0.19)] {
            let m = measured(&g, truth, error);
            let loose = LsConfig {
                tolerance_rad: 1e-9,
                max_iterations: 1000,
            };
            let ls = solve(&g, &m, None, &loose).unwrap().chi_square;
            let bound = misfit_upper_bound(&g, &m, 10).unwrap();
            assert!(
                bound >= ls * (1.0 - 1e-9),
                "{bound} below the LS misfit {ls}"
            );
            assert!(bound <= ls * (1.0 + 1e-6), "{bound} vs {ls}");
        }
    }

    #[test]
    fn one_baseline_is_an_explicit_error() {
        let g = BodyGeometry::new(&[Vec3::new(1.0, 0.0, 0.0)]).unwrap();
        let meas = NedBaselines::new(&[Vec3::new(0.0, 1.0, 0.0)], DMatrix::identity(3, 3)).unwrap();
        assert_eq!(
            solve(&g, &meas, None, &LsConfig::default()),
            Err(AttitudeError::SingleBaseline)
        );
    }
}
