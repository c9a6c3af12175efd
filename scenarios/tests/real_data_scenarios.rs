//! Real-data tier: scenarios reading the shared broadcast navigation files.
//! Run with `cargo test -p skyforge-scenarios --test real_data_scenarios -- --ignored`.
//! The data folder comes from `SKYFORGE_DATA` (default `../shared/data` next to the
//! workspace).

mod common;

use common::*;
use skyforge_orbits::ephemeris::System;
use skyforge_scenarios::bundled;
use std::path::PathBuf;

fn data_dir() -> PathBuf {
    skyforge_orbits::real_data::require_dir()
}

/// The bundled thesis LEO with both constellations read from `nav` (relative to the data
/// folder), starting at `start`.
fn thesis_with_nav(nav: &str, start: &str) -> String {
    let text = bundled()
        .iter()
        .find(|b| b.name == "thesis-leo")
        .expect("thesis-leo")
        .text;
    let text = text.replace(
        "source = \"embedded\"",
        &format!("source = \"rinex\"\nnav_file = \"{nav}\""),
    );
    let text = text.replace("embedded_set = \"bds3\"", "");
    text.replace("2023-03-12T00:00:00 GPST", start)
}

#[test]
#[ignore = "real-data tier: cargo test -- --ignored"]
fn thesis_leo_with_the_rinex4_broadcast_file_of_its_day() {
    let text = thesis_with_nav(
        "nav/BRD400DLR_S_20230710000_01D_MN.rnx.gz",
        "2023-03-12T00:00:00 GPST",
    );
    let world = parse_in(&text, &data_dir())
        .unwrap_or_else(|e| panic!("{e}"))
        .build()
        .unwrap_or_else(|e| panic!("{e}"));
    let valid = |system: System| {
        world
            .satellites
            .iter()
            .filter(|s| s.system == system && world.ephemerides.select(**s, 0.0).is_some())
            .count()
    };
    // March 2023: about 31 GPS satellites and 45 BeiDou (BDS-2 + BDS-3) broadcast.
    let (gps, bds) = (valid(System::Gps), valid(System::Beidou));
    assert!(
        (27..=32).contains(&gps),
        "GPS satellites valid at the start: {gps}"
    );
    assert!(
        (35..=63).contains(&bds),
        "BeiDou satellites valid at the start: {bds}"
    );
}

#[test]
#[ignore = "real-data tier: cargo test -- --ignored"]
fn a_broadcast_file_of_another_day_is_rejected() {
    let text = thesis_with_nav("nav/brdc0010.22n", "2023-03-12T00:00:00 GPST");
    let err = build_error(&text, &data_dir());
    assert_eq!(err.field, "gnss.gps.nav_file", "{err}");
    let at = position_of(
        &text,
        "[gnss.gps]\nsource = \"rinex\"\nnav_file = \"nav/brdc0010.22n\"",
        "\"nav/",
    );
    assert_eq!((err.line, err.column), (Some(at.0), Some(at.1)), "{err}");
    assert!(
        err.allowed.contains("no healthy GPS ephemeris valid"),
        "{err}"
    );

    // On its own day the GPS part is fine, but a GPS-only RINEX 2 file has no BeiDou.
    let text = thesis_with_nav("nav/brdc0010.22n", "2022-01-01T01:00:00 GPST");
    let err = build_error(&text, &data_dir());
    assert_eq!(err.field, "gnss.beidou.nav_file", "{err}");
    assert!(
        err.allowed.contains("no healthy BeiDou ephemeris valid"),
        "{err}"
    );
}
