//! Physically impossible or malformed input: one test per case the issue lists, each
//! checking the field path, the value and that line/column point at it in the text.

mod common;

use common::*;
use std::path::Path;

#[test]
fn base_scenario_is_valid() {
    let s = parse_in(BASE, Path::new(".")).expect("BASE parses");
    assert_eq!(s.name, "base");
    assert_eq!(s.seed, 7);
    assert_eq!(s.time.duration_s, 600.0);
    assert_eq!(s.antennas.len(), 2);
    assert!(s.gnss.gps.enabled && s.gnss.beidou.enabled);
}

#[test]
fn eccentricity_of_one_or_more() {
    for bad in ["1.2", "1.0"] {
        let to = format!("eccentricity = {bad}");
        let field = "platform.leo.elements.eccentricity";
        replaced_error("eccentricity = 0.000846", &to, field, bad);
    }
}

#[test]
fn perigee_below_the_surface() {
    // a (1 - e) = 6800 km * 0.95 = 6460 km would be fine; 6600 km * 0.9 = 5940 km is not.
    let text = replace(
        BASE,
        "semi_major_axis_km = 6971.593",
        "semi_major_axis_km = 6600.0",
    );
    let text = replace(&text, "eccentricity = 0.000846", "eccentricity = 0.1");
    let err = parse_error(&text);
    assert!(err.field.starts_with("platform.leo.elements"), "{err}");
    let (key, value) = if err.field.ends_with("eccentricity") {
        ("eccentricity = 0.1", "0.1")
    } else {
        ("semi_major_axis_km = 6600.0", "6600.0")
    };
    assert_at(&err, position_of(&text, key, value));
    assert!(err.to_string().starts_with(SOURCE), "{err}");
}

#[test]
fn negative_mass() {
    let field = "platform.leo.forces.mass_kg";
    replaced_error("mass_kg = 100.0", "mass_kg = -5.0", field, "-5.0");
}

#[test]
fn negative_area() {
    let field = "platform.leo.forces.area_m2";
    replaced_error("area_m2 = 1.0", "area_m2 = -1.5", field, "-1.5");
}

#[test]
fn no_antennas() {
    let start = BASE.find("[[antennas]]").expect("antennas");
    let without = &BASE[..start];
    let err = parse_error(without);
    assert_error(&err, "antennas", "none", (1, 1));
    let empty = format!("antennas = []\n{without}");
    let err = parse_error(&empty);
    assert_error(
        &err,
        "antennas",
        "none",
        position_of(&empty, "antennas = []", "[]"),
    );
}

#[test]
fn empty_or_reversed_time_span() {
    for bad in ["0.0", "-600.0", "nan"] {
        let to = format!("duration_s = {bad}");
        replaced_error("duration_s = 600.0", &to, "time.duration_s", bad);
    }
}

#[test]
fn non_positive_step() {
    for bad in ["0.0", "-1.0", "inf"] {
        let to = format!("geometry_rate_hz = {bad}");
        replaced_error("geometry_rate_hz = 1.0", &to, "truth.geometry_rate_hz", bad);
    }
    // A step longer than the span.
    let to = "geometry_rate_hz = 0.001";
    let err = replaced_error(
        "geometry_rate_hz = 1.0",
        to,
        "truth.geometry_rate_hz",
        "0.001",
    );
    assert!(err.allowed.contains("1 / time.duration_s"), "{err}");
}

#[test]
fn unknown_prn() {
    let text = replace(BASE, "source = \"embedded\"", "prns = [1, 40]");
    let err = parse_error(&text);
    assert!(err.field.starts_with("gnss.gps.prns"), "{err}");
    let part = if err.field == "gnss.gps.prns[1]" {
        "40"
    } else {
        "[1, 40]"
    };
    assert_at(&err, position_of(&text, "prns = [1, 40]", part));
    assert!(err.to_string().contains("40"), "{err}");

    let text = replace(BASE, "enabled = true", "prns = [64]");
    let err = parse_error(&text);
    assert!(err.field.starts_with("gnss.beidou.prns"), "{err}");
    assert!(err.to_string().contains("64"), "{err}");
}

/// Issue #11: `prns = []` synthesised a recording with no satellites.
#[test]
fn an_empty_prn_list() {
    let text = replace(BASE, "source = \"embedded\"", "prns = []");
    let err = parse_error_at(&text, "gnss.gps.prns", "prns = []", "[]");
    assert!(err.allowed.contains("at least one PRN"), "{err}");
    let text = replace(BASE, "enabled = true", "prns = []");
    parse_error_at(&text, "gnss.beidou.prns", "prns = []", "[]");
    // A disabled constellation's list does not matter.
    let text = replace(BASE, "enabled = true", "enabled = false\nprns = []");
    assert!(parse_in(&text, Path::new(".")).is_ok());
}

/// Issue #11: `semi_major_axis_km = 1e30` was accepted and wrote no observation file.
#[test]
fn an_orbit_beyond_100_000_km() {
    for bad in ["1e30", "100001.0"] {
        let to = format!("semi_major_axis_km = {bad}");
        let err = replaced_error(
            "semi_major_axis_km = 6971.593",
            &to,
            "platform.leo.elements.semi_major_axis_km",
            bad,
        );
        assert!(err.allowed.contains("<= 100000 km"), "{err}");
    }
}

/// Issue #11: `2100-01-01T00:00:01 GPST` (2099-12-31 in UTC) passed the documented limit,
/// a start before 2100-01-01T00:00:00 in its own time scale.
#[test]
fn a_start_from_2100_on() {
    for bad in [
        "2100-01-01T00:00:01 GPST",
        "2100-01-01T00:00:00 GPST",
        "2100-01-01T00:00:00 UTC",
        "2100-01-01T00:00:10 TAI",
        "1980-01-05T23:59:59 GPST",
    ] {
        let to = format!("start = \"{bad}\"");
        let err = parse_error(&replace(BASE, "start = \"2023-03-12T00:00:00 GPST\"", &to));
        assert_eq!(err.field, "time.start", "{bad}: {err}");
        assert!(err.allowed.contains("before 2100-01-01T00:00:00"), "{err}");
        assert_at(
            &err,
            position_of(
                &replace(BASE, "start = \"2023-03-12T00:00:00 GPST\"", &to),
                &to,
                "\"",
            ),
        );
    }
    let last = replace(BASE, "2023-03-12T00:00:00 GPST", "2099-12-31T23:59:59 GPST");
    assert!(parse_in(&last, Path::new(".")).is_ok());
}

#[test]
fn missing_navigation_file() {
    let dir = tempfile::tempdir().expect("tempdir");
    let text = replace(
        BASE,
        "source = \"embedded\"",
        "source = \"rinex\"\nnav_file = \"nav/missing.rnx\"",
    );
    let at = ("nav_file = \"nav/missing.rnx\"", "\"nav/");
    let value = "\"nav/missing.rnx\"";
    let err = build_error_at(&text, dir.path(), "gnss.gps.nav_file", value, at);
    assert!(err.allowed.contains("missing.rnx"), "{err}");
}

#[test]
fn unreadable_navigation_file() {
    let dir = tempfile::tempdir().expect("tempdir");
    std::fs::write(dir.path().join("garbage.rnx"), "this is not RINEX\n").expect("write");
    std::fs::create_dir(dir.path().join("a_directory.rnx")).expect("mkdir");
    for name in ["garbage.rnx", "a_directory.rnx"] {
        let text = replace(
            BASE,
            "source = \"embedded\"",
            &format!("source = \"rinex\"\nnav_file = \"{name}\""),
        );
        let (context, value) = (format!("nav_file = \"{name}\""), format!("\"{name}\""));
        let at = (context.as_str(), "\"");
        build_error_at(&text, dir.path(), "gnss.gps.nav_file", &value, at);
    }
}

#[test]
fn rinex_source_without_a_file() {
    let text = replace(BASE, "source = \"embedded\"", "source = \"rinex\"");
    let err = parse_error(&text);
    assert!(err.field.starts_with("gnss.gps"), "{err}");
    assert!(err.line.is_some(), "{err}");
}

#[test]
fn unknown_key_is_rejected_where_it_is() {
    let text = replace(BASE, "mass_kg = 100.0", "mass_kg = 100.0\nmass_lb = 220.0");
    let err = parse_error(&text);
    let at = position_of(&text, "mass_lb = 220.0", "mass_lb");
    assert_error(&err, "platform.leo.forces.mass_lb", "220.0", at);
    assert!(err.allowed.contains("unknown field `mass_lb`"), "{err}");
    assert!(
        err.allowed.contains("mass_kg"),
        "lists what is allowed: {err}"
    );

    let text = format!("{BASE}\n[receiver]\nbandwidth_hz = 18.0\n");
    let err = parse_error(&text);
    assert_eq!(err.field, "receiver");
    assert_at(&err, (position_of(&text, "[receiver]", "receiver").0, 2));
}

#[test]
fn wrong_type_and_missing_field() {
    let (to, field) = (
        "eccentricity = \"small\"",
        "platform.leo.elements.eccentricity",
    );
    replaced_error("eccentricity = 0.000846", to, field, "\"small\"");

    let text = replace(BASE, "inclination_deg = 34.911\n", "");
    let err = parse_error(&text);
    let at = position_of(&text, "[platform.leo.elements]", "[");
    assert_error(
        &err,
        "platform.leo.elements.inclination_deg",
        "(missing)",
        at,
    );

    let text = replace(BASE, "name = \"base\"\n", "");
    let err = parse_error(&text);
    assert_error(&err, "name", "(missing)", (1, 1));

    replaced_error("seed = 7", "seed = -7", "seed", "-7");

    let text = replace(BASE, "name = \"ant2\"\n", "");
    let err = parse_error(&text);
    assert_eq!(err.field, "antennas[1].name");
    assert_eq!(err.value, "(missing)");
    let second = text.rfind("[[antennas]]").expect("second antenna");
    assert_at(&err, (text[..second].matches('\n').count() + 1, 1));
}

#[test]
fn toml_syntax_error() {
    let text = replace(
        BASE,
        "eccentricity = 0.000846",
        "eccentricity = 0.000846 0.1",
    );
    let err = parse_error(&text);
    let (line, _) = position_of(&text, "eccentricity = 0.000846 0.1", "0.1");
    assert_eq!(err.line, Some(line), "{err}");
    assert!(err.allowed.starts_with("TOML syntax error"), "{err}");
    assert!(
        err.to_string().starts_with(&format!("{SOURCE}:{line}:")),
        "{err}"
    );
}

#[test]
fn bad_epoch() {
    let text = replace(BASE, "2023-03-12T00:00:00 GPST", "2023-13-45T00:00:00 GPST");
    let err = parse_error(&text);
    let at = position_of(&text, "start = \"2023-13-45", "\"");
    assert_error(&err, "time.start", "\"2023-13-45T00:00:00 GPST\"", at);

    let text = replace(BASE, "2023-03-12T00:00:00 GPST", "2001-01-01T00:00:00 GPST");
    let err = parse_error(&text);
    assert_eq!(err.field, "time.start");
    assert!(err.allowed.contains("BeiDou"), "{err}");
    // Without BeiDou an epoch before 2006 is fine.
    let gps_only = replace(&text, "enabled = true", "enabled = false");
    parse_in(&gps_only, Path::new(".")).expect("GPS-only 2001 scenario");
}

/// BASE (GPS + BeiDou) with a `[signal]` table.
fn with_signal(fields: &str) -> String {
    format!("{BASE}\n[signal]\n{fields}\n")
}

#[test]
fn sample_rate_below_the_signal_bandwidth() {
    // 3 Msps complex holds the C/A main lobe but not B1I's (+-2.046 MHz).
    let text = with_signal("sample_rate_hz = 3.0e6\nformat = \"ci8\"");
    let err = parse_error_at(
        &text,
        "signal.sample_rate_hz",
        "sample_rate_hz = 3.0e6",
        "3.0e6",
    );
    assert!(err.to_string().contains("BDS B1I"), "{err}");
    // GPS alone is fine at 3 Msps; below the C/A main lobe it is not.
    let gps_only = replace(
        &text,
        "[gnss.beidou]\nenabled = true",
        "[gnss.beidou]\nenabled = false",
    );
    parse_in(&gps_only, Path::new(".")).expect("GPS at 3 Msps");
    let line = "sample_rate_hz = 1.5e6";
    let text = replace(&gps_only, "sample_rate_hz = 3.0e6", line);
    parse_error_at(&text, "signal.sample_rate_hz", line, "1.5e6");
    // A complex IF offset counts too: 4.092 Msps at IF 1 MHz cannot hold B1I.
    let text = with_signal("sample_rate_hz = 4.092e6\nif_hz = 1.0e6");
    parse_error_at(
        &text,
        "signal.sample_rate_hz",
        "sample_rate_hz = 4.092e6",
        "4.092e6",
    );
}

#[test]
fn intermediate_frequency_outside_nyquist() {
    let text = with_signal("sample_rate_hz = 8.0e6\nif_hz = 5.0e6");
    let err = parse_error_at(&text, "signal.if_hz", "if_hz = 5.0e6", "5.0e6");
    assert!(err.to_string().contains("Nyquist"), "{err}");
    // Real samples: the main lobe must fit between 0 and fs/2 (16.368 Msps: 2.0-6.2 MHz
    // for B1I), and a real recording needs an IF.
    for bad in ["1.0e6", "7.0e6", "0.0"] {
        let text = with_signal(&format!(
            "sample_rate_hz = 16.368e6\nformat = \"ri8\"\nif_hz = {bad}"
        ));
        let err = parse_error(&text);
        assert_eq!(err.field, "signal.if_hz", "{err}");
        assert_at(&err, position_of(&text, &format!("if_hz = {bad}"), bad));
    }
    let ok = with_signal("sample_rate_hz = 16.368e6\nformat = \"ri8\"\nif_hz = 4.092e6");
    parse_in(&ok, Path::new(".")).expect("B1I and C/A at IF 4.092 MHz, 16.368 Msps real");
}

#[test]
fn quantisation_bits_not_in_the_list() {
    for bad in ["3", "12", "0"] {
        let text = with_signal(&format!("format = \"ci16\"\nbits = {bad}"));
        let err = parse_error_at(&text, "signal.bits", &format!("bits = {bad}"), bad);
        assert!(err.to_string().contains("1, 2, 4, 8, 16"), "{err}");
    }
    // 16 bits do not fit an 8-bit container.
    let text = with_signal("format = \"ci8\"\nbits = 16");
    parse_error_at(&text, "signal.bits", "bits = 16", "16");
}

/// Antenna names name output files and the RINEX `MARKER NAME` (issue #11: a name like
/// `../prev/ant1` overwrote another run's recording, an absolute name wrote outside the
/// output directory, a newline broke the RINEX header): each is refused, located at the
/// name.
#[test]
fn antenna_names_that_cannot_name_files_are_refused() {
    for bad in [
        "../prev/ant1",
        "/tmp/ant1",
        "ant\\\\1",
        "..",
        ".",
        "ant\\n1",
        " ant1",
        "antenne\u{e9}",
    ] {
        let quoted = format!("\"{bad}\"");
        let err = replaced_error(
            "name = \"ant1\"",
            &format!("name = {quoted}"),
            "antennas[0].name",
            &quoted,
        );
        assert!(err.to_string().contains("MARKER NAME"), "{err}");
    }
    // Sixty characters are a valid RINEX marker, sixty-one are not (the message shortens
    // the value).
    let long = replace(
        BASE,
        "name = \"ant1\"",
        &format!("name = \"{}\"", "a".repeat(61)),
    );
    let err = parse_error(&long).to_string();
    assert!(
        err.contains("antennas[0].name") && err.contains("MARKER NAME"),
        "{err}"
    );
    let ok = replace(
        BASE,
        "name = \"ant1\"",
        &format!("name = \"{}\"", "a".repeat(60)),
    );
    assert!(parse_in(&ok, Path::new(".")).is_ok());
}

#[test]
fn observation_level_without_a_signal_table() {
    let text = format!("{BASE}\n[observation]\nlevel = \"observation\"\n");
    let err = parse_error(&text);
    assert_eq!(err.field, "observation.level", "{err}");
    assert!(err.to_string().contains("[signal]"), "{err}");
}

#[test]
fn negative_observation_noise() {
    let text = format!(
        "{BASE}\n[observation.noise]\nmodel = \"constant\"\nphase_m = -0.001\ncode_m = 0.3\n"
    );
    parse_error_at(
        &text,
        "observation.noise.phase_m",
        "phase_m = -0.001",
        "-0.001",
    );
}

#[test]
fn elevation_scale_of_zero() {
    let text = format!(
        "{BASE}\n[observation.noise]\nmodel = \"elevation\"\nphase = {{ sigma0_m = 0.002, a0 = 10.0, elev0_deg = 10.0 }}\ncode = {{ sigma0_m = 0.3, a0 = 10.0, elev0_deg = 0.0 }}\n"
    );
    let err = parse_error(&text);
    assert_eq!(err.field, "observation.noise.code.elev0_deg", "{err}");
}

/// Issue #11: the antenna count is bounded (64); the 65th antenna table is named.
#[test]
fn more_than_64_antennas() {
    let extra: String = (3..=64)
        .map(|i| {
            format!("\n[[antennas]]\nname = \"ant{i}\"\nposition_body_m = [0.0, 0.0, {i}.0]\n")
        })
        .collect();
    let sixty_four = format!("{BASE}{extra}");
    assert_eq!(
        parse_in(&sixty_four, Path::new("."))
            .unwrap()
            .antennas
            .len(),
        64
    );
    let text = format!(
        "{sixty_four}\n[[antennas]]\nname = \"ant65\"\nposition_body_m = [0.0, 1.0, 0.0]\n"
    );
    let err = parse_error(&text);
    assert_eq!(err.field, "antennas[64]", "{err}");
    assert!(err.allowed.contains("at most 64 antennas"), "{err}");
    let line = text.lines().position(|l| l == "name = \"ant65\"").unwrap();
    assert!(err.line.is_some_and(|l| l.abs_diff(line + 1) <= 1), "{err}");
}

/// GST - GPST is Galileo's: set on GPS it is refused, and on Galileo beyond what A0G
/// carries, each at its line.
#[test]
fn a_gst_gps_offset_off_galileo_or_beyond_the_broadcast() {
    let text = replace(BASE, "source = \"embedded\"", "gst_gps_ns = 20.0");
    let err = parse_error_at(&text, "gnss.gps.gst_gps_ns", "gst_gps_ns = 20.0", "20.0");
    assert!(err.allowed.contains("only [gnss.galileo]"), "{err}");
    let text = format!("{BASE}\n[gnss.galileo]\ngst_gps_ns = 2000.0\n");
    let err = parse_error_at(
        &text,
        "gnss.galileo.gst_gps_ns",
        "gst_gps_ns = 2000.0",
        "2000.0",
    );
    assert!(err.allowed.contains("953.645 ns"), "{err}");
    let text = format!("{BASE}\n[gnss.galileo]\ngst_gps_ns = -20.0\n");
    assert!(parse_in(&text, Path::new(".")).is_ok());
}
