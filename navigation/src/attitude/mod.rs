//! Attitude from baseline vectors: thesis section 2.5 (frames, LS, KF) and section 4.3.2
//! (the 6-state UKF with attitude rates).
//!
//! Inputs are the fixed (integer-ambiguity) baseline vectors of one epoch in the reference
//! frame (NED, thesis eq. 2.5-7: `B_NED = R(xi) B_0`) with their covariance `Q_BB_NED`,
//! and the body-frame baseline geometry `B_0`. The attitude matrix `R(xi)` and the angles
//! `xi = [yaw, pitch, roll]` are [`YawPitchRoll`] of `skyforge-orbits` (eqs. 2.5-3..2.5-6,
//! `R(xi)` = [`YawPitchRoll::c_body_ref`]).
//!
//! * [`frames`]: baselines and covariance from ECEF to the reference frame (eqs. 2.4-66,
//!   2.4-67).
//! * [`jacobian`]: `J(xi) = d vec(R(xi)) / d xi` (eq. 2.5-10) and the linear map
//!   `h = B_0^T (x) I_3` (eq. 2.5-8).
//! * [`wahba`]: the closed-form optimal rotation (Markley's SVD solution of Wahba's
//!   problem), the start value of the LS and its oracle.
//! * [`least_squares`]: the iterated LS of eqs. 2.5-9..2.5-13.
//! * [`unscented`]: a generic unscented transform (eqs. 4.3-18..4.3-24).
//! * [`filter`]: the [`filter::AttitudeFilter`] trait, the serde configuration that
//!   chooses `least-squares | kf | ukf`, and the process model shared by both filters
//!   (eqs. 2.5-16, 4.3-28..4.3-30).
//! * [`kalman`]: the real-time KF of eqs. 2.5-16, 2.5-17 (an EKF: the measurement is
//!   linearised with `J(xi)`).
//! * [`ukf`]: the UKF of eqs. 4.3-16..4.3-32.

pub(crate) mod config;
pub(crate) mod filter;
pub(crate) mod frames;
pub(crate) mod jacobian;
pub(crate) mod kalman;
pub mod least_squares;
mod ls_stage;
pub(crate) mod ukf;
pub(crate) mod unscented;
pub(crate) mod wahba;

pub use config::{AttitudeConfig, AttitudeMethod, THESIS_KAPPA};
pub use filter::{AttitudeFilter, FilterInit, process_noise, transition};
pub use frames::ned_baselines_from_ecef;
pub use jacobian::vec_r_jacobian;
pub use kalman::EkfAttitude;
pub use ls_stage::LeastSquaresStage;
use nalgebra::{DMatrix, DVector, Matrix3};
use skyforge_orbits::Vec3;
pub use skyforge_orbits::frames::YawPitchRoll;
pub use ukf::UkfAttitude;

/// Shortest body-frame baseline accepted (m): anything shorter is treated as zero.
pub const MIN_BASELINE_M: f64 = 1e-4;
/// Longest baseline accepted (m).
// assumed: 100 000 km, SkyForge's largest apogee radius: baselines here are antennas on
// one body (the thesis's 1 m) but also stations kilometres apart (relative positioning,
// GeoNet), and any two receivers SkyForge simulates are closer; a 1e300 m antenna was
// reported as "collinear".
pub const MAX_BASELINE_M: f64 = 1.0e8;

/// Whether `v` reaches beyond [`MAX_BASELINE_M`], component by component first (the norm
/// of a 1e300 m vector overflows).
pub(crate) fn beyond_max_baseline(v: &Vec3) -> bool {
    v.amax() > MAX_BASELINE_M || v.norm() > MAX_BASELINE_M
}
/// Smallest sine of the angle between two body baselines for a geometry to count as not
/// collinear (1e-3: 0.06 deg; the roll about a nearly common axis then has a variance
/// about 1e6 times that of the other angles, which is no attitude any more).
pub const MIN_BASELINE_SINE: f64 = 1e-3;
/// Relative asymmetry of a covariance matrix tolerated (|Q - Q^T| / max|Q|).
const SYMMETRY_TOLERANCE: f64 = 1e-9;

/// Why an attitude could not be computed. Never a panic: every input-dependent failure is
/// one of these.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum AttitudeError {
    /// The body-frame geometry `B_0` is unusable.
    #[error("body geometry: {0}")]
    Geometry(String),
    /// Measured baselines or covariance not finite, or of the wrong size.
    #[error("baseline measurement: {0}")]
    Measurement(String),
    /// Geometry and measurement disagree in the number of baselines.
    #[error("{geometry} body baselines but {measured} measured baselines")]
    BaselineCount { geometry: usize, measured: usize },
    /// A covariance matrix is not symmetric positive definite.
    #[error("covariance: {0}")]
    Covariance(String),
    /// The LS (eqs. 2.5-9..2.5-13) cannot determine three angles from one baseline.
    #[error(
        "one baseline fixes only two of the three angles (the rotation about the baseline is unobservable); the least-squares attitude needs at least two non-collinear baselines, a filter can use one with a prior"
    )]
    SingleBaseline,
    /// The Gauss-Newton iteration did not converge.
    #[error(
        "least squares did not converge in {iterations} iterations (last step {last_step_rad:e} rad)"
    )]
    NotConverged {
        iterations: usize,
        last_step_rad: f64,
    },
    /// A normal matrix or innovation covariance could not be inverted.
    #[error("singular: {0}")]
    Singular(String),
    /// A filter was used before it had a state, or its covariance lost definiteness.
    #[error("filter: {0}")]
    Filter(String),
    /// Bad configuration value.
    #[error("attitude config: {0}")]
    Config(String),
}

/// The body-frame baselines `B_0` (3 x m, thesis eq. 2.5-7), m >= 1, metres. Validated:
/// finite, each at least [`MIN_BASELINE_M`] and at most [`MAX_BASELINE_M`] long and, for m >= 2, not all collinear (some
/// pair at least [`MIN_BASELINE_SINE`] apart).
#[derive(Debug, Clone, PartialEq)]
pub struct BodyGeometry {
    baselines: Vec<Vec3>,
}

impl BodyGeometry {
    /// Check and keep the body baselines (columns of `B_0`).
    pub fn new(baselines_body_m: &[Vec3]) -> Result<Self, AttitudeError> {
        if baselines_body_m.is_empty() {
            return Err(AttitudeError::Geometry("no baselines".into()));
        }
        for (i, b) in baselines_body_m.iter().enumerate() {
            if !b.iter().all(|v| v.is_finite()) {
                return Err(AttitudeError::Geometry(format!(
                    "baseline {} is not finite: {b:?}",
                    i + 1
                )));
            }
            if b.norm() < MIN_BASELINE_M {
                return Err(AttitudeError::Geometry(format!(
                    "baseline {} is {} m long, shorter than {MIN_BASELINE_M} m",
                    i + 1,
                    b.norm()
                )));
            }
            if beyond_max_baseline(b) {
                return Err(AttitudeError::Geometry(format!(
                    "baseline {} {:?} is longer than {MAX_BASELINE_M:e} m",
                    i + 1,
                    [b.x, b.y, b.z]
                )));
            }
        }
        if baselines_body_m.len() >= 2 {
            let max_sine = baselines_body_m
                .iter()
                .enumerate()
                .flat_map(|(i, a)| {
                    baselines_body_m[i + 1..]
                        .iter()
                        .map(move |b| a.cross(b).norm() / (a.norm() * b.norm()))
                })
                .fold(0.0, f64::max);
            if max_sine < MIN_BASELINE_SINE {
                return Err(AttitudeError::Geometry(format!(
                    "the {} baselines are collinear (largest sine between two is {max_sine:e}, at least {MIN_BASELINE_SINE} needed)",
                    baselines_body_m.len()
                )));
            }
        }
        Ok(Self {
            baselines: baselines_body_m.to_vec(),
        })
    }

    /// The baselines (columns of `B_0`), body frame, m.
    pub fn baselines(&self) -> &[Vec3] {
        &self.baselines
    }

    /// The number of baselines m.
    pub fn len(&self) -> usize {
        self.baselines.len()
    }

    /// Always false (a geometry has at least one baseline); for clippy's `len` rule.
    pub fn is_empty(&self) -> bool {
        self.baselines.is_empty()
    }

    /// The columns of `R(xi) B_0`: the baselines the attitude `xi` gives in the reference
    /// frame, eqs. 2.5-7, 2.5-8.
    pub fn in_reference(&self, angles: &YawPitchRoll) -> Vec<Vec3> {
        let r = angles.c_body_ref();
        self.baselines.iter().map(|b| r * b).collect()
    }

    /// `vec(R(xi) B_0)` (3m): the baselines the attitude `xi` predicts in the reference
    /// frame, eqs. 2.5-7, 2.5-8, 4.3-32.
    pub fn predict(&self, angles: &YawPitchRoll) -> DVector<f64> {
        DVector::from_iterator(
            3 * self.len(),
            self.in_reference(angles)
                .into_iter()
                .flat_map(|v| [v.x, v.y, v.z]),
        )
    }

    /// Error unless `b` has as many baselines as this geometry.
    /// The baselines' lengths (m).
    pub fn lengths_m(&self) -> Vec<f64> {
        self.baselines().iter().map(|b| b.norm()).collect()
    }

    pub(crate) fn check_count(&self, b: &NedBaselines) -> Result<(), AttitudeError> {
        if b.len() == self.len() {
            Ok(())
        } else {
            Err(AttitudeError::BaselineCount {
                geometry: self.len(),
                measured: b.len(),
            })
        }
    }
}

/// Measured baselines in the reference frame (NED for a ground receiver, or the orbital
/// frame, thesis section 2.5.1) with their covariance `Q_BB` (3m x 3m, m^2) in `vec()`
/// order: baseline 1's N, E, D, then baseline 2's, ...
#[derive(Debug, Clone, PartialEq)]
pub struct NedBaselines {
    baselines: Vec<Vec3>,
    covariance: DMatrix<f64>,
}

impl NedBaselines {
    /// Check and keep: at least one baseline, every value finite, the covariance 3m x 3m,
    /// symmetric and positive definite.
    pub fn new(
        baselines_ned_m: &[Vec3],
        covariance_m2: DMatrix<f64>,
    ) -> Result<Self, AttitudeError> {
        let m = baselines_ned_m.len();
        if m == 0 {
            return Err(AttitudeError::Measurement("no baselines".into()));
        }
        check_finite(baselines_ned_m)?;
        check_covariance(&covariance_m2, 3 * m, "Q_BB")?;
        Ok(Self {
            baselines: baselines_ned_m.to_vec(),
            covariance: covariance_m2,
        })
    }

    /// Other baselines of the same number with this covariance (already checked: only
    /// the baselines are).
    pub fn with_baselines(&self, baselines_ned_m: &[Vec3]) -> Result<Self, AttitudeError> {
        if baselines_ned_m.len() != self.baselines.len() {
            return Err(AttitudeError::Measurement(format!(
                "{} baselines for a covariance of {}",
                baselines_ned_m.len(),
                self.baselines.len()
            )));
        }
        check_finite(baselines_ned_m)?;
        Ok(Self {
            baselines: baselines_ned_m.to_vec(),
            covariance: self.covariance.clone(),
        })
    }

    /// The baselines (m).
    pub fn baselines(&self) -> &[Vec3] {
        &self.baselines
    }

    /// Their covariance `Q_BB` (m^2, `vec()` order).
    pub fn covariance(&self) -> &DMatrix<f64> {
        &self.covariance
    }

    /// `vec(B)`: the baselines stacked (3m).
    pub fn vec(&self) -> DVector<f64> {
        DVector::from_iterator(
            3 * self.len(),
            self.baselines.iter().flat_map(|b| [b.x, b.y, b.z]),
        )
    }

    /// The number of baselines m.
    pub fn len(&self) -> usize {
        self.baselines.len()
    }

    /// Always false (at least one baseline); for clippy's `len` rule.
    pub fn is_empty(&self) -> bool {
        self.baselines.is_empty()
    }
}

/// Error unless `q` is `n` x `n`, finite, symmetric (relative [`SYMMETRY_TOLERANCE`]) and
/// positive definite (its Cholesky factor exists).
/// Every baseline finite; the first that is not, named.
fn check_finite(baselines_m: &[Vec3]) -> Result<(), AttitudeError> {
    match baselines_m
        .iter()
        .position(|b| !b.iter().all(|v| v.is_finite()))
    {
        Some(i) => Err(AttitudeError::Measurement(format!(
            "baseline {} is not finite: {:?}",
            i + 1,
            baselines_m[i]
        ))),
        None => Ok(()),
    }
}

pub(crate) fn check_covariance(
    q: &DMatrix<f64>,
    n: usize,
    what: &str,
) -> Result<(), AttitudeError> {
    if q.nrows() != n || q.ncols() != n {
        return Err(AttitudeError::Measurement(format!(
            "{what} is {}x{}, expected {n}x{n}",
            q.nrows(),
            q.ncols()
        )));
    }
    if !q.iter().all(|v| v.is_finite()) {
        return Err(AttitudeError::Measurement(format!("{what} is not finite")));
    }
    let scale = q.amax();
    if (q - q.transpose()).amax() > SYMMETRY_TOLERANCE * scale {
        return Err(AttitudeError::Covariance(format!(
            "{what} is not symmetric"
        )));
    }
    if q.clone().cholesky().is_none() {
        return Err(AttitudeError::Covariance(format!(
            "{what} is not positive definite"
        )));
    }
    Ok(())
}

/// One epoch's attitude from the LS of eqs. 2.5-9..2.5-13.
#[derive(Debug, Clone, PartialEq)]
pub struct AttitudeEstimate {
    /// The angles; yaw and roll in (-pi, pi], pitch in [-pi/2, pi/2].
    pub angles: YawPitchRoll,
    /// Their covariance (rad^2, order yaw, pitch, roll), eq. 2.5-13.
    pub covariance: Matrix3<f64>,
    /// Gauss-Newton iterations used.
    pub iterations: usize,
    /// Post-fit residuals `vec(B) - vec(R(xi) B_0)` (m, 3m).
    pub residual_m: DVector<f64>,
    /// `r^T Q_BB^-1 r`: chi-square with 3m - 3 degrees of freedom when `Q_BB` is right.
    pub chi_square: f64,
}

/// `a - b` wrapped into [-pi, pi): the difference of two angles (rad), e.g. a yaw error
/// across +/-180 deg.
pub fn wrap_diff(a_rad: f64, b_rad: f64) -> f64 {
    wrap_pi(a_rad - b_rad)
}

pub use skyforge_orbits::angles::wrap_pi;

/// The stage `config.method` with the body geometry `geometry`, no initial state.
pub fn build(
    config: &AttitudeConfig,
    geometry: BodyGeometry,
) -> Result<Box<dyn AttitudeFilter>, AttitudeError> {
    config.check()?;
    Ok(match config.method {
        AttitudeMethod::LeastSquares => {
            Box::new(LeastSquaresStage::new(config.least_squares, geometry)?)
        }
        AttitudeMethod::Kf => Box::new(EkfAttitude::new(config, geometry, None)?),
        AttitudeMethod::Ukf => Box::new(UkfAttitude::new(config, geometry, None)?),
    })
}

/// The angle errors `est - truth` (yaw, pitch, roll; rad), each wrapped into [-pi, pi).
pub fn angle_error(est: &YawPitchRoll, truth: &YawPitchRoll) -> Vec3 {
    Vec3::new(
        wrap_diff(est.yaw_rad, truth.yaw_rad),
        wrap_diff(est.pitch_rad, truth.pitch_rad),
        wrap_diff(est.roll_rad, truth.roll_rad),
    )
}
