//! `skyforge attitude` end to end on the observation level: a LEO with three antennas on
//! two 1 m baselines -> observables -> double differences, LAMBDA, fixed baselines,
//! attitude -> compared with the truth SkyForge wrote (`truth.h5`) by the library of
//! `skyforge validate attitude`, and that command itself.

mod support;

use skyforge_formats::attitude::{Status, read_attitude_csv};
use skyforge_navigation::relative::FixMethod;
use skyforge_validate::attitude::AxisStats;
use skyforge_validate::attitude::compare_outputs;
use std::path::Path;
use support::{h5_contents, receive_all_recordings, skyforge, skyforge_ok, text};

/// The thesis LEO with three antennas (master at the body origin, baselines of 1 m along
/// body X and Y), GPS + BDS-3 at 45 dB-Hz, a slow pitch oscillation, `duration_s` long.
fn scenario(dir: &Path, duration_s: u32, gps_only: bool, observation_level: bool) -> String {
    let base = include_str!("../../scenarios/calibration/leo-gps-bds.toml");
    let mut text = base
        .replacen(
            "duration_s = 130.0",
            &format!("duration_s = {duration_s}.0"),
            1,
        )
        .replacen("seed = 20261125", "seed = 5", 1);
    if gps_only {
        text = text.replacen("[gnss.beidou]\n", "[gnss.beidou]\nenabled = false\n", 1);
    }
    text += r#"
[platform.attitude]
pitch = { amplitude_deg = 2.0, period_s = 600.0, phase_deg = 0.0 }
roll = { offset_deg = 0.5 }

[[antennas]]
name = "ant2"
position_body_m = [1.0, 0.0, 0.0]
boresight_body = [0.0, 0.0, -1.0]
fov_half_angle_deg = 80.0

[[antennas]]
name = "ant3"
position_body_m = [0.0, 1.0, 0.0]
boresight_body = [0.0, 0.0, -1.0]
fov_half_angle_deg = 80.0

"#;
    if observation_level {
        text += "\n[observation]\nlevel = \"observation\"\n";
    }
    let path = dir.join("leo.toml");
    std::fs::write(&path, text).unwrap();
    path.to_string_lossy().into_owned()
}

/// `skyforge receive` over every recording in `sim` into `rx`; returns `rx`.
fn receive(sim: &Path, rx: &Path, extra: &[&str]) -> std::path::PathBuf {
    println!("{}", receive_all_recordings(sim, rx, extra, sim));
    rx.to_path_buf()
}

/// Sample standard deviation (the library's, as `skyforge validate attitude` prints it).
fn std(v: &[f64]) -> f64 {
    AxisStats::of(v).std.unwrap_or(f64::NAN)
}

/// The directories of one run of the chain: the simulation, the observations the chain
/// read, the chain's output.
struct ChainDirs {
    sim: std::path::PathBuf,
    observations: std::path::PathBuf,
    attitude: std::path::PathBuf,
}

/// In `dir`: `skyforge run` of [`scenario`] (`duration` s; observation level unless
/// `signal_level`, then `skyforge receive`), then `skyforge attitude` with `config`.
fn run_chain(
    dir: &Path,
    duration: u32,
    gps_only: bool,
    signal_level: bool,
    config: &str,
) -> ChainDirs {
    let path = scenario(dir, duration, gps_only, !signal_level);
    let sim = dir.join("sim");
    skyforge_ok(&["run", &path, "--out", sim.to_str().unwrap()], dir);
    std::fs::write(dir.join("rel.toml"), config).unwrap();
    let (nav, geometry) = (sim.join("nav.rnx"), sim.join("geometry.toml"));
    let rel = dir.join("rel.toml");
    // At the signal level the receiver also runs the chain itself (`--geometry`).
    let chain_args = [
        "--geometry",
        geometry.to_str().unwrap(),
        "--attitude-config",
        rel.to_str().unwrap(),
    ];
    let observations = if signal_level {
        receive(&sim, &dir.join("rx"), &chain_args)
    } else {
        sim.join("observations")
    };
    let obs: Vec<String> = ["ant1", "ant2", "ant3"]
        .iter()
        .map(|a| {
            observations
                .join(format!("{a}.obs.rnx"))
                .to_string_lossy()
                .into_owned()
        })
        .collect();
    let out = dir.join("att");
    let mut args: Vec<&str> = vec!["attitude"];
    args.extend(obs.iter().map(String::as_str));
    args.extend([
        "--nav",
        nav.to_str().unwrap(),
        "--geometry",
        geometry.to_str().unwrap(),
        "--config",
        rel.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    println!("{}", skyforge_ok(&args, dir));
    if signal_level {
        for f in ["attitude.csv", "ambiguities.csv"] {
            let read = |d: &Path| std::fs::read(d.join(f)).unwrap();
            assert!(
                read(&observations) == read(&out),
                "receive --geometry: {f} differs"
            );
        }
        // Every dataset to the bit (the file's own bytes hold creation times).
        let (a, b) = (
            h5_contents(&observations.join("attitude.h5")),
            h5_contents(&out.join("attitude.h5")),
        );
        let differing: Vec<&str> = a
            .iter()
            .zip(&b)
            .filter(|(x, y)| x != y)
            .map(|(x, _)| x.0.as_str())
            .collect();
        assert!(
            !a.is_empty() && a.len() == b.len() && differing.is_empty(),
            "receive --geometry: attitude.h5 differs ({} and {} datasets; {differing:?})",
            a.len(),
            b.len()
        );
    }
    ChainDirs {
        sim,
        observations,
        attitude: out,
    }
}

/// Run the chain with `config` (observation level, 120 s; or signal level of the given
/// duration) and return the fraction of epochs fixed from the first fix on, and the
/// per-axis NED baseline errors (m) and attitude errors (deg) of the fixed epochs.
fn chain_errors(
    gps_only: bool,
    signal_level: Option<u32>,
    config: &str,
) -> (f64, Vec<[f64; 3]>, Vec<[f64; 3]>) {
    let dir = tempfile::tempdir().unwrap();
    let duration = signal_level.unwrap_or(120);
    let run = run_chain(
        dir.path(),
        duration,
        gps_only,
        signal_level.is_some(),
        config,
    );
    // The comparison of `skyforge validate attitude`: every integer of ambiguities.csv
    // against the truth's double-difference integer, every fixed epoch of attitude.csv
    // against truth.h5.
    let comparison = compare_outputs(&run.sim, &run.observations, &run.attitude).unwrap();
    let chain = &comparison.chain;
    let (checked, wrong, worst) = (
        chain.integers_checked,
        chain.integers_wrong,
        chain.largest_integer_distance_cycles,
    );
    println!(
        "INTEGERS checked {checked}, wrong {wrong}, largest distance from an integer {worst:.3} cycles"
    );
    assert!(checked > 0);
    assert_eq!(wrong, 0, "fixed integers differ from the truth's");
    // Every fixed epoch says what fixed it: the body geometry's search, then the hold
    // (the default constraint); no fallback to LAMBDA on this sky.
    let table = read_attitude_csv(&run.attitude.join("attitude.csv")).unwrap();
    for line in &table.rows {
        let v = &line.row;
        if v.status == Status::Fixed {
            assert!(
                matches!(v.method, Some(FixMethod::Geometry | FixMethod::Held)),
                "line {}: {:?} ({})",
                line.line,
                v.method,
                v.note
            );
        }
    }
    assert!(
        worst < 0.25,
        "an observed DD is {worst} cycles from an integer"
    );
    // Per-axis NED errors of both baselines together, and the attitude errors.
    let baseline_err: Vec<[f64; 3]> = chain
        .fixed
        .iter()
        .flat_map(|e| e.baseline_ned_m.iter().copied())
        .collect();
    let attitude_err: Vec<[f64; 3]> = chain.fixed.iter().filter_map(|e| e.attitude_deg).collect();
    (
        comparison.summary().fixed_fraction,
        baseline_err,
        attitude_err,
    )
}

/// Issue #12's bars on the observation level (the signal-level run is the acceptance
/// tier's): every epoch fixed, every fixed integer the truth's; NED baseline error std below 3 mm per axis and no epoch
/// off by a centimetre (a wrong integer moves a 1 m baseline by centimetres); attitude
/// error std below 0.1 deg per axis with the KF.
#[test]
fn leo_three_antennas_fix_every_epoch_with_millimetre_baselines() {
    check_chain(None);
}

/// The same bars at the signal level, as issue #12 states them: 300 s of I/Q for three
/// antennas -> `skyforge receive` -> `skyforge attitude`, GPS + BDS and GPS alone.
#[test]
#[ignore = "acceptance tier: 300 s of I/Q for three antennas, synthesised and received (minutes)"]
fn signal_level_leo_three_antennas_fix_every_epoch_with_millimetre_baselines() {
    check_chain(Some(300));
}

fn check_chain(signal_level: Option<u32>) {
    for gps_only in [false, true] {
        let config = "[relative]\nattitude = { method = \"kf\" }\n";
        let (fixed, b, a) = chain_errors(gps_only, signal_level, config);
        let axis = |v: &[[f64; 3]], i: usize| v.iter().map(|e| e[i]).collect::<Vec<f64>>();
        let b_std: Vec<f64> = (0..3).map(|i| std(&axis(&b, i))).collect();
        let a_std: Vec<f64> = (0..3).map(|i| std(&axis(&a, i))).collect();
        let worst = b.iter().flatten().fold(0.0f64, |m, e| m.max(e.abs()));
        println!(
            "ATTITUDE_CHAIN signal_level={signal_level:?} gps_only={gps_only}: fixed {:.3}, baseline std N/E/D {:.2}/{:.2}/{:.2} mm (worst {:.1} mm), attitude std {:.4}/{:.4}/{:.4} deg over {} epochs",
            fixed,
            b_std[0] * 1e3,
            b_std[1] * 1e3,
            b_std[2] * 1e3,
            worst * 1e3,
            a_std[0],
            a_std[1],
            a_std[2],
            a.len()
        );
        assert_eq!(fixed, 1.0);
        // The first attitude within 30 s of the start: acquisition, pull-in and the first
        // ephemerides. (10 s at first; GPS alone at the signal level first fixed after 13 s.)
        let epochs = signal_level.unwrap_or(120) as usize;
        assert!(
            a.len() + 30 >= epochs,
            "{} epochs with an attitude",
            a.len()
        );
        assert!(b_std.iter().all(|s| *s < 3e-3), "{b_std:?}");
        assert!(worst < 0.01, "{worst}");
        assert!(a_std.iter().all(|s| *s < 0.1), "{a_std:?}");
    }
}

/// `skyforge receive --geometry` runs the chain as an epoch stage on its own observations,
/// in memory, and writes what `skyforge attitude` writes from the RINEX files of the same
/// run (checked in [`run_chain`]: the two CSV files byte for byte, `attitude.h5` dataset by
/// dataset); a geometry naming an
/// antenna without a recording, or without `--assist`, is refused before anything is
/// written.
#[test]
fn receive_with_a_geometry_writes_what_attitude_writes() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let dirs = run_chain(
        d,
        20,
        true,
        true,
        "[relative]\nattitude = { method = \"kf\" }\n",
    );
    let rows = std::fs::read_to_string(dirs.observations.join("attitude.csv")).unwrap();
    // The first fix comes after about 13 s of acquisition, pull-in and ephemerides.
    assert!(
        rows.lines().filter(|l| l.contains(",fixed,")).count() >= 3,
        "{rows}"
    );
    let bad = d.join("bad.toml");
    let geometry = std::fs::read_to_string(dirs.sim.join("geometry.toml")).unwrap();
    std::fs::write(&bad, geometry.replace("\"ant3\"", "\"ant9\"")).unwrap();
    let meta = ["ant1", "ant2", "ant3"].map(|a| {
        dirs.sim
            .join(format!("{a}.gps-l1ca.sigmf-meta"))
            .to_string_lossy()
            .into_owned()
    });
    let nav = dirs.sim.join("nav.rnx").to_string_lossy().into_owned();
    let bad = bad.to_string_lossy().into_owned();
    for (extra, expected) in [
        (vec!["--assist", &nav], "antenna \"ant9\" has no recording"),
        (vec![], "--geometry needs --assist"),
    ] {
        let mut args = vec!["receive"];
        args.extend(meta.iter().map(String::as_str));
        args.extend(extra);
        args.extend(["--geometry", &bad, "--out", "rx2"]);
        let o = skyforge(&args, d);
        assert_eq!(o.status.code(), Some(2), "{}", text(&o));
        assert!(text(&o).contains(expected), "{}", text(&o));
        assert!(!d.join("rx2").exists());
    }
}

/// Bad inputs: one clear error, exit code 2, nothing written.
#[test]
fn attitude_input_errors_are_clear() {
    let dir = tempfile::tempdir().unwrap();
    let path = scenario(dir.path(), 10, false, true);
    let sim = dir.path().join("sim");
    skyforge_ok(&["run", &path, "--out", sim.to_str().unwrap()], dir.path());
    let s = |p: &str| sim.join(p).to_string_lossy().into_owned();
    let out = dir.path().join("att");
    let o_ = out.to_string_lossy().into_owned();
    let cases: Vec<(Vec<String>, &str)> = vec![
        (
            vec![
                s("observations/ant1.obs.rnx"),
                s("observations/ant2.obs.rnx"),
            ],
            "2 observation files for the 3 antennas",
        ),
        (
            vec![
                s("observations/ant1.obs.rnx"),
                s("observations/ant2.obs.rnx"),
                s("nav.rnx"),
            ],
            "nav.rnx",
        ),
    ];
    let all = || {
        ["ant1", "ant2", "ant3"]
            .map(|a| s(&format!("observations/{a}.obs.rnx")))
            .to_vec()
    };
    let config = dir.path().join("rel.toml");
    let config_arg = config.to_string_lossy().into_owned();
    let mut cases: Vec<_> = cases.into_iter().map(|(f, e)| (f, e, None)).collect();
    // Settings outside their domain (issue #32): the file, the key, what is allowed.
    for (line, expected) in [
        (
            "phase = { sigma0_m = 0.0, a0 = 0.0, elev0_deg = 10.0 }",
            "rel.toml: relative.phase.sigma0_m = 0: must be in (0, 100] m",
        ),
        (
            "code = { sigma0_m = 0.3, a0 = 0.0, elev0_deg = 0.0 }",
            "rel.toml: relative.code.elev0_deg = 0: must be in (0, 90] deg",
        ),
        (
            "reverse_filter = { rate_psd_m2_s3 = [1e300, 0, 0, 0, 0, 0] }",
            "rate_psd_m2_s3[0] = 1e300: allowed 0 to 1e6",
        ),
    ] {
        cases.push((all(), expected, Some(format!("[relative]\n{line}\n"))));
    }
    for (files, expected, settings) in cases {
        let mut args: Vec<String> = vec!["attitude".into()];
        args.extend(files);
        args.extend([
            "--nav".into(),
            s("nav.rnx"),
            "--geometry".into(),
            s("geometry.toml"),
            "--out".into(),
            o_.clone(),
        ]);
        if let Some(text) = settings {
            std::fs::write(&config, text).unwrap();
            args.extend(["--config".into(), config_arg.clone()]);
        }
        let refs: Vec<&str> = args.iter().map(String::as_str).collect();
        let o = skyforge(&refs, dir.path());
        assert_eq!(o.status.code(), Some(2), "{}", text(&o));
        assert!(text(&o).contains(expected), "{}", text(&o));
        assert!(!out.exists());
    }
}

/// `skyforge validate attitude` on a short observation-level run: the table with the
/// thesis's values beside ours, the JSON; bad directories and a bad row: one message
/// naming the file, exit code 2.
#[test]
fn validate_attitude_command_reports_and_names_bad_files() {
    let dir = tempfile::tempdir().unwrap();
    let run = run_chain(
        dir.path(),
        30,
        true,
        false,
        "[relative]\nattitude = { method = \"kf\" }\n",
    );
    let p = |p: &Path| p.to_string_lossy().into_owned();
    let (sim, obs, att) = (p(&run.sim), p(&run.observations), p(&run.attitude));
    let json = dir.path().join("validate.json");
    let validate = |truth: &str, observations: &str, attitude: &str| {
        skyforge(
            &[
                "validate",
                "attitude",
                "--truth",
                truth,
                "--observations",
                observations,
                "--attitude",
                attitude,
                "--json",
                json.to_str().unwrap(),
            ],
            dir.path(),
        )
    };
    let o = validate(&sim, &obs, &att);
    let out = text(&o);
    println!("{out}");
    assert!(o.status.success(), "{out}");
    for expected in [
        "integers:",
        " 0 wrong",
        "b1 (ant2) N mm",
        "b2 (ant3) D mm",
        "0.801 (table 5.4-4)",
        "1.700 (table 5.4-4)",
        "yaw deg",
        "0.0410 (table 5.4-5, KF)",
        "0.0741 (table 5.4-5, KF)",
        "0.0806 (table 5.4-5, KF)",
    ] {
        assert!(out.contains(expected), "{expected:?} missing:\n{out}");
    }
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    assert_eq!(v["epochs"], 30);
    assert_eq!(v["fixed_fraction"], 1.0);
    assert_eq!(v["integers"]["wrong"], 0);
    assert!(v["integers"]["checked"].as_u64().unwrap() > 0);
    assert_eq!(v["antennas"][1]["true_body_m"][0], 1.0);
    assert_eq!(v["baselines"].as_array().unwrap().len(), 2);
    for (axis, angle) in [("n", "yaw"), ("e", "pitch"), ("d", "roll")] {
        let ned = v["baselines"][1]["ned_m"][axis]["std"].as_f64().unwrap();
        assert!(ned > 0.0 && ned < 3e-3, "{ned}");
        let a = v["attitude_deg"][angle]["std"].as_f64().unwrap();
        assert!(a > 0.0 && a < 0.1, "{a}");
    }
    assert_eq!(v["thesis_attitude_std_deg"]["yaw"], 0.041);
    assert_eq!(v["baselines"][0]["thesis_ned_std_m"]["n"], 8.0105e-4);
    std::fs::remove_file(&json).unwrap();

    // A corrupt row of attitude.csv: file and line.
    let bad = dir.path().join("bad-att");
    std::fs::create_dir(&bad).unwrap();
    for f in ["attitude.csv", "ambiguities.csv"] {
        std::fs::copy(run.attitude.join(f), bad.join(f)).unwrap();
    }
    let csv = std::fs::read_to_string(bad.join("attitude.csv")).unwrap();
    let mut lines: Vec<String> = csv.lines().map(String::from).collect();
    lines[4] = lines[4].replacen(",fixed,", ",fixd,", 1);
    std::fs::write(bad.join("attitude.csv"), lines.join("\n")).unwrap();
    let bad_s = p(&bad);
    let cases: Vec<([&str; 3], String)> = vec![
        // The attitude directory given as the observations: no attitude.csv.
        (
            [sim.as_str(), obs.as_str(), obs.as_str()],
            format!("{}", run.observations.join("attitude.csv").display()),
        ),
        // The chain's directory given as the run's: no geometry.toml.
        (
            [att.as_str(), obs.as_str(), att.as_str()],
            format!("{}", run.attitude.join("geometry.toml").display()),
        ),
        // The chain's directory given as the observations: no ant1.obs.rnx.
        (
            [sim.as_str(), att.as_str(), att.as_str()],
            format!("{}", run.attitude.join("ant1.obs.rnx").display()),
        ),
        // The run's directory given as the observations: its files are the truth.
        (
            [sim.as_str(), sim.as_str(), att.as_str()],
            "ant1.obs.rnx: is the observation truth itself".to_string(),
        ),
        (
            [sim.as_str(), obs.as_str(), bad_s.as_str()],
            format!(
                "{}:5: status = \"fixd\"",
                bad.join("attitude.csv").display()
            ),
        ),
        (
            [sim.as_str(), obs.as_str(), "no-such-dir"],
            "no-such-dir: not a directory".to_string(),
        ),
    ];
    for ([t, o_, a], expected) in cases {
        let o = validate(t, o_, a);
        let out = text(&o);
        assert_eq!(o.status.code(), Some(2), "{out}");
        assert!(out.contains(&expected), "{expected:?} missing:\n{out}");
        assert_eq!(out.matches("error:").count(), 1, "{out}");
        assert!(!json.exists());
    }
}

/// Issue #33 (5, 9, 12): files with which no epoch can be formed gave exit 0 and every
/// epoch "none" (junk after the header, NaN values, epoch flag 9, version 9.99,
/// pseudoranges of 9.99e300 m, another day, swapped or repeated files, `[relative]
/// signals` absent, no common satellite, a navigation file of another day), and `INTERVAL
/// inf` printed a panic and its backtrace. Each is now one message naming the file and
/// the reason, exit code 2, nothing written; a file that loses one malformed epoch is
/// read with a warning naming the line, and the summary counts the epochs without a
/// result by reason.
#[test]
fn attitude_refuses_inputs_with_which_no_epoch_forms() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let path = scenario(d, 10, false, true);
    skyforge_ok(&["run", &path, "--out", "sim"], d);
    // The same scenario eight days later: its navigation file is of another day.
    let other_day = std::fs::read_to_string(&path)
        .unwrap()
        .replace("2023-03-12T00:00:00", "2023-03-20T00:00:00");
    std::fs::write(d.join("later.toml"), other_day).unwrap();
    skyforge_ok(&["run", "later.toml", "--out", "later"], d);
    let obs = |a: &str| format!("sim/observations/{a}.obs.rnx");
    let ant2 = std::fs::read_to_string(d.join(obs("ant2"))).unwrap();
    let end = ant2.find("END OF HEADER\n").unwrap() + "END OF HEADER\n".len();
    let satellite_lines = regex_free_sat_lines(&ant2);
    let first_sat = satellite_lines[0].clone();
    let value_of = |v: &str| format!("{}{v:>14}{}", &first_sat[..3], &first_sat[17..]);
    // ant2 with every satellite renamed to one that no file observes: no common satellite.
    let seen: Vec<String> = ["ant1", "ant2", "ant3"]
        .iter()
        .flat_map(|a| regex_free_sat_lines(&std::fs::read_to_string(d.join(obs(a))).unwrap()))
        .map(|l| l[..3].to_string())
        .collect();
    let mut free: Vec<String> = (1..=32)
        .map(|p| format!("G{p:02}"))
        .chain((1..=63).map(|p| format!("C{p:02}")))
        .filter(|n| !seen.contains(n))
        .collect();
    let mut names: Vec<String> = satellite_lines.iter().map(|l| l[..3].to_string()).collect();
    names.sort();
    names.dedup();
    let mut renamed = ant2.clone();
    for name in &names {
        let to = free.remove(free.iter().position(|f| f[..1] == name[..1]).unwrap());
        renamed = renamed.replace(&format!("\n{name} "), &format!("\n{to} "));
    }
    let edits: Vec<(&str, String)> = vec![
        ("junk", ant2[..end].to_string() + &"junk\n".repeat(20)),
        ("nan", ant2.replacen(&first_sat, &value_of("NaN"), 1)),
        ("big", ant2.replacen(&first_sat, &value_of("9.99e300"), 1)),
        ("flag9", ant2.replace("0000000  0 ", "0000000  9 ")),
        ("v999", ant2.replacen("     3.04", "     9.99", 1)),
        (
            "interval",
            ant2.replacen("     1.000      ", "       inf      ", 1),
        ),
        ("day", ant2.replace("> 2023 03 12", "> 2023 03 13")),
        ("nocommon", renamed),
    ];
    for (name, text) in &edits {
        assert_ne!(text, &ant2, "{name}: the edit changed nothing");
        std::fs::write(d.join(format!("{name}.rnx")), text).unwrap();
    }
    std::fs::write(d.join("bds.toml"), "[relative]\nsignals = [\"bds-b3i\"]\n").unwrap();
    let run = |files: [&str; 3], nav: &str, config: Option<&str>| {
        let mut args = vec!["attitude"];
        args.extend(files);
        args.extend([
            "--nav",
            nav,
            "--geometry",
            "sim/geometry.toml",
            "--out",
            "att",
        ]);
        if let Some(c) = config {
            args.extend(["--config", c]);
        }
        skyforge(&args, d)
    };
    let (a1, a2, a3) = (obs("ant1"), obs("ant2"), obs("ant3"));
    let nav = "sim/nav.rnx";
    /// The files, the navigation file, `--config`, what the message must hold.
    type Case<'a> = ([&'a str; 3], &'a str, Option<&'a str>, &'a [&'a str]);
    let cases: Vec<Case> = vec![
        (
            [&a1, "junk.rnx", &a3],
            nav,
            None,
            &[
                "junk.rnx: 20 of 20 epochs and lines cannot be read",
                "line 18: neither an epoch line",
            ],
        ),
        (
            [&a1, "nan.rnx", &a3],
            nav,
            None,
            &["nan.rnx:19: ", "pseudorange (m) NaN: allowed -1e9 to 1e9 m"],
        ),
        (
            [&a1, "big.rnx", &a3],
            nav,
            None,
            &["big.rnx:19: ", "pseudorange (m) 9.99e300"],
        ),
        (
            [&a1, "flag9.rnx", &a3],
            nav,
            None,
            &["flag9.rnx: 10 of 10 epochs", "epoch flag 9: allowed 0 to 6"],
        ),
        (
            [&a1, "v999.rnx", &a3],
            nav,
            None,
            &["v999.rnx:1: RINEX version 9.99 is not read"],
        ),
        (
            [&a1, "interval.rnx", &a3],
            nav,
            None,
            &["interval.rnx:13: INTERVAL inf: allowed 0 to 86400 s"],
        ),
        (
            [&a1, "day.rnx", &a3],
            nav,
            None,
            &["day.rnx: no epoch within 0.025 s of an epoch of the master's file"],
        ),
        (
            [&a2, &a1, &a3],
            nav,
            None,
            &["ant2.obs.rnx: MARKER NAME \"ant2\", but it is given for antenna \"ant1\""],
        ),
        (
            [&a1, &a1, &a3],
            nav,
            None,
            &[
                "geometry.toml: antenna \"ant2\" has no file (the files' MARKER NAMEs: ant1, ant1, ant3)",
            ],
        ),
        (
            [&a1, &a2, &a3],
            nav,
            Some("bds.toml"),
            &["ant1.obs.rnx: none of the signals of [relative] signals (bds-b3i)"],
        ),
        (
            [&a1, "nocommon.rnx", &a3],
            nav,
            None,
            &[
                "ant1.obs.rnx: no epoch could be formed (10 of 10 epochs",
                "satellites common to all antennas",
            ],
        ),
        (
            [&a1, &a2, &a3],
            "later/nav.rnx",
            None,
            &[
                "ant1.obs.rnx: no epoch could be formed",
                "no single-point position of the master (10)",
                "later/nav.rnx",
            ],
        ),
    ];
    for (files, nav, config, needles) in cases {
        let o = run(files, nav, config);
        let out = text(&o);
        assert_eq!(o.status.code(), Some(2), "{files:?} {nav}:\n{out}");
        assert_eq!(out.matches("error:").count(), 1, "{files:?}:\n{out}");
        assert!(!out.contains("panicked"), "{files:?}:\n{out}");
        for n in needles {
            assert!(out.contains(n), "{files:?} {nav}: missing {n:?} in\n{out}");
        }
        assert!(!d.join("att").exists());
    }
    // One malformed epoch of ten: read with a warning; the summary counts the epoch ant2
    // lacks.
    let minute = ant2.replacen("> 2023 03 12 00 00  5.0", "> 2023 03 12 00 99  5.0", 1);
    std::fs::write(d.join("minute.rnx"), minute).unwrap();
    let o = run([&a1, "minute.rnx", &a3], nav, None);
    let out = text(&o);
    assert!(o.status.success(), "{out}");
    assert!(
        out.contains(
            "warning: minute.rnx: 1 malformed epochs or lines left out (9 epochs read): line "
        ),
        "{out}"
    );
    assert!(out.contains(": epoch minute 99: allowed 0 to 59"), "{out}");
    assert!(
        out.contains("none       1 epochs gave no result: antenna ant2 has no epoch (1)"),
        "{out}"
    );
    // `validate obs` reads the same way: no panic for INTERVAL inf.
    let o = skyforge(
        &[
            "validate",
            "obs",
            "--truth",
            &a2,
            "--estimate",
            "interval.rnx",
        ],
        d,
    );
    let out = text(&o);
    assert_eq!(o.status.code(), Some(2), "{out}");
    assert!(
        out.contains("interval.rnx:13: INTERVAL inf") && !out.contains("panicked"),
        "{out}"
    );
}

/// The satellite lines of RINEX 3 text (a system letter and two digits, then values).
fn regex_free_sat_lines(text: &str) -> Vec<String> {
    text.lines()
        .filter(|l| {
            let b = l.as_bytes();
            b.len() > 3
                && matches!(b[0], b'G' | b'C')
                && b[1].is_ascii_digit()
                && b[2].is_ascii_digit()
        })
        .map(|l| l.to_string() + "\n")
        .collect()
}
