//! `skyforge validate obs`: a receiver's RINEX observations against the truth, from the
//! command line, on small hand-written RINEX 3.04 files.

mod support;

use std::path::Path;
use std::process::Output;
use support::{skyforge, text};

/// RINEX 3.04 observation text: GPS G05, G07, G09 for `n` epochs tagged `t0_s + k` (within
/// the minute), from a receiver whose tags are `offset_m / c` ahead of the sample clock:
/// pseudoranges `base_i + rate_i (tag - offset_m / c) + offset_m + bump(i, k)` (m), phases
/// the ranges without bump in L1 cycles.
fn rinex(t0_s: f64, n: usize, offset_m: f64, bump: impl Fn(usize, usize) -> f64) -> String {
    rinex_with_l5(t0_s, n, offset_m, bump, None)
}

/// A code error (m) of satellite `i` at epoch `k`.
type Bump<'a> = &'a dyn Fn(usize, usize) -> f64;

/// [`rinex`], with L5 observations beside L1 C/A's when `l5_bump` is given: pseudoranges
/// 3 m longer plus `l5_bump(i, k)`, phases the ranges in L5 cycles.
fn rinex_with_l5(
    t0_s: f64,
    n: usize,
    offset_m: f64,
    bump: impl Fn(usize, usize) -> f64,
    l5_bump: Option<Bump<'_>>,
) -> String {
    let lambda = 299_792_458.0 / 1_575.42e6;
    let lambda5 = 299_792_458.0 / 1_176.45e6;
    let types = if l5_bump.is_some() {
        "G    8 C1C L1C D1C S1C C5Q L5Q D5Q S5Q"
    } else {
        "G    4 C1C L1C D1C S1C"
    };
    let mut t = String::new();
    for (body, label) in [
        (
            format!(
                "{:>9}{:11}{:<20}{:<20}",
                "3.04", "", "OBSERVATION DATA", "G"
            ),
            "RINEX VERSION / TYPE",
        ),
        (types.to_string(), "SYS / # / OBS TYPES"),
        (
            "  2023    03    12    00    00    0.0000000     GPS".to_string(),
            "TIME OF FIRST OBS",
        ),
        (String::new(), "END OF HEADER"),
    ] {
        t += &format!("{body:<60}{label}\n");
    }
    for k in 0..n {
        let tag = t0_s + k as f64;
        t += &format!("> 2023 03 12 00 00 {tag:10.7}  0  3\n");
        let sample_time = tag - offset_m / 299_792_458.0;
        for (i, sat) in ["G05", "G07", "G09"].iter().enumerate() {
            let rate = 100.0 * (i as f64 - 1.0);
            let pr = 2.0e7 + 1e6 * i as f64 + rate * sample_time + offset_m;
            let pr_bumped = pr + bump(i, k);
            t += &format!(
                "{sat}{:14.3}  {:14.3}  {:14.3}  {:14.3}  ",
                pr_bumped,
                pr / lambda,
                -rate / lambda,
                45.0
            );
            if let Some(b5) = l5_bump {
                let pr5 = pr + 3.0;
                t += &format!(
                    "{:14.3}  {:14.3}  {:14.3}  {:14.3}  ",
                    pr5 + b5(i, k),
                    pr5 / lambda5,
                    -rate / lambda5,
                    48.0
                );
            }
            t += "\n";
        }
    }
    t
}

/// `skyforge validate obs --truth truth.rnx <args>` in `dir`, after writing there a
/// 22-epoch `truth.rnx` from a receiver without clock offset or code errors.
fn validate_obs(dir: &Path, args: &[&str]) -> Output {
    std::fs::write(dir.join("truth.rnx"), rinex(0.0, 22, 0.0, |_, _| 0.0)).unwrap();
    let mut all = vec!["validate", "obs", "--truth", "truth.rnx"];
    all.extend_from_slice(args);
    skyforge(&all, dir)
}

#[test]
fn validate_obs_prints_per_satellite_errors_and_writes_json() {
    let dir = tempfile::tempdir().unwrap();
    // Receiver: tags at fractional seconds, 300 m (1 us) clock offset, G07 +/-1 m
    // alternating code error.
    let bump = |i: usize, k: usize| if i == 1 { [1.0, -1.0][k % 2] } else { 0.0 };
    std::fs::write(dir.path().join("est.rnx"), rinex(1.25, 20, 300.0, bump)).unwrap();
    let o = validate_obs(dir.path(), &["--estimate", "est.rnx", "--json", "cmp.json"]);
    assert!(o.status.success(), "{}", text(&o));
    let stdout = String::from_utf8_lossy(&o.stdout);
    for needle in ["G05", "G07", "G09", "overall", "20 matched"] {
        assert!(stdout.contains(needle), "{needle}:\n{stdout}");
    }
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("cmp.json")).unwrap())
            .unwrap();
    // 300 m of clock is 1 us of time offset.
    let d = v["time_offset_s"]["mean"].as_f64().unwrap();
    assert!((d - 300.0 / 299_792_458.0).abs() < 1e-9, "{d}");
    // The alternating +/-1 m on one of three satellites, after removing the epoch means
    // and satellite biases: residuals +/-2/3 on G07, -/+1/3 on the others, with 20 - 1
    // epochs and 3 - 1 biases of 60 samples taken: sqrt((20 * (4/9 + 2/9)) / 38).
    let std = v["pseudorange_m"]["overall"]["std"].as_f64().unwrap();
    let expected = (20.0 * (4.0 / 9.0 + 2.0 / 9.0) / 38.0f64).sqrt();
    assert!((std - expected).abs() < 1e-3, "{std} vs {expected}");
    assert_eq!(v["pseudorange_m"]["per_satellite"][1]["sat"], "G07");
}

/// `--json` follows the rules of every output: a file `validate` did not write stays,
/// `--force` or not (a JSON object of another kind included); its own is replaced only
/// with `--force`; a directory or a missing folder is refused before the comparison.
#[test]
fn validate_obs_json_replaces_only_its_own_file_with_force() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::write(d.join("est.rnx"), rinex(1.25, 20, 300.0, |_, _| 0.0)).unwrap();
    let refused = |args: &[&str], needle: &str| {
        let mut all = vec!["--estimate", "est.rnx"];
        all.extend_from_slice(args);
        let o = validate_obs(d, &all);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", text(&o));
        assert!(text(&o).contains(needle), "{args:?}: {}", text(&o));
    };
    // A JSON object that begins as ours is told apart by its first key, once the
    // comparison is made.
    let foreign = "not a validation JSON skyforge wrote";
    let user_files = [
        ("notes.json", "precious\n", foreign),
        ("other.json", "{\n  \"mine\": 1\n}\n", "give --force"),
    ];
    for (name, content, unforced) in user_files {
        std::fs::write(d.join(name), content).unwrap();
        refused(&["--json", name], unforced);
        refused(&["--json", name, "--force"], foreign);
        assert_eq!(std::fs::read_to_string(d.join(name)).unwrap(), content);
    }
    std::fs::create_dir(d.join("sub")).unwrap();
    refused(&["--json", "sub"], "is a directory");
    refused(
        &["--json", "nowhere/cmp.json"],
        "nowhere is not a directory",
    );

    let ok = |args: &[&str]| {
        let mut all = vec!["--estimate", "est.rnx"];
        all.extend_from_slice(args);
        let o = validate_obs(d, &all);
        assert!(o.status.success(), "{args:?}: {}", text(&o));
    };
    ok(&["--json", "cmp.json"]);
    refused(&["--json", "cmp.json"], "give --force");
    ok(&["--json", "cmp.json", "--force"]);
}

#[test]
fn validate_obs_rejects_a_missing_file_as_bad_input() {
    let dir = tempfile::tempdir().unwrap();
    let o = validate_obs(dir.path(), &["--estimate", "missing.rnx"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("missing.rnx"));
}

/// `--from`/`--to` keep the epochs measured in that sample-time span (the estimate's tags
/// are 1.25 + k s, 1 us ahead of its sample times); a bad epoch or an empty span is bad
/// input.
#[test]
fn validate_obs_restricts_the_comparison_to_a_sample_time_span() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("est.rnx"),
        rinex(1.25, 20, 300.0, |_, _| 0.0),
    )
    .unwrap();
    let span = [
        "--from",
        "2023-03-12T00:00:05 GPST",
        "--to",
        "2023-03-12T00:00:10 GPST",
    ];
    let mut args = vec!["--estimate", "est.rnx"];
    args.extend_from_slice(&span);
    let o = validate_obs(dir.path(), &args);
    assert!(o.status.success(), "{}", text(&o));
    let stdout = String::from_utf8_lossy(&o.stdout);
    // Sample times 5.25 .. 9.25 s: five epochs.
    assert!(stdout.contains("5 matched"), "{stdout}");
    assert!(
        stdout.contains("sample times of the matched epochs: 2023-03-12T00:00:05.249998999 GPST"),
        "{stdout}"
    );

    let o = validate_obs(
        dir.path(),
        &[
            "--estimate",
            "est.rnx",
            "--from",
            "yesterday",
            "--to",
            "2023-03-12T00:00:10 GPST",
        ],
    );
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(stderr.contains("--from \"yesterday\""), "{stderr}");

    let o = validate_obs(
        dir.path(),
        &[
            "--estimate",
            "est.rnx",
            "--from",
            "2023-03-12T01:00:00 GPST",
            "--to",
            "2023-03-12T01:00:10 GPST",
        ],
    );
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(
        String::from_utf8_lossy(&o.stderr).contains("no estimate epoch was measured between"),
        "{}",
        text(&o)
    );
}

/// Observations of GPS L1 C/A and L5: each signal compared with its own truth, a table
/// each; the L5 code error (+/-1 m alternating on G09) found on L5 alone.
#[test]
fn validate_obs_compares_two_signals_of_a_system_one_at_a_time() {
    let dir = tempfile::tempdir().unwrap();
    let none = |_: usize, _: usize| 0.0;
    let l5 = |i: usize, k: usize| if i == 2 { [1.0, -1.0][k % 2] } else { 0.0 };
    let truth = rinex_with_l5(0.0, 22, 0.0, none, Some(&none));
    std::fs::write(dir.path().join("truth.rnx"), truth).unwrap();
    let est = rinex_with_l5(1.25, 20, 300.0, none, Some(&l5));
    std::fs::write(dir.path().join("est.rnx"), est).unwrap();
    let args = [
        "validate",
        "obs",
        "--truth",
        "truth.rnx",
        "--estimate",
        "est.rnx",
        "--json",
        "c.json",
    ];
    let o = skyforge(&args, dir.path());
    assert!(o.status.success(), "{}", text(&o));
    let stdout = String::from_utf8_lossy(&o.stdout);
    for needle in ["== gps-l1ca ==", "== gps-l5 =="] {
        assert!(stdout.contains(needle), "{needle}:\n{stdout}");
    }
    let v: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.path().join("c.json")).unwrap()).unwrap();
    let layers = v["signals"].as_array().unwrap();
    assert_eq!(layers.len(), 2);
    assert_eq!(layers[0]["signals"][0], "gps-l1ca");
    assert_eq!(layers[1]["signals"][0], "gps-l5");
    let std = |k: usize| {
        layers[k]["pseudorange_m"]["overall"]["std"]
            .as_f64()
            .unwrap()
    };
    // As in validate_obs_prints_per_satellite_errors_and_writes_json, on L5 alone.
    let expected = (20.0 * (4.0 / 9.0 + 2.0 / 9.0) / 38.0f64).sqrt();
    assert!(std(0) < 1e-3, "L1 C/A: {}", std(0));
    assert!(
        (std(1) - expected).abs() < 1e-3,
        "L5: {} vs {expected}",
        std(1)
    );
}
