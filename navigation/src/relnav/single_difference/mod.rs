//! Mode `single-difference` of `skyforge relnav`: the book's pseudorange relative DGPS
//! filter (section 5.6.4, eq. 5-59): a Kalman filter of the chaser's position and
//! velocity relative to the target (target orbit frame) and of the receivers' clock
//! difference and its drift, updated by the single differences (chaser minus target) of
//! the pseudoranges and Doppler range rates of every satellite both receivers track.
//!
//! Per epoch of the paired files (the target's receive instant `t`, its fix's):
//! 1. Each receiver's single-point fix on the satellites both track, and its Doppler
//!    velocity; an epoch without both is missed.
//! 2. The target's orbit filter (`[target_orbit]`, as the other modes) on its fix: the
//!    target's state the chaser's is relative to, and the orbit frame.
//! 3. The relative state predicted by the Hill dynamics of eq. 5-34 with `U` and the
//!    relative clock ([`filter`]); the first epoch starts it from the two fixes'
//!    difference (moved to one instant as the other modes) and clock difference.
//! 4. The single differences of pseudorange and Doppler range rate of every satellite
//!    both receivers measured, above the elevation mask at both ([`measurement`]).
//!    # assumed: every such satellite, where the book writes four; one signal per
//!    satellite (the first of the run's signals both have: the book's single frequency);
//!    one relative clock for every system (the receivers' inter-system biases alike).
//! 5. The update, each single difference gated at [`filter::GATE_SIGMAS`]; where more
//!    than half the pseudorange differences fail the gate, the filter starts again from
//!    this epoch's fixes.
//!
//! Left out as the book does: the differential ionosphere (32 km apart at 500 km: the
//! pierce points see almost the same electrons) and the satellites' orbit errors beyond
//! `|b| / rho` (eq. 5-58: what remains is twice a receiver's noise).
//!
//! Reads only what the receivers could: observations, broadcast ephemerides, settings.

pub(crate) mod config;
pub(crate) mod filter;
pub(crate) mod measurement;
#[cfg(test)]
mod tests;

use super::engine::{Context, Engine};
use super::estimate::RelativeEstimate;
use super::hill_dynamics::TargetState;
use super::same_satellites::SameSatellites;
use crate::orbit_determination::{FixInput, PositionFilter};
use crate::pvt::{Fix, PvtConfig};
use crate::relative::files::FixStream;
use filter::SdFilter;
use measurement::{CLOCK, EpochFrame, State, satellites};
use skyforge_gnss::observation::ObsEpoch;
use skyforge_gnss::signal::Signal;
use skyforge_orbits::Vec3;
use skyforge_orbits::ephemeris::SatId;
use skyforge_orbits::frames::earth_rotation::EarthRotation;
use skyforge_orbits::frames::relative_in_frame_of;
use std::collections::BTreeSet;

/// The first state's standard deviations (eq. 5-59's order).
/// # assumed: 10 m and 1 m/s per axis, beyond two fixes' and Doppler velocities'
/// differences on the same satellites; 30 m of clock difference, beyond the two fixes'
/// (whose errors on the same satellites largely cancel); 1000 m/s of drift difference,
/// uninformative (two TCXOs' frequency offsets of a few ppm, 300 m/s per ppm).
const START_SIGMA: [f64; 8] = [10.0, 10.0, 10.0, 30.0, 1.0, 1.0, 1.0, 1000.0];

/// One vehicle at an epoch: its fix and Doppler velocity (ECEF).
struct Solution<'a> {
    fix: &'a Fix,
    v_ecef_mps: Vec3,
}

/// The state the two solutions give at the target's state `target` (the chaser's fix
/// moved to the target fix's instant along its velocity, as the other modes do).
fn initial_state(
    (t, c): (&Solution, &Solution),
    target: &TargetState,
    earth: &EarthRotation,
) -> State {
    let t_s = t.fix.t_s;
    let r_c = c.fix.r_ecef_m + c.v_ecef_mps * (t_s - c.fix.t_s);
    let (rt, vt) = earth.ecef_to_eci(t_s, &t.fix.r_ecef_m, &t.v_ecef_mps);
    let (rc, vc) = earth.ecef_to_eci(t_s, &r_c, &c.v_ecef_mps);
    let (p, v) = relative_in_frame_of(&target.r_eci_m, &target.v_eci_mps, &(rc - rt), &(vc - vt));
    let mut x = State::zeros();
    x.fixed_rows_mut::<3>(0).copy_from(&p);
    x.fixed_rows_mut::<3>(4).copy_from(&v);
    x[CLOCK] = c.fix.clock_bias_m - t.fix.clock_bias_m;
    x
}

/// Mode `single-difference` epoch by epoch (module docs).
#[derive(Debug)]
pub(crate) struct SdEngine {
    config: config::SingleDifferenceConfig,
    signals: Vec<Signal>,
    elevation_mask_rad: f64,
    start: hifitime::Epoch,
    /// Each receiver's fixes (target, chaser).
    fixes: [FixStream; 2],
    orbit: PositionFilter,
    filter: Option<SdFilter>,
    earth: EarthRotation,
    set: SameSatellites<BTreeSet<SatId>>,
}

impl SdEngine {
    /// The engine of `config` on `signals` from `start`, the fixes with `pvt`.
    pub(crate) fn new(
        config: &super::RelnavConfig,
        pvt: &PvtConfig,
        signals: &[Signal],
        start: hifitime::Epoch,
    ) -> Self {
        Self {
            config: config.single_difference.clone(),
            signals: signals.to_vec(),
            elevation_mask_rad: config.elevation_mask_deg.to_radians(),
            start,
            fixes: [FixStream::new(pvt), FixStream::new(pvt)],
            orbit: PositionFilter::new(config.target_orbit.clone(), start),
            filter: None,
            earth: EarthRotation::at_origin(start),
            set: SameSatellites::new(),
        }
    }
}

impl Engine for SdEngine {
    fn missed(&self) -> usize {
        self.set.missed()
    }

    fn epoch(
        &mut self,
        (target, chaser): (&ObsEpoch, &ObsEpoch),
        at: &Context,
    ) -> Option<RelativeEstimate> {
        let (store, origin) = (at.store, at.origin);
        let signals = &self.signals;
        let [t_fix, c_fix] = at.fixes(&mut self.fixes, (target, chaser), signals);
        let solution = |epoch: &ObsEpoch, fix| {
            let v = at.velocity(epoch, fix, signals)?;
            Some(Solution { fix, v_ecef_mps: v })
        };
        let both = match (&t_fix, &c_fix) {
            (Ok(tf), Ok(cf)) => solution(target, tf).zip(solution(chaser, cf)),
            _ => None,
        };
        let Some((ts, cs)) = both else {
            return self.set.miss();
        };
        let earth = &self.earth;
        let t = ts.fix.t_s;
        let o = self.orbit.update(&FixInput {
            t_s: t,
            r_ecef_m: ts.fix.r_ecef_m,
            v_ecef_mps: Some(ts.v_ecef_mps),
            gdop: ts.fix.dop.gdop,
        });
        let state = TargetState {
            t_s: t,
            r_eci_m: o.r_eci_m,
            v_eci_mps: o.v_eci_mps,
        };
        let sigma = State::from_row_slice(&START_SIGMA);
        let first = (state, initial_state((&ts, &cs), &state, earth));
        let f = match self.filter.as_mut() {
            Some(f) => {
                f.predict(state);
                f
            }
            None => (self.filter).insert(SdFilter::new(&self.config, self.start, first, &sigma)),
        };
        let tags = (
            origin.seconds_since_start(target.time),
            origin.seconds_since_start(chaser.time),
        );
        let frame = EpochFrame {
            target: state,
            c_eci_ecef: earth.c_eci_ecef(t),
            omega_earth_rad_s: earth.omega_rad_s(),
            tag_difference_s: tags.1 - tags.0,
        };
        let records = (&target.sats[..], &chaser.sats[..]);
        let sats = satellites(records, tags, signals, store);
        let mask_rad = self.elevation_mask_rad;
        let used = f.update(&frame, &sats, mask_rad).unwrap_or_else(|_| {
            f.restart(first, &sigma);
            f.update(&frame, &sats, mask_rad).unwrap_or_default()
        });
        let (position_m, velocity_mps) = f.estimate();
        Some(RelativeEstimate {
            t_s: t,
            position_m,
            velocity_mps,
            same_satellites_s: self.set.at(used, t),
            baseline_ecef_m: None,
            ambiguities: None,
        })
    }
}
