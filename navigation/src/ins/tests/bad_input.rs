//! Misuse from files: bad intervals, non-finite values, order, gaps, non-adjacent
//! previous increments and degenerate alignment inputs are errors, and leave the state
//! untouched.

use super::truth::{Bias, Static, increments, site, t0, true_state};
use crate::ins::{FineAlignmentConfig, InsError, coarse_alignment, fine_alignment, static_means};
use hifitime::Duration;
use skyforge_gnss::imu::ImuIncrement;
use skyforge_orbits::Vec3;
use skyforge_orbits::frames::YawPitchRoll;

fn setup() -> (Static, Vec<ImuIncrement>) {
    let traj = Static::new(&site(), YawPitchRoll::new(0.3, 0.0, 0.0));
    let incs = increments(&traj, 0.01, 3, &Bias::default());
    (traj, incs)
}

/// Propagating `inc` (after `prev`) from the true state fails with an error matching
/// `want`, and the state is unchanged.
fn refused(prev: Option<&ImuIncrement>, inc: &ImuIncrement, want: fn(&InsError) -> bool) {
    let (traj, _) = setup();
    let mut state = true_state(&traj, 0.0);
    let before = state;
    let err = state.propagate(prev, inc).unwrap_err();
    assert!(want(&err), "unexpected {err:?}");
    assert_eq!(state, before);
}

#[test]
fn non_positive_or_non_finite_interval_is_refused() {
    let (_, incs) = setup();
    for dt in [0.0, -0.01, f64::NAN, f64::INFINITY] {
        let inc = ImuIncrement {
            dt_s: dt,
            ..incs[0]
        };
        refused(None, &inc, |e| matches!(e, InsError::BadInterval { .. }));
    }
}

#[test]
fn non_finite_increment_is_refused() {
    let (_, incs) = setup();
    let inc = ImuIncrement {
        dv_mps: Vec3::new(0.0, f64::NAN, 0.0),
        ..incs[0]
    };
    refused(None, &inc, |e| matches!(e, InsError::NonFinite { .. }));
}

#[test]
fn out_of_order_and_overlapping_increments_are_refused() {
    let (_, incs) = setup();
    // Ends at the state time.
    let at_start = ImuIncrement {
        t_end: t0(),
        ..incs[0]
    };
    refused(None, &at_start, |e| {
        matches!(e, InsError::OutOfOrder { .. })
    });
    // Ends after it but begins before it (overlap).
    let long = ImuIncrement {
        dt_s: 0.02,
        ..incs[0]
    };
    refused(None, &long, |e| matches!(e, InsError::OutOfOrder { .. }));
    // Replaying an increment after the state has moved past it.
    let (traj, incs) = setup();
    let mut state = true_state(&traj, 0.0);
    state.propagate_all(&incs[..2]).unwrap();
    let err = state.propagate(None, &incs[0]).unwrap_err();
    assert!(matches!(err, InsError::OutOfOrder { .. }), "{err:?}");
}

#[test]
fn gap_is_refused() {
    let (_, incs) = setup();
    refused(None, &incs[1], |e| matches!(e, InsError::Gap { .. }));
    let late = ImuIncrement {
        t_end: incs[0].t_end + Duration::from_seconds(1e-5),
        ..incs[0]
    };
    refused(None, &late, |e| matches!(e, InsError::Gap { .. }));
}

#[test]
fn non_adjacent_previous_increment_is_refused() {
    let (traj, incs) = setup();
    let mut state = true_state(&traj, 0.0);
    state.propagate(None, &incs[0]).unwrap();
    let err = state.propagate(Some(&incs[1]), &incs[1]).unwrap_err();
    assert!(matches!(err, InsError::PrevNotAdjacent { .. }), "{err:?}");
    state.propagate(Some(&incs[0]), &incs[1]).unwrap();
}

#[test]
fn alignment_misuse_is_refused() {
    let (traj, incs) = setup();
    assert_eq!(static_means(&[]), Err(InsError::Empty));
    let g = site();
    let zero = coarse_alignment(&Vec3::zeros(), &Vec3::z(), &g);
    assert!(matches!(zero, Err(InsError::Degenerate(_))));
    let parallel = coarse_alignment(&Vec3::z(), &Vec3::z(), &g);
    assert!(matches!(parallel, Err(InsError::Degenerate(_))));
    let initial = true_state(&traj, 0.0);
    let cfg = FineAlignmentConfig::default();
    assert_eq!(fine_alignment(&initial, &[], &cfg), Err(InsError::Empty));
    let bad = FineAlignmentConfig {
        update_every: 0,
        ..cfg
    };
    let err = fine_alignment(&initial, &incs, &bad).unwrap_err();
    assert!(
        matches!(
            err,
            InsError::BadSetting {
                name: "update_every",
                ..
            }
        ),
        "{err:?}"
    );
    let bad = FineAlignmentConfig {
        zupt_sigma_mps: -1.0,
        ..cfg
    };
    assert!(fine_alignment(&initial, &incs, &bad).is_err());
}
