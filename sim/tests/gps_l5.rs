//! GPS L5 through the CLI: `synth` writes its recording, a GNSS-SDR configuration for it,
//! the ephemerides as broadcast and L5 observation truth (the bundled receiver's fixes on
//! L5: tests/pilot_signals.rs).

mod support;

/// The bundled static ground site with GPS alone on L5, `duration_s` long, `extra`
/// appended after its `[signal]` table.
fn scenario(dir: &std::path::Path, duration_s: f64, extra: &str) -> String {
    let mut text = support::bundled_edited(
        "ground-static",
        &[
            (
                "[gnss.beidou]\nsource = \"embedded\"",
                "[gnss.beidou]\nenabled = false",
            ),
            ("duration_s = 3600.0", &format!("duration_s = {duration_s}")),
        ],
    );
    text.push_str(
        "\n[signal]\nsignals = [\"gps-l5\"]\nsample_rate_hz = 20.46e6\nformat = \"ci8\"\ncn0_dbhz = 45.0\n",
    );
    text.push_str(extra);
    support::write_scenario(dir, "l5.toml", &text)
}

#[test]
fn synth_writes_an_l5_recording_its_configuration_and_observation_truth() {
    let dir = tempfile::tempdir().expect("tempdir");
    let path = scenario(dir.path(), 1.0, "");
    let out = dir.path().join("out");
    support::skyforge_ok(
        &["synth", &path, "--out", out.to_str().unwrap()],
        dir.path(),
    );
    assert!(!out.join("ant1.gps-l1ca.sigmf-data").exists());
    let data = std::fs::metadata(out.join("ant1.gps-l5.sigmf-data")).expect("L5 recording");
    // 1 s of complex 8-bit samples at 20.46 MHz.
    assert_eq!(data.len(), 2 * 20_460_000);
    let meta = std::fs::read_to_string(out.join("ant1.gps-l5.sigmf-meta")).expect("meta");
    assert!(meta.contains("1176450000"), "{meta}");
    let conf = std::fs::read_to_string(out.join("ant1.gps-l5.gnss-sdr.conf")).expect("conf");
    for key in [
        "Channels_L5.count=",
        "Acquisition_L5.implementation=GPS_L5i_PCPS_Acquisition",
        "Tracking_L5.implementation=GPS_L5_DLL_PLL_Tracking",
        "Tracking_L5.track_pilot=true",
        "TelemetryDecoder_L5.implementation=GPS_L5_Telemetry_Decoder",
    ] {
        assert!(conf.contains(key), "{key}");
    }
    assert!(!conf.contains("Channels_1C"), "{conf}");
    // Every GPS satellite's ephemeris as CNAV carries it (toe on the 300 s grid), and L5
    // observation truth under the reference code 5I.
    let nav = std::fs::read_to_string(out.join("nav.rnx")).expect("nav");
    let body = nav.split("END OF HEADER").nth(1).unwrap_or("");
    let gps: Vec<&str> = body.lines().filter(|l| l.starts_with('G')).collect();
    assert!(gps.len() >= 24, "{} GPS records", gps.len());
    for l in gps {
        let minute: u32 = l[17..19].trim().parse().expect("minute");
        let second: u32 = l[20..22].trim().parse().expect("second");
        assert!(
            minute.is_multiple_of(5) && second == 0,
            "toc off the 300 s grid: {l}"
        );
    }
    let obs = std::fs::read_to_string(out.join("ant1.obs.rnx")).expect("obs");
    assert!(obs.contains("G    4 C5I L5I D5I S5I"), "{obs}");
}

/// The observation level draws GPS L5 observables (code 5I) with the configured noise;
/// the calibrated model, measured on what the bundled receiver tracks, refuses them.
#[test]
fn observation_level_l5_has_the_configured_noise() {
    let dir = tempfile::tempdir().expect("tempdir");
    let at = |extra: &str| scenario(dir.path(), 120.0, extra);
    support::assert_constant_observation_noise(dir.path(), at, "GPS", "gps-l5");
    let obs =
        std::fs::read_to_string(dir.path().join("out/observations/ant1.obs.rnx")).expect("obs");
    assert!(obs.contains("G    4 C5I L5I D5I S5I"), "{obs}");
}
