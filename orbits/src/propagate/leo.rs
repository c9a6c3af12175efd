//! The LEO propagator: integrates forward on demand and hands out dense-output windows, so
//! memory stays bounded however long the scenario is.
//!
//! The equations of motion `r'' = a(t, r, r')` of [`ForceModel`] are integrated in the
//! scenario ECI frame by the adaptive Dormand-Prince 5(4) of [`super::dormand_prince`]
//! with the configured relative tolerance; the absolute tolerance is `abs_tol_m` on the
//! position and `abs_tol_m x 1e-3 /s` on the velocity (1e-3 rad/s is about a LEO's mean
//! motion, so both halves of the state are weighted alike). With the default tolerances
//! (1e-12, 1e-4 m) a two-body LEO stays within 0.5 m of the analytical Kepler solution over
//! 24 h (5 mm with 1e-13, 1e-6 m); see `tests/propagate_oracles.rs`.

use std::collections::VecDeque;

use super::PropagateError;
use super::atmosphere::geodetic_height_m;
use super::config::{LeoConfig, MIN_ALTITUDE_M, StateFrame};
use super::dormand_prince::{DenseStep, DormandPrince, Settings, State6};
use super::elements::KeplerianElements;
use super::forces::ForceModel;
use super::tle::Tle;
use crate::Vec3;
use crate::frames::earth_rotation::EarthRotation;
use crate::time::TimeOrigin;

/// Velocity absolute tolerance per metre of position tolerance (1/s).
const VELOCITY_TOL_PER_S: f64 = 1e-3;
/// Step-size limits (s).
const H_MIN_S: f64 = 1e-6;
const H_MAX_S: f64 = 300.0;
/// History kept behind the end of the last window: at least this long (s) ...
const KEEP_HISTORY_S: f64 = 60.0;
/// ... and at least this many steps.
const KEEP_MIN_STEPS: usize = 2;
/// Slack when comparing window bounds with step bounds (s).
const TIME_EPS_S: f64 = 1e-9;
/// History integrated before `t = 0`, so that windows may start slightly before the
/// scenario start (the finite-difference stencils of the first geometry epochs need it).
pub const PRE_HISTORY_S: f64 = 60.0;

/// A dense-output trajectory over a time window (ECI).
#[derive(Debug, Clone)]
pub struct DenseTrajectory {
    /// Consecutive integrator steps covering the window (never empty).
    steps: Vec<DenseStep>,
    force: ForceModel,
}

impl DenseTrajectory {
    /// First and last time covered (s since the scenario start): the bounds of the
    /// integrator steps kept for the window, which contain the requested window.
    pub fn span(&self) -> (f64, f64) {
        let first = self.steps.first().map_or(f64::NAN, DenseStep::t_start_s);
        let last = self.steps.last().map_or(f64::NAN, DenseStep::t_end_s);
        (first, last)
    }

    /// ECI position, velocity and acceleration at `t_s` (inside the span).
    ///
    /// Position and velocity come from the 4th-order dense output of the step holding
    /// `t_s`; the acceleration is the force model evaluated at that interpolated state
    /// (more accurate than differentiating the interpolant). Outside the span the nearest
    /// step is extrapolated, which is accurate only a small fraction of a step away.
    pub fn state_eci(&self, t_s: f64) -> (Vec3, Vec3, Vec3) {
        let (r, v) = self.position_velocity_eci(t_s);
        let a = self.force.acceleration_eci(t_s, &r, &v);
        (r, v, a)
    }

    /// The force model's gravitation at `r_eci_m` (ECI, m/s^2): the part of
    /// [`Self::state_eci`]'s acceleration an accelerometer does not sense.
    pub fn gravity_eci(&self, r_eci_m: &Vec3) -> Vec3 {
        self.force.gravity_eci(r_eci_m)
    }

    /// ECI position and velocity at `t_s` (as [`Self::state_eci`], without the force
    /// evaluation).
    pub fn position_velocity_eci(&self, t_s: f64) -> (Vec3, Vec3) {
        let index = self
            .steps
            .partition_point(|s| s.t_end_s() < t_s)
            .min(self.steps.len().saturating_sub(1));
        let y = self.steps[index].state_at(t_s);
        split(&y)
    }
}

/// A numerically propagated LEO.
#[derive(Debug, Clone)]
pub struct LeoPropagator {
    force: ForceModel,
    integrator: DormandPrince,
    /// Accepted steps not yet dropped, in time order.
    history: VecDeque<DenseStep>,
    r0_eci_m: Vec3,
    v0_eci_mps: Vec3,
    /// Set once the propagation failed (decay, step underflow); repeated afterwards.
    stopped: Option<PropagateError>,
}

impl LeoPropagator {
    /// A propagator starting at `t = 0` (the scenario start of `origin`) from the initial
    /// state `cfg` gives: elements (osculating, ECI, mu = `GM_GPS`), a TLE (SGP4 to the
    /// start, TEME taken as ECI, see [`super::tle`]) or a state vector (ECEF converted with
    /// `earth` at `t = 0`). The configuration is checked first.
    pub fn new(
        cfg: &LeoConfig,
        origin: &TimeOrigin,
        earth: &EarthRotation,
    ) -> Result<LeoPropagator, PropagateError> {
        cfg.check()?;
        let (r0_eci_m, v0_eci_mps) = initial_state_eci(cfg, origin, earth)?;
        let h = r0_eci_m.cross(&v0_eci_mps);
        let inclination_rad = (h.z / h.norm()).clamp(-1.0, 1.0).acos();
        let force = ForceModel::new(&cfg.forces, origin.start(), inclination_rad);
        let abs_pos = cfg.integrator.abs_tol_m;
        let abs_vel = abs_pos * VELOCITY_TOL_PER_S;
        let settings = Settings {
            rel_tol: cfg.integrator.rel_tol,
            abs_tol: State6::new(abs_pos, abs_pos, abs_pos, abs_vel, abs_vel, abs_vel),
            h_min_s: H_MIN_S,
            h_max_s: H_MAX_S,
            h_initial_s: None,
        };
        let y0 = join(&r0_eci_m, &v0_eci_mps);
        let y_pre = state_before_start(&force, y0, settings)?;
        let mut f = |t: f64, y: &State6| derivative(&force, t, y);
        let integrator = DormandPrince::new(&mut f, -PRE_HISTORY_S, y_pre, settings);
        Ok(Self {
            force,
            integrator,
            history: VecDeque::new(),
            r0_eci_m,
            v0_eci_mps,
            stopped: None,
        })
    }

    /// The ECI position (m) and velocity (m/s) at `t = 0`.
    pub fn initial_state_eci(&self) -> (Vec3, Vec3) {
        (self.r0_eci_m, self.v0_eci_mps)
    }

    /// Osculating elements (mu = `GM_GPS`) of the initial state.
    pub fn initial_elements(&self) -> KeplerianElements {
        KeplerianElements::from_cartesian(&self.r0_eci_m, &self.v0_eci_mps, self.force.gm())
    }

    /// The resolved force model.
    pub fn force_model(&self) -> &ForceModel {
        &self.force
    }

    /// Dense output covering `[t0_s, t1_s]`. Windows must move forward: `t0_s` may reach
    /// back at most into the last integrator steps kept from the previous window (at least
    /// the last 2 steps and the last 60 s before the previous window's end).
    ///
    /// Errors: [`PropagateError::WindowBeforeHistory`] for a start before the kept history
    /// (or a non-finite bound); [`PropagateError::Decayed`] when the integration reaching
    /// `t1_s` passes below 80 km geodetic height; [`PropagateError::StepUnderflow`] when the
    /// tolerance cannot be met. After a failure, windows that need to integrate further
    /// repeat the error.
    pub fn window(&mut self, t0_s: f64, t1_s: f64) -> Result<DenseTrajectory, PropagateError> {
        let t1_s = t1_s.max(t0_s);
        let kept_from_s = self
            .history
            .front()
            .map_or(self.integrator.t_s(), DenseStep::t_start_s);
        if t0_s.is_nan() || t0_s < kept_from_s - TIME_EPS_S || !t1_s.is_finite() {
            return Err(PropagateError::WindowBeforeHistory { t0_s, kept_from_s });
        }
        while self.history.is_empty() || self.integrator.t_s() < t1_s {
            if let Some(err) = &self.stopped {
                return Err(err.clone());
            }
            self.advance()?;
        }
        let steps: Vec<DenseStep> = self
            .history
            .iter()
            .filter(|s| s.t_end_s() >= t0_s - TIME_EPS_S && s.t_start_s() <= t1_s + TIME_EPS_S)
            .cloned()
            .collect();
        self.prune(t1_s);
        Ok(DenseTrajectory {
            steps,
            force: self.force.clone(),
        })
    }

    /// Take one integrator step and check the altitude at its end.
    fn advance(&mut self) -> Result<(), PropagateError> {
        let force = &self.force;
        let mut f = |t: f64, y: &State6| derivative(force, t, y);
        let step = match self.integrator.step(&mut f) {
            Ok(step) => step,
            Err(underflow) => {
                let err = PropagateError::StepUnderflow { t_s: underflow.t_s };
                self.stopped = Some(err.clone());
                return Err(err);
            }
        };
        let (r_end, _) = split(&step.end_state());
        let t_end_s = step.t_end_s();
        self.history.push_back(step);
        let altitude_m = geodetic_height_m(&r_end);
        if altitude_m < MIN_ALTITUDE_M {
            let err = PropagateError::Decayed {
                t_s: t_end_s,
                altitude_m,
            };
            self.stopped = Some(err.clone());
            return Err(err);
        }
        Ok(())
    }

    /// Drop the steps that ended more than [`KEEP_HISTORY_S`] before `t_end_s`, keeping at
    /// least [`KEEP_MIN_STEPS`].
    fn prune(&mut self, t_end_s: f64) {
        let keep_from_s = t_end_s - KEEP_HISTORY_S;
        while self.history.len() > KEEP_MIN_STEPS
            && self
                .history
                .front()
                .is_some_and(|s| s.t_end_s() < keep_from_s)
        {
            self.history.pop_front();
        }
    }
}

/// The initial ECI state from whichever source `cfg` names.
fn initial_state_eci(
    cfg: &LeoConfig,
    origin: &TimeOrigin,
    earth: &EarthRotation,
) -> Result<(Vec3, Vec3), PropagateError> {
    if let Some(el) = &cfg.elements {
        let elements = KeplerianElements {
            a_m: el.semi_major_axis_km * 1e3,
            e: el.eccentricity,
            i_rad: el.inclination_deg.to_radians(),
            raan_rad: el.raan_deg.to_radians(),
            argp_rad: el.arg_perigee_deg.to_radians(),
            mean_anomaly_rad: el.mean_anomaly_deg.to_radians(),
        };
        return Ok(elements.to_cartesian(crate::constants::GM_GPS));
    }
    if let Some(tle) = &cfg.tle {
        return Tle::parse(tle)?.state_teme(origin.start());
    }
    match &cfg.state {
        Some(state) => {
            let r = Vec3::from(state.position_m);
            let v = Vec3::from(state.velocity_mps);
            Ok(match state.frame {
                StateFrame::Eci => (r, v),
                StateFrame::Ecef => earth.ecef_to_eci(0.0, &r, &v),
            })
        }
        // `check` guarantees one source; keep the error rather than a panic.
        None => Err(crate::check::Invalid::new(
            "elements",
            "missing",
            "exactly one of `elements`, `tle`, `state` gives the initial state",
        )
        .into()),
    }
}

/// `d/dt (r, v) = (v, a)`.
/// The state at `t = -PRE_HISTORY_S`, integrated backwards from `y0` at `t = 0` in the
/// reversed time tau = -t (dy/dtau = -f(-tau, y)).
fn state_before_start(
    force: &ForceModel,
    y0: State6,
    settings: Settings,
) -> Result<State6, PropagateError> {
    let mut g = |tau: f64, y: &State6| -derivative(force, -tau, y);
    let mut back = DormandPrince::new(&mut g, 0.0, y0, settings);
    loop {
        let step = back
            .step(&mut g)
            .map_err(|e| PropagateError::StepUnderflow { t_s: -e.t_s })?;
        if step.t_end_s() >= PRE_HISTORY_S {
            return Ok(step.state_at(PRE_HISTORY_S));
        }
    }
}

fn derivative(force: &ForceModel, t_s: f64, y: &State6) -> State6 {
    let (r, v) = split(y);
    let a = force.acceleration_eci(t_s, &r, &v);
    join(&v, &a)
}

fn split(y: &State6) -> (Vec3, Vec3) {
    (Vec3::new(y[0], y[1], y[2]), Vec3::new(y[3], y[4], y[5]))
}

fn join(a: &Vec3, b: &Vec3) -> State6 {
    State6::new(a.x, a.y, a.z, b.x, b.y, b.z)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fixtures::thesis_elements;
    use crate::propagate::config::{
        ForceModelConfig, IntegratorConfig, StateVectorConfig, TleConfig,
    };
    use hifitime::{Duration, Epoch, TimeScale};

    fn start() -> Epoch {
        Epoch::from_gregorian(2023, 3, 12, 0, 0, 0, 0, TimeScale::GPST)
    }

    fn thesis() -> LeoConfig {
        LeoConfig {
            elements: Some(thesis_elements()),
            tle: None,
            state: None,
            forces: ForceModelConfig::default(),
            integrator: IntegratorConfig::default(),
        }
    }

    fn build(cfg: &LeoConfig, start: Epoch) -> Result<LeoPropagator, PropagateError> {
        LeoPropagator::new(
            cfg,
            &TimeOrigin::new(start),
            &EarthRotation::at_origin(start),
        )
    }

    #[test]
    fn initial_state_comes_from_the_elements() {
        let leo = build(&thesis(), start()).unwrap();
        let el = leo.initial_elements();
        assert!((el.a_m - 6_971_593.0).abs() < 1e-6);
        assert!((el.e - 0.000846).abs() < 1e-12);
        assert!((el.i_rad.to_degrees() - 34.911).abs() < 1e-10);
        assert!((el.raan_rad.to_degrees() - (360.0 - 78.005)).abs() < 1e-9);
        let (r, _) = leo.initial_state_eci();
        assert!((r.norm() - 6_971_593.0).abs() < 0.000846 * 6_971_593.0 + 1.0);
    }

    #[test]
    fn consecutive_overlapping_windows_reproduce_one_long_window() {
        let mut long = build(&thesis(), start()).unwrap();
        let reference = long.window(0.0, 7500.0).unwrap();
        let mut leo = build(&thesis(), start()).unwrap();
        let mut t0 = 0.0;
        while t0 < 7000.0 {
            let t1 = t0 + 300.0;
            let w = leo.window(t0, t1).unwrap();
            let (first, last) = w.span();
            assert!(
                first <= t0 && last >= t1,
                "span {first}..{last} for {t0}..{t1}"
            );
            for k in 0..=30 {
                let t = t0 + 10.0 * f64::from(k);
                let (r, v, a) = w.state_eci(t);
                let (r_ref, v_ref, a_ref) = reference.state_eci(t);
                assert_eq!((r, v, a), (r_ref, v_ref, a_ref), "t = {t}");
            }
            // The next window reaches 10 s back into this one.
            t0 = t1 - 10.0;
        }
    }

    #[test]
    fn acceleration_is_the_force_model_at_the_interpolated_state() {
        let mut leo = build(&thesis(), start()).unwrap();
        let w = leo.window(100.0, 200.0).unwrap();
        let (r, v, a) = w.state_eci(123.4);
        assert_eq!(a, leo.force_model().acceleration_eci(123.4, &r, &v));
        // And it is consistent with the velocity's rate of change.
        let (_, v1, _) = w.state_eci(123.5);
        let (_, v0, _) = w.state_eci(123.3);
        assert!(((v1 - v0) / 0.2 - a).norm() < 1e-6 * a.norm());
    }

    #[test]
    fn window_starting_before_the_kept_history_is_refused() {
        let mut leo = build(&thesis(), start()).unwrap();
        leo.window(0.0, 3600.0).unwrap();
        // 60 s of history are kept behind the previous end.
        leo.window(3541.0, 3700.0).unwrap();
        match leo.window(1000.0, 4000.0) {
            Err(PropagateError::WindowBeforeHistory { t0_s, kept_from_s }) => {
                assert_eq!(t0_s, 1000.0);
                assert!(
                    kept_from_s > 3000.0 && kept_from_s <= 3640.0,
                    "{kept_from_s}"
                );
            }
            other => panic!("unexpected {other:?}"),
        }
        assert!(matches!(
            leo.window(f64::NAN, 4000.0),
            Err(PropagateError::WindowBeforeHistory { .. })
        ));
    }

    #[test]
    fn zero_length_window_at_the_start() {
        let mut leo = build(&thesis(), start()).unwrap();
        let w = leo.window(0.0, 0.0).unwrap();
        let (r, v, _) = w.state_eci(0.0);
        let (r0, v0) = leo.initial_state_eci();
        // The forward integration starts PRE_HISTORY_S before t = 0 from a backward
        // integration, so t = 0 reproduces the initial state to the integration tolerance.
        assert!((r - r0).norm() < 1e-5 && (v - v0).norm() < 1e-8);
    }

    #[test]
    fn heavy_drag_decays_with_an_error() {
        let mut cfg = thesis();
        if let Some(el) = cfg.elements.as_mut() {
            el.semi_major_axis_km = 6378.137 + 150.0;
            el.eccentricity = 0.0;
        }
        cfg.forces.area_m2 = 10.0;
        let mut leo = build(&cfg, start()).unwrap();
        let err = leo.window(0.0, 86_400.0).unwrap_err();
        match err {
            PropagateError::Decayed { t_s, altitude_m } => {
                assert!(t_s > 0.0 && t_s < 86_400.0);
                assert!(
                    altitude_m < MIN_ALTITUDE_M && altitude_m > 0.0,
                    "{altitude_m}"
                );
            }
            ref other => panic!("unexpected {other:?}"),
        }
        // The failure repeats for any window that needs to go further.
        assert_eq!(leo.window(86_000.0, 86_400.0).unwrap_err(), err);
    }

    #[test]
    fn ecef_state_is_converted_with_the_earth_rotation() {
        let eci = build(&thesis(), start()).unwrap();
        let (r_eci, v_eci) = eci.initial_state_eci();
        let earth = EarthRotation::at_origin(start());
        let (r_ecef, v_ecef) = earth.eci_to_ecef(0.0, &r_eci, &v_eci);
        let cfg = LeoConfig {
            elements: None,
            state: Some(StateVectorConfig {
                frame: StateFrame::Ecef,
                position_m: r_ecef.into(),
                velocity_mps: v_ecef.into(),
            }),
            ..thesis()
        };
        let leo = build(&cfg, start()).unwrap();
        let (r, v) = leo.initial_state_eci();
        assert!((r - r_eci).norm() < 1e-6, "{}", (r - r_eci).norm());
        assert!((v - v_eci).norm() < 1e-9);
        // ECEF and ECI differ (the test is not vacuous).
        assert!((r_ecef - r_eci).norm() > 1e3);
    }

    #[test]
    fn tle_state_is_sgp4_at_the_scenario_start() {
        let tle = TleConfig {
            line1: "1 25544U 98067A   20194.88612269 -.00002218  00000-0 -31515-4 0  9992".into(),
            line2: "2 25544  51.6461 221.2784 0001413  89.1723 280.4612 15.49507896236008".into(),
        };
        let parsed = Tle::parse(&tle).unwrap();
        let scenario_start = parsed.epoch() + Duration::from_seconds(3600.0);
        let cfg = LeoConfig {
            elements: None,
            tle: Some(tle),
            ..thesis()
        };
        let leo = build(&cfg, scenario_start).unwrap();
        let (r, v) = leo.initial_state_eci();
        let (r_ref, v_ref) = parsed.state_teme(scenario_start).unwrap();
        assert_eq!((r, v), (r_ref, v_ref));
        assert!((r.norm() - 6.79e6).abs() < 30e3, "{}", r.norm());
    }

    #[test]
    fn invalid_configuration_is_refused() {
        let mut cfg = thesis();
        cfg.forces.mass_kg = -1.0;
        match build(&cfg, start()) {
            Err(PropagateError::Config(invalid)) => assert_eq!(invalid.field, "forces.mass_kg"),
            other => panic!("unexpected {other:?}"),
        }
    }
}
