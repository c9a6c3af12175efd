//! Galileo through the CLI: `run` writes its satellites into the truth, `synth` its E5a
//! recording, F/NAV records and observation truth, the observation level its observables.

mod support;

use skyforge_formats::truth::TruthFile;

/// The bundled static ground site with `[gnss.galileo]`, `duration_s` long, `extra`
/// appended.
fn scenario(dir: &std::path::Path, duration_s: f64, extra: &str) -> String {
    let mut text = support::bundled_edited(
        "ground-static",
        &[
            ("[platform.ground]", "[gnss.galileo]\n\n[platform.ground]"),
            ("duration_s = 3600.0", &format!("duration_s = {duration_s}")),
        ],
    );
    text.push_str(extra);
    support::write_scenario(dir, "galileo.toml", &text)
}

#[test]
fn run_writes_galileo_truth() {
    let dir = tempfile::tempdir().expect("tempdir");
    let path = scenario(dir.path(), 600.0, "");
    let out = dir.path().join("out");
    support::skyforge_ok(&["run", &path, "--out", out.to_str().unwrap()], dir.path());
    let truth = TruthFile::open(&out.join("truth.h5")).expect("truth.h5");
    let sats = truth.satellite_ids(1000).expect("satellites");
    let gal: Vec<usize> = (0..sats.len())
        .filter(|&k| sats[k].starts_with('E'))
        .collect();
    assert_eq!(gal.len(), 24, "{sats:?}");
    let epochs = truth.times(1_000_000).expect("times").len();
    let visible = truth
        .visible("ant1", epochs, sats.len(), 10_000_000)
        .expect("visible");
    // Galileo satellites above a 10 deg mask at 30 N: typically 6-10 (24 MEO at
    // 29 600 km); the bound only asks for a plausible count at every epoch.
    for k in 0..epochs {
        let n = gal
            .iter()
            .filter(|&&s| visible[k * sats.len() + s] != 0)
            .count();
        assert!(
            (4..=14).contains(&n),
            "epoch {k}: {n} Galileo satellites visible"
        );
    }
}

#[test]
fn synth_writes_an_e5a_recording_its_nav_records_and_observation_truth() {
    let dir = tempfile::tempdir().expect("tempdir");
    let path = scenario(
        dir.path(),
        1.0,
        "\n[signal]\nsample_rate_hz = 20.46e6\nformat = \"ci8\"\ncn0_dbhz = 45.0\n",
    );
    let out = dir.path().join("out");
    support::skyforge_ok(
        &["synth", &path, "--out", out.to_str().unwrap()],
        dir.path(),
    );
    let data = std::fs::metadata(out.join("ant1.gal-e5a.sigmf-data")).expect("E5a recording");
    // 1 s of complex 8-bit samples at 20.46 MHz.
    assert_eq!(data.len(), 2 * 20_460_000);
    let meta = std::fs::read_to_string(out.join("ant1.gal-e5a.sigmf-meta")).expect("meta");
    assert!(meta.contains("1176450000"), "{meta}");
    let conf = std::fs::read_to_string(out.join("ant1.gal-e5a.gnss-sdr.conf")).expect("conf");
    for key in [
        "Acquisition_5X.implementation=Galileo_E5a_Pcps_Acquisition",
        "Tracking_5X.track_pilot=true",
        "TelemetryDecoder_5X.implementation=Galileo_E5a_Telemetry_Decoder",
    ] {
        assert!(conf.contains(key), "{key}");
    }
    // F/NAV records (data sources 258) for every satellite, and E5a-Q observation types.
    let nav = std::fs::read_to_string(out.join("nav.rnx")).expect("nav");
    assert_eq!(nav.lines().filter(|l| l.starts_with('E')).count(), 24);
    assert_eq!(nav.matches(" 2.580000000000E+02").count(), 24);
    let obs = std::fs::read_to_string(out.join("ant1.obs.rnx")).expect("obs");
    assert!(obs.contains("E    4 C5Q L5Q D5Q S5Q"), "{obs}");
}

/// Galileo E1 at the signal level, with made-up code tables (SkyForge does not ship the
/// ICD's, docs/signals.md): refused without tables, with tables that are not the ICD's
/// (unless the check is off) and below the CBOC bandwidth (13.6 Msps), each by name; then
/// its recording, the GNSS-SDR blocks for E1 with the 4 ms code and VEML spacings, I/NAV
/// records in nav.rnx, E1 observation truth on the pilot's code.
#[test]
fn synth_writes_an_e1_recording_its_inav_records_and_observation_truth() {
    let dir = tempfile::tempdir().expect("tempdir");
    let tables = dir.path().join("e1");
    std::fs::create_dir(&tables).expect("tables dir");
    support::made_up_e1_tables(&tables);
    let signal = |rate: &str| {
        format!(
            "\n[signal]\nsignals = [\"gps-l1ca\", \"bds-b1i\", \"gal-e1\"]\nsample_rate_hz = {rate}\nformat = \"ci8\"\ncn0_dbhz = 46.5\n"
        )
    };
    let (codes, check) = (
        "SKYFORGE_GALILEO_E1_CODES",
        "SKYFORGE_GALILEO_E1_CODES_CHECK",
    );
    let tables = tables.to_str().unwrap();
    for (rate, env, expect) in [
        ("15e6", [(codes, None), (check, None)], "does not ship"),
        (
            "15e6",
            [(codes, Some(tables)), (check, None)],
            "not the ICD's codes",
        ),
        (
            "4.092e6",
            [(codes, Some(tables)), (check, Some("off"))],
            "GAL E1",
        ),
    ] {
        let path = scenario(dir.path(), 1.0, &signal(rate));
        let refused = support::skyforge_with_env(&["synth", &path, "--out", "x"], dir.path(), &env);
        let text = support::text(&refused);
        assert!(
            !refused.status.success() && text.contains("signal.") && text.contains(expect),
            "{text}"
        );
    }
    let path = scenario(dir.path(), 1.0, &signal("15e6"));
    let out = dir.path().join("out");
    let made = support::skyforge_with_env(
        &["synth", &path, "--out", out.to_str().unwrap()],
        dir.path(),
        &[(codes, Some(tables)), (check, Some("off"))],
    );
    assert!(made.status.success(), "{}", support::text(&made));
    let data = std::fs::metadata(out.join("ant1.gal-e1.sigmf-data")).expect("E1 recording");
    // 1 s of complex 8-bit samples at 15 MHz.
    assert_eq!(data.len(), 2 * 15_000_000);
    let meta = std::fs::read_to_string(out.join("ant1.gal-e1.sigmf-meta")).expect("meta");
    assert!(meta.contains("1575420000"), "{meta}");
    let conf = std::fs::read_to_string(out.join("ant1.gal-e1.gnss-sdr.conf")).expect("conf");
    for key in [
        "Acquisition_1B.implementation=Galileo_E1_PCPS_Ambiguous_Acquisition",
        "Acquisition_1B.coherent_integration_time_ms=4",
        "Acquisition_1B.doppler_step=125",
        "Tracking_1B.enable_fll_pull_in=true",
        "Tracking_1B.implementation=Galileo_E1_DLL_PLL_VEML_Tracking",
        "Tracking_1B.very_early_late_space_chips=0.6",
        "Tracking_1B.track_pilot=true",
        "TelemetryDecoder_1B.implementation=Galileo_E1B_Telemetry_Decoder",
    ] {
        assert!(conf.contains(key), "{key}");
    }
    // I/NAV records (data sources 517, as SkyForge writes I/NAV: E1-B and E5b-I, clock
    // for E5b/E1) for every satellite.
    let nav = std::fs::read_to_string(out.join("nav.rnx")).expect("nav");
    assert_eq!(nav.lines().filter(|l| l.starts_with('E')).count(), 24);
    assert_eq!(nav.matches(" 5.170000000000E+02").count(), 24);
    let obs = std::fs::read_to_string(out.join("ant1.obs.rnx")).expect("obs");
    assert!(obs.contains("E    4 C1C L1C D1C S1C"), "{obs}");
}

/// The observation level draws Galileo E5a observables with the configured noise; the
/// calibrated model, measured on GPS and BeiDou only, refuses them by name.
#[test]
fn observation_level_galileo_has_the_configured_noise() {
    let dir = tempfile::tempdir().expect("tempdir");
    let signal = "\n[signal]\nsample_rate_hz = 20.46e6\nformat = \"ci8\"\ncn0_dbhz = 45.0\n";
    let at = |extra: &str| scenario(dir.path(), 120.0, &format!("{signal}{extra}"));
    support::assert_constant_observation_noise(dir.path(), at, "Galileo", "gal-e5a");
}

/// Galileo E1 as an observed-only signal beside the transmitted E5a: one RINEX line per
/// satellite with both, and the ionosphere (1/f^2) making E1's pseudorange shorter than
/// E5a's by (1 - (f5/f1)^2) of E5a's delay: between 0 and 10 m at the Klobuchar defaults.
#[test]
fn galileo_e1_observed_beside_e5a_carries_less_ionosphere() {
    let dir = tempfile::tempdir().expect("tempdir");
    let extra = "\n[signal]\nsample_rate_hz = 20.46e6\nformat = \"ci8\"\ncn0_dbhz = 45.0\n\n[observation]\nlevel = \"observation\"\nobserved_signals = [\"gal-e1\"]\n\n[observation.noise]\nmodel = \"constant\"\nphase_m = 0.0\ncode_m = 0.0\n";
    let path = scenario(dir.path(), 10.0, extra);
    let out = dir.path().join("out");
    support::skyforge_ok(&["run", &path, "--out", out.to_str().unwrap()], dir.path());
    let obs = std::fs::read_to_string(out.join("observations/ant1.obs.rnx")).expect("obs");
    assert!(
        obs.contains("E    8 C5Q L5Q D5Q S5Q C1C L1C D1C S1C"),
        "{obs}"
    );
    let body = obs.split("END OF HEADER").nth(1).unwrap_or("");
    let mut lines = 0;
    for line in body.lines().filter(|l| l.starts_with('E')) {
        let value = |k: usize| -> f64 {
            line.get(3 + 16 * k..3 + 16 * k + 14)
                .and_then(|v| v.trim().parse().ok())
                .unwrap_or(f64::NAN)
        };
        let (c5, c1) = (value(0), value(4));
        let d = c5 - c1;
        assert!(d > 0.0 && d < 10.0, "{line}: C5Q - C1C = {d} m");
        lines += 1;
    }
    assert!(lines > 20, "{lines} Galileo lines");
}

/// An observed-only signal follows its own phase centre (`[[antennas.phase_centres]]`):
/// with E1's 10 cm above the reference point and E5a's there, E5a's observables stay as
/// they were and E1's code and carrier both shorten by 0.1 m x sin(elevation), between 0
/// and 0.1 m (to the RINEX file's millimetres), the same in both.
#[test]
fn an_observed_signal_follows_its_own_phase_centre() {
    let dir = tempfile::tempdir().expect("tempdir");
    let extra = "\n[signal]\nsample_rate_hz = 20.46e6\nformat = \"ci8\"\ncn0_dbhz = 45.0\n\n[observation]\nlevel = \"observation\"\nobserved_signals = [\"gal-e1\"]\n\n[observation.noise]\nmodel = \"constant\"\nphase_m = 0.0\ncode_m = 0.0\n";
    let centre = "\n[[antennas.phase_centres]]\nsignal = \"gal-e1\"\npco_m = [0.0, 0.0, 0.1]\n";
    let mut bodies = Vec::new();
    for (name, text) in [
        ("plain", extra.to_owned()),
        ("centre", format!("{extra}{centre}")),
    ] {
        let path = scenario(dir.path(), 10.0, &text);
        let renamed = dir.path().join(format!("{name}.toml"));
        std::fs::rename(&path, &renamed).expect("rename");
        let out = dir.path().join(name);
        let args = [
            "run",
            renamed.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ];
        support::skyforge_ok(&args, dir.path());
        let obs = std::fs::read_to_string(out.join("observations/ant1.obs.rnx")).expect("obs");
        bodies.push(obs.split("END OF HEADER").nth(1).unwrap_or("").to_owned());
    }
    let value = |line: &str, k: usize| -> f64 {
        line.get(3 + 16 * k..3 + 16 * k + 14)
            .and_then(|v| v.trim().parse().ok())
            .unwrap_or(f64::NAN)
    };
    let lambda_e1 = skyforge_gnss::signal::Signal::GalE1.wavelength_m();
    let pairs: Vec<(&str, &str)> = (bodies[0].lines().zip(bodies[1].lines()))
        .filter(|(a, _)| a.starts_with('E'))
        .collect();
    assert!(pairs.len() > 20, "{} Galileo lines", pairs.len());
    for (plain, centre) in pairs {
        assert_eq!(plain[..3 + 16 * 4], centre[..3 + 16 * 4], "E5a changed");
        let code = value(centre, 4) - value(plain, 4);
        let phase = (value(centre, 5) - value(plain, 5)) * lambda_e1;
        // F14.3 values: each rounded to a millimetre.
        assert!(
            (-0.101..0.0).contains(&code),
            "{centre}: C1C moved {code} m"
        );
        assert!(
            (phase - code).abs() < 2e-3,
            "{centre}: L1C moved {phase} m, C1C {code} m"
        );
    }
}

/// GST - GPST (`[gnss.galileo] gst_gps_ns`): Galileo's satellite clocks run that far ahead
/// of GPST, so every Galileo pseudorange and carrier phase shortens by c x 100 ns =
/// 29.979 m against the same run without it, GPS's stay as they were, and the navigation
/// file broadcasts the offset (`GAGP`, A0G = 1e-7 s) as the messages do.
#[test]
fn gst_runs_ahead_of_gpst_by_the_offset_galileo_broadcasts() {
    let dir = tempfile::tempdir().expect("tempdir");
    let extra = "\n[signal]\nsample_rate_hz = 20.46e6\nformat = \"ci8\"\ncn0_dbhz = 45.0\n\n[observation]\nlevel = \"observation\"\n\n[observation.noise]\nmodel = \"constant\"\nphase_m = 0.0\ncode_m = 0.0\n";
    let run = |name: &str, galileo: &str| {
        let mut text = support::bundled_edited(
            "ground-static",
            &[
                (
                    "[platform.ground]",
                    &format!("{galileo}\n\n[platform.ground]"),
                ),
                ("duration_s = 3600.0", "duration_s = 10.0"),
            ],
        );
        text.push_str(extra);
        let path = support::write_scenario(dir.path(), &format!("{name}.toml"), &text);
        let out = dir.path().join(name);
        support::skyforge_ok(&["run", &path, "--out", out.to_str().unwrap()], dir.path());
        let obs = std::fs::read_to_string(out.join("observations/ant1.obs.rnx")).expect("obs");
        let nav = std::fs::read_to_string(out.join("nav.rnx")).expect("nav");
        (obs, nav)
    };
    let (base, base_nav) = run("base", "[gnss.galileo]");
    let (ahead, nav) = run("ahead", "[gnss.galileo]\ngst_gps_ns = 100.0");
    let gagp = nav.lines().find(|l| l.ends_with("TIME SYSTEM CORR"));
    assert!(
        gagp.is_some_and(|l| l.starts_with("GAGP  1.0000000000E-07 0.000000000E+00")),
        "{gagp:?}"
    );
    assert!(base_nav.contains("GAGP  0.0000000000E+00"), "{base_nav}");
    let shift_m = -299_792_458.0 * 100e-9;
    let lambda_m = 299_792_458.0 / 1_176.45e6;
    let (mut galileo, mut gps) = (0, 0);
    let body = |obs: &str| obs.split("END OF HEADER").nth(1).unwrap_or("").to_string();
    let (base, ahead) = (body(&base), body(&ahead));
    for (a, b) in base.lines().zip(ahead.lines()) {
        let value = |line: &str, k: usize| -> f64 {
            line.get(3 + 16 * k..3 + 16 * k + 14)
                .and_then(|v| v.trim().parse().ok())
                .unwrap_or(f64::NAN)
        };
        if a.starts_with('E') {
            let code = value(b, 0) - value(a, 0);
            let phase_m = (value(b, 1) - value(a, 1)) * lambda_m;
            assert!((code - shift_m).abs() < 2e-3, "{a}\n{b}: code {code} m");
            assert!(
                (phase_m - shift_m).abs() < 2e-3,
                "{a}\n{b}: phase {phase_m} m"
            );
            galileo += 1;
        } else if a.starts_with('G') {
            assert_eq!(a, b);
            gps += 1;
        }
    }
    assert!(
        galileo > 20 && gps > 20,
        "{galileo} Galileo, {gps} GPS lines"
    );
}
