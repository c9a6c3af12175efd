//! Runs over files: every consecutive pair anchored at the truth, and dead reckoning
//! chained from a known start, stopped by a gap.

use super::world::World;
use crate::tdcp::{Solver, TdcpConfig, TdcpError, dead_reckoning, tdcp_from_file};
use hifitime::Epoch;
use skyforge_orbits::Vec3;

/// A receiver driving a circle of 50 m radius at 10 m/s (5 s per radian), 1 Hz, 40 s.
fn circle(w: &World) -> impl Fn(f64) -> Vec3 + '_ {
    move |t: f64| {
        let a = t / 5.0;
        w.site + w.ned(50.0 * a.cos(), 50.0 * a.sin(), 0.0)
    }
}

/// Each pair anchored at the true position of its first epoch and linearised about the
/// true second one (the last pair, whose second epoch has no position, about its
/// anchor): every position true to a millimetre, with both solvers.
#[test]
fn every_pair_of_a_file() {
    let w = World::new(1e-7);
    let r = circle(&w);
    let tags: Vec<f64> = (0..40).map(f64::from).collect();
    let file = w.file(&tags, &r);
    let tag = |t: Epoch| (t - w.start).to_seconds();
    for solver in [Solver::SingleDifferences, Solver::DoubleDifferences] {
        let positions = |t: Epoch| (tag(t) < 39.0).then(|| r(tag(t)));
        let steps = tdcp_from_file(
            &file,
            w.ephemerides.clone(),
            &TdcpConfig::default(),
            solver,
            positions,
        );
        let steps = steps.unwrap();
        assert_eq!(steps.len(), 39);
        let worst = (steps.iter())
            .map(|s| {
                let d = s.solution.as_ref().unwrap();
                (d.r2_m - r(tag(s.t2))).norm()
            })
            .fold(0.0f64, f64::max);
        println!("{solver:?}: worst error over 39 pairs {worst:.2e} m");
        assert!(worst < 1e-3);
    }
}

/// Dead reckoning around the circle from the true start: after 39 chained pairs the
/// position is true to a millimetre. With the epochs 20..24 missing, the chain stops at
/// the 6 s gap (beyond the 5 s allowed).
#[test]
fn dead_reckoning_from_a_known_start() {
    let w = World::new(1e-7);
    let r = circle(&w);
    let tags: Vec<f64> = (0..40).map(f64::from).collect();
    let file = w.file(&tags, &r);
    let config = TdcpConfig::default();
    let run = dead_reckoning(
        &file,
        w.ephemerides.clone(),
        &config,
        Solver::DoubleDifferences,
        r(0.0),
    )
    .unwrap();
    assert!(run.stopped.is_none());
    assert_eq!(run.track.len(), 40);
    let (t_end, r_end) = run.track[39];
    let error = (r_end - r((t_end - w.start).to_seconds())).norm();
    println!("dead reckoning: error after 39 pairs {error:.2e} m");
    assert!(error < 1e-3);
    let gapped: Vec<f64> = tags
        .into_iter()
        .filter(|t| !(20.0..25.0).contains(t))
        .collect();
    let file = w.file(&gapped, &r);
    let run = dead_reckoning(
        &file,
        w.ephemerides.clone(),
        &config,
        Solver::default(),
        r(0.0),
    );
    let run = run.unwrap();
    assert_eq!(run.track.len(), 20);
    assert!(
        matches!(run.stopped, Some(TdcpError::Gap { gap_s, .. }) if gap_s == 6.0),
        "{:?}",
        run.stopped
    );
}
