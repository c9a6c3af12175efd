//! The Kalman filter of book eq. 5-59: the state `[x y z c dt x' y' z' c dt']` (target
//! orbit frame, the relative clock in metres), predicted by the Hill dynamics of eq. 5-34
//! about the target's orbit with `U` ([`HillDynamics`], the book's relative filter's)
//! and a two-state relative clock, updated by the single differences
//! ([`super::measurement`]).
//!
//! The clock: `c dt` integrates its drift `c dt'`, with white frequency noise on `c dt`
//! and a random walk on `c dt'` (two free-running TCXOs; `[single_difference]`), the
//! usual two-state model: over a step `dt` with densities `q_f` (m^2/s) and `q_g`
//! (m^2/s^3), `Q = [[q_f dt + q_g dt^3 / 3, q_g dt^2 / 2], [q_g dt^2 / 2, q_g dt]]`.

use super::config::SingleDifferenceConfig;
use super::measurement::{CLOCK, DRIFT, EpochFrame, SdSatellite, State, elevations, predict};
use crate::relnav::hill_dynamics::HillDynamics;
use crate::relnav::hill_dynamics::TargetState;
use nalgebra::{Matrix2, SMatrix, Vector6};
use skyforge_orbits::Vec3;
use skyforge_orbits::ephemeris::SatId;
use std::collections::BTreeSet;

/// The state's covariance.
pub(crate) type Covariance = SMatrix<f64, 8, 8>;

/// A single difference whose innovation lies beyond this many of its predicted standard
/// deviations is not used. 5: a normal innovation passes it but for a chance of 6e-7, none
/// in a run's 10^4 rows, while a fault of one satellite (multipath, a tracking error)
/// of more than 5 sigma (5 m of code at the default) is left out.
pub(crate) const GATE_SIGMAS: f64 = 5.0;

/// Eq. 5-59's state in the dynamics' order `[x y z x' y' z' c dt c dt']`.
const DYNAMICS_ORDER: [usize; 8] = [0, 1, 2, 4, 5, 6, CLOCK, DRIFT];

/// More than half of an epoch's pseudorange differences failed the gate: the state,
/// not the satellites, is wrong (a receiver re-steered its clock, or a long gap).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Disagreement;

/// One single difference at the predicted state.
struct Row {
    sat: SatId,
    code: bool,
    innovation: f64,
    h: State,
    variance: f64,
}

/// The filter.
#[derive(Debug, Clone)]
pub(crate) struct SdFilter {
    config: SingleDifferenceConfig,
    dynamics: HillDynamics,
    /// The target's state of the last epoch, the relative state and its covariance then.
    target: TargetState,
    x: State,
    p: Covariance,
}

/// The permutation matrix from eq. 5-59's order to [`DYNAMICS_ORDER`].
fn to_dynamics_order() -> Covariance {
    Covariance::from_fn(|i, j| f64::from(u8::from(DYNAMICS_ORDER[i] == j)))
}

impl SdFilter {
    /// A filter for a run starting at `start` (the force model's date), started at
    /// `target`'s epoch from `x` with independent standard deviations `sigma` (eq.
    /// 5-59's order).
    pub(crate) fn new(
        config: &SingleDifferenceConfig,
        start: hifitime::Epoch,
        (target, x): (TargetState, State),
        sigma: &State,
    ) -> Self {
        Self {
            dynamics: HillDynamics::new(&config.forces, start),
            config: config.clone(),
            target,
            x,
            p: Covariance::from_diagonal(&sigma.map(|s| s * s)),
        }
    }

    /// Start again at `target`'s epoch from `x` with standard deviations `sigma`.
    pub(crate) fn restart(&mut self, (target, x): (TargetState, State), sigma: &State) {
        self.target = target;
        self.x = x;
        self.p = Covariance::from_diagonal(&sigma.map(|s| s * s));
    }

    /// The relative position and rate (target orbit frame).
    pub(crate) fn estimate(&self) -> (Vec3, Vec3) {
        let x = &self.x;
        (Vec3::new(x[0], x[1], x[2]), Vec3::new(x[4], x[5], x[6]))
    }

    /// The clock's transition and process noise over `dt_s` (module docs).
    fn clock_step(&self, dt_s: f64) -> (Matrix2<f64>, Matrix2<f64>) {
        let q_f = self.config.clock_sigma_m_per_sqrt_s.powi(2);
        let q_g = self.config.clock_drift_sigma_mps_per_sqrt_s.powi(2);
        let cross = q_g * dt_s.powi(2) / 2.0;
        let q = Matrix2::new(
            q_f * dt_s + q_g * dt_s.powi(3) / 3.0,
            cross,
            cross,
            q_g * dt_s,
        );
        (Matrix2::new(1.0, dt_s, 0.0, 1.0), q)
    }

    /// Carry the state to `target`'s epoch (eq. 5-34 and the clock).
    pub(crate) fn predict(&mut self, target: TargetState) {
        let (from, x, p) = (self.target, self.x, self.p);
        let dt = target.t_s - from.t_s;
        let order = to_dynamics_order();
        let (y, py) = (order * x, order * p * order.transpose());
        let hill = Vector6::from_fn(|i, _| y[i]);
        let step = self.dynamics.step(&from, &hill, &target, dt);
        let (b, q_clock) = self.clock_step(dt);
        let clock = b * y.fixed_rows::<2>(6);
        let mut p1 = Covariance::zeros();
        let pxx = py.fixed_view::<6, 6>(0, 0).into_owned();
        let pxc = step.transition() * py.fixed_view::<6, 2>(0, 6) * b.transpose();
        let pcc = b * py.fixed_view::<2, 2>(6, 6) * b.transpose() + q_clock;
        (p1.fixed_view_mut::<6, 6>(0, 0))
            .copy_from(&step.covariance(&pxx, self.config.acceleration_sigma_mps2));
        p1.fixed_view_mut::<6, 2>(0, 6).copy_from(&pxc);
        p1.fixed_view_mut::<2, 6>(6, 0).copy_from(&pxc.transpose());
        p1.fixed_view_mut::<2, 2>(6, 6).copy_from(&pcc);
        let y1 = State::from_iterator(step.state.iter().chain(clock.iter()).copied());
        let back = order.transpose();
        self.target = target;
        self.x = back * y1;
        self.p = back * p1 * order;
    }

    /// The rows of the satellites of `sats` above `mask_rad` at both receivers, at the
    /// predicted state `x` (eq. 5-59, noise eq. 5-58).
    fn rows(&self, frame: &EpochFrame, sats: &[SdSatellite], x: &State, mask_rad: f64) -> Vec<Row> {
        let rx = frame.receivers(x);
        let c = &self.config;
        let mut rows = Vec::new();
        for s in sats
            .iter()
            .filter(|s| elevations(s, &rx).iter().all(|&e| e >= mask_rad))
        {
            let m = predict(s, x, &rx);
            rows.push(Row {
                sat: s.sat,
                code: true,
                innovation: s.code_m - m.code_m,
                h: m.h_code,
                variance: c.code_sigma_m.powi(2),
            });
            if let Some(rate) = s.rate_mps {
                rows.push(Row {
                    sat: s.sat,
                    code: false,
                    innovation: rate - m.rate_mps,
                    h: m.h_rate,
                    variance: c.range_rate_sigma_mps.powi(2),
                });
            }
        }
        rows
    }

    /// Take the epoch's single differences `sats` (the state already predicted to
    /// `frame`'s epoch): the satellites whose pseudorange difference was used, or
    /// [`Disagreement`] (nothing taken).
    pub(crate) fn update(
        &mut self,
        frame: &EpochFrame,
        sats: &[SdSatellite],
        mask_rad: f64,
    ) -> Result<BTreeSet<SatId>, Disagreement> {
        let (x0, p0) = (self.x, self.p);
        let rows = self.rows(frame, sats, &x0, mask_rad);
        let passes = |r: &Row| {
            r.innovation.powi(2)
                <= GATE_SIGMAS.powi(2) * ((r.h.transpose() * p0 * r.h)[0] + r.variance)
        };
        let codes = rows.iter().filter(|r| r.code).count();
        let failed = rows.iter().filter(|r| r.code && !passes(r)).count();
        if 2 * failed > codes {
            return Err(Disagreement);
        }
        let kept: Vec<&Row> = rows.iter().filter(|r| passes(r)).collect();
        // One row at a time (independent noise), each innovation from the linearisation
        // at the predicted state: the batch update's result.
        let (mut x, mut p) = (x0, p0);
        for r in &kept {
            let ph = p * r.h;
            let s = (r.h.transpose() * ph)[0] + r.variance;
            let k = ph / s;
            x += k * (r.innovation - (r.h.transpose() * (x - x0))[0]);
            let i_kh = Covariance::identity() - k * r.h.transpose();
            p = i_kh * p * i_kh.transpose() + k * k.transpose() * r.variance;
        }
        (self.x, self.p) = (x, p);
        Ok((kept.iter()).filter(|r| r.code).map(|r| r.sat).collect())
    }
}
