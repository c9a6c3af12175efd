//! Galileo in scenarios: opt-in (scenarios without `[gnss.galileo]` have none), the
//! embedded constellation, a RINEX navigation file of I/NAV and F/NAV records, and the
//! checks of the table.

mod common;

use common::*;
use hifitime::{Epoch, TimeScale};
use skyforge_orbits::ephemeris::{NavMessage, SatId, System, nominal, write_nav};

fn galileo_sats(text: &str, dir: &std::path::Path) -> Vec<SatId> {
    let world = parse_in(text, dir)
        .expect("parses")
        .build()
        .unwrap_or_else(|e| panic!("{e}"));
    world
        .satellites
        .into_iter()
        .filter(|s| s.system == System::Galileo)
        .collect()
}

#[test]
fn galileo_is_opt_in() {
    let dir = tempfile::tempdir().expect("tempdir");
    assert!(galileo_sats(BASE, dir.path()).is_empty());
    let s = parse_in(BASE, dir.path()).expect("parses");
    assert!(!s.gnss.galileo.enabled);
    // An empty table enables the embedded constellation.
    let with = replace(
        BASE,
        "[platform.leo.elements]",
        "[gnss.galileo]\n\n[platform.leo.elements]",
    );
    let sats = galileo_sats(&with, dir.path());
    assert_eq!(sats.len(), 24);
    assert!(sats.contains(&SatId::galileo(10)) && !sats.contains(&SatId::galileo(14)));
    // Galileo alone is a valid set of constellations.
    let alone = replace(
        &with,
        "[gnss.gps]\nsource = \"embedded\"",
        "[gnss.gps]\nenabled = false",
    );
    let alone = replace(
        &alone,
        "[gnss.beidou]\nenabled = true",
        "[gnss.beidou]\nenabled = false",
    );
    assert_eq!(galileo_sats(&alone, dir.path()).len(), 24);
}

#[test]
fn galileo_table_is_checked() {
    let with = |extra: &str| {
        replace(
            BASE,
            "[platform.leo.elements]",
            &format!("[gnss.galileo]\n{extra}\n\n[platform.leo.elements]"),
        )
    };
    let err = parse_error(&with("prns = [37]"));
    assert!(
        err.field == "gnss.galileo.prns" && err.allowed.contains("1..=36"),
        "{err}"
    );
    let early = replace(
        &with(""),
        "2023-03-12T00:00:00 GPST",
        "1999-08-21T00:00:00 GPST",
    );
    let err = parse_error(&early);
    assert!(
        err.field == "time.start" && err.allowed.contains("Galileo epoch"),
        "{err}"
    );
    // The BeiDou epoch check still applies first when BeiDou is on; with it off the
    // Galileo epoch decides.
    let no_bds = replace(
        &early,
        "[gnss.beidou]\nenabled = true",
        "[gnss.beidou]\nenabled = false",
    );
    let err = parse_error(&no_bds);
    assert!(err.allowed.contains("Galileo epoch"), "{err}");
}

#[test]
fn a_rinex_file_of_inav_and_fnav_sets_gives_the_fnav_sets() {
    let dir = tempfile::tempdir().expect("tempdir");
    let start = Epoch::from_gregorian(2023, 3, 12, 0, 0, 0, 0, TimeScale::GST);
    let mut ephs = nominal::galileo(start);
    for e in &mut ephs {
        e.fit_interval_s = 4.0 * 3600.0;
        e.message = NavMessage::GalileoInav;
    }
    let fnav: Vec<_> = ephs
        .iter()
        .map(|e| {
            let mut f = e.clone();
            f.message = NavMessage::GalileoFnav;
            f
        })
        .collect();
    // F/NAV first: were both kept, the I/NAV set read last would win.
    let ephs: Vec<_> = fnav.into_iter().chain(ephs).collect();
    let mut text = Vec::new();
    write_nav(
        &ephs,
        &skyforge_orbits::ephemeris::NavHeader::new("test"),
        &mut text,
    )
    .expect("write");
    std::fs::write(dir.path().join("gal.rnx"), text).expect("write nav file");
    let scenario = replace(
        BASE,
        "[platform.leo.elements]",
        "[gnss.galileo]\nsource = \"rinex\"\nnav_file = \"gal.rnx\"\n\n[platform.leo.elements]",
    );
    let world = parse_in(&scenario, dir.path())
        .expect("parses")
        .build()
        .unwrap_or_else(|e| panic!("{e}"));
    let gal: Vec<_> = world
        .satellites
        .iter()
        .filter(|s| s.system == System::Galileo)
        .collect();
    assert_eq!(gal.len(), 24);
    // The F/NAV sets, the message of E5a (the Galileo signal SkyForge transmits).
    for sat in gal {
        let sets = world.ephemerides.ephemerides(*sat);
        assert_eq!(sets.len(), 1, "{sat}");
        assert_eq!(sets[0].eph.message, NavMessage::GalileoFnav, "{sat}");
    }
    // The GPS table does not take the Galileo records of a file.
    let gps_from_file = replace(
        &scenario,
        "[gnss.gps]\nsource = \"embedded\"",
        "[gnss.gps]\nsource = \"rinex\"\nnav_file = \"gal.rnx\"",
    );
    let err = parse_in(&gps_from_file, dir.path())
        .expect("parses")
        .build()
        .expect_err("no GPS records");
    assert!(
        err.to_string().contains("no healthy GPS ephemeris"),
        "{err}"
    );
}
