//! `[signal] signals`: which signal each constellation transmits, checked against the
//! enabled constellations and the recorded band.

mod common;

use common::*;
use skyforge_gnss::signal::Signal;
use skyforge_orbits::ephemeris::System;

/// [`BASE`] with a `[signal]` table holding `keys`.
fn with_signal(keys: &str) -> String {
    format!("{BASE}\n[signal]\n{keys}\n")
}

#[test]
fn the_default_is_each_constellations_first_signal() {
    let s = parse_in(&with_signal(""), std::path::Path::new(".")).expect("parses");
    let signal = s.signal.as_ref().expect("[signal]");
    assert_eq!(signal.signals_of(System::Gps), [Signal::GpsL1Ca]);
    assert_eq!(signal.signals_of(System::Beidou), [Signal::BdsB1I]);
    assert_eq!(signal.signals_of(System::Galileo), [Signal::GalE5a]);
}

#[test]
fn gps_may_transmit_l5_in_a_band_that_holds_it() {
    let text = with_signal("signals = [\"gps-l5\", \"bds-b1i\"]\nsample_rate_hz = 20.46e6");
    let s = parse_in(&text, std::path::Path::new(".")).expect("parses");
    let signal = s.signal.as_ref().expect("[signal]");
    assert_eq!(signal.signals_of(System::Gps), [Signal::GpsL5]);
    assert_eq!(signal.signals_of(System::Beidou), [Signal::BdsB1I]);
    s.build().unwrap_or_else(|e| panic!("{e}"));
    // At the default 4.092 Msps the L5 main lobe (+-10.23 MHz) does not fit.
    let err = parse_error(&with_signal("signals = [\"gps-l5\", \"bds-b1i\"]"));
    assert!(
        err.field == "signal.sample_rate_hz" && err.allowed.contains("GPS L5"),
        "{err}"
    );
}

#[test]
fn every_enabled_constellation_needs_one_signal_and_no_other() {
    let err = parse_error(&with_signal(
        "signals = [\"gps-l5\"]\nsample_rate_hz = 20.46e6",
    ));
    assert!(
        err.field == "signal.signals" && err.allowed.contains("no signal of BeiDou"),
        "{err}"
    );
    let err = parse_error(&with_signal(
        "signals = [\"gps-l1ca\", \"bds-b1i\", \"gal-e5a\"]",
    ));
    assert!(
        err.field == "signal.signals[2]"
            && err.value == "gal-e5a"
            && err.allowed.contains("Galileo is not enabled"),
        "{err}"
    );
    let err = parse_error(&with_signal(
        "signals = [\"gps-l1ca\", \"bds-b1i\", \"gps-l1ca\"]",
    ));
    assert!(
        err.field == "signal.signals[2]" && err.allowed.contains("listed twice"),
        "{err}"
    );
}

/// A constellation may transmit several signals, one recording each.
#[test]
fn gps_may_transmit_l1_and_l5_together() {
    let text =
        with_signal("signals = [\"gps-l1ca\", \"gps-l5\", \"bds-b1i\"]\nsample_rate_hz = 20.46e6");
    let s = parse_in(&text, std::path::Path::new(".")).expect("parses");
    let signal = s.signal.as_ref().expect("[signal]");
    assert_eq!(
        signal.signals_of(System::Gps),
        [Signal::GpsL1Ca, Signal::GpsL5]
    );
}

#[test]
fn only_transmitted_signals_may_be_chosen() {
    let err = parse_error(&with_signal("signals = [\"gps-l2\", \"bds-b1i\"]"));
    assert!(
        err.field == "signal.signals[0]"
            && err.value == "gps-l2"
            && err.allowed.contains("gps-l1ca, bds-b1i, gal-e5a, gps-l5"),
        "{err}"
    );
    let err = parse_error(&with_signal("signals = [\"gps-l9\"]"));
    assert!(err.field.starts_with("signal.signals"), "{err}");
}

/// BeiDou may transmit B2a (BDS-3 MEO/IGSO) in a band that holds its +-10.23 MHz lobe.
#[test]
fn beidou_may_transmit_b2a_in_a_band_that_holds_it() {
    let text = with_signal("signals = [\"gps-l1ca\", \"bds-b2a\"]\nsample_rate_hz = 20.46e6");
    let s = parse_in(&text, std::path::Path::new(".")).expect("parses");
    let signal = s.signal.as_ref().expect("[signal]");
    assert_eq!(signal.signals_of(System::Beidou), [Signal::BdsB2a]);
    s.build().unwrap_or_else(|e| panic!("{e}"));
    let err = parse_error(&with_signal("signals = [\"gps-l1ca\", \"bds-b2a\"]"));
    assert!(
        err.field == "signal.sample_rate_hz" && err.allowed.contains("BDS B2a"),
        "{err}"
    );
}

/// BeiDou may transmit B1C in a band that holds its QMBOC's BOC(6,1) lobes (+-7.161 MHz,
/// as Galileo E1's): 15 Msps, not the default 4.092 Msps.
#[test]
fn beidou_may_transmit_b1c_in_a_band_that_holds_its_boc61_lobes() {
    let text = with_signal("signals = [\"gps-l1ca\", \"bds-b1c\"]\nsample_rate_hz = 15e6");
    let s = parse_in(&text, std::path::Path::new(".")).expect("parses");
    let signal = s.signal.as_ref().expect("[signal]");
    assert_eq!(signal.signals_of(System::Beidou), [Signal::BdsB1C]);
    s.build().unwrap_or_else(|e| panic!("{e}"));
    let err = parse_error(&with_signal("signals = [\"gps-l1ca\", \"bds-b1c\"]"));
    assert!(
        err.field == "signal.sample_rate_hz" && err.allowed.contains("BDS B1C"),
        "{err}"
    );
}
