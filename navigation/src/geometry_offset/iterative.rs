//! Thesis section 4.2.1: Ardalan's iterative attitude correction from the antennas'
//! relative lever coordinates.
//!
//! Three antennas with known body coordinates `r_1^b, r_2^b, r_3^b` whose baselines are
//! not along the body axes (mounting misalignment, antennas at different heights), and
//! the baselines `r_12^l, r_13^l` measured in the l-frame. Frames (thesis fig. 4.2-1):
//! b-frame x starboard, y bow, z up; l-frame east, north, up at antenna 1.
//! `C_l^b = R_y(roll) R_x(pitch) R_z(yaw)` (eq. 4.2-1), `C_b^l` its transpose (eq. 4.2-2).
//! Baseline 12 is the longitudinal one (antenna 2 ahead of antenna 1), 13 the lateral one
//! (antenna 3 to starboard). Yaw turns the bow from north towards west (a heading is
//! `-yaw`).
//!
//! The iteration: roll from the vertical of baseline 13 given pitch (eqs. 4.2-3, 4.2-4,
//! corrected as in 4.2-6, 4.2-10), then pitch from the vertical of baseline 12 given roll
//! (eqs. 4.2-8, 4.2-9, corrected as in 4.2-5, 4.2-7), from pitch 0, until neither changes
//! by more than the tolerance; then yaw from baseline 12 by the LS of the 3 x 2 system of
//! eq. 4.2-11 and `atan2` (eq. 4.2-12).
//!
//! Reconstructed from the garbled OCR and the geometry (row 3 of eq. 4.2-2:
//! `z^l = -s_r c_p x^b + s_p y^b + c_r c_p z^b`):
//!
//! * `z_12''`, `z_13''` in eqs. 4.2-7, 4.2-8, 4.2-10 are the *corrected* l-frame
//!   verticals; `x_12''`, `y_12''`, `z_12''` in eq. 4.2-11 are the *measured* l-frame
//!   components `x_12^l, y_12^l, z_12^l` (only these make eq. 4.2-11 equal to
//!   `r_12^b = C_l^b r_12^l`, which the text names as its origin).
//! * The thesis' corrections are additive and drop the other angle (pitch 0 in eq. 4.2-7,
//!   roll 0 in eq. 4.2-10), and eqs. 4.2-3/4.2-8 divide by the full baseline length (so
//!   eq. 4.2-3 misses the `cos(pitch)` foreshortening of the lateral baseline). Taken
//!   literally, their fixed point is off: in roll by 0.16 deg at 10 deg of pitch and roll
//!   (2 deg misalignment), by 4 deg at 30 deg (5 deg misalignment). Here each step solves
//!   its vertical exactly for its angle, given the other:
//!   `(z_13^l - s_p y_13^b) / c_p = rho_13 sin(a_13 - roll)` with
//!   `rho_13 = |(x_13^b, z_13^b)|`, `a_13 = atan2(z_13^b, x_13^b)`, and
//!   `z_12^l = rho_12 sin(pitch + b_12)` with `u_12 = -s_r x_12^b + c_r z_12^b`,
//!   `rho_12 = |(y_12^b, u_12)|`, `b_12 = atan2(u_12, y_12^b)`. With the baselines in
//!   the thesis' planes (`y_13^b = 0`, `x_12^b = 0`) and the other angle 0 these are
//!   eqs. 4.2-3/4.2-4 and 4.2-8/4.2-9 to the letter (`-a_13` and `b_12` are the
//!   misalignment angles `alpha`); otherwise they agree with the thesis to first order.
//!
//! Validity: the arcsine's principal branch must hold, `|a_13 - roll| < 90 deg` and
//! `|pitch + b_12| < 90 deg`, and the fixed point must attract. The iteration couples
//! the two one-angle equations through the misalignment of baseline 12 and through
//! `tan(pitch) tan(a_13 - roll)`: the tests cover `|pitch|, |roll| < 60 deg` with each
//! baseline turned up to 10 deg about both other body axes (up to about 100 passes), and
//! `< 45 deg` with 15 deg (up to about 45 passes), any yaw; at 60 deg and 15 deg it can
//! oscillate ([`AttitudeError::NotConverged`]). Small misalignments converge in ten or so.
//! Like the thesis' algorithm it estimates no offset: the body levers must be known (the
//! thesis' own criticism, end of section 4.2.1).

use crate::attitude::least_squares::LsConfig;
use crate::attitude::{AttitudeError, BodyGeometry, MIN_BASELINE_SINE};
use nalgebra::{Matrix2, Matrix3x2, Vector3};
use skyforge_orbits::{Mat3, Vec3};

/// Smallest cosine between a baseline and its body axis (baseline 12 and `+y^b`, 13 and
/// `+x^b`): 45 deg of misalignment at most.
const MIN_AXIS_COSINE: f64 = std::f64::consts::FRAC_1_SQRT_2;

/// Largest misfit `|C_l^b r^l - r^b|` accepted after the iteration, relative to the
/// shorter baseline: beyond it the measured baselines do not fit the levers at any
/// attitude in the method's validity range (wrong antenna order, a wrong branch).
const MAX_RELATIVE_MISFIT: f64 = 0.05;

/// Angles of thesis eq. 4.2-1 (rad): `C_l^b = R_y(roll) R_x(pitch) R_z(yaw)`, l-frame ENU,
/// b-frame starboard, bow, up.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct LeverAttitude {
    pub yaw_rad: f64,
    pub pitch_rad: f64,
    pub roll_rad: f64,
}

impl LeverAttitude {
    /// Thesis eq. 4.2-1: `C_l^b` (l-frame ENU components to body components).
    pub fn c_l_b(&self) -> Mat3 {
        let (sy, cy) = self.yaw_rad.sin_cos();
        let (sp, cp) = self.pitch_rad.sin_cos();
        let (sr, cr) = self.roll_rad.sin_cos();
        Mat3::new(
            cr * cy - sr * sp * sy,
            cr * sy + sr * sp * cy,
            -sr * cp,
            -cp * sy,
            cp * cy,
            sp,
            sr * cy + cr * sp * sy,
            sr * sy - cr * sp * cy,
            cr * cp,
        )
    }
}

/// The body lever coordinates of the three antennas, kept as the baselines
/// `r_12^b = r_2^b - r_1^b` and `r_13^b = r_3^b - r_1^b` (m).
#[derive(Debug, Clone, PartialEq)]
pub struct AntennaLevers {
    r12_b: Vec3,
    r13_b: Vec3,
}

impl AntennaLevers {
    /// Check and keep: finite, no two antennas coincident, baselines not collinear
    /// (the checks of [`BodyGeometry`]), baseline 12 within 45 deg of the bow (`+y^b`),
    /// 13 within 45 deg of starboard (`+x^b`).
    pub fn new(r1_b_m: Vec3, r2_b_m: Vec3, r3_b_m: Vec3) -> Result<Self, AttitudeError> {
        let geometry = BodyGeometry::new(&[r2_b_m - r1_b_m, r3_b_m - r1_b_m])?;
        let (r12_b, r13_b) = (geometry.baselines()[0], geometry.baselines()[1]);
        if r12_b.y < MIN_AXIS_COSINE * r12_b.norm() {
            return Err(AttitudeError::Geometry(format!(
                "baseline 12 {r12_b:?} must point within 45 deg of the bow (+y)"
            )));
        }
        if r13_b.x < MIN_AXIS_COSINE * r13_b.norm() {
            return Err(AttitudeError::Geometry(format!(
                "baseline 13 {r13_b:?} must point within 45 deg of starboard (+x)"
            )));
        }
        Ok(Self { r12_b, r13_b })
    }

    /// `r_12^b` (m).
    pub fn r12_b(&self) -> Vec3 {
        self.r12_b
    }

    /// `r_13^b` (m).
    pub fn r13_b(&self) -> Vec3 {
        self.r13_b
    }
}

/// The iterated attitude.
#[derive(Debug, Clone, PartialEq)]
pub struct IterativeSolution {
    /// Yaw in (-pi, pi], pitch and roll in (-pi/2, pi/2).
    pub attitude: LeverAttitude,
    /// Roll/pitch passes (eqs. 4.2-3..4.2-10) until convergence.
    pub iterations: usize,
    /// The larger of `|C_l^b r_12^l - r_12^b|` and `|C_l^b r_13^l - r_13^b|` (m): the
    /// measurement noise, plus model error if the levers are wrong.
    pub misfit_m: f64,
}

/// `asin(x)` with `x` clamped to [-1, 1] (an early iterate's other angle can push a
/// vertical past its baseline's length; a converged attitude that does not fit the levers
/// is refused by [`checked_misfit`]), or an error when `x` is NaN (pitch at +/-90 deg).
fn asin_clamped(x: f64, what: &str) -> Result<f64, AttitudeError> {
    if x.is_nan() {
        Err(AttitudeError::Singular(format!(
            "{what}: vertical / length is not a number (pitch at +/-90 deg?)"
        )))
    } else {
        Ok(x.clamp(-1.0, 1.0).asin())
    }
}

/// Thesis eqs. 4.2-3, 4.2-4 with the correction of eqs. 4.2-6, 4.2-10 (exact form):
/// roll from the vertical `z_13^l` of the lateral baseline, given pitch.
fn roll_from_lateral(r13_b: &Vec3, z13_l: f64, pitch_rad: f64) -> Result<f64, AttitudeError> {
    let (sp, cp) = pitch_rad.sin_cos();
    // The vertical baseline 13 would have at pitch 0: pitch's lever of the bow component
    // removed (eq. 4.2-10) and the cos(pitch) foreshortening undone.
    let z13_corrected = (z13_l - sp * r13_b.y) / cp;
    let rho = r13_b.x.hypot(r13_b.z);
    // Eq. 4.2-4: the lateral baseline's vertical misalignment.
    let alpha = -r13_b.z.atan2(r13_b.x);
    Ok(-asin_clamped(z13_corrected / rho, "roll (baseline 13)")? - alpha)
}

/// Thesis eqs. 4.2-8, 4.2-9 with the correction of eqs. 4.2-5, 4.2-7 (exact form): pitch
/// from the vertical `z_12^l` of the longitudinal baseline, given roll.
fn pitch_from_longitudinal(r12_b: &Vec3, z12_l: f64, roll_rad: f64) -> Result<f64, AttitudeError> {
    let (sr, cr) = roll_rad.sin_cos();
    // Baseline 12's vertical after the roll alone: roll's lever of the starboard
    // component removed (eq. 4.2-7).
    let u12 = -sr * r12_b.x + cr * r12_b.z;
    let rho = r12_b.y.hypot(u12);
    // Eq. 4.2-9: the longitudinal baseline's vertical misalignment.
    let alpha = u12.atan2(r12_b.y);
    Ok(asin_clamped(z12_l / rho, "pitch (baseline 12)")? - alpha)
}

/// Thesis eq. 4.2-11: the 3 x 2 system `A [sin yaw, cos yaw]^T = y` from
/// `r_12^b = C_l^b r_12^l` at known roll and pitch (`r12_l`: measured, ENU).
fn yaw_system(
    r12_b: &Vec3,
    r12_l: &Vec3,
    pitch_rad: f64,
    roll_rad: f64,
) -> (Matrix3x2<f64>, Vector3<f64>) {
    let (sp, cp) = pitch_rad.sin_cos();
    let (sr, cr) = roll_rad.sin_cos();
    let (x, y, z) = (r12_l.x, r12_l.y, r12_l.z);
    let a = Matrix3x2::new(
        -x * sr * sp + y * cr,
        x * cr + y * sr * sp,
        -x * cp,
        y * cp,
        x * cr * sp + y * sr,
        x * sr - y * cr * sp,
    );
    let rhs = Vector3::new(
        r12_b.x + z * sr * cp,
        r12_b.y - z * sp,
        r12_b.z - z * cr * cp,
    );
    (a, rhs)
}

/// Thesis eqs. 4.2-11, 4.2-12: yaw by LS for `a = sin yaw`, `b = cos yaw`, then
/// `atan2(a, b)`. `A^T A = (x_12^l^2 + y_12^l^2) I`, so a baseline 12 within
/// [`MIN_BASELINE_SINE`] of the vertical leaves yaw undetermined (an error).
fn yaw_from_longitudinal(
    r12_b: &Vec3,
    r12_l: &Vec3,
    pitch_rad: f64,
    roll_rad: f64,
) -> Result<f64, AttitudeError> {
    let (a, rhs) = yaw_system(r12_b, r12_l, pitch_rad, roll_rad);
    let normal: Matrix2<f64> = a.transpose() * a;
    if normal.trace() <= 2.0 * (MIN_BASELINE_SINE * r12_l.norm()).powi(2) {
        return Err(AttitudeError::Singular(format!(
            "baseline 12 {r12_l:?} is vertical in the l-frame: yaw is undetermined (eq. 4.2-11)"
        )));
    }
    // A^T A = (x^2 + y^2) I: the LS solution is A^T rhs over half the trace.
    let sol = a.transpose() * rhs / (0.5 * normal.trace());
    Ok(sol[0].atan2(sol[1]))
}

/// Error unless every component of the measured baselines is finite.
fn check_finite(r12_l: &Vec3, r13_l: &Vec3) -> Result<(), AttitudeError> {
    if r12_l.iter().chain(r13_l.iter()).all(|v| v.is_finite()) {
        Ok(())
    } else {
        Err(AttitudeError::Measurement(format!(
            "l-frame baselines are not finite: r12 {r12_l:?}, r13 {r13_l:?}"
        )))
    }
}

/// The attitude of thesis section 4.2.1 from the measured l-frame (ENU at antenna 1)
/// baselines `r_12^l`, `r_13^l` (m). `config`: the roll/pitch tolerance (rad) and the
/// passes allowed ([`AttitudeError::NotConverged`] beyond them); the default's 50 passes
/// cover 45 deg of tilt with 10 deg of misalignment, allow 200 near the validity limits.
pub fn solve(
    levers: &AntennaLevers,
    r12_l_m: &Vec3,
    r13_l_m: &Vec3,
    config: &LsConfig,
) -> Result<IterativeSolution, AttitudeError> {
    config.check()?;
    check_finite(r12_l_m, r13_l_m)?;
    let (mut roll, mut pitch) = (0.0, 0.0);
    let mut last_step = f64::INFINITY;
    for iteration in 1..=config.max_iterations {
        let new_roll = roll_from_lateral(&levers.r13_b, r13_l_m.z, pitch)?;
        let new_pitch = pitch_from_longitudinal(&levers.r12_b, r12_l_m.z, new_roll)?;
        last_step = (new_roll - roll).abs().max((new_pitch - pitch).abs());
        (roll, pitch) = (new_roll, new_pitch);
        if last_step < config.tolerance_rad {
            let yaw = yaw_from_longitudinal(&levers.r12_b, r12_l_m, pitch, roll)?;
            let attitude = LeverAttitude {
                yaw_rad: yaw,
                pitch_rad: pitch,
                roll_rad: roll,
            };
            let misfit_m = checked_misfit(levers, &attitude, r12_l_m, r13_l_m)?;
            return Ok(IterativeSolution {
                attitude,
                iterations: iteration,
                misfit_m,
            });
        }
    }
    Err(AttitudeError::NotConverged {
        iterations: config.max_iterations,
        last_step_rad: last_step,
    })
}

/// The misfit of [`IterativeSolution::misfit_m`], or an error above
/// [`MAX_RELATIVE_MISFIT`] of the shorter baseline.
fn checked_misfit(
    levers: &AntennaLevers,
    attitude: &LeverAttitude,
    r12_l: &Vec3,
    r13_l: &Vec3,
) -> Result<f64, AttitudeError> {
    let c = attitude.c_l_b();
    let misfit = (c * r12_l - levers.r12_b)
        .norm()
        .max((c * r13_l - levers.r13_b).norm());
    let limit = MAX_RELATIVE_MISFIT * levers.r12_b.norm().min(levers.r13_b.norm());
    if misfit <= limit {
        Ok(misfit)
    } else {
        Err(AttitudeError::Measurement(format!(
            "the measured baselines miss the levers by {misfit} m at the iterated attitude {attitude:?} (limit {limit} m)"
        )))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The thesis' literal eqs. 4.2-3/4.2-4 (roll at pitch 0) and 4.2-8/4.2-9 (pitch at
    /// roll 0, uncorrected) for baselines in the thesis' planes.
    #[test]
    fn steps_are_the_thesis_formulas_for_in_plane_baselines_at_zero_other_angle() {
        let r13 = Vec3::new(1.3, 0.0, 0.07);
        let l13 = r13.norm();
        for z in [-0.4, 0.02, 0.9] {
            let thesis = -(z / l13).asin() + (r13.z / l13).asin();
            assert!((roll_from_lateral(&r13, z, 0.0).unwrap() - thesis).abs() < 1e-15);
        }
        let r12 = Vec3::new(0.0, 2.1, -0.05);
        let l12 = r12.norm();
        for z in [-0.7, 0.0, 1.5] {
            let thesis = (z / l12).asin() - (r12.z / l12).asin();
            assert!((pitch_from_longitudinal(&r12, z, 0.0).unwrap() - thesis).abs() < 1e-15);
        }
    }

    /// Eqs. 4.2-3..4.2-10 taken literally (additive corrections, full lengths), iterated
    /// to their fixed point: (pitch, roll).
    fn literal_thesis_iteration(r12: &Vec3, r13: &Vec3, z12_l: f64, z13_l: f64) -> (f64, f64) {
        let (l12, l13) = (r12.norm(), r13.norm());
        let (mut pitch, mut roll) = (0.0f64, 0.0f64);
        for _ in 0..200 {
            let z13c = z13_l - r13.z * (pitch.cos() - 1.0) - r13.y * pitch.sin();
            roll = -(z13c / l13).asin() + (r13.z / l13).asin();
            let z12c = z12_l - r12.z * (roll.cos() - 1.0) + r12.x * roll.sin();
            pitch = (z12c / l12).asin() - (r12.z / l12).asin();
        }
        (pitch, roll)
    }

    /// The figures of the module documentation: the literal equations' roll is off by
    /// 0.16 deg at 10 deg tilt (2 deg misalignment) and 4.3 deg at 30 deg (5 deg); the
    /// exact steps are not.
    #[test]
    fn literal_thesis_corrections_are_biased_where_the_exact_steps_are_not() {
        for (tilt_deg, mis_deg, roll_err_deg) in [(10.0f64, 2.0f64, 0.158), (30.0, 5.0, 4.35)] {
            let (tilt, mis) = (tilt_deg.to_radians(), mis_deg.to_radians());
            let r12 = Vec3::new(2.0 * mis.sin(), 2.0 * mis.cos(), 0.1);
            let r13 = Vec3::new(1.2, 1.2 * mis.sin(), -0.08);
            let truth = LeverAttitude {
                yaw_rad: 0.4,
                pitch_rad: tilt,
                roll_rad: -tilt,
            };
            let c_b_l = truth.c_l_b().transpose();
            let (r12_l, r13_l) = (c_b_l * r12, c_b_l * r13);
            let (_, roll) = literal_thesis_iteration(&r12, &r13, r12_l.z, r13_l.z);
            let err = (roll - truth.roll_rad).to_degrees();
            assert!((err - roll_err_deg).abs() < 0.01, "{err}");
            let levers = AntennaLevers::new(Vec3::zeros(), r12, r13).unwrap();
            let exact = solve(&levers, &r12_l, &r13_l, &LsConfig::default()).unwrap();
            assert!((exact.attitude.roll_rad - truth.roll_rad).abs() < 1e-12);
        }
    }

    #[test]
    fn yaw_system_is_c_l_b_applied_to_baseline_12() {
        let att = LeverAttitude {
            yaw_rad: 2.0,
            pitch_rad: -0.4,
            roll_rad: 0.7,
        };
        let r12_l = Vec3::new(0.3, -1.1, 0.25);
        let r12_b = att.c_l_b() * r12_l;
        let (a, rhs) = yaw_system(&r12_b, &r12_l, att.pitch_rad, att.roll_rad);
        let ab = nalgebra::Vector2::new(att.yaw_rad.sin(), att.yaw_rad.cos());
        assert!((a * ab - rhs).amax() < 1e-15);
    }
}
