//! Thesis section 4.3.2: on-orbit estimation of the antenna geometry offsets `dB_0` by a
//! UKF that stacks four epochs (eqs. 4.3-5..4.3-26), for two baselines.
//!
//! State (eq. 4.3-5), 22 values: the attitudes of four consecutive epochs, newest first
//! (`xi_{t+3}, xi_{t+2}, xi_{t+1}, xi_t`), the attitude rates `xi'` (one for the four), the
//! six offsets `dx1, dy1, dz1, dx2, dy2, dz2` of the body baselines (columns of `dB_0`) and
//! one offset rate `Delta'` common to all six. One step moves the window one epoch on:
//! every stacked attitude advances by `T xi'` and every offset by `T Delta'` (eqs. 4.3-6,
//! 4.3-7). The measurement is the four epochs' baselines `vec(B)` in the reference frame,
//! `h(X) = [R(xi_{t+3}) b'_1; R(xi_{t+3}) b'_2; ...; R(xi_t) b'_2]` with
//! `b'_i = b_i + Delta_i` (eqs. 4.3-12..4.3-15), `R = blockdiag(Q_BB)` (eq. 4.3-13).
//!
//! One epoch gives six equations in nine unknowns (three angles, six offsets): the
//! offsets become observable only through the dynamics that tie epochs together. A
//! rotation of the whole antenna triangle in the body frame is taken up by the attitude
//! at every epoch (`R Q^T Q B'_0 = R B'_0`), so that part of `dB_0` is determined only as
//! far as the constant-rate attitude model (eqs. 4.3-7..4.3-10) tells a rotated attitude
//! from the true one; the shape of the triangle (lengths, angle) is determined by every
//! epoch. docs/geometry.md gives what this means for the estimates.
//!
//! The thesis leaves the filter's start open. Here: the four epochs' LS attitudes on the
//! nominal `B_0` (eqs. 2.5-9..2.5-13), their mean rate, offsets and offset rate zero, with
//! the prior sigmas of [`OffsetConfig`].

use crate::attitude::config::{MAX_PSD, check_filter};
use crate::attitude::least_squares::{LsConfig, solve};
use crate::attitude::unscented::{transform, update};
use crate::attitude::{AttitudeError, BodyGeometry, NedBaselines, YawPitchRoll, wrap_pi};
use nalgebra::{DMatrix, DVector, SMatrix, SVector};
use skyforge_orbits::Vec3;
use std::collections::VecDeque;

/// Epochs stacked in the state (eq. 4.3-5).
pub const WINDOW: usize = 4;
/// State dimension for two baselines (eq. 4.3-5).
pub const STATES: usize = 3 * WINDOW + 3 + 6 + 1;
/// Baselines the filter is written for (eq. 4.3-4: `m = 2`).
pub const BASELINES: usize = 2;
/// Index of the rates `xi'` in the state.
const RATES: usize = 3 * WINDOW;
/// Index of the first offset `dx1`.
const OFFSETS: usize = RATES + 3;
/// Index of the offset rate `Delta'`.
const OFFSET_RATE: usize = OFFSETS + 6;
/// Relative tolerance on the epoch spacing (a fraction of the period).
const SPACING_TOLERANCE: f64 = 1e-3;

type State = SVector<f64, STATES>;
type Covariance = SMatrix<f64, STATES, STATES>;

/// Thesis section 4.3.4: `S_yaw' = S_pitch' = S_roll' = 1e-9`.
pub const THESIS_RATE_PSD: f64 = 1e-9;
/// Thesis section 4.3.4: `S_Delta' = 1e-15`.
pub const THESIS_OFFSET_RATE_PSD: f64 = 1e-15;

/// Settings of the offset estimator (`[geometry_offsets]` of a relative TOML file).
#[derive(Debug, Clone, Copy, PartialEq, serde::Deserialize, serde::Serialize)]
#[serde(default, deny_unknown_fields)]
pub struct OffsetConfig {
    /// Power spectral densities of the yaw, pitch and roll accelerations (rad^2/s^3),
    /// eq. 4.3-10; default the thesis's 1e-9.
    pub rate_psd_rad2_s3: [f64; 3],
    /// Power spectral density of the offset rate's noise (m^2/s^3), eq. 4.3-11; default
    /// the thesis's 1e-15.
    pub offset_rate_psd_m2_s3: f64,
    /// The epoch period `T` (s), eq. 4.3-7; default 1 s, the thesis's.
    pub period_s: f64,
    /// Sigma-point spread kappa, eqs. 4.3-18..4.3-20; default the thesis's 0.5.
    pub kappa: f64,
    /// Prior 1-sigma of each offset (m). Default 0.05 (# assumed: mounting errors of a
    /// few centimetres, the size the thesis simulates).
    pub initial_offset_sigma_m: f64,
    /// Prior 1-sigma of each attitude rate (rad/s). Default 0.01 (# assumed: as the
    /// real-time filters' start, `AttitudeConfig::initial_rate_sigma_rad_s`).
    pub initial_rate_sigma_rad_s: f64,
    /// Prior 1-sigma of the offset rate (m/s). Default 1e-6 (# assumed: a geometry that
    /// drifts by less than 4 mm an hour).
    pub initial_offset_rate_sigma_m_s: f64,
    /// How an epoch's `Q_BB` weighs in each of the four windows it enters.
    pub window_weighting: WindowWeighting,
    /// What fixes the orientation of the antenna geometry in the body frame.
    pub orientation: Orientation,
}

/// Baselines do not see a rotation of the whole antenna geometry in the body frame
/// ([`super::shape`]); something else has to fix it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Deserialize, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Orientation {
    /// As the thesis: all six offsets free; the orientation is set only by the prior and
    /// by how well the constant-rate attitude model tells a turned attitude from the true
    /// one, and the filter's covariance of it is not to be trusted.
    Free,
    /// The geometry keeps the nominal orientation: the pseudo-measurement
    /// `sum_k b'_k x b_k = 0` (the estimated baselines are already the rotation closest to
    /// the nominal ones, [`super::shape::align`]); the offsets are then the shape change
    /// only, and the attitude is that of the nominal antenna frame (default).
    #[default]
    Nominal,
}

/// Variance of the orientation pseudo-measurement (m^4): the cross products held at zero
/// to 1e-6 m^2 (# assumed: a micro-radian on a 1 m baseline, far below any real offset).
const ORIENTATION_VARIANCE: f64 = 1e-12;

/// Each epoch's baselines enter four consecutive updates (eq. 4.3-14).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Deserialize, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum WindowWeighting {
    /// `R = blockdiag(Q_BB)` as eq. 4.3-13 writes it: an epoch's information is counted
    /// four times, so the filter's covariance is too small (about four times in the
    /// variances that the measurements set).
    Thesis,
    /// `R = 4 blockdiag(Q_BB)`: each epoch counted once over its four windows (default).
    #[default]
    Once,
}

impl Default for OffsetConfig {
    fn default() -> Self {
        Self {
            rate_psd_rad2_s3: [THESIS_RATE_PSD; 3],
            offset_rate_psd_m2_s3: THESIS_OFFSET_RATE_PSD,
            period_s: 1.0,
            kappa: 0.5,
            initial_offset_sigma_m: 0.05,
            initial_rate_sigma_rad_s: 0.01,
            initial_offset_rate_sigma_m_s: 1e-6,
            window_weighting: WindowWeighting::Once,
            orientation: Orientation::Nominal,
        }
    }
}

impl OffsetConfig {
    /// The filter settings in their domain ([`check_filter`], `22 + kappa > 0`), the
    /// offsets' spectral density in `[0, MAX_PSD]`, the period and the prior sigmas finite
    /// and > 0.
    pub fn check(&self) -> Result<(), AttitudeError> {
        let error = AttitudeError::Config;
        check_filter(
            STATES,
            ("rate_psd_rad2_s3", &self.rate_psd_rad2_s3),
            ("initial_rate_sigma_rad_s", self.initial_rate_sigma_rad_s),
            self.kappa,
        )
        .map_err(error)?;
        let psd = self.offset_rate_psd_m2_s3;
        if !(0.0..=MAX_PSD).contains(&psd) {
            return Err(error(format!(
                "offset_rate_psd_m2_s3 = {psd:e}: allowed 0 to {MAX_PSD:e}"
            )));
        }
        for (key, v) in [
            ("period_s", self.period_s),
            ("initial_offset_sigma_m", self.initial_offset_sigma_m),
            (
                "initial_offset_rate_sigma_m_s",
                self.initial_offset_rate_sigma_m_s,
            ),
        ] {
            if !(v.is_finite() && v > 0.0) {
                return Err(error(format!("{key} = {v}: must be finite and above 0")));
            }
        }
        Ok(())
    }
}

/// Thesis eq. 4.3-7: `Phi` (22 x 22) for the period `t`.
pub fn transition(t: f64) -> Covariance {
    let mut phi = Covariance::identity();
    for epoch in 0..WINDOW {
        for axis in 0..3 {
            phi[(3 * epoch + axis, RATES + axis)] = t;
        }
    }
    for k in 0..6 {
        phi[(OFFSETS + k, OFFSET_RATE)] = t;
    }
    phi
}

/// Thesis eqs. 4.3-9..4.3-11: `Q = blockdiag(c, d)`, `c` the attitude block
/// `[[e4 e4^T T^3/3, e4 T^2/2], [e4^T T^2/2, T]] (x) diag(a)` and `d` the offset block
/// `[[e6 e6^T T^3/3, e6 T^2/2], [e6^T T^2/2, T]] b` (the thesis writes `(x) a` for the
/// vector `a` of the three PSDs; a 15 x 15 block needs its diagonal).
pub fn process_noise(t: f64, rate_psd: &[f64; 3], offset_rate_psd: f64) -> Covariance {
    // The integrated white noise of a rate: `T^3/3` between two integrated quantities,
    // `T^2/2` between one and the rate, `T` for the rate itself.
    let value = |i_is_rate: bool, j_is_rate: bool| match (i_is_rate, j_is_rate) {
        (false, false) => t.powi(3) / 3.0,
        (true, true) => t,
        _ => t * t / 2.0,
    };
    let mut q = Covariance::zeros();
    // Attitude block: slots 0..4 are the stacked epochs, slot 4 their rate.
    for i in 0..=WINDOW {
        for j in 0..=WINDOW {
            for (axis, s) in rate_psd.iter().enumerate() {
                q[(3 * i + axis, 3 * j + axis)] = value(i == WINDOW, j == WINDOW) * s;
            }
        }
    }
    // Offset block: six offsets, then their common rate.
    for i in 0..7 {
        for j in 0..7 {
            q[(OFFSETS + i, OFFSETS + j)] = value(i == 6, j == 6) * offset_rate_psd;
        }
    }
    q
}

/// The attitude of stacked epoch `slot` (0 the newest, `xi_{t+3}`; 3 the oldest, `xi_t`).
fn angles(x: &State, slot: usize) -> YawPitchRoll {
    YawPitchRoll::new(x[3 * slot], x[3 * slot + 1], x[3 * slot + 2])
}

/// The offset of baseline `k` (column `k` of `dB_0`, m).
fn offset(x: &State, k: usize) -> Vec3 {
    Vec3::new(
        x[OFFSETS + 3 * k],
        x[OFFSETS + 3 * k + 1],
        x[OFFSETS + 3 * k + 2],
    )
}

/// `b'_k = b_k + dB_k`: the nominal body baselines `b0` with the state's offsets.
fn corrected(x: &State, b0: &[Vec3]) -> Vec<Vec3> {
    b0.iter()
        .enumerate()
        .map(|(k, b)| b + offset(x, k))
        .collect()
}

/// Thesis eq. 4.3-15: the four epochs' baselines, newest first, for the nominal body
/// baselines `b0` and the state's offsets; with `pinned`, then the orientation
/// pseudo-measurement `sum_k b'_k x b_k = sum_k dB_k x b_k`, zero when the offset
/// geometry is the rotation of itself closest to the nominal one.
fn measurement(x: &State, b0: &[Vec3], pinned: bool) -> DVector<f64> {
    let body = corrected(x, b0);
    let mut h = Vec::with_capacity(3 * BASELINES * WINDOW + 3);
    for slot in 0..WINDOW {
        let r = angles(x, slot).c_body_ref();
        for b in &body {
            h.extend((r * b).iter());
        }
    }
    if pinned {
        let sum = b0
            .iter()
            .enumerate()
            .fold(Vec3::zeros(), |a, (k, b)| a + offset(x, k).cross(b));
        h.extend(sum.iter());
    }
    DVector::from_vec(h)
}

/// The estimate after an update.
#[derive(Debug, Clone, PartialEq)]
pub struct OffsetState {
    /// Time of the oldest stacked epoch, `xi_t` (s, the caller's clock).
    pub oldest_t_s: f64,
    /// The four stacked attitudes, oldest (`xi_t`) first.
    pub window: [YawPitchRoll; WINDOW],
    /// Attitude rates (rad/s).
    pub rates_rad_s: Vec3,
    /// `dB_0`: the offset of each body baseline (m).
    pub offsets_m: [Vec3; BASELINES],
    /// The common offset rate `Delta'` (m/s).
    pub offset_rate_m_s: f64,
    /// Covariance of the offsets, `dx1, dy1, dz1, dx2, dy2, dz2` (m^2).
    pub offsets_covariance_m2: SMatrix<f64, 6, 6>,
}

/// What an epoch did.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Step {
    /// Kept, waiting for four consecutive epochs.
    Filling,
    /// The filter started from the four epochs' LS attitudes.
    Started,
    /// Measurement update; the innovation's chi-square with `dof` degrees of freedom.
    Updated { chi_square: f64, dof: usize },
}

/// The stacked UKF of eqs. 4.3-5..4.3-26.
#[derive(Debug, Clone)]
pub struct OffsetEstimator {
    config: OffsetConfig,
    nominal: BodyGeometry,
    phi: Covariance,
    q: Covariance,
    /// The newest epochs, newest first, all one period apart.
    window: VecDeque<(f64, NedBaselines)>,
    xp: Option<(State, Covariance)>,
}

impl OffsetEstimator {
    /// An estimator for the nominal geometry `nominal` (`B_0`, two baselines).
    pub fn new(config: OffsetConfig, nominal: BodyGeometry) -> Result<Self, AttitudeError> {
        config.check()?;
        if nominal.len() != BASELINES {
            return Err(AttitudeError::Geometry(format!(
                "the geometry-offset UKF (thesis 4.3) is written for {BASELINES} baselines (three antennas); the geometry has {}",
                nominal.len()
            )));
        }
        Ok(Self {
            phi: transition(config.period_s),
            q: process_noise(
                config.period_s,
                &config.rate_psd_rad2_s3,
                config.offset_rate_psd_m2_s3,
            ),
            config,
            nominal,
            window: VecDeque::with_capacity(WINDOW),
            xp: None,
        })
    }

    /// One epoch's baselines at `t_s` (s, increasing). Epochs must lie on the period
    /// grid; a gap of whole periods keeps the state (it is predicted across) and refills
    /// the window before the next update.
    pub fn push(&mut self, t_s: f64, measured: NedBaselines) -> Result<Step, AttitudeError> {
        self.nominal.check_count(&measured)?;
        let steps = match self.window.front() {
            None => 0,
            Some((last, _)) => self.periods_since(*last, t_s)?,
        };
        if steps != 1 {
            self.window.clear();
        }
        if let Some((x, p)) = self.xp.as_mut() {
            for _ in 0..steps {
                *x = self.phi * *x;
                let pp = self.phi * *p * self.phi.transpose() + self.q;
                *p = 0.5 * (pp + pp.transpose());
            }
        }
        self.window.push_front((t_s, measured));
        self.window.truncate(WINDOW);
        if self.window.len() < WINDOW {
            return Ok(Step::Filling);
        }
        if self.xp.is_none() {
            self.xp = Some(self.start()?);
            return Ok(Step::Started);
        }
        self.update()
    }

    /// Whole periods from `last` to `t` (at least one), or an error off the grid.
    fn periods_since(&self, last: f64, t: f64) -> Result<usize, AttitudeError> {
        let periods = (t - last) / self.config.period_s;
        let n = periods.round();
        if !(periods.is_finite() && n >= 1.0 && (periods - n).abs() <= SPACING_TOLERANCE) {
            return Err(AttitudeError::Measurement(format!(
                "epoch at {t} s is not a whole number of {} s periods after the previous one at {last} s",
                self.config.period_s
            )));
        }
        Ok(n as usize)
    }

    /// The start: LS attitudes of the four epochs on the nominal `B_0`, their mean rate,
    /// zero offsets; angle variance the LS's plus the nominal geometry's possible error
    /// (an offset of one prior sigma over the shortest baseline), common to the four.
    fn start(&self) -> Result<(State, Covariance), AttitudeError> {
        let ls = LsConfig::default();
        let mut x = State::zeros();
        let mut p = Covariance::zeros();
        let mut previous = None;
        for (slot, (_, b)) in self.window.iter().enumerate() {
            let e = solve(&self.nominal, b, previous, &ls)?;
            let a = e.angles;
            x.fixed_rows_mut::<3>(3 * slot).copy_from(&Vec3::new(
                a.yaw_rad,
                a.pitch_rad,
                a.roll_rad,
            ));
            p.fixed_view_mut::<3, 3>(3 * slot, 3 * slot)
                .copy_from(&e.covariance);
            previous = Some(a);
        }
        let span = (WINDOW - 1) as f64 * self.config.period_s;
        for axis in 0..3 {
            let newest = x[axis];
            let oldest = x[3 * (WINDOW - 1) + axis];
            x[RATES + axis] = wrap_pi(newest - oldest) / span;
        }
        let shortest = self
            .nominal
            .baselines()
            .iter()
            .map(|b| b.norm())
            .fold(f64::INFINITY, f64::min);
        let geometry_var = (self.config.initial_offset_sigma_m / shortest).powi(2);
        for i in 0..RATES {
            for j in 0..RATES {
                if i % 3 == j % 3 {
                    p[(i, j)] += geometry_var;
                }
            }
        }
        for axis in 0..3 {
            p[(RATES + axis, RATES + axis)] = self.config.initial_rate_sigma_rad_s.powi(2);
        }
        for k in 0..6 {
            p[(OFFSETS + k, OFFSETS + k)] = self.config.initial_offset_sigma_m.powi(2);
        }
        p[(OFFSET_RATE, OFFSET_RATE)] = self.config.initial_offset_rate_sigma_m_s.powi(2);
        Ok((x, p))
    }

    /// Eqs. 4.3-12..4.3-26 on the four epochs of the window (and the orientation
    /// pseudo-measurement with [`Orientation::Nominal`]).
    fn update(&mut self) -> Result<Step, AttitudeError> {
        let Some((x, p)) = self.xp else {
            return Err(AttitudeError::Filter("update before the start".into()));
        };
        let n = 3 * BASELINES;
        let pinned = self.config.orientation == Orientation::Nominal;
        let rows = n * WINDOW + if pinned { 3 } else { 0 };
        let mut z = DVector::zeros(rows);
        let mut r = DMatrix::zeros(rows, rows);
        let weight = match self.config.window_weighting {
            WindowWeighting::Thesis => 1.0,
            WindowWeighting::Once => WINDOW as f64,
        };
        for (slot, (_, b)) in self.window.iter().enumerate() {
            z.rows_mut(n * slot, n).copy_from(&b.vec());
            r.view_mut((n * slot, n * slot), (n, n))
                .copy_from(&(b.covariance() * weight));
        }
        for i in n * WINDOW..rows {
            r[(i, i)] = ORIENTATION_VARIANCE;
        }
        let b0 = self.nominal.baselines();
        let filter = |e: crate::attitude::unscented::UnscentedError| {
            AttitudeError::Filter(format!("geometry offsets: {e}"))
        };
        let t = transform(&x, &p, self.config.kappa, |xj| measurement(xj, b0, pinned))
            .map_err(filter)?;
        let (mut x_new, p_new, v, s) = update(&x, &p, &t, &z, &r).map_err(filter)?;
        if !x_new.iter().chain(p_new.iter()).all(|v| v.is_finite()) {
            return Err(AttitudeError::Filter(
                "geometry offsets: the updated state is not finite".into(),
            ));
        }
        for slot in 0..WINDOW {
            x_new[3 * slot] = wrap_pi(x_new[3 * slot]);
            x_new[3 * slot + 2] = wrap_pi(x_new[3 * slot + 2]);
        }
        let chi_square = s
            .cholesky()
            .map(|c| v.dot(&c.solve(&v)))
            .unwrap_or(f64::NAN);
        self.xp = Some((x_new, p_new));
        Ok(Step::Updated {
            chi_square,
            dof: v.len(),
        })
    }

    /// The current estimate (`None` before the start).
    pub fn state(&self) -> Option<OffsetState> {
        let (x, p) = self.xp.as_ref()?;
        let newest_t_s = self.window.front().map(|(t, _)| *t)?;
        let oldest_t_s = newest_t_s - self.config.period_s * (WINDOW - 1) as f64;
        Some(OffsetState {
            oldest_t_s,
            window: [3, 2, 1, 0].map(|slot| angles(x, slot)),
            rates_rad_s: Vec3::new(x[RATES], x[RATES + 1], x[RATES + 2]),
            offsets_m: [offset(x, 0), offset(x, 1)],
            offset_rate_m_s: x[OFFSET_RATE],
            offsets_covariance_m2: p.fixed_view::<6, 6>(OFFSETS, OFFSETS).into_owned(),
        })
    }

    /// `B'_0 = B_0 + dB_0` with the current offsets (the nominal geometry before the
    /// start): the corrected geometry of eq. 4.3-35 and the end of section 4.3.2.
    pub fn corrected_geometry(&self) -> Result<BodyGeometry, AttitudeError> {
        let Some((x, _)) = &self.xp else {
            return Ok(self.nominal.clone());
        };
        let corrected = corrected(x, self.nominal.baselines());
        BodyGeometry::new(&corrected)
    }
}

#[cfg(test)]
mod tests;
