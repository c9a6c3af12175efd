//! The B-value monitor at the signal level: the integrity-lab set-up synthesised (BeiDou
//! B1I I/Q for the four receivers), received by the bundled receiver, monitored and
//! scored. A code step (the paper's multipath) and a quarter-cycle carrier jump at
//! station C must be detected and isolated at C, by the monitor or by the receiver's own
//! loss-of-lock flag. (A jump by whole cycles leaves a synthesised carrier unchanged: a
//! PLL cannot see it; docs/integrity.md.) The stations' positions are given as surveyed
//! (the truth's RINEX headers), as reference stations are: the receivers' own first fixes
//! are metres off, and over minutes that error turns into carrier B drifts of centimetres.

mod support;

use support::skyforge_ok;

#[test]
#[ignore = "acceptance tier (minutes, 4 GB of I/Q): cargo test -p skyforge-sim --test monitor_signal_level -- --ignored"]
fn a_code_step_and_a_carrier_jump_at_one_station_are_detected_at_the_signal_level() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    let lab = skyforge_ok(&["scenarios", "show", "integrity-lab"], d);
    // assumed: 150 s (the smoothed code is tested from 100 s), BeiDou only (half the
    // samples), faults from 110 s; chosen before the first run.
    let scenario = lab
        .replace("duration_s = 1800.0", "duration_s = 150.0")
        .replace("[gnss.gps]\nsource", "[gnss.gps]\nenabled = false\nsource")
        .replace("level = \"observation\"", "level = \"signal\"")
        + "\n[[errors.events]]\nkind = \"code-step\"\nantenna = \"C\"\nsatellite = \"C03\"\n\
           start_s = 110.0\nend_s = 115.0\nvalue = 30.0\n\
           \n[[errors.events]]\nkind = \"phase-jump\"\nantenna = \"C\"\nsatellite = \"C01\"\n\
           start_s = 110.0\nend_s = 150.0\nvalue = 0.25\n";
    assert!(scenario.contains("enabled = false") && scenario.contains("level = \"signal\""));
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
    let obs: Vec<String> = ["A", "B", "C", "D"]
        .iter()
        .map(|s| format!("rx/{s}.obs.rnx"))
        .collect();
    // The surveyed positions: the truth RINEX headers' APPROX POSITION XYZ.
    let mut stations = String::new();
    for s in ["A", "B", "C", "D"] {
        let header = std::fs::read_to_string(d.join(format!("sim/{s}.obs.rnx"))).unwrap();
        let line = header
            .lines()
            .find(|l| l.contains("APPROX POSITION XYZ"))
            .unwrap();
        let xyz: Vec<f64> = (0..3)
            .map(|k| line[14 * k..14 * k + 14].trim().parse().unwrap())
            .collect();
        stations += &format!(
            "[[stations]]\nname = \"{s}\"\nposition_ecef_m = [{:?}, {:?}, {:?}]\n",
            xyz[0], xyz[1], xyz[2]
        );
    }
    let bundled = skyforge_scenarios::BUNDLED_MONITOR_CONFIG.replace("stations = []\n", "");
    let at = bundled.find("[thresholds]").unwrap();
    let config = format!("{}{stations}\n{}", &bundled[..at], &bundled[at..]);
    std::fs::write(d.join("monitor.toml"), config).unwrap();
    let mut args = vec!["monitor", "run"];
    args.extend(obs.iter().map(String::as_str));
    args.extend([
        "--nav",
        "sim/nav.rnx",
        "--config",
        "monitor.toml",
        "--out",
        "mon",
    ]);
    let printed = skyforge_ok(&args, d);
    eprintln!("{printed}");
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
