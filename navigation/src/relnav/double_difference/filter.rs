//! The double-difference Kalman filter of two spacecraft (module docs of [`super`]).
//!
//! State: the baseline `b = r_chaser - r_target` and its rate (ECI, m and m/s), then per
//! system the receivers' clock difference `c (dt_c - dt_t)` (m), per satellite its
//! single-difference slant ionosphere `I_s` (chaser minus target, m, on the GPS L1
//! frequency) and per satellite and signal its single-difference ambiguity `N_s`
//! (cycles). The measurements are the single differences between the receivers (chaser
//! `c` minus target `t`; `rho` the geometric range to the satellite at the receiver's own
//! transmit time, `dT` the satellite clock there, `mu_f = (f_L1 / f)^2`):
//!
//! `SD P_f   = SD (rho - c dT) + c dt + mu_f I_s`
//! `SD Phi_f = SD (rho - c dT) + c dt - mu_f I_s + lambda_f N_s`  (m)
//!
//! Their information is that of the double differences (the clock difference `c dt`
//! takes the rest) plus one thing the double differences lack: the clock difference
//! itself. The receivers sample on their own clocks, so the chaser measures at
//! `t_c = t_t + (tag_c - tag_t) - dt`, where it is `v_c dt` away from where it is at the
//! target's instant: `r_c(t_c) = r_t + C b + v_c ((tag_c - tag_t) - dt)`. In a double
//! difference that move is exactly a baseline change along `v_c` (`d DD / d dt = -d DD /
//! d b . v_c`), so `dt` must come from elsewhere: a nanosecond is 7.6 mm at LEO speed.
//! One fix's clock is good to nanoseconds; here the code of every satellite and epoch
//! estimates it through the constant single-difference ambiguities (the phase ties the
//! clock's change to millimetres), `d SD / d (c dt) = 1 + (e_c . v_c) / c`.
//!
//! **Orbit errors** (`orbit_error_sigma_m` > 0; off by default). A satellite's broadcast
//! position is off by `o_s` (true minus broadcast, ECEF) and the anchor, the target's
//! position from its orbit filter, by `o_t`; both move the single difference by
//!
//! `d SD = (e_c - e_t) . (o_s - o_t)`, `|e_c - e_t| ~ |b_perp| / rho`
//!
//! (`e` each receiver's unit line of sight to the satellite, `b_perp` the baseline across
//! it): 1 % across 200 km, a centimetre per metre, on code and phase alike, against the
//! phase's millimetres. The satellite clock cancels. Each `o` is three states, each axis
//! a first-order Gauss-Markov process (Gelb table 4.4-1; as the reduced-dynamic filter's
//! range errors): over a step `dt`, `o <- exp(-dt / tau) o` with the variance
//! `sigma^2 (1 - exp(-2 dt / tau))` added, `sigma` = `orbit_error_sigma_m`, `tau` =
//! `orbit_error_tau_s` for the satellites and [`ANCHOR_TAU_S`] for the anchor; a new
//! satellite's start at zero with `sigma^2`. Why states of the orbit error and not a
//! measurement covariance or one single-difference range-error state per satellite:
//! the errors are correlated over hours, which a covariance per epoch would let the
//! filter average away in minutes; and the direction `e_c - e_t` turns with the
//! baseline, which turns with the orbit (38 deg in 10 min), so one orbit error's effect
//! changes within minutes while the error itself does not: the three states keep the
//! error's hours and the geometry's known turn.
//!
//! The ranges are computed exactly at each receiver (no short-baseline `-los . b`), so
//! 200 km costs nothing. The single differences of one epoch are independent, of variance
//! `sigma_t(el_t)^2 + sigma_c(el_c)^2` (thesis eqs. 2.4-9/2.4-10). The integers are those
//! of the double differences ([`super::fixing`]); the single-difference states need no
//! re-mapping when the reference satellite changes.

use super::config::DoubleDifferenceConfig;
use super::dynamics::{process_noise, propagate, transition};
use nalgebra::{DMatrix, DVector};
use skyforge_gnss::observation::ElevationNoise;
use skyforge_gnss::signal::Signal;
use skyforge_orbits::constants::C_MPS;
use skyforge_orbits::ephemeris::{SatId, System};
use skyforge_orbits::propagate::ForceModel;
use skyforge_orbits::{Mat3, Vec3};
use std::collections::BTreeMap;

/// The GPS L1 frequency the ionosphere states refer to (Hz).
const F_IONO_REF_HZ: f64 = 1_575.42e6;

/// Correlation time of the anchor's position error (s), with orbit errors on.
/// # assumed: 10 min: the anchor follows the target's fixes, whose satellites change every
/// few minutes on a LEO (about ten in view, each for about 45 min), and with them the
/// broadcast errors the fixes take; the satellites' own errors last hours.
pub(crate) const ANCHOR_TAU_S: f64 = 600.0;

/// One signal's single differences of one satellite (chaser minus target).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct SignalSd {
    pub signal: Signal,
    pub code_m: f64,
    pub phase_cycles: f64,
    /// A cycle slip or a new track at either receiver: the ambiguity starts afresh.
    pub slip: bool,
}

/// One satellite seen by both receivers at one epoch.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct SatPair {
    pub sat: SatId,
    /// The satellite at its transmit time toward each receiver, in the Earth-fixed frame
    /// of that receiver's receive instant (m).
    pub at_target_m: Vec3,
    pub at_chaser_m: Vec3,
    /// `c (dT at the chaser's transmit time - dT at the target's)` (m).
    pub clock_sd_m: f64,
    /// Elevations at the target and the chaser (rad): the weights.
    pub elevation_rad: [f64; 2],
    pub signals: Vec<SignalSd>,
}

/// What one epoch gives the filter.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct DdEpoch {
    /// The target's position at its receive instant (ECEF, m): the anchor of the ranges.
    pub r_target_ecef_m: Vec3,
    /// ECI -> ECEF at the target's receive instant.
    pub c_eci_ecef: Mat3,
    /// The chaser's velocity (ECEF, m/s): its move between the receive instants.
    pub v_chaser_ecef_mps: Vec3,
    /// The chaser's time tag less the target's (s): its receive instant is this less the
    /// clock difference after the target's.
    pub tag_difference_s: f64,
    pub sats: Vec<SatPair>,
}

/// The target's state (ECI) at a time: what the relative dynamics move about.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Anchor {
    pub t_s: f64,
    pub r_eci_m: Vec3,
    pub v_eci_mps: Vec3,
}

/// A state beyond the baseline and its rate.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub(crate) enum Key {
    /// `c (dt_chaser - dt_target)` of one system's time (m).
    Clock(System),
    Iono(SatId),
    Ambiguity(SatId, Signal),
    /// One ECEF axis (0-2) of a satellite's orbit error, true minus broadcast (m).
    Orbit(SatId, usize),
    /// One ECEF axis (0-2) of the anchor's error, true minus the orbit filter's (m).
    Anchor(usize),
}

/// One double difference of the epoch: satellite `sat` against `reference` on `signal`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Pairing {
    pub signal: Signal,
    pub reference: SatId,
    pub sat: SatId,
}

/// The filter.
#[derive(Debug, Clone)]
pub(crate) struct DdFilter {
    pub(crate) config: DoubleDifferenceConfig,
    forces: ForceModel,
    /// `[b, b_dot]` then one entry per key.
    pub(crate) x: DVector<f64>,
    pub(crate) p: DMatrix<f64>,
    pub(crate) keys: Vec<Key>,
    /// When each satellite was last measured (s).
    last_seen: BTreeMap<SatId, f64>,
    anchor: Option<Anchor>,
    /// A new system's clock difference (m).
    clock_start_m: f64,
}

/// `mu_f` of the ionosphere on `signal` relative to L1.
fn iono_factor(signal: Signal) -> f64 {
    (F_IONO_REF_HZ / signal.carrier_hz()).powi(2)
}

impl DdFilter {
    /// A filter with no state yet ([`DdFilter::start`] gives it one).
    pub(crate) fn new(config: DoubleDifferenceConfig, forces: ForceModel) -> Self {
        Self {
            config,
            forces,
            x: DVector::zeros(0),
            p: DMatrix::zeros(0, 0),
            keys: Vec::new(),
            last_seen: BTreeMap::new(),
            anchor: None,
            clock_start_m: 0.0,
        }
    }

    /// Whether the filter has a baseline.
    pub(crate) fn started(&self) -> bool {
        self.anchor.is_some()
    }

    /// Start at `anchor` with the baseline `b`, `b_dot` (ECI) of standard deviations
    /// `sigma_b_m`, `sigma_v_mps` per axis; each system's clock difference starts at
    /// `clock_m` (the fixes') when first seen.
    pub(crate) fn start(
        &mut self,
        anchor: Anchor,
        (b, b_dot): (Vec3, Vec3),
        (sigma_b_m, sigma_v_mps): (f64, f64),
        clock_m: f64,
    ) {
        self.clock_start_m = clock_m;
        self.x = DVector::from_iterator(6, b.iter().chain(b_dot.iter()).copied());
        self.p = DMatrix::from_diagonal(&DVector::from_fn(6, |i, _| {
            if i < 3 {
                sigma_b_m * sigma_b_m
            } else {
                sigma_v_mps * sigma_v_mps
            }
        }));
        self.keys.clear();
        self.last_seen.clear();
        self.anchor = Some(anchor);
    }

    /// The baseline and its rate (ECI).
    pub(crate) fn baseline(&self) -> (Vec3, Vec3) {
        (
            Vec3::new(self.x[0], self.x[1], self.x[2]),
            Vec3::new(self.x[3], self.x[4], self.x[5]),
        )
    }

    /// The index of `key` in the state.
    pub(crate) fn index(&self, key: Key) -> Option<usize> {
        self.keys.iter().position(|k| *k == key).map(|i| i + 6)
    }

    /// Move the baseline to `anchor`'s time along the relative dynamics (the target's
    /// state of the previous epoch integrated with the chaser's); `anchor` becomes the
    /// target's state the next step starts from.
    pub(crate) fn predict(&mut self, anchor: Anchor) {
        let Some(previous) = self.anchor else {
            return;
        };
        let dt = anchor.t_s - previous.t_s;
        let (b, b_dot) = self.baseline();
        let (b1, v1) = propagate(
            &self.forces,
            (previous.r_eci_m, previous.v_eci_mps),
            (b, b_dot),
            dt,
        );
        let phi6 = transition(self.forces.gm(), &(previous.r_eci_m + b), dt);
        let n = self.x.len();
        let mut phi = DMatrix::<f64>::identity(n, n);
        phi.view_mut((0, 0), (6, 6)).copy_from(&phi6);
        let mut q = DMatrix::<f64>::zeros(n, n);
        q.view_mut((0, 0), (6, 6))
            .copy_from(&process_noise(self.config.acceleration_sigma_mps2, dt));
        let iono_var = self.config.iono_sigma_m_per_sqrt_s.powi(2) * dt.abs();
        let clock_var = self.config.clock_sigma_m_per_sqrt_s.powi(2) * dt.abs();
        // The orbit errors: first-order Gauss-Markov (module docs).
        let sigma2 = self.config.orbit_error_sigma_m.powi(2);
        let decay = |tau_s: f64| (-dt.abs() / tau_s).exp();
        let orbit_decay = [decay(self.config.orbit_error_tau_s), decay(ANCHOR_TAU_S)];
        for (i, key) in self.keys.iter().enumerate() {
            let k = i + 6;
            let d = match key {
                Key::Iono(_) => {
                    q[(k, k)] = iono_var;
                    continue;
                }
                Key::Clock(_) => {
                    q[(k, k)] = clock_var;
                    continue;
                }
                Key::Ambiguity(..) => continue,
                Key::Orbit(..) => orbit_decay[0],
                Key::Anchor(_) => orbit_decay[1],
            };
            phi[(k, k)] = d;
            q[(k, k)] = sigma2 * (1.0 - d * d);
            self.x[k] *= d;
        }
        for i in 0..3 {
            self.x[i] = b1[i];
            self.x[i + 3] = v1[i];
        }
        self.p = &phi * &self.p * phi.transpose() + q;
        self.anchor = Some(anchor);
    }

    /// Append a state of value `value` and variance `var`, uncorrelated.
    fn add(&mut self, key: Key, value: f64, var: f64) {
        let n = self.x.len();
        self.x = self.x.clone().insert_row(n, value);
        self.p = self.p.clone().insert_row(n, 0.0).insert_column(n, 0.0);
        self.p[(n, n)] = var;
        self.keys.push(key);
    }

    /// Set state `i` to `value` with variance `var`, uncorrelated with the others.
    fn reset(&mut self, i: usize, value: f64, var: f64) {
        self.x[i] = value;
        self.p.row_mut(i).fill(0.0);
        self.p.column_mut(i).fill(0.0);
        self.p[(i, i)] = var;
    }

    /// Drop the states of satellites unseen for longer than the gap allows, add those of
    /// new satellites and signals, and restart the ambiguities that slipped.
    fn manage_states(&mut self, t_s: f64, sats: &[SatPair]) {
        for s in sats {
            self.last_seen.insert(s.sat, t_s);
        }
        let max_gap = self.config.max_gap_s;
        let gone = |sat: &SatId, seen: &BTreeMap<SatId, f64>| {
            seen.get(sat).is_none_or(|t| t_s - t > max_gap)
        };
        let keep: Vec<bool> = (self.keys.iter())
            .map(|k| match k {
                Key::Clock(_) | Key::Anchor(_) => true,
                Key::Iono(sat) | Key::Ambiguity(sat, _) | Key::Orbit(sat, _) => {
                    !gone(sat, &self.last_seen)
                }
            })
            .collect();
        if keep.iter().any(|k| !k) {
            let rows: Vec<usize> = (0..6)
                .chain((0..self.keys.len()).filter(|&i| keep[i]).map(|i| i + 6))
                .collect();
            self.x = DVector::from_iterator(rows.len(), rows.iter().map(|&i| self.x[i]));
            self.p = DMatrix::from_fn(rows.len(), rows.len(), |i, j| self.p[(rows[i], rows[j])]);
            let mut k = 0;
            self.keys.retain(|_| {
                k += 1;
                keep[k - 1]
            });
            self.last_seen.retain(|_, t| t_s - *t <= max_gap);
        }
        let iono0 = self.config.iono_initial_sigma_m.powi(2);
        let amb0 = self.config.ambiguity_initial_sigma_cycles.powi(2);
        let orbit0 = self.config.orbit_error_sigma_m.powi(2);
        let orbits = orbit0 > 0.0;
        for s in sats {
            if self.index(Key::Clock(s.sat.system)).is_none() {
                // # assumed: 10 m about the fixes' difference (nanoseconds of two code fixes).
                self.add(Key::Clock(s.sat.system), self.clock_start_m, 100.0);
            }
            if self.index(Key::Iono(s.sat)).is_none() {
                self.add(Key::Iono(s.sat), 0.0, iono0);
            }
            for axis in 0..3 {
                if orbits && self.index(Key::Anchor(axis)).is_none() {
                    self.add(Key::Anchor(axis), 0.0, orbit0);
                }
                if orbits && self.index(Key::Orbit(s.sat, axis)).is_none() {
                    self.add(Key::Orbit(s.sat, axis), 0.0, orbit0);
                }
            }
            for f in &s.signals {
                // Code minus phase: the clocks cancel, the ionosphere (2 mu I) is left to
                // the variance.
                let value = f.phase_cycles - f.code_m / f.signal.wavelength_m();
                match self.index(Key::Ambiguity(s.sat, f.signal)) {
                    None => self.add(Key::Ambiguity(s.sat, f.signal), value, amb0),
                    Some(i) if f.slip => self.reset(i, value, amb0),
                    Some(_) => {}
                }
            }
        }
    }

    /// The indices of satellite `sat`'s and the anchor's orbit-error states per axis;
    /// `None` with orbit errors off.
    fn orbit_indices(&self, sat: SatId) -> Option<[(usize, usize); 3]> {
        let mut out = [(0, 0); 3];
        for (axis, o) in out.iter_mut().enumerate() {
            *o = (
                self.index(Key::Orbit(sat, axis))?,
                self.index(Key::Anchor(axis))?,
            );
        }
        Some(out)
    }

    /// The double differences of the epoch: per system and signal the satellite highest
    /// above the target's horizon is the reference.
    pub(crate) fn pairings(sats: &[SatPair]) -> Vec<Pairing> {
        let mut best: BTreeMap<(System, Signal), (f64, SatId)> = BTreeMap::new();
        for s in sats {
            for f in &s.signals {
                let e = best
                    .entry((s.sat.system, f.signal))
                    .or_insert((s.elevation_rad[0], s.sat));
                if s.elevation_rad[0] > e.0 {
                    *e = (s.elevation_rad[0], s.sat);
                }
            }
        }
        let mut out = Vec::new();
        for ((_, signal), (_, reference)) in best {
            for s in sats {
                if s.sat != reference && s.signals.iter().any(|f| f.signal == signal) {
                    out.push(Pairing {
                        signal,
                        reference,
                        sat: s.sat,
                    });
                }
            }
        }
        out
    }

    /// Take the epoch's single differences; the double differences whose integers
    /// [`super::fixing`] resolves (empty when fewer than two satellites share a signal).
    pub(crate) fn update(&mut self, t_s: f64, epoch: &DdEpoch) -> Vec<Pairing> {
        self.manage_states(t_s, &epoch.sats);
        let rows: usize = epoch.sats.iter().map(|s| 2 * s.signals.len()).sum();
        let n = self.x.len();
        let mut h = DMatrix::<f64>::zeros(rows, n);
        let mut innovation = DVector::<f64>::zeros(rows);
        let mut r = DMatrix::<f64>::zeros(rows, rows);
        let (b, _) = self.baseline();
        let c = epoch.c_eci_ecef;
        let r_t = epoch.r_target_ecef_m;
        let v_c = epoch.v_chaser_ecef_mps;
        let var = |w: &ElevationNoise, s: &SatPair| {
            w.sigma_m(s.elevation_rad[0]).powi(2) + w.sigma_m(s.elevation_rad[1]).powi(2)
        };
        let mut row = 0;
        for s in &epoch.sats {
            let (Some(ic), Some(ii)) = (
                self.index(Key::Clock(s.sat.system)),
                self.index(Key::Iono(s.sat)),
            ) else {
                continue;
            };
            let clock_m = self.x[ic];
            // The chaser at its own receive instant.
            let r_c = r_t + c * b + v_c * (epoch.tag_difference_s - clock_m / C_MPS);
            let (dt, dc) = (s.at_target_m - r_t, s.at_chaser_m - r_c);
            let los = dc / dc.norm();
            // The orbit errors' states (satellite's, anchor's) per axis and their row
            // `e_c - e_t` (module docs).
            let orbit = self.orbit_indices(s.sat);
            let g = los - dt / dt.norm();
            let orbit_m: f64 = (orbit.iter().flatten().enumerate())
                .map(|(k, &(is, ia))| g[k] * (self.x[is] - self.x[ia]))
                .sum();
            let geometry = dc.norm() - dt.norm() - s.clock_sd_m + orbit_m;
            // d rho_c / d b_eci = -los^T C; d rho_c / d (c dt) = los . v_c / c.
            let row_b = -los.transpose() * c;
            let d_clock = 1.0 + los.dot(&v_c) / C_MPS;
            let iono = self.x[ii];
            for f in &s.signals {
                let Some(ia) = self.index(Key::Ambiguity(s.sat, f.signal)) else {
                    continue;
                };
                let lambda = f.signal.wavelength_m();
                let mu = iono_factor(f.signal);
                let (code, phase) = (row, row + 1);
                row += 2;
                for j in 0..3 {
                    h[(code, j)] = row_b[j];
                    h[(phase, j)] = row_b[j];
                }
                h[(code, ic)] = d_clock;
                h[(phase, ic)] = d_clock;
                h[(code, ii)] = mu;
                h[(phase, ii)] = -mu;
                h[(phase, ia)] = lambda;
                for (k, &(is, ia)) in orbit.iter().flatten().enumerate() {
                    for r in [code, phase] {
                        h[(r, is)] = g[k];
                        h[(r, ia)] = -g[k];
                    }
                }
                innovation[code] = f.code_m - (geometry + clock_m + mu * iono);
                innovation[phase] = f.phase_cycles * lambda
                    - (geometry + clock_m - mu * iono + lambda * self.x[ia]);
                r[(code, code)] = var(&self.config.code, s);
                r[(phase, phase)] = var(&self.config.phase, s);
            }
        }
        if row > 0 {
            let (h, innovation, r) = (
                h.rows(0, row).into_owned(),
                innovation.rows(0, row).into_owned(),
                r.view((0, 0), (row, row)).into_owned(),
            );
            self.measure(&h, &innovation, &r);
        }
        Self::pairings(&epoch.sats)
    }

    /// The Kalman update with rows `h`, innovations `z - h(x)` and their covariance `r`
    /// (Joseph form, kept symmetric).
    pub(crate) fn measure(
        &mut self,
        h: &DMatrix<f64>,
        innovation: &DVector<f64>,
        r: &DMatrix<f64>,
    ) {
        let ph = &self.p * h.transpose();
        let s = h * &ph + r;
        let Some(chol) = s.clone().cholesky() else {
            return;
        };
        let k = chol.solve(&ph.transpose()).transpose();
        self.x += &k * innovation;
        let n = self.x.len();
        let i_kh = DMatrix::<f64>::identity(n, n) - &k * h;
        let p = &i_kh * &self.p * i_kh.transpose() + &k * r * k.transpose();
        self.p = (&p + p.transpose()) * 0.5;
    }
}
