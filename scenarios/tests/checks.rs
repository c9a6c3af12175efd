//! Cross-field and whole-scenario checks: platform kind, ground site, attitude profile,
//! antennas, constellations, defaults.

mod common;

use common::*;
use skyforge_orbits::ephemeris::{BeidouSet, ConstellationSource};
use std::path::Path;

#[test]
fn defaults_fill_everything_not_essential() {
    let minimal = r#"
name = "minimal"
[time]
start = "2023-03-12T00:00:00 GPST"
duration_s = 60.0
[platform.ground]
latitude_deg = 30.0
longitude_deg = 114.0
height_m = 50.0
[[antennas]]
name = "a"
position_body_m = [0.0, 0.0, 0.0]
"#;
    let s = parse_in(minimal, Path::new("/some/dir")).expect("minimal scenario");
    assert_eq!(s.seed, 0);
    assert_eq!(s.description, None);
    assert_eq!(s.truth.geometry_rate_hz, 1.0);
    for c in [&s.gnss.gps, &s.gnss.beidou] {
        assert!(c.enabled);
        assert_eq!(c.source, ConstellationSource::Embedded);
        assert_eq!(c.prns, None);
    }
    assert_eq!(s.gnss.beidou.embedded_set, BeidouSet::Bds3);
    let a = &s.antennas[0];
    assert_eq!(a.boresight_body, [0.0, 0.0, -1.0]);
    assert_eq!(a.fov_half_angle_deg, 90.0);
    assert_eq!(a.elevation_mask_deg, -90.0);
    assert_eq!(s.source, SOURCE);
    assert_eq!(s.base_dir, Path::new("/some/dir"));
    assert_eq!(s.text, minimal);
}

#[test]
fn exactly_one_platform_kind() {
    let two = replace(
        BASE,
        "[platform.leo.forces]",
        "[platform.ground]\nlatitude_deg = 1.0\nlongitude_deg = 2.0\nheight_m = 3.0\n\n[platform.leo.forces]",
    );
    let err = parse_error(&two);
    assert_eq!(err.field, "platform");
    assert_eq!(err.value, "leo + ground");
    assert_at(
        &err,
        position_of(&two, "[platform.leo.elements]", "platform"),
    );

    let none = replace(
        &ground("latitude_deg = 1.0\nlongitude_deg = 2.0\nheight_m = 3.0"),
        "[platform.ground]",
        "[platform.attitude]",
    );
    let err = parse_error(&none);
    assert!(err.field.starts_with("platform"), "{err}");
}

#[test]
fn ground_site_checks() {
    let ok = ground("latitude_deg = 30.0\nlongitude_deg = 114.0\nheight_m = 50.0");
    parse_in(&ok, Path::new(".")).expect("valid ground site");
    let ok = ground("ecef_m = [-2267000.0, 5009000.0, 3221000.0]");
    parse_in(&ok, Path::new(".")).expect("valid ECEF site");

    let text = ground("latitude_deg = 95.0\nlongitude_deg = 114.0\nheight_m = 50.0");
    parse_error_at(
        &text,
        "platform.ground.latitude_deg",
        "latitude_deg = 95.0",
        "95.0",
    );

    let text = ground("latitude_deg = 30.0\nlongitude_deg = 114.0");
    let err = parse_error(&text);
    assert_eq!(err.field, "platform.ground.height_m");
    assert_at(&err, (position_of(&text, "[platform.ground]", "[").0, 1));

    let text = ground(
        "latitude_deg = 30.0\nlongitude_deg = 114.0\nheight_m = 5.0\necef_m = [6378137.0, 0.0, 0.0]",
    );
    assert_eq!(parse_error(&text).field, "platform.ground.ecef_m");

    let text = ground("ecef_m = [1000.0, 0.0, 0.0]");
    let err = parse_error(&text);
    assert_eq!(err.field, "platform.ground.ecef_m");
    assert_at(&err, position_of(&text, "ecef_m = [1000.0", "[1000.0"));

    let text = ground("ecef_m = [nan, 0.0, 0.0]");
    parse_error_at(&text, "platform.ground.ecef_m[0]", "[nan", "nan");

    let text = ground("");
    assert_eq!(parse_error(&text).field, "platform.ground");
}

#[test]
fn attitude_profile_checks() {
    let with = |attitude: &str| {
        replace(
            BASE,
            "[platform.leo.forces]",
            &format!("[platform.attitude]\n{attitude}\n\n[platform.leo.forces]"),
        )
    };
    parse_in(
        &with("yaw = { amplitude_deg = 2.0, period_s = 600.0 }"),
        Path::new("."),
    )
    .expect("sinusoid");

    let text = with("pitch = { amplitude_deg = 2.0 }");
    let err = parse_error(&text);
    assert_eq!(err.field, "platform.attitude.pitch.period_s");
    assert_at(&err, (position_of(&text, "pitch = {", "{").0, 9));

    let text = with("roll = { offset_deg = inf }");
    parse_error_at(
        &text,
        "platform.attitude.roll.offset_deg",
        "offset_deg = inf",
        "inf",
    );

    let text = with("csv = \"attitude.csv\"\nyaw = { offset_deg = 1.0 }");
    assert_eq!(parse_error(&text).field, "platform.attitude.yaw");
}

#[test]
fn antenna_checks_are_located_per_antenna() {
    let (to, field) = ("fov_half_angle_deg = 0.0", "antennas[1].fov_half_angle_deg");
    replaced_error("fov_half_angle_deg = 80.0", to, field, "0.0");

    let text = replace(BASE, "name = \"ant2\"", "name = \"ant1\"");
    let err = parse_error(&text);
    let second = text.rfind("name = \"ant1\"").expect("second") + "name = ".len();
    assert_eq!(err.field, "antennas[1].name");
    assert_eq!(err.value, "\"ant1\"");
    assert_at(&err, (text[..second].matches('\n').count() + 1, 8));

    let text = replace(
        BASE,
        "position_body_m = [1.0, 0.0, 0.0]",
        "position_body_m = [1.0, 0.0, nan]",
    );
    parse_error_at(
        &text,
        "antennas[1].position_body_m[2]",
        "[1.0, 0.0, nan]",
        "nan",
    );

    let text = replace(
        BASE,
        "position_body_m = [1.0, 0.0, 0.0]",
        "position_body_m = [1.0, 0.0]",
    );
    let err = parse_error(&text);
    assert_error(
        &err,
        "antennas[1].position_body_m",
        "[1.0, 0.0]",
        position_of(&text, "position_body_m = [1.0, 0.0]", "[1.0"),
    );
}

#[test]
fn at_least_one_constellation() {
    let text = replace(BASE, "source = \"embedded\"", "enabled = false");
    let text = replace(&text, "enabled = true", "enabled = false");
    let err = parse_error(&text);
    assert_eq!(err.field, "gnss");
    assert!(err.line.is_some());
}

#[test]
fn bad_enum_value() {
    let to = "source = \"almanac\"";
    let err = replaced_error(
        "source = \"embedded\"",
        to,
        "gnss.gps.source",
        "\"almanac\"",
    );
    assert!(err.allowed.contains("embedded"), "{err}");
}

#[test]
fn build_checks_a_scenario_changed_after_parsing() {
    let mut s = parse_in(BASE, Path::new(".")).expect("BASE parses");
    s.time.duration_s = -1.0;
    let err = s.build().expect_err("negative duration");
    // Located at the field in the original text, with the value actually checked.
    let at = position_of(BASE, "duration_s = 600.0", "600.0");
    assert_error(&err, "time.duration_s", "-1", at);

    let mut s = parse_in(BASE, Path::new(".")).expect("BASE parses");
    s.antennas.clear();
    assert_eq!(s.build().expect_err("no antennas").field, "antennas");
}

#[test]
fn satellite_error_processes_are_checked_and_located() {
    let table = "[errors.satellite]\nmodel = \"gauss-markov\"\n[errors.satellite.processes]\nradial_m = 1.0\nalong_m = 1.0\n\
                 cross_m = 1.0\norbit_tau_s = 3600.0\nclock_m = 1.0\nclock_tau_s = -5.0\n\
                 node_spacing_s = 60.0\n";
    let text = format!("{BASE}\n{table}");
    parse_error_at(
        &text,
        "errors.satellite.processes.clock_tau_s",
        "clock_tau_s = -5.0",
        "-5.0",
    );
    let unknown = format!("{BASE}\n[errors.satellite]\nmodel = \"selective-availability\"\n");
    let err = parse_error(&unknown);
    assert!(err.to_string().contains("book-sa"), "{err}");
}

#[test]
fn a_precise_model_needs_a_readable_sp3_file_of_the_day() {
    let dir = tempfile::tempdir().unwrap();
    let missing = format!("{BASE}\n[errors.satellite]\nmodel = \"precise\"\nsp3 = \"day.sp3\"\n");
    let err = build_error_at(
        &missing,
        dir.path(),
        "errors.satellite.sp3",
        "\"day.sp3\"",
        ("sp3 = \"day.sp3\"", "\"day.sp3\""),
    );
    assert!(err.to_string().contains("readable SP3 file"), "{err}");
    // A file of another day: no satellite covered over the run.
    std::fs::write(
        dir.path().join("day.sp3"),
        "#cP2020  6 25  0  0  0.00000000\n*  2020  6 25  0  0  0.00000000\n\
         PG01 -10814.532184  19731.805009 -14065.684961     15.943802\n",
    )
    .unwrap();
    let err = build_error(&missing, dir.path());
    assert_eq!(err.field, "errors.satellite.sp3");
    assert!(err.to_string().contains("holds no satellite"), "{err}");
    let none = format!("{BASE}\n[errors.satellite]\nmodel = \"precise\"\n");
    assert_eq!(parse_error(&none).field, "errors.satellite.sp3");
}

#[test]
fn doppler_noise_needs_the_calibrated_model_or_a_constant_doppler_sigma() {
    let constant = |doppler_noise: bool, doppler: &str| {
        format!(
            "{BASE}\n[signal]\ncn0_dbhz = 45.0\n[observation]\nlevel = \"observation\"\n\
             doppler_noise = {doppler_noise}\n[observation.noise]\nmodel = \"constant\"\n\
             phase_m = 0.003\ncode_m = 0.3\n{doppler}"
        )
    };
    let scenario = parse_in(&constant(true, ""), Path::new(".")).expect("parses");
    let err = scenario.observation_model(1, 1.0).unwrap_err();
    assert_eq!(err.field, "observation.doppler_noise");
    assert!(err.to_string().contains("doppler_mps"), "{err}");
    let with_sigma = constant(true, "doppler_mps = 0.1\n");
    let scenario = parse_in(&with_sigma, Path::new(".")).expect("parses");
    assert!(scenario.observation_model(1, 1.0).is_ok());
    let err = parse_error(&constant(false, "doppler_mps = 0.1\n"));
    assert_eq!(err.field, "observation.noise.doppler_mps");
    assert!(err.to_string().contains("doppler_noise = true"), "{err}");
    let err = parse_error(&constant(true, "doppler_mps = -1.0\n"));
    assert_eq!(err.field, "observation.noise.doppler_mps");
    let calibrated = format!(
        "{BASE}\n[signal]\ncn0_dbhz = 45.0\n[observation]\nlevel = \"observation\"\n\
         doppler_noise = true\n"
    );
    let scenario = parse_in(&calibrated, Path::new(".")).expect("parses");
    assert!(scenario.observation_model(1, 1.0).is_ok());
}
