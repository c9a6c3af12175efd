//! `skyforge monitor run`, `monitor calibrate` and `validate monitor` on the bundled
//! integrity-lab scenario at the observation level: a cycle slip at one station is
//! detected, isolated and scored; bad input gets one located error and writes nothing.

mod support;

use std::path::Path;
use support::{dataset, skyforge, skyforge_ok, text};

/// The lab scenario with `events` appended, 1800 s, written to `dir/lab.toml`.
fn lab(dir: &Path, events: &str) -> String {
    let base = skyforge_ok(&["scenarios", "show", "integrity-lab"], dir);
    let path = dir.join("lab.toml");
    std::fs::write(&path, base + events).unwrap();
    path.display().to_string()
}

const SLIP: &str = "\n[[errors.events]]\nkind = \"phase-jump\"\nantenna = \"C\"\n\
                    satellite = \"C03\"\nstart_s = 500.0\nend_s = 1800.0\nvalue = 100.0\n";

fn files(sim: &Path) -> Vec<String> {
    ["A", "B", "C", "D"]
        .iter()
        .map(|s| {
            sim.join(format!("observations/{s}.obs.rnx"))
                .display()
                .to_string()
        })
        .collect()
}

#[test]
fn a_slip_at_one_station_is_detected_isolated_and_scored() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let scenario = lab(d, SLIP);
    skyforge_ok(&["run", &scenario, "--out", "sim"], d);
    let sim = d.join("sim");
    let mut args = vec!["monitor", "run"];
    let f = files(&sim);
    args.extend(f.iter().map(String::as_str));
    args.extend(["--nav", "sim/nav.rnx", "--out", "mon"]);
    let printed = skyforge_ok(&args, d);
    assert!(printed.contains("stations   A, B, C, D"), "{printed}");
    // Every alarm is on the slipped satellite, from the first epoch after the slip.
    let summary = support::json_file(&d.join("mon/summary.json"));
    let alarms = summary["alarms"].as_array().unwrap();
    assert!(!alarms.is_empty());
    for a in alarms {
        assert_eq!(a["sat"], "C03", "{a}");
        assert!(a["first_t_s"].as_f64().unwrap() >= 500.0, "{a}");
    }
    let carrier_c = alarms
        .iter()
        .find(|a| a["station"] == "C" && a["statistic"] == "carrier")
        .expect("carrier alarm at C");
    assert!(carrier_c["first_t_s"].as_f64().unwrap() <= 501.0);
    // monitor.csv and monitor.h5 hold the same rows.
    let csv = std::fs::read_to_string(d.join("mon/monitor.csv")).unwrap();
    let rows = csv.lines().count() - 1;
    assert!(csv.starts_with("time_gpst,t_s,sat,signal,station,elevation_deg,track_age_s,code,"));
    let h5 = hdf5::File::open(d.join("mon/monitor.h5")).unwrap();
    assert_eq!(dataset::<f64>(&h5, "t_s").len(), rows);
    assert_eq!(dataset::<f64>(&h5, "b").len(), 4 * rows);
    // The observation level flags no loss of lock on continuous tracks.
    assert!(dataset::<u8>(&h5, "loss_of_lock").iter().all(|&f| f == 0));
    assert_eq!(summary["monitored"].as_u64().unwrap() as usize, rows);
    // validate monitor: detected at once, isolated at C, no false alarm.
    let (out, score) = support::validate_monitor(d);
    assert!(out.contains("phase-jump"), "{out}");
    let e = &score["events"][0];
    assert_eq!(e["detected"], true, "{score}");
    assert!(e["delay_s"].as_f64().unwrap() <= 1.0, "{score}");
    assert_eq!(e["first_station"], "C");
    assert_eq!(e["isolated"], true);
    assert_eq!(score["false_alarms"], 0, "{score}");
}

/// The fault-free lab (`dir/lab.toml`, returned) and its first 400 s
/// (`dir/short.toml`), calibrated by `monitor calibrate` on `seeds` seeds into
/// `dir/cal/monitor.toml`.
fn calibrated_short_lab(d: &Path, seeds: &str) -> String {
    let scenario = lab(d, "");
    let short = std::fs::read_to_string(&scenario)
        .unwrap()
        .replace("duration_s = 1800.0", "duration_s = 400.0");
    std::fs::write(d.join("short.toml"), short).unwrap();
    skyforge_ok(
        &[
            "monitor",
            "calibrate",
            "short.toml",
            "--seeds",
            seeds,
            "--out",
            "cal",
        ],
        d,
    );
    scenario
}

#[test]
fn calibrate_writes_a_configuration_that_run_reads() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let scenario = calibrated_short_lab(d, "2");
    let config = std::fs::read_to_string(d.join("cal/monitor.toml")).unwrap();
    assert!(config.contains("[thresholds.sigma.bds-b1i]"), "{config}");
    assert!(config.contains("[thresholds.sigma.gps-l1ca]"));
    // Fault events are refused: they would count as noise.
    std::fs::write(
        d.join("lab-slip.toml"),
        std::fs::read_to_string(&scenario).unwrap() + SLIP,
    )
    .unwrap();
    let o = skyforge(&["monitor", "calibrate", "lab-slip.toml", "--out", "x"], d);
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(text(&o).contains("fault events"), "{}", text(&o));
    assert!(!d.join("x").exists());
    // The calibrated configuration runs.
    skyforge_ok(&["run", "short.toml", "--out", "sim"], d);
    let mut args = vec!["monitor", "run"];
    let f = files(&d.join("sim"));
    args.extend(f.iter().map(String::as_str));
    args.extend([
        "--nav",
        "sim/nav.rnx",
        "--config",
        "cal/monitor.toml",
        "--out",
        "mon",
    ]);
    skyforge_ok(&args, d);
}

/// The sigma tables of a configuration's text: (signal tag, column key) -> values.
fn sigma_columns(config: &str) -> std::collections::BTreeMap<(String, String), Vec<f64>> {
    let value: toml::Table = toml::from_str(config).unwrap();
    let mut out = std::collections::BTreeMap::new();
    for (tag, table) in value["thresholds"]["sigma"].as_table().unwrap() {
        for (key, column) in table.as_table().unwrap() {
            let values = column
                .as_array()
                .unwrap()
                .iter()
                .map(|v| v.as_float().unwrap())
                .collect();
            out.insert((tag.clone(), key.clone()), values);
        }
    }
    out
}

#[test]
fn calibrate_files_measures_what_calibrate_measures_on_the_same_run() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    calibrated_short_lab(d, "1");
    skyforge_ok(&["run", "short.toml", "--out", "sim"], d);
    let f = files(&d.join("sim"));
    // `monitor ACTION` on the four files with `extra` arguments.
    let on_files = |action: &str, extra: &[&str]| {
        let mut args = vec!["monitor", action];
        args.extend(f.iter().map(String::as_str));
        args.extend(["--nav", "sim/nav.rnx"]);
        args.extend(extra);
        skyforge_ok(&args, d)
    };
    on_files("calibrate-files", &["--out", "calf"]);
    // The same run (scenario and seed), once in memory and once through its RINEX files:
    // the same B values but for the files' rounding, so the same sigma tables.
    let in_memory = sigma_columns(&std::fs::read_to_string(d.join("cal/monitor.toml")).unwrap());
    let from_files = sigma_columns(&std::fs::read_to_string(d.join("calf/monitor.toml")).unwrap());
    assert_eq!(
        in_memory.keys().collect::<Vec<_>>(),
        from_files.keys().collect::<Vec<_>>()
    );
    for (key, a) in &in_memory {
        let b = &from_files[key];
        assert_eq!(a.len(), b.len(), "{key:?}");
        for (x, y) in a.iter().zip(b) {
            assert!((x - y).abs() <= 0.02 * x, "{key:?}: {a:?} against {b:?}");
        }
    }
    // A base configuration's stations (here the files' own positions) and false-alarm
    // probability are kept, and the result runs.
    let surveyed = support::with_stations(
        &std::fs::read_to_string(d.join("calf/monitor.toml")).unwrap(),
        &support::surveyed_stations(&d.join("sim/observations")),
    );
    let base = surveyed.replace("false_alarm = 0.0000001", "false_alarm = 0.00001");
    assert_ne!(base, surveyed);
    std::fs::write(d.join("base.toml"), base).unwrap();
    on_files(
        "calibrate-files",
        &["--config", "base.toml", "--out", "calg"],
    );
    let written = std::fs::read_to_string(d.join("calg/monitor.toml")).unwrap();
    assert_eq!(written.matches("[[stations]]").count(), 4, "{written}");
    assert!(written.contains("false_alarm = 0.00001"), "{written}");
    on_files("run", &["--config", "calg/monitor.toml", "--out", "mon"]);
    // With the GEOs apart: BeiDou gets a GEO table, GPS none; the other BeiDou satellites'
    // table leaves the GEOs out; the result runs.
    on_files("calibrate-files", &["--geo-apart", "--out", "calh"]);
    let apart: toml::Table =
        toml::from_str(&std::fs::read_to_string(d.join("calh/monitor.toml")).unwrap()).unwrap();
    let geo = apart["thresholds"]["sigma_geo"].as_table().unwrap();
    assert_eq!(geo.keys().collect::<Vec<_>>(), ["bds-b1i"], "{apart}");
    let code_of = |t: &toml::Value| t["code_m"].clone();
    assert_ne!(
        code_of(&apart["thresholds"]["sigma"]["bds-b1i"]),
        code_of(&geo["bds-b1i"])
    );
    let together: toml::Table =
        toml::from_str(&std::fs::read_to_string(d.join("calf/monitor.toml")).unwrap()).unwrap();
    assert_ne!(
        code_of(&apart["thresholds"]["sigma"]["bds-b1i"]),
        code_of(&together["thresholds"]["sigma"]["bds-b1i"])
    );
    assert_eq!(
        apart["thresholds"]["sigma"]["gps-l1ca"],
        together["thresholds"]["sigma"]["gps-l1ca"]
    );
    on_files(
        "run",
        &["--config", "calh/monitor.toml", "--out", "mon-apart"],
    );
}

#[test]
fn bad_input_gets_one_error_and_nothing_written() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let scenario = lab(d, "");
    let text_of = std::fs::read_to_string(&scenario)
        .unwrap()
        .replace("duration_s = 1800.0", "duration_s = 30.0");
    std::fs::write(&scenario, text_of).unwrap();
    skyforge_ok(&["run", &scenario, "--out", "sim"], d);
    let f = files(&d.join("sim"));
    let run = |extra: &[&str]| {
        let mut args = vec!["monitor", "run"];
        args.extend(f.iter().map(String::as_str));
        args.extend(["--nav", "sim/nav.rnx", "--out", "mon"]);
        args.extend(extra);
        skyforge(&args, d)
    };
    // A configuration with an unknown key, a bad threshold, a station count that does
    // not match the files.
    for (config, says) in [
        ("smoothing_s = 100.0\nbogus = 1\n", "bogus"),
        (
            "[thresholds]\nfalse_alarm = 2.0\nsmoothed_code_m = 0.5\n[thresholds.sigma.gps-l1ca]\nelevation_deg = [10.0]\ncode_m = [1.0]\nsmoothed_code_m = [1.0]\ncarrier_cycles = [1.0]\ndivergence_mps = [1.0]\n",
            "false_alarm = 2",
        ),
        (
            "[[stations]]\nname = \"A\"\nposition_ecef_m = [-2267000.0, 5009000.0, 3221000.0]\n[thresholds]\nfalse_alarm = 1e-7\nsmoothed_code_m = 0.5\n[thresholds.sigma.gps-l1ca]\nelevation_deg = [10.0]\ncode_m = [1.0]\nsmoothed_code_m = [1.0]\ncarrier_cycles = [1.0]\ndivergence_mps = [1.0]\n",
            "4 observation files but 1 [[stations]]",
        ),
    ] {
        std::fs::write(d.join("bad.toml"), config).unwrap();
        let o = run(&["--config", "bad.toml"]);
        assert_eq!(o.status.code(), Some(2), "{}", text(&o));
        assert!(text(&o).contains(says), "{config}: {}", text(&o));
        assert!(!d.join("mon").exists());
    }
    // A file without APPROX POSITION XYZ and no positions in the configuration.
    let no_pos: String = std::fs::read_to_string(&f[0])
        .unwrap()
        .lines()
        .filter(|l| !l.contains("APPROX POSITION XYZ"))
        .map(|l| format!("{l}\n"))
        .collect();
    std::fs::write(d.join("nopos.obs.rnx"), no_pos).unwrap();
    let mut args = vec!["monitor", "run", "nopos.obs.rnx"];
    args.extend(f[1..].iter().map(String::as_str));
    args.extend(["--nav", "sim/nav.rnx", "--out", "mon"]);
    let o = skyforge(&args, d);
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(
        text(&o).contains("nopos.obs.rnx: no APPROX POSITION XYZ"),
        "{}",
        text(&o)
    );
    assert!(!d.join("mon").exists());
    // validate monitor on a directory without truth.h5.
    let o = skyforge(
        &["validate", "monitor", "--truth", "mon", "--monitor", "sim"],
        d,
    );
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(text(&o).contains("truth.h5"), "{}", text(&o));
    // calibrate-files on 30 s: no track is old enough to test the divergence.
    let mut args = vec!["monitor", "calibrate-files"];
    args.extend(f.iter().map(String::as_str));
    args.extend(["--nav", "sim/nav.rnx", "--out", "cal"]);
    let o = skyforge(&args, d);
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(
        text(&o).contains("cannot calibrate") && text(&o).contains("300 s old"),
        "{}",
        text(&o)
    );
    assert!(!d.join("cal").exists());
}

/// The 30 s fault-free lab run into `dir/NAME` from `start`; the scenario file is removed.
fn short_lab_run(d: &Path, name: &str, start: &str) {
    let scenario = lab(d, "");
    let text = std::fs::read_to_string(&scenario)
        .unwrap()
        .replace("duration_s = 1800.0", "duration_s = 30.0")
        .replace("2023-03-12T00:00:00 GPST", start);
    std::fs::write(&scenario, text).unwrap();
    skyforge_ok(&["run", &scenario, "--out", name], d);
    std::fs::remove_file(scenario).unwrap();
}

/// `f`'s text with its `APPROX POSITION XYZ` record replaced by `x y z`, written to `to`.
fn with_position(f: &str, to: &Path, xyz: [&str; 3]) -> String {
    let text: String = std::fs::read_to_string(f)
        .unwrap()
        .lines()
        .map(|l| {
            if l.ends_with("APPROX POSITION XYZ") {
                format!(
                    "{:>14}{:>14}{:>14}{:18}APPROX POSITION XYZ\n",
                    xyz[0], xyz[1], xyz[2], ""
                )
            } else {
                format!("{l}\n")
            }
        })
        .collect();
    std::fs::write(to, text).unwrap();
    to.display().to_string()
}

/// Issue #33 item 8: a monitor run that could monitor nothing (a navigation file of
/// another day or without records, stations of different days, positions off the ground,
/// two files of one station name, a common point at the Earth's centre) is refused with
/// the file and the reason, never reported as "alarms 0"; a run monitors and says how
/// much; `validate monitor` refuses another run's truth.
#[test]
fn a_monitor_that_can_monitor_nothing_is_refused_with_the_reason() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    short_lab_run(d, "sim", "2023-03-12T00:00:00 GPST");
    short_lab_run(d, "later", "2023-03-14T00:00:00 GPST");
    let f = files(&d.join("sim"));
    let g = files(&d.join("later"));
    let refused = |files: &[&str], extra: &[&str], says: &[&str]| {
        let mut args = vec!["monitor", "run"];
        args.extend(files);
        args.extend(["--out", "mon"]);
        args.extend(extra);
        let o = skyforge(&args, d);
        let out = text(&o);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {out}");
        assert_eq!(out.matches("error:").count(), 1, "{args:?}: {out}");
        for s in says {
            assert!(out.contains(s), "{args:?}: missing {s:?} in {out}");
        }
        assert!(!d.join("mon").exists(), "{args:?}");
    };
    let sim: Vec<&str> = f.iter().map(String::as_str).collect();
    // A navigation file of another day: SkyForge's own are valid at any time (fit
    // interval 277 778 h), so give them the usual 4 h; no ephemeris is valid two days on.
    let nav = std::fs::read_to_string(d.join("sim/nav.rnx")).unwrap();
    let four_hours = nav.replace("2.777777777778E+05", "4.000000000000E+00");
    assert_ne!(four_hours, nav);
    std::fs::write(d.join("day.rnx"), four_hours).unwrap();
    let later: Vec<&str> = g.iter().map(String::as_str).collect();
    refused(
        &later,
        &["--nav", "day.rnx"],
        &[
            "monitored no satellite in 30 epochs of ",
            "satellite-epochs without an ephemeris in day.rnx valid then",
        ],
    );
    // A navigation file with its header only.
    let header = &nav[..nav.find("END OF HEADER").unwrap() + "END OF HEADER\n".len()];
    std::fs::write(d.join("empty.rnx"), header).unwrap();
    refused(
        &sim,
        &["--nav", "empty.rnx"],
        &["empty.rnx: no GPS or BeiDou ephemeris record"],
    );
    // A station of another day.
    let mixed = [sim[0], sim[1], sim[2], g[3].as_str()];
    refused(
        &mixed,
        &["--nav", "sim/nav.rnx"],
        &[
            "later/observations/D.obs.rnx: no epoch in common with",
            "A.obs.rnx",
        ],
    );
    // Positions at 1e13 m and at the Earth's centre.
    for (xyz, shown) in [
        (["1e13", "0.0", "0.0"], "[1e13, 0, 0] (radius 1e13 m)"),
        (["0.0", "0.0", "0.0"], "[0, 0, 0] (radius 0 m)"),
    ] {
        let moved = with_position(&f[1], &d.join("B.obs.rnx"), xyz);
        refused(
            &[sim[0], &moved, sim[2], sim[3]],
            &["--nav", "sim/nav.rnx"],
            &[
                &format!("B.obs.rnx: APPROX POSITION XYZ = {shown}"),
                "must lie at a radius in [6355000, 6480000] m",
            ],
        );
    }
    // Two files of one station name.
    std::fs::create_dir(d.join("copy")).unwrap();
    std::fs::copy(&f[0], d.join("copy/A.obs.rnx")).unwrap();
    refused(
        &[sim[0], "copy/A.obs.rnx", sim[2], sim[3]],
        &["--nav", "sim/nav.rnx"],
        &[
            "copy/A.obs.rnx: station name \"A\" is also",
            "sim/observations/A.obs.rnx",
        ],
    );
    // A common point at the Earth's centre.
    let bundled =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenarios/calibration/monitor-lab.toml");
    let config = std::fs::read_to_string(bundled).unwrap();
    std::fs::write(
        d.join("centre.toml"),
        format!("common_point_ecef_m = [0.0, 0.0, 0.0]\n{config}"),
    )
    .unwrap();
    refused(
        &sim,
        &["--nav", "sim/nav.rnx", "--config", "centre.toml"],
        &["centre.toml: common_point_ecef_m = [0, 0, 0] (radius 0 m): must lie at a radius"],
    );
    // A run that monitors says how much it monitored.
    let mut args = vec!["monitor", "run"];
    args.extend(&sim);
    args.extend(["--nav", "sim/nav.rnx", "--out", "mon"]);
    let printed = skyforge_ok(&args, d);
    assert!(
        printed.contains("monitored  30 of 30 epochs; satellites "),
        "{printed}"
    );
    let summary = support::json_file(&d.join("mon/summary.json"));
    assert_eq!(summary["epochs_monitored"], 30, "{summary}");
    assert!(
        summary["unmonitored"]["below_mask"].as_u64().is_some(),
        "{summary}"
    );
    // validate monitor against the truth of another run (two days later).
    let o = skyforge(
        &[
            "validate",
            "monitor",
            "--truth",
            "later",
            "--monitor",
            "mon",
        ],
        d,
    );
    let out = text(&o);
    assert_eq!(o.status.code(), Some(2), "{out}");
    assert!(
        out.contains("mon/monitor.csv: epochs from -172800.0 s")
            && out.contains("the monitor watched another run"),
        "{out}"
    );
}

/// Issue #33 (15): `monitor calibrate` said "no B value" without the reason. With every
/// station but the first blind (a 0.5 deg field of view), no satellite is seen by two
/// stations, and the refusal says so, with the counts.
#[test]
fn a_calibration_without_b_values_says_why() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    let path = support::short_scenario(d, "integrity-lab", 60);
    let text_of = std::fs::read_to_string(&path).unwrap();
    let mut parts: Vec<String> = text_of.split("[[antennas]]").map(String::from).collect();
    for p in parts.iter_mut().skip(2) {
        *p = p.replacen("fov_half_angle_deg = 90.0", "fov_half_angle_deg = 0.5", 1);
    }
    let blind = parts.join("[[antennas]]");
    assert_ne!(blind, text_of);
    std::fs::write(&path, blind).unwrap();
    let o = skyforge(
        &[
            "monitor",
            "calibrate",
            "short.toml",
            "--out",
            "x",
            "--seeds",
            "2",
        ],
        d,
    );
    let said = text(&o);
    assert_eq!(o.status.code(), Some(2), "{said}");
    assert!(
        said.contains("the calibration runs (2 seeds, 120 epochs) gave no B value:")
            && said
                .contains("satellite-epochs observed (code and phase) by fewer than two stations"),
        "{said}"
    );
    assert!(!d.join("x").exists());
}
