//! The book's position filter (section 5.5.4, eqs. 5-36..5-40): a Kalman filter whose
//! measurements are single-point fixes and whose dynamics are the Hill equations about a
//! circular reference orbit through the current estimate, with J2 and drag as a constant
//! input over each step.
//!
//! Per step (book algorithm, L5797-5813):
//! 1. The reference circle through the estimate: radius `R = |r|`, `n = sqrt(mu / R^3)`,
//!    refreshed at every step (the book leaves the interval open).
//! 2. The state relative to it in the target orbit frame (x along-track, y negative orbit
//!    normal, z nadir; `orbits::frames::c_orbital_eci`) is propagated with `Phi` and
//!    `Gamma` of eq. 5-34 ([`super::clohessy_wiltshire`]), `U` the J2 (eq. 5-38, its
//!    z-term read as `(3 - 5 sin^2 B) Z / R`, which the OCR garbled) and drag (eq. 5-37,
//!    `k = Cd A / m`, the exponential atmosphere) accelerations in that frame (eq. 5-39),
//!    held over the step at the mean of their values at its two ends (the book holds the
//!    start's; see `predict`).
//! 3. The fix (ECEF, converted to ECI with the Earth rotation a receiver knows) updates
//!    the estimate (eq. 5-40). Eq. 5-40d prints `- Q_k` where the derivation needs
//!    `+ Gamma Q Gamma^T`; the latter is used.
//!
//! The covariance is carried in ECI (position, inertial velocity) and mapped into each
//! step's orbit frame and back, so refreshing the reference never loses it. The
//! measurement noise is `R_k = GDOP^2 R_0` (the book prints `GDOP R_0`; a variance scales
//! with the square of the dilution).

use super::clohessy_wiltshire::{input, transition};
use nalgebra::{Matrix3, Matrix6, Vector3, Vector6};
use skyforge_orbits::frames::c_orbital_eci;
use skyforge_orbits::frames::earth_rotation::EarthRotation;
use skyforge_orbits::propagate::{ForceModel, ForceModelConfig};
use skyforge_orbits::{Mat3, Vec3};

/// The filter's settings; every default is an assumption a user can change.
#[derive(Debug, Clone, PartialEq, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct PositionFilterConfig {
    /// The filter's force model beyond the point mass (the book: J2 and drag only).
    /// # assumed: J2..J6 and the exponential drag of the default spacecraft: without
    /// J3..J6 a LEO's filter is off by about 1e-4 m/s^2 at times, metres over its memory
    /// (docs/orbit-determination.md).
    #[serde(default = "default_forces")]
    pub forces: ForceModelConfig,
    /// 1-sigma error of one fix coordinate at GDOP 1 (m): `R_0`'s position part.
    /// # assumed: 3 m, a single-frequency fix without SA (UERE of a few metres over
    /// sqrt(3) and more); B-5.5's SA-era value is 18.6 m.
    #[serde(default = "default_position_sigma_m")]
    pub position_sigma_m: f64,
    /// 1-sigma error of one fix velocity coordinate at GDOP 1 (m/s).
    /// # assumed: 0.05 m/s, a Doppler velocity without SA.
    #[serde(default = "default_velocity_sigma_mps")]
    pub velocity_sigma_mps: f64,
    /// 1-sigma error of the input acceleration per axis, held over a step (m/s^2): `Q`.
    /// # assumed: 1e-5 m/s^2, B-5.5's (the unmodelled forces of a LEO: higher zonals,
    /// drag's error, are of this order).
    #[serde(default = "default_acceleration_sigma_mps2")]
    pub acceleration_sigma_mps2: f64,
}

fn default_forces() -> ForceModelConfig {
    ForceModelConfig {
        higher_zonals: true,
        ..ForceModelConfig::default()
    }
}
fn default_position_sigma_m() -> f64 {
    3.0
}
fn default_velocity_sigma_mps() -> f64 {
    0.05
}
fn default_acceleration_sigma_mps2() -> f64 {
    1e-5
}

impl Default for PositionFilterConfig {
    fn default() -> Self {
        Self {
            forces: default_forces(),
            position_sigma_m: default_position_sigma_m(),
            velocity_sigma_mps: default_velocity_sigma_mps(),
            acceleration_sigma_mps2: default_acceleration_sigma_mps2(),
        }
    }
}

impl PositionFilterConfig {
    /// Whether the values are usable: the sigmas positive and finite, the spacecraft's
    /// drag parameters physical.
    pub fn check(&self) -> Result<(), String> {
        crate::config_file::check_positive(&[
            ("position_sigma_m", self.position_sigma_m, 1e6),
            ("velocity_sigma_mps", self.velocity_sigma_mps, 1e4),
            ("acceleration_sigma_mps2", self.acceleration_sigma_mps2, 1.0),
        ])?;
        check_forces(&self.forces)
    }
}

/// Whether a filter's spacecraft drag parameters are physical.
pub(crate) fn check_forces(f: &ForceModelConfig) -> Result<(), String> {
    crate::config_file::check_positive(&[
        ("forces.drag_coefficient", f.drag_coefficient, 1e6),
        ("forces.area_m2", f.area_m2, 1e6),
        ("forces.mass_kg", f.mass_kg, 1e6),
    ])
}

/// One single-point fix as the filter takes it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FixInput {
    /// Seconds since the start of the run (GPST).
    pub t_s: f64,
    pub r_ecef_m: Vec3,
    /// The fix's velocity, where the receiver solved one.
    pub v_ecef_mps: Option<Vec3>,
    /// Geometric dilution of precision of the fix.
    pub gdop: f64,
}

/// The filter's estimate after a fix.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OrbitEstimate {
    pub t_s: f64,
    pub r_eci_m: Vec3,
    pub v_eci_mps: Vec3,
    /// Covariance of `[r_eci, v_eci]`.
    pub covariance: Matrix6<f64>,
}

/// The book's position filter.
#[derive(Debug, Clone)]
pub struct PositionFilter {
    config: PositionFilterConfig,
    earth: EarthRotation,
    forces: ForceModel,
    estimate: Option<OrbitEstimate>,
}

/// `[a]x`, the cross-product matrix.
pub(crate) fn cross_matrix(a: &Vec3) -> Mat3 {
    Mat3::new(0.0, -a.z, a.y, a.z, 0.0, -a.x, -a.y, a.x, 0.0)
}

/// The Jacobian of the absolute state `[r, v]` (ECI) with respect to the relative state
/// in an orbit frame `c` (columns: its axes in ECI) rotating at `omega` (ECI):
/// `r = r_ref + c dr`, `v = omega x r + c dv`.
fn relative_to_absolute(c: &Mat3, omega: &Vec3) -> Matrix6<f64> {
    let mut j = Matrix6::zeros();
    j.fixed_view_mut::<3, 3>(0, 0).copy_from(c);
    j.fixed_view_mut::<3, 3>(3, 0)
        .copy_from(&(cross_matrix(omega) * c));
    j.fixed_view_mut::<3, 3>(3, 3).copy_from(c);
    j
}

/// The rotation by `angle` about the unit vector `axis`.
fn rotation(axis: &Vec3, angle: f64) -> Mat3 {
    *nalgebra::Rotation3::from_axis_angle(&nalgebra::Unit::new_normalize(*axis), angle).matrix()
}

impl PositionFilter {
    /// A filter for a run starting at `start` (its Earth rotation converts the fixes).
    pub fn new(config: PositionFilterConfig, start: hifitime::Epoch) -> Self {
        // The exponential atmosphere needs neither the date nor the inclination.
        let forces = ForceModel::new(&config.forces, start, 0.0);
        Self {
            config,
            earth: EarthRotation::at_origin(start),
            forces,
            estimate: None,
        }
    }

    /// The J2 and drag accelerations (m/s^2, ECI) of the filter's model at `r`, `v`.
    fn perturbation(&self, t_s: f64, r: &Vec3, v: &Vec3) -> Vec3 {
        let point_mass = -r * (self.forces.gm() / r.norm().powi(3));
        self.forces.gravity_eci(r) - point_mass + self.forces.drag_eci(t_s, r, v)
    }

    /// The fix in ECI as a state `[r, v]` (a fix without velocity at rest in the
    /// Earth-fixed frame), the variances `R_k` of what it measures and the rows of the
    /// state those are.
    fn measurement(&self, fix: &FixInput) -> (Vector6<f64>, Vec<f64>, Vec<usize>) {
        let v_ecef = fix.v_ecef_mps.unwrap_or_else(Vec3::zeros);
        let (r, v) = self.earth.ecef_to_eci(fix.t_s, &fix.r_ecef_m, &v_ecef);
        let g2 = fix.gdop * fix.gdop;
        let sr = g2 * self.config.position_sigma_m.powi(2);
        let sv = g2 * self.config.velocity_sigma_mps.powi(2);
        let state = Vector6::from_iterator(r.iter().chain(v.iter()).copied());
        if fix.v_ecef_mps.is_some() {
            (state, vec![sr, sr, sr, sv, sv, sv], (0..6).collect())
        } else {
            (state, vec![sr; 3], vec![0, 1, 2])
        }
    }

    /// Predict the estimate to `t_s` (book eqs. 5-34, 5-39, 5-40d).
    pub fn predict(&self, e: &OrbitEstimate, t_s: f64) -> OrbitEstimate {
        let dt = t_s - e.t_s;
        let (r, v) = (e.r_eci_m, e.v_eci_mps);
        let mu = self.forces.gm();
        let n = (mu / r.norm().powi(3)).sqrt();
        let c = c_orbital_eci(&r, &v);
        let normal = r.cross(&v).normalize();
        let omega = normal * n;
        // Relative state at the start of the step: on the reference point, moving with
        // the velocity's difference from the rotating frame's.
        let rel = Vector6::from_iterator(
            Vec3::zeros()
                .iter()
                .copied()
                .chain((c.transpose() * (v - omega.cross(&r))).iter().copied()),
        );
        let (phi, gamma) = (transition(n, dt), input(n, dt));
        let turn = rotation(&normal, n * dt);
        let c1 = turn * c;
        // The relative state after the step under input `u`, and the absolute state.
        let step = |u: &Vec3| {
            let rel1 = phi * rel + gamma * Vector3::from(*u);
            let r1 = turn * r + c1 * rel1.fixed_rows::<3>(0);
            let v1 = omega.cross(&r1) + c1 * rel1.fixed_rows::<3>(3);
            (r1, v1)
        };
        // U held over the step (eq. 5-39), as the mean of its values in the rotating
        // frame at the two ends (the end from a first pass with the start's): holding the
        // start's alone misses J2's change over a 60 s step, about 6e-4 m/s^2, and puts
        // the prediction 1 m off.
        let u0 = c.transpose() * self.perturbation(e.t_s, &r, &v);
        let (r_first, v_first) = step(&u0);
        let u1 = c1.transpose() * self.perturbation(t_s, &r_first, &v_first);
        let (r1, v1) = step(&((u0 + u1) * 0.5));
        // Covariance: absolute -> relative (start frame), propagate, relative -> absolute
        // (end frame).
        let j0 = relative_to_absolute(&c, &omega);
        let j1 = relative_to_absolute(&c1, &omega);
        let j0_inv = j0.try_inverse().unwrap_or_else(Matrix6::identity);
        let p_rel = j0_inv * e.covariance * j0_inv.transpose();
        let q = Matrix3::identity() * self.config.acceleration_sigma_mps2.powi(2);
        let p_rel1 = phi * p_rel * phi.transpose() + gamma * q * gamma.transpose();
        OrbitEstimate {
            t_s,
            r_eci_m: r1,
            v_eci_mps: v1,
            covariance: j1 * p_rel1 * j1.transpose(),
        }
    }

    /// Take one fix (fixes in time order); the estimate after it.
    pub fn update(&mut self, fix: &FixInput) -> OrbitEstimate {
        let (measured, var, rows) = self.measurement(fix);
        let z: Vec<f64> = rows.iter().map(|&i| measured[i]).collect();
        let predicted = match &self.estimate {
            Some(e) => self.predict(e, fix.t_s),
            None => {
                // The first fix initialises the filter (without a measured velocity: at
                // rest in the Earth-fixed frame, with an uninformative variance).
                let r = Vec3::new(measured[0], measured[1], measured[2]);
                let v = Vec3::new(measured[3], measured[4], measured[5]);
                let mut p = Matrix6::zeros();
                for (i, row) in rows.iter().enumerate() {
                    p[(*row, *row)] = var[i];
                }
                for row in 0..6 {
                    if p[(row, row)] == 0.0 {
                        // No measured velocity: 1 km/s, uninformative.
                        p[(row, row)] = 1e6;
                    }
                }
                let estimate = OrbitEstimate {
                    t_s: fix.t_s,
                    r_eci_m: r,
                    v_eci_mps: v,
                    covariance: p,
                };
                self.estimate = Some(estimate);
                return estimate;
            }
        };
        let x = Vector6::from_iterator(
            predicted
                .r_eci_m
                .iter()
                .chain(predicted.v_eci_mps.iter())
                .copied(),
        );
        let m = rows.len();
        let mut h = nalgebra::DMatrix::<f64>::zeros(m, 6);
        for (i, row) in rows.iter().enumerate() {
            h[(i, *row)] = 1.0;
        }
        let p = nalgebra::DMatrix::from_iterator(6, 6, predicted.covariance.iter().copied());
        let r_k = nalgebra::DMatrix::from_diagonal(&nalgebra::DVector::from_vec(var));
        let s = &h * &p * h.transpose() + &r_k;
        let Some(s_inv) = s.try_inverse() else {
            self.estimate = Some(predicted);
            return predicted;
        };
        let k = &p * h.transpose() * s_inv;
        let xd = nalgebra::DVector::from_iterator(6, x.iter().copied());
        let innovation = nalgebra::DVector::from_vec(z) - &h * &xd;
        let x1 = xd + &k * innovation;
        // Joseph form (book eq. 5-40c, kept symmetric and positive).
        let i_kh = nalgebra::DMatrix::<f64>::identity(6, 6) - &k * &h;
        let p1 = &i_kh * p * i_kh.transpose() + &k * r_k * k.transpose();
        let estimate = OrbitEstimate {
            t_s: fix.t_s,
            r_eci_m: Vec3::new(x1[0], x1[1], x1[2]),
            v_eci_mps: Vec3::new(x1[3], x1[4], x1[5]),
            covariance: Matrix6::from_iterator(p1.iter().copied()),
        };
        self.estimate = Some(estimate);
        estimate
    }

    /// An estimate in the Earth-fixed frame: position and velocity (ECEF).
    pub fn to_ecef(&self, e: &OrbitEstimate) -> (Vec3, Vec3) {
        self.earth.eci_to_ecef(e.t_s, &e.r_eci_m, &e.v_eci_mps)
    }

    /// An estimate in the Earth-fixed frame with its covariance ([`ecef_estimate`]).
    pub fn to_ecef_estimate(&self, e: &OrbitEstimate) -> EcefEstimate {
        ecef_estimate(&self.earth, e.t_s, &e.r_eci_m, &e.v_eci_mps, &e.covariance)
    }
}

/// An ECI state `[r, v]` at `t_s` with its covariance in the Earth-fixed frame:
/// `P_ecef = J P J^T`, `J = [[C, 0], [-[w]x C, C]]` the Jacobian of `r_e = C r`,
/// `v_e = C v - w x C r`.
pub(crate) fn ecef_estimate(
    earth: &EarthRotation,
    t_s: f64,
    r_eci_m: &Vec3,
    v_eci_mps: &Vec3,
    covariance: &Matrix6<f64>,
) -> EcefEstimate {
    let (r_ecef_m, v_ecef_mps) = earth.eci_to_ecef(t_s, r_eci_m, v_eci_mps);
    let c = earth.c_eci_ecef(t_s);
    let mut j = Matrix6::zeros();
    j.fixed_view_mut::<3, 3>(0, 0).copy_from(&c);
    j.fixed_view_mut::<3, 3>(3, 0)
        .copy_from(&(-cross_matrix(&earth.omega_rad_s()) * c));
    j.fixed_view_mut::<3, 3>(3, 3).copy_from(&c);
    EcefEstimate {
        t_s,
        r_ecef_m,
        v_ecef_mps,
        covariance: j * covariance * j.transpose(),
    }
}

/// An estimate in the Earth-fixed frame (what `skyforge od` writes).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EcefEstimate {
    /// Seconds since the start of the run (GPST).
    pub t_s: f64,
    pub r_ecef_m: Vec3,
    pub v_ecef_mps: Vec3,
    /// Covariance of `[r_ecef, v_ecef]` (m, m/s).
    pub covariance: Matrix6<f64>,
}
