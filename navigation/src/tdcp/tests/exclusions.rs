//! Satellites left out with their reasons, and the errors.

use super::world::{SIGNAL, World, quiet};
use crate::tdcp::{
    Exclusion, Solver, TdcpConfig, TdcpError, solve, solve_double, solve_single, time_differences,
};
use skyforge_gnss::observation::{LLI_LOSS_OF_LOCK, ObsEpoch, ObsRecord};
use skyforge_gnss::signal::Signal;
use skyforge_orbits::ephemeris::SatId;

/// Two noise-free epochs of the static site, 1 s apart.
fn epochs(w: &World) -> (ObsEpoch, ObsEpoch) {
    (
        w.epoch(300.0, w.site, &mut quiet),
        w.epoch(301.0, w.site, &mut quiet),
    )
}

/// The record of `sat` in `epoch`.
fn record(epoch: &mut ObsEpoch, sat: SatId) -> &mut ObsRecord {
    epoch.sats.iter_mut().find(|r| r.sat == sat).unwrap()
}

/// A loss of lock at `t2`, a phase missing at `t1`, a pseudorange missing at `t2`, a
/// satellite new at `t2`, one on another signal at `t1`, one without ephemeris (PRN 32
/// is not in the nominal constellation): each left out with its reason, the rest used;
/// a 30 deg mask leaves out the low ones.
#[test]
fn satellites_are_left_out_with_their_reasons() {
    let w = World::new(1e-7);
    let (mut prev, mut cur) = epochs(&w);
    let config = TdcpConfig::default();
    let all = time_differences(&prev, &cur, w.site, w.site, &w.store, &w.origin, &config);
    let all = all.unwrap();
    let used = all.sats.len();
    assert!(used >= 8, "{used} satellites");
    let below = all.excluded_count(Exclusion::BelowMask);
    assert_eq!(all.excluded.len(), below);
    // Five satellites above the mask, one for each of the first five reasons.
    let sats: Vec<SatId> = all.sats.iter().take(5).map(|s| s.sat).collect();
    let expected = [
        (sats[0], Exclusion::LossOfLock),
        (sats[1], Exclusion::MissingPhase),
        (sats[2], Exclusion::MissingPseudorange),
        (sats[3], Exclusion::NotInPrevious),
        (sats[4], Exclusion::DifferentSignal),
        (SatId::gps(32), Exclusion::NoEphemeris),
    ];
    record(&mut cur, sats[0]).phase_lli = LLI_LOSS_OF_LOCK;
    record(&mut prev, sats[1]).carrier_phase_cycles = None;
    record(&mut cur, sats[2]).pseudorange_m = Some(f64::NAN);
    prev.sats.retain(|r| r.sat != sats[3]);
    record(&mut prev, sats[4]).signal = Signal::GpsL5;
    let ghost = ObsRecord::complete(SatId::gps(32), SIGNAL, 2.1e7, 1.1e8, 0.0, 45.0);
    prev.sats.push(ghost);
    cur.sats.push(ghost);
    let epoch = time_differences(&prev, &cur, w.site, w.site, &w.store, &w.origin, &config);
    let epoch = epoch.unwrap();
    for (sat, reason) in expected {
        assert!(epoch.excluded.contains(&(sat, reason)), "{sat} {reason:?}");
        assert!(epoch.sats.iter().all(|s| s.sat != sat), "{sat} used");
        let count = epoch.excluded_count(reason);
        assert_eq!(count, 1, "{reason:?}");
    }
    assert_eq!(epoch.sats.len(), used - 5);
    assert_eq!(epoch.excluded_count(Exclusion::BelowMask), below);
    // The remaining satellites still give the static solution.
    let dd = solve_double(&epoch.double_differences().unwrap()).unwrap();
    assert!(dd.delta_r_m.norm() < 1e-3);
    // A loss of lock at t1 alone is no slip between the epochs.
    let (mut prev, cur) = epochs(&w);
    record(&mut prev, sats[0]).phase_lli = LLI_LOSS_OF_LOCK;
    let epoch = time_differences(&prev, &cur, w.site, w.site, &w.store, &w.origin, &config);
    assert_eq!(epoch.unwrap().sats.len(), used);
    // A 30 deg mask.
    let high = TdcpConfig {
        elevation_mask_deg: 30.0,
        ..config
    };
    let epoch = time_differences(&prev, &cur, w.site, w.site, &w.store, &w.origin, &high);
    let epoch = epoch.unwrap();
    println!(
        "{used} used at 10 deg ({below} below it), {} at 30 deg",
        epoch.sats.len()
    );
    assert!(epoch.excluded_count(Exclusion::BelowMask) > below);
    assert!(
        epoch
            .sats
            .iter()
            .all(|s| s.elevation_rad >= 30f64.to_radians())
    );
}

/// Three satellites: no single-difference solution (4 unknowns), no double-difference
/// one (2 double differences); one satellite: no double differences at all.
#[test]
fn too_few_satellites() {
    let w = World::new(1e-7);
    let (mut prev, mut cur) = epochs(&w);
    let config = TdcpConfig {
        elevation_mask_deg: -90.0,
        ..TdcpConfig::default()
    };
    prev.sats.truncate(3);
    cur.sats.truncate(3);
    let epoch = time_differences(&prev, &cur, w.site, w.site, &w.store, &w.origin, &config);
    let epoch = epoch.unwrap();
    let expected = TdcpError::TooFewSatellites {
        needed: 4,
        have: 3,
        t: cur.time,
    };
    assert_eq!(solve_single(&epoch).unwrap_err(), expected);
    let dd = epoch.double_differences().unwrap();
    assert_eq!(dd.z_m.len(), 2);
    assert_eq!(solve_double(&dd).unwrap_err(), expected);
    assert_eq!(
        solve(&epoch, Solver::DoubleDifferences).unwrap_err(),
        expected
    );
    cur.sats.truncate(1);
    let epoch = time_differences(&prev, &cur, w.site, w.site, &w.store, &w.origin, &config);
    assert!(epoch.unwrap().double_differences().is_none());
}

/// A gap beyond `max_gap_s`, the same epoch twice, the epochs reversed: errors naming the
/// gap. A position not finite, or at the geocentre: errors naming it.
#[test]
fn bad_pairs_and_positions_are_errors() {
    let w = World::new(1e-7);
    let config = TdcpConfig::default();
    let prev = w.epoch(300.0, w.site, &mut quiet);
    let late = w.epoch(306.0, w.site, &mut quiet);
    let run = |a: &ObsEpoch, b: &ObsEpoch, r1, r2| {
        time_differences(a, b, r1, r2, &w.store, &w.origin, &config).unwrap_err()
    };
    for (a, b, gap) in [
        (&prev, &late, 6.0),
        (&prev, &prev, 0.0),
        (&late, &prev, -6.0),
    ] {
        let error = run(a, b, w.site, w.site);
        assert!(
            matches!(error, TdcpError::Gap { gap_s, max_gap_s, .. }
                if gap_s == gap && max_gap_s == 5.0),
            "{error}"
        );
    }
    let cur = w.epoch(301.0, w.site, &mut quiet);
    let mut nan = w.site;
    nan.y = f64::NAN;
    assert_eq!(
        run(&prev, &cur, nan, w.site),
        TdcpError::NonFinite { what: "r1" }
    );
    assert_eq!(
        run(&prev, &cur, w.site, nan * f64::INFINITY),
        TdcpError::NonFinite { what: "r2_hat" }
    );
    assert_eq!(
        run(&prev, &cur, w.site, skyforge_orbits::Vec3::zeros()),
        TdcpError::NotAPosition { what: "r2_hat" }
    );
}

/// Each setting out of its range is refused, naming the field.
#[test]
fn bad_settings_name_the_field() {
    let w = World::new(1e-7);
    let (prev, cur) = epochs(&w);
    let base = TdcpConfig::default();
    assert!(base.check().is_ok());
    let cases = [
        (
            "sigma_phase_m",
            TdcpConfig {
                sigma_phase_m: 0.0,
                ..base
            },
        ),
        (
            "sigma_phase_m",
            TdcpConfig {
                sigma_phase_m: f64::NAN,
                ..base
            },
        ),
        (
            "max_gap_s",
            TdcpConfig {
                max_gap_s: -1.0,
                ..base
            },
        ),
        (
            "max_gap_s",
            TdcpConfig {
                max_gap_s: f64::INFINITY,
                ..base
            },
        ),
        (
            "elevation_mask_deg",
            TdcpConfig {
                elevation_mask_deg: 90.0,
                ..base
            },
        ),
        (
            "elevation_mask_deg",
            TdcpConfig {
                elevation_mask_deg: f64::NAN,
                ..base
            },
        ),
    ];
    for (field, config) in cases {
        let error = time_differences(&prev, &cur, w.site, w.site, &w.store, &w.origin, &config)
            .unwrap_err();
        assert!(
            matches!(&error, TdcpError::Config { field: f, .. } if *f == field),
            "{field}: {error}"
        );
        assert!(error.to_string().contains(field), "{error}");
    }
}
