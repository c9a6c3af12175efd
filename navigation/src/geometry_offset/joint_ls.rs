//! Thesis section 4.2.2: the joint least squares of the attitude and a deformation of the
//! antenna geometry (Cohen and Cannon's wing flexure, eqs. 4.2-13..4.2-17; Tsujii's wing
//! and lateral flexure, eqs. 4.2-18..4.2-22).
//!
//! `B_Ref = R(xi) (B_0 + dB_0(p))` with `dB_0(p) = sum_j p_j P_j`: `B_0` the nominal body
//! geometry (3 x m), `P_j` caller-given 3 x m patterns, `p` their amplitudes (m).
//! Unknowns `X = [yaw, pitch, roll, p_1, ..., p_k]`; `R(xi)` =
//! [`YawPitchRoll::c_body_ref`] (thesis eq. 4.3-3, the reference frame NED). Gauss-Newton
//! with the Jacobian of eqs. 4.2-14/4.2-19,
//! `H = [ (B_0'^T (x) I_3) J(xi) | vec(R P_1) | ... | vec(R P_k) ]` (`B_0' = B_0 + dB_0(p)`,
//! `J(xi) = d vec(R) / d xi`), and the weighted step of eqs. 4.2-17/4.2-22,
//! `dX = (H^T Q^-1 H)^-1 H^T Q^-1 (vec(B_Ref) - vec(F(X_0)))`, `Q = Q_BB_Ref`. The start is
//! the Wahba attitude of the nominal `B_0` (or a caller's) with `p = 0`.
//!
//! Limits: a pattern (or a combination of patterns) that is an infinitesimal rotation of
//! `B_0`, `P = [w x b_1, ..., w x b_m]`, is absorbed by the attitude (the normal matrix is
//! singular); that, more unknowns than `3m`, and near-singular normal matrices are refused
//! with [`AttitudeError::Singular`] rather than returned as huge variances. The model is
//! the thesis': the deformation must be known up to the amplitudes (the thesis' own
//! criticism, end of section 4.2.2: equal offsets along one fixed axis are an idealisation).

use crate::attitude::jacobian::design_matrix as attitude_columns;
use crate::attitude::least_squares::LsConfig;
use crate::attitude::wahba::wahba_attitude;
use crate::attitude::{AttitudeError, BodyGeometry, NedBaselines, YawPitchRoll};
use nalgebra::{Cholesky, DMatrix, DVector, Dyn};
use skyforge_orbits::Vec3;

/// Smallest eigenvalue of the normal matrix scaled to unit diagonal (the correlation
/// matrix of the estimate's inverse) for `X` to count as observable: below it some
/// combination of unknowns is determined 1e5 times worse than the unknowns alone.
const MIN_SCALED_EIGENVALUE: f64 = 1e-10;

/// The deformation model `dB_0(p) = sum_j p_j P_j`: k >= 1 patterns of m columns (body
/// frame; the unit of `p_j` times the pattern's unit is metres).
#[derive(Debug, Clone, PartialEq)]
pub struct DeformationModel {
    patterns: Vec<Vec<Vec3>>,
}

impl DeformationModel {
    /// Check and keep: at least one pattern, all with the same number (>= 1) of columns,
    /// finite, none all zero.
    pub fn new(patterns: Vec<Vec<Vec3>>) -> Result<Self, AttitudeError> {
        let m = patterns.first().map_or(0, Vec::len);
        if m == 0 {
            return Err(AttitudeError::Geometry(
                "deformation model: no pattern, or a pattern without columns".into(),
            ));
        }
        for (j, p) in patterns.iter().enumerate() {
            if p.len() != m {
                return Err(AttitudeError::Geometry(format!(
                    "deformation pattern {} has {} columns, pattern 1 has {m}",
                    j + 1,
                    p.len()
                )));
            }
            if !p.iter().flat_map(|c| c.iter()).all(|v| v.is_finite()) {
                return Err(AttitudeError::Geometry(format!(
                    "deformation pattern {} is not finite",
                    j + 1
                )));
            }
            if p.iter().all(|c| c.norm() == 0.0) {
                return Err(AttitudeError::Geometry(format!(
                    "deformation pattern {} is zero",
                    j + 1
                )));
            }
        }
        Ok(Self { patterns })
    }

    /// Thesis eq. 4.2-13 (Cohen, Cannon): the wing flexure `fw` for baselines 1 (tail ->
    /// left wing tip), 2 (tail -> nose), 3 (tail -> right wing tip): both wing baselines
    /// change by `-fw` along `z_b`.
    pub fn wing_flexure() -> Self {
        Self {
            patterns: vec![wing_pattern()],
        }
    }

    /// Thesis eq. 4.2-18 (Tsujii): `p = [fw, fl]`, the wing flexure of eq. 4.2-13 and the
    /// lateral flexure `fl`, which changes all three baselines by `+fl` along `y_b`.
    pub fn wing_and_lateral_flexure() -> Self {
        Self {
            patterns: vec![wing_pattern(), vec![Vec3::y(); 3]],
        }
    }

    /// The patterns `P_j` (each m columns).
    pub fn patterns(&self) -> &[Vec<Vec3>] {
        &self.patterns
    }

    /// The number of parameters k.
    pub fn len(&self) -> usize {
        self.patterns.len()
    }

    /// Always false (at least one pattern); for clippy's `len` rule.
    pub fn is_empty(&self) -> bool {
        self.patterns.is_empty()
    }

    /// Error unless the patterns have as many columns as `nominal` has baselines.
    fn check_columns(&self, nominal: &BodyGeometry) -> Result<(), AttitudeError> {
        let (columns, m) = (self.patterns.first().map_or(0, Vec::len), nominal.len());
        if columns == m {
            Ok(())
        } else {
            Err(AttitudeError::Geometry(format!(
                "the deformation patterns have {columns} columns, B_0 has {m}"
            )))
        }
    }

    /// `B_0' = B_0 + sum_j p_j P_j`, checked as a [`BodyGeometry`]. `p` has k values.
    pub fn deformed(
        &self,
        nominal: &BodyGeometry,
        p: &[f64],
    ) -> Result<BodyGeometry, AttitudeError> {
        self.check_columns(nominal)?;
        let columns: Vec<Vec3> = nominal
            .baselines()
            .iter()
            .enumerate()
            .map(|(i, b0)| {
                self.patterns
                    .iter()
                    .zip(p)
                    .fold(*b0, |acc, (pattern, pj)| acc + *pj * pattern[i])
            })
            .collect();
        BodyGeometry::new(&columns)
    }
}

/// The pattern of thesis eq. 4.2-13: `-z_b` on baselines 1 and 3.
fn wing_pattern() -> Vec<Vec3> {
    vec![-Vec3::z(), Vec3::zeros(), -Vec3::z()]
}

/// The joint estimate.
#[derive(Debug, Clone, PartialEq)]
pub struct JointEstimate {
    /// The angles; yaw and roll in (-pi, pi], pitch in [-pi/2, pi/2].
    pub angles: YawPitchRoll,
    /// The deformation amplitudes `p` (k).
    pub parameters: DVector<f64>,
    /// `(H^T Q^-1 H)^-1` at the solution ((3 + k) x (3 + k); yaw, pitch, roll (rad),
    /// then `p`).
    pub covariance: DMatrix<f64>,
    /// Gauss-Newton iterations used.
    pub iterations: usize,
    /// `r^T Q^-1 r` of the post-fit residuals: chi-square with `3m - 3 - k` degrees of
    /// freedom when the model and `Q_BB_Ref` are right.
    pub chi_square: f64,
}

/// Thesis eqs. 4.2-14, 4.2-19: `H = d vec(F(X)) / dX` (3m x (3 + k)) at `xi` and the
/// deformed geometry `deformed` (= `B_0 + dB_0(p)`): the attitude columns
/// `(B_0'^T (x) I_3) J(xi)`, then `vec(R(xi) P_j)`. An error unless `model`'s patterns
/// have as many columns as `deformed`.
pub fn jacobian(
    deformed: &BodyGeometry,
    model: &DeformationModel,
    xi: &YawPitchRoll,
) -> Result<DMatrix<f64>, AttitudeError> {
    model.check_columns(deformed)?;
    let m = deformed.len();
    let r = xi.c_body_ref();
    let mut h = DMatrix::<f64>::zeros(3 * m, 3 + model.len());
    h.columns_mut(0, 3)
        .copy_from(&attitude_columns(deformed, xi));
    for (j, pattern) in model.patterns().iter().enumerate() {
        for (i, column) in pattern.iter().enumerate() {
            h.fixed_view_mut::<3, 1>(3 * i, 3 + j)
                .copy_from(&(r * column));
        }
    }
    Ok(h)
}

/// Error unless the normal matrix `n` is observable: positive diagonal and, scaled to unit
/// diagonal, smallest eigenvalue at least [`MIN_SCALED_EIGENVALUE`].
fn check_observable(n: &DMatrix<f64>) -> Result<(), AttitudeError> {
    let d = n.diagonal();
    if let Some(j) = d.iter().position(|v| !(v.is_finite() && *v > 0.0)) {
        return Err(AttitudeError::Singular(format!(
            "unknown {} of X does not enter the model (its column of H is zero)",
            j + 1
        )));
    }
    let inv_sqrt = d.map(|v| 1.0 / v.sqrt());
    let scaled = DMatrix::from_diagonal(&inv_sqrt) * n * DMatrix::from_diagonal(&inv_sqrt);
    let eigen = scaled.symmetric_eigen();
    let (k, smallest) = eigen.eigenvalues.argmin();
    if smallest.is_finite() && smallest >= MIN_SCALED_EIGENVALUE {
        return Ok(());
    }
    // The weak direction in the unknowns' own units, largest component 1.
    let weak = eigen.eigenvectors.column(k).component_mul(&inv_sqrt);
    let weak: Vec<f64> = (&weak / weak.amax()).iter().copied().collect();
    Err(AttitudeError::Singular(format!(
        "H^T Q^-1 H is singular (scaled eigenvalue {smallest:e}): the combination {weak:?} of [yaw, pitch, roll, p...] is unobservable (a pattern the attitude absorbs, such as a rotation of B_0, or patterns that repeat each other)"
    )))
}

/// The normal equations at `(xi, p)`: `(H^T Q^-1 H, H^T Q^-1 r, r^T Q^-1 r)` with
/// `r = vec(B_Ref) - vec(R(xi) B_0')`.
fn normal_equations(
    nominal: &BodyGeometry,
    model: &DeformationModel,
    measured: &NedBaselines,
    q_chol: &Cholesky<f64, Dyn>,
    xi: &YawPitchRoll,
    p: &DVector<f64>,
) -> Result<(DMatrix<f64>, DVector<f64>, f64), AttitudeError> {
    let deformed = model.deformed(nominal, p.as_slice())?;
    let h = jacobian(&deformed, model, xi)?;
    let r = measured.vec() - deformed.predict(xi);
    let w_h = q_chol.solve(&h);
    Ok((
        h.transpose() * &w_h,
        w_h.transpose() * &r,
        r.dot(&q_chol.solve(&r)),
    ))
}

/// Error unless nominal geometry, model and measurement agree in the number of baselines
/// and `3 + k <= 3m`; else the Cholesky factor of `Q_BB_Ref`.
fn check_sizes(
    nominal: &BodyGeometry,
    model: &DeformationModel,
    measured: &NedBaselines,
) -> Result<Cholesky<f64, Dyn>, AttitudeError> {
    let m = nominal.len();
    model.check_columns(nominal)?;
    nominal.check_count(measured)?;
    if 3 + model.len() > 3 * m {
        return Err(AttitudeError::Singular(format!(
            "{} unknowns (3 angles, {} deformation parameters) from {} observations",
            3 + model.len(),
            model.len(),
            3 * m
        )));
    }
    measured
        .covariance()
        .clone()
        .cholesky()
        .ok_or_else(|| AttitudeError::Covariance("Q_BB_Ref is not positive definite".into()))
}

/// The joint LS of thesis eqs. 4.2-13..4.2-22. `start`: the first attitude (`None`: the
/// Wahba attitude of the nominal `B_0`); the parameters start at 0. `config`: the
/// iteration ends when every step component is below `tolerance_rad` (rad for the angles,
/// the parameters' unit for `p`).
pub fn solve(
    nominal: &BodyGeometry,
    model: &DeformationModel,
    measured: &NedBaselines,
    start: Option<YawPitchRoll>,
    config: &LsConfig,
) -> Result<JointEstimate, AttitudeError> {
    config.check()?;
    let q_chol = check_sizes(nominal, model, measured)?;
    let mut xi = match start {
        Some(s)
            if [s.yaw_rad, s.pitch_rad, s.roll_rad]
                .iter()
                .all(|v| v.is_finite()) =>
        {
            s
        }
        Some(s) => {
            return Err(AttitudeError::Measurement(format!(
                "start attitude is not finite: {s:?}"
            )));
        }
        None => wahba_attitude(nominal, measured)?,
    };
    let mut p = DVector::<f64>::zeros(model.len());
    let mut last_step = f64::INFINITY;
    for iteration in 1..=config.max_iterations {
        let (n, u, _) = normal_equations(nominal, model, measured, &q_chol, &xi, &p)?;
        check_observable(&n)?;
        let step = n
            .cholesky()
            .map(|c| c.solve(&u))
            .filter(|s| s.iter().all(|v| v.is_finite()))
            .ok_or_else(|| AttitudeError::Singular(format!("H^T Q^-1 H at {xi:?}, p {p:?}")))?;
        xi = YawPitchRoll::new(
            xi.yaw_rad + step[0],
            xi.pitch_rad + step[1],
            xi.roll_rad + step[2],
        );
        p += step.rows(3, model.len());
        last_step = step.amax();
        if last_step < config.tolerance_rad {
            return finish(nominal, model, measured, &q_chol, xi, p, iteration);
        }
    }
    Err(AttitudeError::NotConverged {
        iterations: config.max_iterations,
        last_step_rad: last_step,
    })
}

/// The estimate at the converged `(xi, p)`: canonical angles, covariance and chi-square
/// there.
fn finish(
    nominal: &BodyGeometry,
    model: &DeformationModel,
    measured: &NedBaselines,
    q_chol: &Cholesky<f64, Dyn>,
    xi: YawPitchRoll,
    p: DVector<f64>,
    iterations: usize,
) -> Result<JointEstimate, AttitudeError> {
    let xi = YawPitchRoll::from_c_ref_body(&xi.c_ref_body());
    let (n, _, chi_square) = normal_equations(nominal, model, measured, q_chol, &xi, &p)?;
    check_observable(&n)?;
    let covariance = n
        .try_inverse()
        .ok_or_else(|| AttitudeError::Singular(format!("H^T Q^-1 H at {xi:?}, p {p:?}")))?;
    Ok(JointEstimate {
        angles: xi,
        parameters: p,
        covariance: 0.5 * (&covariance + covariance.transpose()),
        iterations,
        chi_square,
    })
}
