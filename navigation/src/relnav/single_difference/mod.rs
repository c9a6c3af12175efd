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

use super::RelativeEstimate;
use super::double_difference::Inputs;
use super::hill_filter::TargetState;
use super::same_satellites::SameSatellites;
use crate::orbit_determination::{FixInput, PositionFilter};
use crate::pvt::{Fix, records_velocity};
use crate::relative::single_point_fixes;
use filter::SdFilter;
use measurement::{CLOCK, EpochFrame, State, satellites};
use skyforge_gnss::observation::ObsFile;
use skyforge_orbits::Vec3;
use skyforge_orbits::frames::earth_rotation::EarthRotation;
use skyforge_orbits::frames::relative_in_frame_of;

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

/// The estimates of the paired files `target`, `chaser` (one epoch each, in step) and
/// the count of epochs without both fixes and velocities.
pub(crate) fn run(
    target: &ObsFile,
    chaser: &ObsFile,
    inputs: &Inputs,
) -> (Vec<RelativeEstimate>, usize) {
    let (config, origin) = (inputs.config, inputs.origin);
    let mask_rad = config.elevation_mask_deg.to_radians();
    let earth = EarthRotation::at_origin(inputs.start);
    let fixes = |f| single_point_fixes(f, inputs.store, origin, inputs.signals, inputs.pvt);
    let (t_fixes, c_fixes) = (fixes(target), fixes(chaser));
    let solution = |file: &ObsFile, k: usize, fix| {
        let t_rx = origin.seconds_since_start(file.epochs[k].time);
        let v = records_velocity(
            &file.epochs[k].sats,
            inputs.signals,
            t_rx,
            inputs.store,
            fix,
        )?;
        Some(Solution { fix, v_ecef_mps: v })
    };
    let mut orbit = PositionFilter::new(config.target_orbit.clone(), inputs.start);
    let mut filter: Option<SdFilter> = None;
    let sigma = State::from_row_slice(&START_SIGMA);
    let (mut estimates, mut missed) = (Vec::new(), 0);
    let mut set = SameSatellites::new();
    for k in 0..target.epochs.len() {
        let both = match (&t_fixes[k], &c_fixes[k]) {
            (Ok(tf), Ok(cf)) => solution(target, k, tf).zip(solution(chaser, k, cf)),
            _ => None,
        };
        let Some((ts, cs)) = both else {
            missed += 1;
            set.missed();
            continue;
        };
        let t = ts.fix.t_s;
        let o = orbit.update(&FixInput {
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
        let first = (state, initial_state((&ts, &cs), &state, &earth));
        let f = match filter.as_mut() {
            Some(f) => {
                f.predict(state);
                f
            }
            None => filter.insert(SdFilter::new(
                &config.single_difference,
                inputs.start,
                first,
                &sigma,
            )),
        };
        let tags = (
            origin.seconds_since_start(target.epochs[k].time),
            origin.seconds_since_start(chaser.epochs[k].time),
        );
        let frame = EpochFrame {
            target: state,
            c_eci_ecef: earth.c_eci_ecef(t),
            omega_earth_rad_s: earth.omega_rad_s(),
            tag_difference_s: tags.1 - tags.0,
        };
        let records = (&target.epochs[k].sats[..], &chaser.epochs[k].sats[..]);
        let sats = satellites(records, tags, inputs.signals, inputs.store);
        let used = f.update(&frame, &sats, mask_rad).unwrap_or_else(|_| {
            f.restart(first, &sigma);
            f.update(&frame, &sats, mask_rad).unwrap_or_default()
        });
        let (position_m, velocity_mps) = f.estimate();
        let same_satellites_s = set.at(used, t);
        estimates.push(RelativeEstimate {
            t_s: t,
            position_m,
            velocity_mps,
            same_satellites_s,
            baseline_ecef_m: None,
            ambiguities: None,
        });
    }
    (estimates, missed)
}
