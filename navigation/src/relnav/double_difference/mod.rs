//! Mode `double-difference` of `skyforge relnav`: double-difference carrier phase and code
//! between the two spacecraft with integer ambiguity resolution, for baselines of
//! kilometres to hundreds of kilometres (a GRACE-like pair 200 km apart).
//!
//! Per epoch (the target's receive instant `t_t`, its receiver's tag less its fix's clock):
//! 1. Each receiver's single-point fix (dual-frequency, ionosphere-free code where both
//!    carriers are measured): its clock, hence its receive instant; the chaser's
//!    `t_c - t_t` (microseconds under two TCXOs) becomes a move along its velocity.
//! 2. The target's orbit filter (`[target_orbit]`, as the other modes) on its fix: the
//!    anchor of the ranges and the orbit frame of the output. The anchor's error enters
//!    the double differences through the lines of sight' change across the baseline,
//!    `|b| / rho`, 1 % at 200 km: a metre of anchor error is a centimetre of baseline.
//! 3. The relative state predicted along the gravity difference ([`dynamics`]).
//! 4. The single differences of every satellite both track ([`observations`]), the
//!    Kalman update on their double differences ([`filter`]) and the integers
//!    ([`fixing`]): LAMBDA with the ratio and success-rate tests, held once fixed.
//!
//! The ionosphere: a LEO at 500 km sees a tenth of the ground delay in SkyForge's model
//! (docs/scenario.md), through other pierce points and elevations 200 km apart: the
//! double difference is centimetres, not zero. Each satellite's single-difference slant
//! delay is a state (random walk), both signals' code and phase are used, and LAMBDA
//! fixes both signals' integers (the wide lane first in effect: the decorrelation finds
//! it). No troposphere above 50 km.
//!
//! Reads only what the receivers could: observations, broadcast ephemerides, settings.

pub(crate) mod config;
pub(crate) mod dynamics;
pub(crate) mod filter;
pub(crate) mod fixing;
pub(crate) mod observations;
#[cfg(test)]
mod tests;

use super::engine::{Context, Engine};
use super::estimate::RelativeEstimate;
use super::same_satellites::SameSatellites;
use crate::orbit_determination::{FixInput, PositionFilter};
use crate::pvt::{IonosphereCorrection, PvtConfig};
use crate::relative::files::FixStream;
use filter::{Anchor, DdEpoch, DdFilter};
use observations::{Receiver, Settings, SlipDetector, single_differences};
use skyforge_gnss::observation::ObsEpoch;
use skyforge_gnss::signal::Signal;
use skyforge_orbits::ephemeris::SatId;
use skyforge_orbits::frames::earth_rotation::EarthRotation;
use skyforge_orbits::frames::relative_in_frame_of;
use std::collections::BTreeSet;

/// The first baseline's standard deviation per axis (m): two code fixes.
/// # assumed: 10 m, beyond two dual-frequency fixes' errors.
const START_SIGMA_M: f64 = 10.0;
/// The first baseline rate's (m/s): two Doppler velocities.
/// # assumed: 1 m/s.
const START_SIGMA_MPS: f64 = 1.0;

/// Mode `double-difference` epoch by epoch (module docs).
#[derive(Debug)]
pub(crate) struct DdEngine {
    signals: Vec<Signal>,
    elevation_mask_rad: f64,
    /// Each receiver's fixes (target, chaser): dual-frequency where two carriers are.
    fixes: [FixStream; 2],
    orbit: PositionFilter,
    filter: DdFilter,
    /// The float filter that checks the held integers (`fixing::check_held`).
    twin: Option<DdFilter>,
    slips: SlipDetector,
    earth: EarthRotation,
    set: SameSatellites<BTreeSet<SatId>>,
}

impl DdEngine {
    /// The engine of `config` on `signals` from `start`; the fixes with `pvt`'s settings,
    /// the ionosphere-free code where two carriers are measured (the receive instants and
    /// the target's anchor), no smoothing.
    pub(crate) fn new(
        config: &super::RelnavConfig,
        pvt: &PvtConfig,
        signals: &[Signal],
        start: hifitime::Epoch,
    ) -> Self {
        let carriers: BTreeSet<u64> = signals.iter().map(|s| s.carrier_hz() as u64).collect();
        let pvt = PvtConfig {
            ionosphere: if carriers.len() > 1 {
                IonosphereCorrection::DualFrequency
            } else {
                IonosphereCorrection::Broadcast
            },
            carrier_smoothing: None,
            ..pvt.clone()
        };
        let dd = &config.double_difference;
        Self {
            signals: signals.to_vec(),
            elevation_mask_rad: config.elevation_mask_deg.to_radians(),
            fixes: [FixStream::new(&pvt), FixStream::new(&pvt)],
            orbit: PositionFilter::new(config.target_orbit.clone(), start),
            filter: DdFilter::new(
                dd.clone(),
                dynamics::gravity_field(&config.target_orbit.forces, start),
            ),
            twin: None,
            slips: SlipDetector::default(),
            earth: EarthRotation::at_origin(start),
            set: SameSatellites::new(),
        }
    }
}

impl Engine for DdEngine {
    fn missed(&self) -> usize {
        self.set.missed()
    }

    fn epoch(
        &mut self,
        (te, ce): (&ObsEpoch, &ObsEpoch),
        at: &Context,
    ) -> Option<RelativeEstimate> {
        let (store, origin) = (at.store, at.origin);
        let signals = &self.signals;
        let [Ok(tf), Ok(cf)] = at.fixes(&mut self.fixes, (te, ce), signals) else {
            return self.set.miss();
        };
        let (Some(vt), Some(vc)) = (at.velocity(te, &tf, signals), at.velocity(ce, &cf, signals))
        else {
            return self.set.miss();
        };
        let earth = &self.earth;
        let t = tf.t_s;
        let o = self.orbit.update(&FixInput {
            t_s: t,
            r_ecef_m: tf.r_ecef_m,
            v_ecef_mps: Some(vt),
            gdop: tf.dop.gdop,
        });
        let anchor = Anchor {
            t_s: t,
            r_eci_m: o.r_eci_m,
            v_eci_mps: o.v_eci_mps,
        };
        let (r_t, _) = earth.eci_to_ecef(t, &o.r_eci_m, &o.v_eci_mps);
        // The chaser's receive instant relative to the target's (s).
        let shift_s = cf.t_s - t;
        let filter = &mut self.filter;
        if filter.started() {
            filter.predict(anchor);
            if let Some(twin) = self.twin.as_mut() {
                twin.predict(anchor);
            }
        } else {
            let b = cf.r_ecef_m - vc * shift_s - r_t;
            let b_eci = earth.ecef_to_eci(t, &b, &(vc - vt));
            let clock_m = cf.clock_bias_m - tf.clock_bias_m;
            filter.start(anchor, b_eci, (START_SIGMA_M, START_SIGMA_MPS), clock_m);
            self.twin = filter.config.check_held.then(|| filter.clone());
        }
        let (b, b_dot) = filter.baseline();
        let c_eci_ecef = earth.c_eci_ecef(t);
        let (_, v_c) = earth.eci_to_ecef(t, &(o.r_eci_m + b), &(o.v_eci_mps + b_dot));
        let r_c = r_t + c_eci_ecef * b + v_c * shift_s;
        let rt = Receiver {
            records: &te.sats,
            t_tag_s: origin.seconds_since_start(te.time),
            r_ecef_m: r_t,
        };
        let rc = Receiver {
            records: &ce.sats,
            t_tag_s: origin.seconds_since_start(ce.time),
            r_ecef_m: r_c,
        };
        let settings = Settings {
            signals,
            elevation_mask_rad: self.elevation_mask_rad,
            slip_threshold_m: filter.config.slip_threshold_m,
            max_gap_s: filter.config.max_gap_s,
        };
        let sats = single_differences((&rt, &rc), store, &settings, t, &mut self.slips);
        let epoch = DdEpoch {
            r_target_ecef_m: r_t,
            c_eci_ecef,
            v_chaser_ecef_mps: v_c,
            tag_difference_s: rc.t_tag_s - rt.t_tag_s,
            sats,
        };
        let pairings = filter.update(t, &epoch);
        if let Some(twin) = self.twin.as_mut() {
            twin.update(t, &epoch);
            fixing::check_held(filter, twin, &pairings);
        }
        let count = fixing::resolve(filter, &pairings);
        let (b, b_dot) = filter.baseline();
        let (position_m, velocity_mps) = relative_in_frame_of(&o.r_eci_m, &o.v_eci_mps, &b, &b_dot);
        let used: BTreeSet<_> = epoch.sats.iter().map(|s| s.sat).collect();
        Some(RelativeEstimate {
            t_s: t,
            position_m,
            velocity_mps,
            same_satellites_s: self.set.at(used, t),
            baseline_ecef_m: Some(c_eci_ecef * b),
            ambiguities: Some(count),
        })
    }
}
