//! The reduced-dynamic extended Kalman filter: the orbit of [`super::dynamics`], the
//! receiver clock (offset and drift, plus a bias per further system), a range error per
//! satellite and a float ambiguity per carrier-phase arc ([`super::state`]), updated at
//! every epoch by the pseudoranges, the range rates of the Doppler and the carrier phases
//! (Montenbruck and Gill 2000, section 8.3, the extended Kalman filter; Montenbruck, van
//! Helleputte, Kroes and Gill 2005, the spaceborne receiver's measurement model).
//!
//! Measurement models at the receive instant `t = tag - b / c` (receiver ECEF position
//! `r_e`; the satellite at its transmit time seen in the ECEF frame of `t`,
//! [`crate::pvt::Transmitted`]):
//! - code: `P = |r_s - r_e| + b + b_sys - c dt_s + s` (`s` the satellite's range error;
//!   no atmosphere: a receiver in orbit is above the ground ionosphere model and the
//!   troposphere, and two carriers remove the ionosphere where it exists);
//! - range rate from the Doppler: `-lambda D = e . (v_s - v_e) + d - c ddt_s`;
//! - carrier: `lambda phi = |r_s - r_e| + b + b_sys - c dt_s + s + A`, `A` the arc's
//!   ambiguity (m), started at `lambda phi - P` and carried while the receiver keeps lock.

use super::ReducedDynamicConfig;
use super::dynamics::{Orbit9, OrbitModel};
use super::observed::{Observed, observed};
use super::rows::{Receiver, Row};
use super::state::{Slot, State};
use crate::orbit_determination::EcefEstimate;
use crate::orbit_determination::position_filter::ecef_estimate;
use crate::pvt::{
    Measurement, PvtConfig, SatView, Transmitted, local_frame, ranging_delay_beyond_tgd_s, solve,
    solve_velocity,
};
use hifitime::Epoch;
use nalgebra::{DMatrix, DVector, Matrix6};
use skyforge_gnss::observation::ObsRecord;
use skyforge_orbits::constants::C_MPS;
use skyforge_orbits::ephemeris::{EphemerisStore, System};
use skyforge_orbits::frames::az_el;
use skyforge_orbits::frames::earth_rotation::EarthRotation;
use skyforge_orbits::propagate::ForceModel;
use skyforge_orbits::time::TimeOrigin;

/// The receiver clock's offset (m) and drift (m/s) in the state.
const BIAS: usize = 9;
const DRIFT: usize = 10;
/// The first inter-system bias (m).
const FIRST_ISB: usize = 11;

/// The initial 1-sigma of a state from a single-point fix: position (m), velocity (m/s),
/// drift (m/s), clock offset and biases (m).
/// # assumed: a few times a single-point fix's errors; the filter forgets them in minutes.
const INITIAL_SIGMA: [f64; 4] = [10.0, 1.0, 1.0, 30.0];

/// The predictions after a clock jump: the first from the jumped offset, a second to
/// take up the few metres the receive instant's move left (a LEO moves 7.5 m in 1 us).
const JUMP_PASSES: usize = 3;

/// One observed ranging above the mask with its satellite as seen from the predicted
/// orbit (what every row of it needs; the same before and after the slots follow the
/// epoch's satellites).
struct Seen<'o> {
    o: &'o Observed,
    view: SatView,
}

/// The reduced-dynamic filter of a receiver's observations.
#[derive(Debug, Clone)]
pub struct ReducedDynamicFilter {
    config: ReducedDynamicConfig,
    model: OrbitModel,
    earth: EarthRotation,
    /// The systems of the observations: the clock offset is the first's, each further
    /// one has an inter-system bias.
    systems: Vec<System>,
    mask_rad: f64,
    state: Option<State>,
}

impl ReducedDynamicFilter {
    /// A filter for a run starting at `start`, on observations of `systems` (the first
    /// one's clock is the receiver's), with satellites below `elevation_mask_deg` left out.
    pub fn new(
        config: ReducedDynamicConfig,
        start: Epoch,
        systems: &[System],
        elevation_mask_deg: f64,
    ) -> Self {
        let model = OrbitModel {
            forces: ForceModel::new(&config.forces, start, 0.0),
            tau_s: config.empirical_tau_s,
            sigma_mps2: config.empirical_sigma_mps2,
        };
        Self {
            config,
            model,
            earth: EarthRotation::at_origin(start),
            systems: systems.to_vec(),
            mask_rad: elevation_mask_deg.to_radians(),
            state: None,
        }
    }

    /// Take the epoch tagged `tag_s` (receiver time, s since `origin`, the ephemerides'
    /// and the filter's start; epochs in time order) with its `records`; the estimate
    /// after it, or `None` while the filter has no state (it starts from a single-point
    /// fix with a Doppler velocity).
    pub fn epoch(
        &mut self,
        tag_s: f64,
        records: &[ObsRecord],
        store: &EphemerisStore,
        origin: &TimeOrigin,
    ) -> Option<EcefEstimate> {
        let observed = observed(records, &self.systems, self.config.ionosphere);
        let (mut state, (receiver, seen)) = match self.state.take() {
            Some(state) => self.predict_through_jumps(state, tag_s, &observed, store),
            None => {
                let state = self.initialise(tag_s, &observed, store, origin)?;
                let seen = self.seen(&state, &observed, store);
                (state, seen)
            }
        };
        self.follow(&mut state, &observed);
        let rows = self.rows(&mut state, &receiver, &seen);
        update(&mut state, &rows);
        let e = self.estimate(&state);
        self.state = Some(state);
        Some(e)
    }

    /// The first state: a single-point fix and its Doppler velocity.
    fn initialise(
        &self,
        tag_s: f64,
        observed: &[Observed],
        store: &EphemerisStore,
        origin: &TimeOrigin,
    ) -> Option<State> {
        let meas: Vec<Measurement> = observed.iter().map(Observed::measurement).collect();
        let pvt = PvtConfig {
            elevation_mask_rad: self.mask_rad,
            troposphere: false,
            ..PvtConfig::default()
        };
        let fix = solve(&meas, tag_s, store, origin, &pvt, None).ok()?;
        let velocity = solve_velocity(&meas, tag_s, store, &fix).ok()?;
        let t_s = tag_s - fix.clock_bias_m / C_MPS;
        let (r, v) = self
            .earth
            .ecef_to_eci(t_s, &fix.r_ecef_m, &velocity.v_ecef_mps);
        let n = FIRST_ISB + self.systems.len().saturating_sub(1);
        let mut x = DVector::zeros(n);
        x.fixed_rows_mut::<3>(0).copy_from(&r);
        x.fixed_rows_mut::<3>(3).copy_from(&v);
        x[BIAS] = fix.clock_bias_m;
        x[DRIFT] = velocity.clock_drift_mps;
        if let (Some(isb), true) = (fix.inter_system_bias_m, n > FIRST_ISB) {
            x[FIRST_ISB] = isb;
        }
        let [sr, sv, sd, sb] = INITIAL_SIGMA;
        let sa = self.config.empirical_sigma_mps2;
        let ends = [(3, sr), (6, sv), (BIAS, sa), (DRIFT, sb), (FIRST_ISB, sd)];
        let sigma = |k: usize| ends.iter().find(|(end, _)| k < *end).map_or(sb, |e| e.1);
        let p = DMatrix::from_fn(n, n, |i, j| if i == j { sigma(i).powi(2) } else { 0.0 });
        Some(State {
            t_s,
            tag_s,
            x,
            p,
            first_slot: n,
            slots: Vec::new(),
        })
    }

    /// The state at the receive instant of the epoch tagged `tag_s`: the orbit
    /// integrated, the clock's offset grown by its drift, the satellites' range errors
    /// decayed, each with its process noise.
    fn predict(&self, s: State, tag_s: f64) -> State {
        let c = &self.config;
        let bias = s.x[BIAS] + s.x[DRIFT] * (tag_s - s.tag_s);
        let t_s = tag_s - bias / C_MPS;
        let dt = t_s - s.t_s;
        let orbit = Orbit9::from_iterator(s.x.rows(0, 9).iter().copied());
        let (orbit1, phi9, q9) = self.model.propagate(s.t_s, &orbit, dt);
        let n = s.x.len();
        let mut phi = DMatrix::<f64>::identity(n, n);
        phi.view_mut((0, 0), (9, 9)).copy_from(&phi9);
        phi[(BIAS, DRIFT)] = dt;
        let mut q = DMatrix::<f64>::zeros(n, n);
        q.view_mut((0, 0), (9, 9)).copy_from(&q9);
        // The clock: white frequency noise on the offset, a random walk of the drift.
        let (qb, qd, h) = (
            c.clock_walk_m_sqrt_s.powi(2),
            c.drift_walk_mps_sqrt_s.powi(2),
            dt.abs(),
        );
        q[(BIAS, BIAS)] = qb * h + qd * h.powi(3) / 3.0;
        q[(BIAS, DRIFT)] = qd * dt * h / 2.0;
        q[(DRIFT, BIAS)] = q[(BIAS, DRIFT)];
        q[(DRIFT, DRIFT)] = qd * h;
        // The satellites' range errors: first-order Gauss-Markov (Gelb table 4.4-1).
        let decay = (-h / c.satellite_tau_s).exp();
        for (i, slot) in s.slots.iter().enumerate() {
            if let Slot::Bias(_) = slot {
                let k = s.first_slot + i;
                phi[(k, k)] = decay;
                q[(k, k)] = c.satellite_sigma_m.powi(2) * (1.0 - decay * decay);
            }
        }
        let mut x = &phi * &s.x;
        x.rows_mut(0, 9).copy_from(&orbit1);
        let p = &phi * &s.p * phi.transpose() + q;
        State {
            t_s,
            tag_s,
            x,
            p: symmetric(p),
            ..s
        }
    }

    /// [`Self::predict`] to the epoch tagged `tag_s`; where the receiver's clock jumped
    /// ([`Self::clock_jump`]) the jump moves the clock offset, whose spread starts
    /// again, and the prediction is made again from there (the receive instant follows
    /// the offset), at most [`JUMP_PASSES`] times.
    fn predict_through_jumps<'o>(
        &self,
        mut previous: State,
        tag_s: f64,
        observed: &'o [Observed],
        store: &EphemerisStore,
    ) -> (State, (Receiver, Vec<Seen<'o>>)) {
        for _ in 0..JUMP_PASSES {
            let predicted = self.predict(previous.clone(), tag_s);
            let seen = self.seen(&predicted, observed, store);
            let Some(jump) = self.clock_jump(&predicted, &seen.1) else {
                return (predicted, seen);
            };
            let value = previous.x[BIAS] + jump;
            previous.restart(BIAS, value, self.config.code_sigma_m.powi(2) * 100.0);
        }
        let predicted = self.predict(previous, tag_s);
        let seen = self.seen(&predicted, observed, store);
        (predicted, seen)
    }

    /// Drop the slots of satellites no longer observed and of arcs that lost lock; start
    /// a range error for every new satellite and an ambiguity for every new arc.
    fn follow(&self, s: &mut State, observed: &[Observed]) {
        let carrier = self.config.observables.carrier;
        s.retain(|slot| match slot {
            Slot::Bias(sat) => observed.iter().any(|o| o.ranging.sat == *sat),
            Slot::Ambiguity(arc) => observed
                .iter()
                .any(|o| o.arc() == *arc && o.phase_m.is_some() && !o.lost_lock),
        });
        for o in observed {
            let bias = Slot::Bias(o.ranging.sat);
            if s.index(&bias).is_none() {
                s.push(bias, 0.0, self.config.satellite_sigma_m.powi(2));
            }
            let arc = Slot::Ambiguity(o.arc());
            if let (true, None, Some((value, variance))) = (
                carrier,
                s.index(&arc),
                o.ambiguity_start(self.config.code_sigma_m),
            ) {
                s.push(arc, value, variance);
            }
        }
    }

    /// Each observed ranging above the mask with its ephemeris and its satellite as seen
    /// from the state's orbit; and the receiver the rows need.
    fn seen<'o>(
        &self,
        s: &State,
        observed: &'o [Observed],
        store: &EphemerisStore,
    ) -> (Receiver, Vec<Seen<'o>>) {
        let (r_e, v_e) = self.earth.eci_to_ecef(s.t_s, &s.r_eci(), &s.v_eci());
        let receiver = Receiver {
            rot: self.earth.c_eci_ecef(s.t_s),
            omega: self.earth.omega_rad_s(),
            v_e,
        };
        let frame = local_frame(&r_e);
        let mut out = Vec::new();
        for o in observed {
            let m = &o.ranging;
            let Some(eph) = store.select(m.sat, s.tag_s) else {
                continue;
            };
            let tx = Transmitted::of(eph, s.tag_s, m.pseudorange_m)
                .clock_shifted(ranging_delay_beyond_tgd_s(m, &eph.eph));
            let view = tx.seen_from(&r_e, None);
            if frame.is_some_and(|f| az_el(&(f * view.los)).1 < self.mask_rad) {
                continue;
            }
            out.push(Seen { o, view });
        }
        (receiver, out)
    }

    /// The state indices of a code's clock, system and satellite terms (each enters with
    /// a one).
    fn offset_indices(&self, s: &State, seen: &Seen) -> [Option<usize>; 3] {
        let sat = seen.o.ranging.sat;
        [
            Some(BIAS),
            self.isb_index(sat.system),
            s.index(&Slot::Bias(sat)),
        ]
    }

    /// The modelled code (m): the range with the clock, system and satellite terms.
    fn code(&self, s: &State, seen: &Seen) -> f64 {
        let offsets: f64 = self
            .offset_indices(s, seen)
            .iter()
            .flatten()
            .map(|&k| s.x[k])
            .sum();
        seen.view.range_m - C_MPS * seen.view.clock_s + offsets
    }

    /// The receiver clock's jump at this epoch (m), when the median code innovation lies
    /// beyond the gate of the clock offset's predicted spread: a receiver that re-steers
    /// its clock moves every pseudorange and its epoch tags at once.
    fn clock_jump(&self, s: &State, seen: &[Seen]) -> Option<f64> {
        let mut innovations: Vec<f64> = (seen.iter())
            .map(|r| r.o.ranging.pseudorange_m - self.code(s, r))
            .collect();
        if innovations.is_empty() {
            return None;
        }
        innovations.sort_by(f64::total_cmp);
        let median = innovations[innovations.len() / 2];
        let spread = s.p[(BIAS, BIAS)] + self.config.code_sigma_m.powi(2);
        (median.powi(2) > self.config.gate_sigma.powi(2) * spread).then_some(median)
    }

    /// The epoch's measurement rows, linearised at the predicted state, those that pass
    /// the gate; an arc whose carrier fails it starts again from this epoch's code.
    fn rows(&self, s: &mut State, receiver: &Receiver, seen: &[Seen]) -> Vec<Row> {
        let c = &self.config;
        let n = s.x.len();
        let mut rows = Vec::new();
        for one in seen {
            let (o, view) = (one.o, &one.view);
            let m = &o.ranging;
            let code = self.code(s, one);
            let mut h = receiver.range_row(n, view);
            for k in self.offset_indices(s, one).into_iter().flatten() {
                h[k] = 1.0;
            }
            let nf = m.noise_factor();
            rows.push(Row {
                innovation: m.pseudorange_m - code,
                variance: (c.code_sigma_m * nf).powi(2),
                h: h.clone(),
            });
            if let (true, Some(doppler)) = (c.observables.doppler, o.doppler_hz) {
                let (rate, mut h) = receiver.rate_row(n, view);
                h[DRIFT] = 1.0;
                rows.push(Row {
                    innovation: -doppler * C_MPS / m.signal.carrier_hz() - rate - s.x[DRIFT],
                    variance: c.doppler_sigma_mps.powi(2),
                    h,
                });
            }
            let arc = s.index(&Slot::Ambiguity(o.arc()));
            if let (Some(phase), Some(k)) = (o.phase_m, arc) {
                let mut h = h;
                h[k] = 1.0;
                let row = Row {
                    innovation: phase - code - s.x[k],
                    variance: (c.phase_sigma_m * nf).powi(2),
                    h,
                };
                if self.passes(s, &row) {
                    rows.push(row);
                } else if let Some((value, variance)) = o.ambiguity_start(c.code_sigma_m) {
                    s.restart(k, value, variance);
                }
            }
        }
        rows.retain(|row| self.passes(s, row));
        rows
    }

    /// Whether a row's innovation lies within `gate_sigma` of its predicted spread.
    fn passes(&self, s: &State, row: &Row) -> bool {
        let spread = row.h.dot(&(&s.p * &row.h)) + row.variance;
        row.innovation.powi(2) <= self.config.gate_sigma.powi(2) * spread
    }

    fn isb_index(&self, system: System) -> Option<usize> {
        let i = self.systems.iter().position(|s| *s == system)?;
        (i > 0).then_some(FIRST_ISB + i - 1)
    }

    /// The state's orbit as an ECEF estimate.
    fn estimate(&self, s: &State) -> EcefEstimate {
        let cov = Matrix6::from_fn(|i, j| s.p[(i, j)]);
        ecef_estimate(&self.earth, s.t_s, &s.r_eci(), &s.v_eci(), &cov)
    }
}

/// The Kalman update with every row at once (Joseph form).
fn update(s: &mut State, rows: &[Row]) {
    if rows.is_empty() {
        return;
    }
    let (m, n) = (rows.len(), s.x.len());
    let h = DMatrix::from_fn(m, n, |i, j| rows[i].h[j]);
    let z = DVector::from_iterator(m, rows.iter().map(|r| r.innovation));
    let r = DMatrix::from_diagonal(&DVector::from_iterator(m, rows.iter().map(|r| r.variance)));
    let ph = &s.p * h.transpose();
    let Some(chol) = (&h * &ph + &r).cholesky() else {
        return;
    };
    let k = ph * chol.inverse();
    s.x += &k * z;
    let i_kh = DMatrix::<f64>::identity(n, n) - &k * &h;
    s.p = symmetric(&i_kh * &s.p * i_kh.transpose() + &k * r * k.transpose());
}

fn symmetric(p: DMatrix<f64>) -> DMatrix<f64> {
    (&p + p.transpose()) * 0.5
}
