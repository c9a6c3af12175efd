//! Navigation files in `build`: ephemerides valid at the start, per system, PRN filters.
//! The file is a hand-made RINEX 3.05 record (own values, not copied from any station):
//! G07, toc = toe = 2022-01-01T00:00:00 GPST (GPS week 2190, 518400 s of week), healthy.

mod common;

use common::*;
use skyforge_orbits::ephemeris::{SatId, System};
use skyforge_orbits::fixtures::RINEX3_GPS_NAV;
use std::path::Path;

/// [`BASE`] reading GPS from `brdc.rnx`, BeiDou disabled, starting at `start`.
fn scenario(start: &str, gps_extra: &str) -> String {
    let text = replace(
        BASE,
        "source = \"embedded\"",
        &format!("source = \"rinex\"\nnav_file = \"brdc.rnx\"{gps_extra}"),
    );
    let text = replace(&text, "enabled = true", "enabled = false");
    replace(&text, "2023-03-12T00:00:00 GPST", start)
}

fn nav_dir() -> tempfile::TempDir {
    let dir = tempfile::tempdir().expect("tempdir");
    std::fs::write(dir.path().join("brdc.rnx"), RINEX3_GPS_NAV).expect("write nav file");
    dir
}

#[test]
fn a_file_valid_at_the_start_builds() {
    let dir = nav_dir();
    let text = scenario("2022-01-01T00:30:00 GPST", "");
    let world = parse_in(&text, dir.path())
        .expect("parses")
        .build()
        .unwrap_or_else(|e| panic!("{e}"));
    let g07 = SatId {
        system: System::Gps,
        prn: 7,
    };
    assert_eq!(world.satellites, [g07]);
    assert!(world.ephemerides.select(g07, 0.0).is_some());
}

#[test]
fn a_file_without_ephemeris_for_the_requested_time() {
    let dir = nav_dir();
    let text = scenario("2023-03-12T00:00:00 GPST", "");
    let at = ("nav_file = \"brdc.rnx\"", "\"brdc");
    let err = build_error_at(&text, dir.path(), "gnss.gps.nav_file", "\"brdc.rnx\"", at);
    assert!(
        err.allowed
            .contains("no healthy GPS ephemeris valid at the scenario start"),
        "{err}"
    );
}

#[test]
fn a_file_without_ephemeris_of_the_system() {
    let dir = nav_dir();
    let text = replace(
        BASE,
        "enabled = true",
        "source = \"rinex\"\nnav_file = \"brdc.rnx\"",
    );
    let text = replace(&text, "source = \"embedded\"", "enabled = false");
    let text = replace(
        &text,
        "2023-03-12T00:00:00 GPST",
        "2022-01-01T00:30:00 GPST",
    );
    let at = ("nav_file = \"brdc.rnx\"", "\"brdc");
    let err = build_error_at(
        &text,
        dir.path(),
        "gnss.beidou.nav_file",
        "\"brdc.rnx\"",
        at,
    );
    assert!(err.allowed.contains("BeiDou"), "{err}");
}

#[test]
fn a_requested_prn_without_ephemeris() {
    let dir = nav_dir();
    let text = scenario("2022-01-01T00:30:00 GPST", "\nprns = [7, 5]");
    let at = ("prns = [7, 5]", "5]");
    let err = build_error_at(&text, dir.path(), "gnss.gps.prns[1]", "5", at);
    assert!(err.allowed.contains("G05"), "{err}");

    let text = scenario("2022-01-01T00:30:00 GPST", "\nprns = [7]");
    let world = parse_in(&text, dir.path()).expect("parses").build();
    assert_eq!(world.map(|w| w.satellites.len()).ok(), Some(1));
}

#[test]
fn relative_paths_start_at_the_scenario_directory() {
    let dir = nav_dir();
    let path = dir.path().join("scenario.toml");
    std::fs::write(&path, scenario("2022-01-01T00:30:00 GPST", "")).expect("write");
    let s = skyforge_scenarios::load(&path).expect("loads");
    assert_eq!(s.base_dir, dir.path());
    assert!(s.build().is_ok());
    // The same text parsed against another directory does not find the file.
    let elsewhere = build_error(&s.text, Path::new("/"));
    assert_eq!(elsewhere.field, "gnss.gps.nav_file");
}

/// Issue #11: a navigation file cut inside a record built with its missing fields read as
/// 0, and `/dev/zero` or a directory was reported as missing. Each is now one located
/// error at `nav_file` saying what is wrong.
#[test]
fn a_cut_file_a_directory_and_a_device_are_refused_with_what_they_are() {
    let dir = nav_dir();
    let cut = RINEX3_GPS_NAV
        .trim_end()
        .rsplit_once('\n')
        .expect("lines")
        .0;
    std::fs::write(dir.path().join("cut.rnx"), cut).expect("write");
    std::fs::create_dir(dir.path().join("navdir")).expect("mkdir");
    for (name, expected) in [
        ("cut.rnx", "cut.rnx:9: record cut short: it has 7 lines"),
        ("navdir", "is a directory, not a navigation file"),
        ("/dev/zero", "more than 256 MiB: not a navigation file"),
    ] {
        let text =
            scenario("2022-01-01T00:30:00 GPST", "").replace("\"brdc.rnx\"", &format!("{name:?}"));
        let quoted = format!("{name:?}");
        let context = format!("nav_file = {quoted}");
        let err = build_error_at(
            &text,
            dir.path(),
            "gnss.gps.nav_file",
            &quoted,
            (&context, &quoted),
        );
        assert!(err.allowed.contains(expected), "{name}: {err}");
        assert!(!err.allowed.contains("does not exist"), "{name}: {err}");
    }
}
