//! Modes `standalone`, `position-difference` and `carrier-smoothed` epoch by epoch (the
//! module docs of [`super`]): each receiver's fix, on the common satellites both fixes
//! again on the satellites both used, the target's orbit filter for the frame, the
//! difference in the target's orbit frame, optionally through the book's relative filter.
//! One engine for a pair of files and for a receiver's epoch stage.

use super::RelnavConfig;
use super::engine::{Context, Engine};
use super::estimate::RelativeEstimate;
use super::hill_dynamics::TargetState;
use super::hill_filter::HillFilter;
use super::same_satellites::SameSatellites;
use crate::orbit_determination::{FixInput, PositionFilter};
use crate::pvt::{Fix, PvtConfig};
use crate::relative::files::FixStream;
use hifitime::Epoch;
use skyforge_gnss::observation::ObsEpoch;
use skyforge_gnss::signal::Signal;
use skyforge_orbits::Vec3;
use skyforge_orbits::ephemeris::SatId;
use skyforge_orbits::frames::earth_rotation::EarthRotation;
use skyforge_orbits::frames::relative_in_frame_of;
use std::collections::BTreeSet;

/// The satellites `fix` used (none without one).
fn used_satellites(fix: &Result<Fix, String>) -> BTreeSet<SatId> {
    (fix.as_ref())
        .map(|f| f.used.iter().map(|u| u.0).collect())
        .unwrap_or_default()
}

/// The satellites the target's and the chaser's fix of an epoch used.
#[derive(Debug, PartialEq)]
struct SatelliteSetPair {
    target: BTreeSet<SatId>,
    chaser: BTreeSet<SatId>,
}

impl SatelliteSetPair {
    fn of(target: &Result<Fix, String>, chaser: &Result<Fix, String>) -> Self {
        Self {
            target: used_satellites(target),
            chaser: used_satellites(chaser),
        }
    }

    /// Both fixes on the same satellites.
    fn same(&self) -> bool {
        self.target == self.chaser
    }
}

/// One vehicle's solution at an epoch: its fix's time (s since the start), position and
/// Doppler velocity (ECEF).
struct Solution {
    t_s: f64,
    r_ecef_m: Vec3,
    v_ecef_mps: Vec3,
}

/// `epoch` with the records of the satellites in `keep` alone.
fn restricted(epoch: &ObsEpoch, keep: &BTreeSet<SatId>) -> ObsEpoch {
    ObsEpoch {
        time: epoch.time,
        sats: (epoch.sats.iter())
            .filter(|r| keep.contains(&r.sat))
            .cloned()
            .collect(),
    }
}

/// The engine of the three modes (module docs).
#[derive(Debug)]
pub(crate) struct BookModes {
    signals: Vec<Signal>,
    /// Each receiver's fixes with its own elevation mask and residual test (target,
    /// chaser).
    first: [FixStream; 2],
    /// On the common satellites: both again on the satellites both first fixes used,
    /// with neither (module docs of [`super`]).
    again: Option<[FixStream; 2]>,
    orbit: PositionFilter,
    relative_filter: Option<HillFilter>,
    sets: SameSatellites<SatelliteSetPair>,
    earth: EarthRotation,
}

impl BookModes {
    /// The engine of `config`'s mode with the fixes' `pvt` settings on `signals`, from
    /// `start`; `common`: both fixes on the satellites both use.
    pub(crate) fn new(
        config: &RelnavConfig,
        pvt: &PvtConfig,
        signals: &[Signal],
        start: Epoch,
        common: bool,
    ) -> Self {
        let same = PvtConfig {
            elevation_mask_rad: -std::f64::consts::FRAC_PI_2,
            raim_pfa: 0.0,
            ..pvt.clone()
        };
        Self {
            signals: signals.to_vec(),
            first: [FixStream::new(pvt), FixStream::new(pvt)],
            again: common.then(|| [FixStream::new(&same), FixStream::new(&same)]),
            orbit: PositionFilter::new(config.target_orbit.clone(), start),
            relative_filter: (config.filter.clone()).map(|f| HillFilter::new(f, start)),
            sets: SameSatellites::new(),
            earth: EarthRotation::at_origin(start),
        }
    }
}

impl Engine for BookModes {
    fn missed(&self) -> usize {
        self.sets.missed()
    }

    /// One pair of epochs, each vehicle's records of the run's signals (with `common`,
    /// those of the satellites and signals both measured).
    fn epoch(
        &mut self,
        (target, chaser): (&ObsEpoch, &ObsEpoch),
        at: &Context,
    ) -> Option<RelativeEstimate> {
        let signals = &self.signals;
        let [mut tf, mut cf] = at.fixes(&mut self.first, (target, chaser), signals);
        let both_used;
        let (target, chaser) = match self.again.as_mut() {
            Some(again) => {
                // Each receiver's mask and residual test choose among the common
                // satellites on their own (a satellite at the mask for one vehicle is
                // just below it for the other, 32 km away): both again on the satellites
                // both fixes used.
                let keep: BTreeSet<SatId> = used_satellites(&tf)
                    .intersection(&used_satellites(&cf))
                    .copied()
                    .collect();
                both_used = (restricted(target, &keep), restricted(chaser, &keep));
                [tf, cf] = at.fixes(again, (&both_used.0, &both_used.1), signals);
                (&both_used.0, &both_used.1)
            }
            None => (target, chaser),
        };
        let solution = |epoch: &ObsEpoch, fix: &Fix| {
            Some(Solution {
                t_s: fix.t_s,
                r_ecef_m: fix.r_ecef_m,
                v_ecef_mps: at.velocity(epoch, fix, signals)?,
            })
        };
        let both = match (&tf, &cf) {
            (Ok(t_fix), Ok(c_fix)) => solution(target, t_fix)
                .zip(solution(chaser, c_fix))
                .map(|both| (t_fix, both)),
            _ => None,
        };
        let Some((t_fix, (t, c))) = both else {
            return self.sets.miss();
        };
        let used = SatelliteSetPair::of(&tf, &cf);
        let same = used.same();
        let unchanged_s = self.sets.at(used, t.t_s);
        let earth = &self.earth;
        // The chaser's fix moved to the target fix's instant (ECEF, its own velocity).
        let r_c = c.r_ecef_m + c.v_ecef_mps * (t.t_s - c.t_s);
        let (rt, vt) = earth.ecef_to_eci(t.t_s, &t.r_ecef_m, &t.v_ecef_mps);
        let (rc, vc) = earth.ecef_to_eci(t.t_s, &r_c, &c.v_ecef_mps);
        // The frame from the target's filtered orbit (config docs).
        let filtered = self.orbit.update(&FixInput {
            t_s: t.t_s,
            r_ecef_m: t.r_ecef_m,
            v_ecef_mps: Some(t.v_ecef_mps),
            gdop: t_fix.dop.gdop,
        });
        let (mut position_m, mut velocity_mps) = relative_in_frame_of(
            &filtered.r_eci_m,
            &filtered.v_eci_mps,
            &(rc - rt),
            &(vc - vt),
        );
        if let Some(f) = self.relative_filter.as_mut() {
            let target = TargetState {
                t_s: t.t_s,
                r_eci_m: filtered.r_eci_m,
                v_eci_mps: filtered.v_eci_mps,
            };
            let e = f.update(target, position_m, Some(velocity_mps));
            (position_m, velocity_mps) = (e.position_m, e.velocity_mps);
        }
        Some(RelativeEstimate {
            t_s: t.t_s,
            position_m,
            velocity_mps,
            same_satellites_s: if same { unchanged_s } else { 0.0 },
            baseline_ecef_m: None,
            ambiguities: None,
        })
    }
}
