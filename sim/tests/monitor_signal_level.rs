//! The B-value monitor at the signal level: the integrity-lab set-up synthesised (BeiDou
//! B1I I/Q for the four receivers), received by the bundled receiver, monitored and
//! scored. A code step (the paper's multipath) and a quarter-cycle carrier jump at
//! station C must be detected and isolated at C, by the monitor or by the receiver's own
//! loss-of-lock flag. (A jump by whole cycles leaves a synthesised carrier unchanged: a
//! PLL cannot see it; docs/integrity.md.) The stations' positions are given as surveyed
//! (the truth's RINEX headers), as reference stations are: the receivers' own first fixes
//! are metres off, and over minutes that error turns into carrier B drifts of centimetres.
//! Over longer spans the GEOs' code errors wander (their codes cross-correlate), beyond
//! thresholds calibrated at the observation level; thresholds calibrated on the
//! receivers' own fault-free files hold (the second test).

mod support;

use std::path::Path;
use support::skyforge_ok;

/// The bundled monitor configuration with the surveyed station positions: the truth
/// RINEX headers' APPROX POSITION XYZ in `sim`.
fn surveyed(sim: &Path) -> String {
    support::with_stations(
        skyforge_scenarios::BUNDLED_MONITOR_CONFIG,
        &support::surveyed_stations(sim),
    )
}

/// The lab at the signal level, BeiDou only, `duration_s` long from `start`, on `seed`,
/// with `events` appended.
fn signal_lab(d: &Path, duration_s: u32, start: &str, seed: u64, events: &str) -> String {
    let mut scenario = skyforge_ok(&["scenarios", "show", "integrity-lab"], d);
    for (from, to) in [
        (
            "duration_s = 1800.0",
            format!("duration_s = {duration_s}.0"),
        ),
        (
            "start = \"2023-03-12T00:00:00 GPST\"",
            format!("start = \"{start}\""),
        ),
        ("seed = 2002", format!("seed = {seed}")),
        (
            "[gnss.gps]\nsource",
            "[gnss.gps]\nenabled = false\nsource".to_string(),
        ),
        ("level = \"observation\"", "level = \"signal\"".to_string()),
    ] {
        assert!(scenario.contains(from), "the bundled lab has no {from:?}");
        scenario = scenario.replace(from, &to);
    }
    scenario + events
}

/// `monitor run` (or with `action` = "calibrate-files", the calibration) of the four
/// receivers' files in `rx` with the ephemerides of `sim`, into `out`.
fn monitor(d: &Path, action: &str, rx: &str, sim: &str, config: &str, out: &str) -> String {
    let obs: Vec<String> = ["A", "B", "C", "D"]
        .iter()
        .map(|s| format!("{rx}/{s}.obs.rnx"))
        .collect();
    let nav = format!("{sim}/nav.rnx");
    let mut args = vec!["monitor", action];
    args.extend(obs.iter().map(String::as_str));
    args.extend(["--nav", &nav, "--config", config, "--out", out]);
    skyforge_ok(&args, d)
}

#[test]
#[ignore = "acceptance tier (minutes, 4 GB of I/Q): cargo test -p skyforge-sim --test monitor_signal_level -- --ignored"]
fn a_code_step_and_a_carrier_jump_at_one_station_are_detected_at_the_signal_level() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    // assumed: 150 s (the smoothed code is tested from 100 s), BeiDou only (half the
    // samples), faults from 110 s; chosen before the first run.
    let scenario = signal_lab(
        d,
        150,
        "2023-03-12T00:00:00 GPST",
        2002,
        "\n[[errors.events]]\nkind = \"code-step\"\nantenna = \"C\"\nsatellite = \"C03\"\n\
         start_s = 110.0\nend_s = 115.0\nvalue = 30.0\n\
         \n[[errors.events]]\nkind = \"phase-jump\"\nantenna = \"C\"\nsatellite = \"C01\"\n\
         start_s = 110.0\nend_s = 150.0\nvalue = 0.25\n",
    );
    std::fs::write(d.join("lab.toml"), &scenario).unwrap();
    skyforge_ok(&["synth", "lab.toml", "--out", "sim"], d);
    let metas: Vec<String> = ["A", "B", "C", "D"]
        .iter()
        .map(|s| format!("sim/{s}.bds-b1i.sigmf-meta"))
        .collect();
    let mut args = vec!["receive"];
    args.extend(metas.iter().map(String::as_str));
    args.extend(["--assist", "sim/nav.rnx", "--out", "rx"]);
    skyforge_ok(&args, d);
    for s in ["A", "B", "C", "D"] {
        std::fs::remove_file(d.join(format!("sim/{s}.bds-b1i.sigmf-data"))).unwrap();
    }
    std::fs::write(d.join("monitor.toml"), surveyed(&d.join("sim"))).unwrap();
    eprintln!("{}", monitor(d, "run", "rx", "sim", "monitor.toml", "mon"));
    let (scored, score) = support::validate_monitor(d);
    eprintln!("{scored}");
    // Each fault: a monitor alarm isolating C, or C's receiver flagging a loss of lock,
    // within 5 s.
    for e in score["events"].as_array().unwrap() {
        let by_monitor =
            e["detected"] == true && e["isolated"] == true && e["delay_s"].as_f64().unwrap() <= 5.0;
        let by_receiver =
            e["lock_lost_station"] == "C" && e["lock_lost_s"].as_f64().unwrap() <= 5.0;
        assert!(by_monitor || by_receiver, "{e}");
    }
    assert_eq!(
        score["events"][0]["detected"], true,
        "the code step: {score}"
    );
    assert_eq!(score["false_alarms"], 0, "{score}");
}

/// Thresholds calibrated at the signal level (the fault-free 600 s before, another seed,
/// `monitor calibrate-files`) hold on the lab's run, where the bundled observation-level
/// ones raise false alarms on the GEOs (their code errors wander by metres over minutes:
/// docs/integrity.md), and the paper's multipath is still detected and isolated at C.
/// (The scoring counts any alarm on C03 from the step to 600 s after it, the end of this
/// run, as the step's, so "no false alarm" speaks of the other satellites. The last
/// assertion records that observation-level thresholds do not hold here: should the
/// receiver's GEO errors shrink enough for it to fail, docs/integrity.md needs a rewrite.)
#[test]
#[ignore = "acceptance tier (minutes): cargo test -p skyforge-sim --test monitor_signal_level -- --ignored"]
fn signal_level_thresholds_hold_where_observation_level_ones_raise_false_alarms() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    // assumed, chosen before the first run: 600 s each; calibration the 600 s before the
    // lab's start on seed 2003; the paper's 30 m multipath on C03 at C from 400 s.
    let calibration = signal_lab(d, 600, "2023-03-11T23:50:00 GPST", 2003, "");
    std::fs::write(d.join("calibration.toml"), calibration).unwrap();
    skyforge_ok(
        &["synth", "calibration.toml", "--out", "cal", "--receive"],
        d,
    );
    std::fs::write(d.join("base.toml"), surveyed(&d.join("cal"))).unwrap();
    monitor(
        d,
        "calibrate-files",
        "cal/receive",
        "cal",
        "base.toml",
        "thresholds",
    );
    let lab = signal_lab(
        d,
        600,
        "2023-03-12T00:00:00 GPST",
        2002,
        "\n[[errors.events]]\nkind = \"code-step\"\nantenna = \"C\"\nsatellite = \"C03\"\n\
         start_s = 400.0\nend_s = 405.0\nvalue = 30.0\n",
    );
    std::fs::write(d.join("lab.toml"), lab).unwrap();
    skyforge_ok(&["synth", "lab.toml", "--out", "sim", "--receive"], d);
    eprintln!(
        "{}",
        monitor(
            d,
            "run",
            "sim/receive",
            "sim",
            "thresholds/monitor.toml",
            "mon"
        )
    );
    let (scored, score) = support::validate_monitor(d);
    eprintln!("{scored}");
    let e = &score["events"][0];
    assert_eq!(e["detected"], true, "{score}");
    assert_eq!(e["isolated"], true, "{score}");
    assert!(e["delay_s"].as_f64().unwrap() <= 5.0, "{score}");
    assert_eq!(score["false_alarms"], 0, "{score}");
    // The same files against the observation-level thresholds.
    std::fs::write(d.join("bundled.toml"), surveyed(&d.join("sim"))).unwrap();
    monitor(
        d,
        "run",
        "sim/receive",
        "sim",
        "bundled.toml",
        "mon-bundled",
    );
    let (printed, bundled) = support::validate_monitor_of(d, "mon-bundled", "score-bundled.json");
    eprintln!("{printed}");
    assert!(
        bundled["false_alarms"].as_u64().unwrap() > 0,
        "observation-level thresholds: {bundled}"
    );
}
