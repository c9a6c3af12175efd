//! `skyforge relnav` and `skyforge validate relnav` end to end on two vehicles of one
//! scenario (`[[vehicles]]`): the observation level's files in, `relnav.csv` out, compared
//! with the run's `relative.csv`.

mod support;

use std::path::Path;

/// `relnav` of `pair`'s two vehicles with the settings `config` (TOML) into `out`, then
/// `validate relnav` from `settle` s with JSON; the comparison and what relnav printed.
fn relnav(d: &Path, config: &str, out: &str, settle: &str) -> (serde_json::Value, String) {
    let path = format!("{out}.toml");
    std::fs::write(d.join(&path), config).unwrap();
    let printed = support::skyforge_ok(
        &[
            "relnav",
            "pair/target/observations/ant1.obs.rnx",
            "pair/chaser/observations/ant1.obs.rnx",
            "--nav",
            "pair/target/nav.rnx",
            "--config",
            &path,
            "--out",
            out,
        ],
        d,
    );
    let json = format!("{out}.json");
    support::skyforge_ok(
        &[
            "validate",
            "relnav",
            "--truth",
            "pair",
            "--relnav",
            out,
            "--settle-s",
            settle,
            "--json",
            &json,
        ],
        d,
    );
    (support::json_file(&d.join(json)), printed)
}

/// On `book-relnav-leo` (SA-era satellite errors, seed 1), after 100 s: relative DGPS
/// (fixes on the common satellites) under 5 m 3-D RMS (# assumed bar: the SA errors,
/// tens of metres in each fix, cancel; what remains is two receivers' code noise through
/// the geometry), carrier smoothing better still, and the chaser 32 km behind in every
/// estimate. Through the book's relative filter (`[filter]`) relative DGPS is closer to
/// the truth than without (on B-5.6's seeds 1-4, 0.74 against 1.49 m).
#[test]
fn relnav_modes_on_the_book_pair() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    support::skyforge_ok(&["synth", "book-relnav-leo", "--out", "pair"], d);
    let (pd, _) = relnav(d, "mode = \"position-difference\"\n", "pd", "100");
    let (cs, _) = relnav(d, "mode = \"carrier-smoothed\"\n", "cs", "100");
    let filtered = "mode = \"position-difference\"\n[filter]\n";
    let (pdf, printed) = relnav(d, filtered, "pdf", "100");
    assert!(printed.contains("the book's relative filter"), "{printed}");
    let rms = |v: &serde_json::Value| v["position_m"]["rms_3d"].as_f64().unwrap();
    eprintln!(
        "position-difference {:.3} m, carrier-smoothed {:.3} m",
        rms(&pd),
        rms(&cs)
    );
    assert!(rms(&pd) < 5.0, "{pd}");
    assert!(rms(&cs) < rms(&pd), "{cs}");
    eprintln!("position-difference through the filter {:.3} m", rms(&pdf));
    assert!(rms(&pdf) < rms(&pd), "{pdf}");
    assert_eq!(pd["vehicle"], "chaser");
    let rows = skyforge_formats::relative::read_relative_csv(&d.join("cs/relnav.csv")).unwrap();
    assert!(rows.iter().all(|r| (r.position_m.x + 32.0e3).abs() < 1.0e3));
}

/// Bad input: an unknown mode, a missing file, vehicle names that are not in the truth:
/// one error each, exit code 2, nothing written.
#[test]
fn bad_relnav_input_is_named() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    support::skyforge_ok(&["synth", "book-relnav-leo", "--out", "pair"], d);
    std::fs::write(d.join("bad.toml"), "mode = \"kalman\"\n").unwrap();
    let base = [
        "relnav",
        "pair/target/observations/ant1.obs.rnx",
        "pair/chaser/observations/ant1.obs.rnx",
        "--nav",
        "pair/target/nav.rnx",
        "--out",
        "rel",
    ];
    for (extra, names) in [
        (vec!["--config", "bad.toml"], "kalman"),
        (vec!["--chaser-name", "a,b"], "--chaser-name"),
    ] {
        let args: Vec<&str> = base.iter().copied().chain(extra).collect();
        let o = support::skyforge(&args, d);
        let err = support::text(&o);
        assert_eq!(o.status.code(), Some(2), "{err}");
        assert!(err.contains(names), "{err}");
        assert!(!d.join("rel").exists());
    }
    let args: Vec<&str> = base
        .iter()
        .copied()
        .chain(["--chaser-name", "other"])
        .collect();
    support::skyforge_ok(&args, d);
    let o = support::skyforge(
        &["validate", "relnav", "--truth", "pair", "--relnav", "rel"],
        d,
    );
    let err = support::text(&o);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains("no truth of other relative to target"),
        "{err}"
    );
}

/// The receiver's epoch stage (`receive --relnav`) runs the same engines as the files:
/// fed the chaser's file epoch by epoch against the target's file, it gives exactly the
/// estimates `relative_from_files` gives, in every mode (and each vehicle's own satellite
/// sets, whose smoothing runs along whole files, and the relative filter).
#[test]
fn the_epoch_stage_gives_what_the_files_give() {
    use skyforge_navigation::relnav::{RelnavConfig, RelnavStage, relative_from_files};
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    support::skyforge_ok(&["synth", "book-relnav-leo", "--out", "pair"], d);
    let obs = |v: &str| {
        let path = d.join(format!("pair/{v}/observations/ant1.obs.rnx"));
        skyforge_gnss::observation::read_obs_file(&path).unwrap()
    };
    let (target, chaser) = (obs("target"), obs("chaser"));
    let nav = d.join("pair/target/nav.rnx");
    let (ephemerides, iono) =
        skyforge_orbits::ephemeris::rinex_nav::read_nav_file_with_iono(&nav).unwrap();
    for text in [
        "mode = \"position-difference\"",
        "mode = \"carrier-smoothed\"",
        "mode = \"standalone\"",
        "mode = \"carrier-smoothed\"\n[filter]",
        "mode = \"carrier-smoothed\"\nsatellite_sets = \"own\"",
        "mode = \"single-difference\"",
        "mode = \"double-difference\"",
    ] {
        let config = RelnavConfig::parse(&format!("signals = [\"gps-l1ca\"]\n{text}\n")).unwrap();
        let files =
            relative_from_files(&target, &chaser, ephemerides.clone(), &iono, &config).unwrap();
        let mut stage =
            RelnavStage::new(target.clone(), ephemerides.clone(), &iono, &config).unwrap();
        for e in &chaser.epochs {
            stage.epoch(e.time, &e.sats);
        }
        let run = stage.run();
        assert!(files.estimates.len() > 500, "{text}");
        assert_eq!(run.estimates, files.estimates, "{text}");
        assert_eq!(run.missed, files.missed, "{text}");
    }
}
