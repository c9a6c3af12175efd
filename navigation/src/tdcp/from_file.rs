//! TDCP over the consecutive epochs of an observation file (SkyForge's or any receiver's
//! RINEX): each pair anchored at given positions, or chained from a known start.

use super::config::TdcpConfig;
use super::displacement::{Displacement, Solver, solve};
use super::error::TdcpError;
use super::records::Exclusion;
use super::single_difference::time_differences;
use hifitime::Epoch;
use skyforge_gnss::observation::{ObsEpoch, ObsFile};
use skyforge_orbits::Vec3;
use skyforge_orbits::ephemeris::{BroadcastEphemeris, EphemerisStore, SatId};
use skyforge_orbits::time::TimeOrigin;

/// One pair of consecutive epochs of a file.
#[derive(Debug, Clone)]
pub struct TdcpStep {
    /// The first epoch's time tag.
    pub t1: Epoch,
    /// The second epoch's time tag.
    pub t2: Epoch,
    /// The satellites of `t2` left out, with the reason (empty when the pair itself
    /// failed before the satellites were looked at).
    pub excluded: Vec<(SatId, Exclusion)>,
    /// The solution, or why none.
    pub solution: Result<Displacement, TdcpError>,
}

/// The ephemerides bound to the file's first epoch, and that origin.
fn bound(
    obs: &ObsFile,
    ephemerides: Vec<BroadcastEphemeris>,
) -> Option<(EphemerisStore, TimeOrigin)> {
    let origin = TimeOrigin::new(obs.epochs.first()?.time);
    Some((EphemerisStore::new(ephemerides, &origin), origin))
}

/// One pair's step: the differences of `pair` anchored at `r1`, about `r2_hat`.
fn step(
    pair: (&ObsEpoch, &ObsEpoch),
    (r1, r2_hat): (Vec3, Vec3),
    (store, origin): (&EphemerisStore, &TimeOrigin),
    config: &TdcpConfig,
    solver: Solver,
) -> TdcpStep {
    let (prev, cur) = pair;
    let differences = time_differences(prev, cur, r1, r2_hat, store, origin, config);
    let excluded = (differences.as_ref()).map_or_else(|_| Vec::new(), |e| e.excluded.clone());
    TdcpStep {
        t1: prev.time,
        t2: cur.time,
        excluded,
        solution: differences.and_then(|e| solve(&e, solver)),
    }
}

/// Every pair of consecutive epochs of `obs`, each anchored at `positions(t1)` (the
/// antenna, e.g. a code fix or the truth) and linearised about `positions(t2)` (or the
/// anchor when it has none). A pair whose first epoch has no position fails with
/// [`TdcpError::NoPosition`]; a bad setting fails the whole run.
pub fn tdcp_from_file(
    obs: &ObsFile,
    ephemerides: Vec<BroadcastEphemeris>,
    config: &TdcpConfig,
    solver: Solver,
    positions: impl Fn(Epoch) -> Option<Vec3>,
) -> Result<Vec<TdcpStep>, TdcpError> {
    config.check()?;
    let Some((store, origin)) = bound(obs, ephemerides) else {
        return Ok(Vec::new());
    };
    let steps = (obs.epochs.windows(2))
        .map(|w| {
            let Some(r1) = positions(w[0].time) else {
                return TdcpStep {
                    t1: w[0].time,
                    t2: w[1].time,
                    excluded: Vec::new(),
                    solution: Err(TdcpError::NoPosition { t: w[0].time }),
                };
            };
            let r2_hat = positions(w[1].time).unwrap_or(r1);
            step(
                (&w[0], &w[1]),
                (r1, r2_hat),
                (&store, &origin),
                config,
                solver,
            )
        })
        .collect();
    Ok(steps)
}

/// Pure TDCP dead reckoning: positions chained from a known start.
#[derive(Debug, Clone)]
pub struct DeadReckoning {
    /// The start, then each solved epoch's antenna position (ECEF, m).
    pub track: Vec<(Epoch, Vec3)>,
    /// Each pair's solution, in order.
    pub steps: Vec<Displacement>,
    /// The pair that ended the chain, and why (a gap, a slip on too many satellites);
    /// `None` when the file's last epoch was reached.
    pub stopped: Option<TdcpError>,
}

/// The antenna from `start` (at the first epoch of `obs`, ECEF) on, each pair anchored at
/// the previous solution and linearised about it: the error of each displacement adds
/// up (a random walk; consecutive pairs share an epoch, so their errors are correlated,
/// module docs). Stops at the first pair without a solution.
pub fn dead_reckoning(
    obs: &ObsFile,
    ephemerides: Vec<BroadcastEphemeris>,
    config: &TdcpConfig,
    solver: Solver,
    start: Vec3,
) -> Result<DeadReckoning, TdcpError> {
    config.check()?;
    let mut out = DeadReckoning {
        track: Vec::new(),
        steps: Vec::new(),
        stopped: None,
    };
    let Some((store, origin)) = bound(obs, ephemerides) else {
        return Ok(out);
    };
    let mut r = start;
    out.track
        .extend(obs.epochs.first().map(|e| (e.time, start)));
    for w in obs.epochs.windows(2) {
        match step((&w[0], &w[1]), (r, r), (&store, &origin), config, solver).solution {
            Ok(d) => {
                r = d.r2_m;
                out.track.push((d.t2, r));
                out.steps.push(d);
            }
            Err(e) => {
                out.stopped = Some(e);
                break;
            }
        }
    }
    Ok(out)
}
