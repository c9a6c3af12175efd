//! End-to-end tests of the `skyforge` binary.

mod support;

use std::path::Path;
use std::process::Command;
use support::{
    RAW_CI8_4MSPS_GPS, dataset, h5_contents, results_file, results_json, short_scenario, skyforge,
    text,
};

#[test]
fn run_writes_truth_h5_with_the_documented_schema() {
    let tmp = tempfile::tempdir().unwrap();
    let scenario = short_scenario(tmp.path(), "thesis-leo", 120);
    let o = skyforge(
        &[
            "run",
            scenario.to_str().unwrap(),
            "--out",
            "out",
            "--seed",
            "7",
        ],
        tmp.path(),
    );
    assert!(o.status.success(), "{}", text(&o));
    assert!(text(&o).contains("mean visible"));

    let file = hdf5::File::open(tmp.path().join("out/truth.h5")).unwrap();
    assert_eq!(file.attr("seed").unwrap().read_scalar::<u64>().unwrap(), 7);
    let t: Vec<f64> = dataset(&file, "time/t_s");
    assert_eq!(t.len(), 121);
    assert_eq!((t[0], t[120]), (0.0, 120.0));
    let r = file.dataset("platform/r_ecef_m").unwrap();
    assert_eq!(r.shape(), vec![121, 3]);
    let r: Vec<f64> = r.read_raw().unwrap();
    let radius = (r[0] * r[0] + r[1] * r[1] + r[2] * r[2]).sqrt();
    // Osculating a = 6971.593 km, e = 0.000846: the radius lies within a(1 +/- e).
    assert!(
        (radius - 6_971_593.0).abs() < 6_971_593.0 * 0.000846 + 1.0,
        "radius {radius}"
    );
    let n_sat = file.dataset("satellites/id").unwrap().shape()[0];
    assert!(n_sat > 50, "GPS + BeiDou satellites: {n_sat}");
    for ant in ["ant1", "ant2", "ant3"] {
        let g = file.group(&format!("antennas/{ant}")).unwrap();
        let visible = g.dataset("visible").unwrap();
        assert_eq!(visible.shape(), vec![121, n_sat]);
        let visible: Vec<u8> = visible.read_raw().unwrap();
        let range = g.dataset("range_m").unwrap();
        let units: hdf5::types::VarLenUnicode = range.attr("units").unwrap().read_scalar().unwrap();
        assert_eq!(units.as_str(), "m");
        let range: Vec<f64> = range.read_raw().unwrap();
        let epochs: Vec<u32> = dataset(&g, "epoch_index");
        let sats: Vec<u16> = dataset(&g, "sat_index");
        // One value per visible link, in row-major order of the mask.
        let expected: Vec<(u32, u16)> = (0..121u32)
            .flat_map(|k| (0..n_sat as u16).map(move |s| (k, s)))
            .filter(|&(k, s)| visible[k as usize * n_sat + s as usize] == 1)
            .collect();
        assert_eq!(
            epochs
                .iter()
                .copied()
                .zip(sats.iter().copied())
                .collect::<Vec<_>>(),
            expected
        );
        assert_eq!(range.len(), expected.len());
        assert!(range.iter().all(|r| (1.9e7..4.8e7).contains(r)));
        let per_epoch = expected.len() as f64 / 121.0;
        assert!(
            (4.0..40.0).contains(&per_epoch),
            "{ant}: {per_epoch} visible per epoch"
        );
    }
}

#[test]
fn a_bad_scenario_exits_2_names_the_place_and_writes_nothing() {
    let tmp = tempfile::tempdir().unwrap();
    let scenario = short_scenario(tmp.path(), "thesis-leo", 60);
    let text_in = std::fs::read_to_string(&scenario).unwrap();
    let line = text_in
        .lines()
        .find(|l| l.trim_start().starts_with("eccentricity"))
        .unwrap();
    std::fs::write(&scenario, text_in.replacen(line, "eccentricity = 1.5", 1)).unwrap();
    let o = skyforge(&["run", "short.toml", "--out", "out"], tmp.path());
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    let msg = text(&o);
    let line_no = text_in.lines().position(|l| l == line).unwrap() + 1;
    assert!(msg.contains(&format!("short.toml:{line_no}:")), "{msg}");
    assert!(msg.contains("eccentricity") && msg.contains("1.5"), "{msg}");
    assert!(!tmp.path().join("out").exists());
    assert_eq!(
        std::fs::read_dir(tmp.path()).unwrap().count(),
        1,
        "stray files"
    );
}

#[test]
fn an_existing_output_needs_force_and_force_replaces_only_what_skyforge_wrote() {
    let tmp = tempfile::tempdir().unwrap();
    let scenario = short_scenario(tmp.path(), "thesis-leo", 10);
    let scenario = scenario.to_str().unwrap();
    let run = |out: &str, force: bool| {
        let mut args = vec!["run", scenario, "--out", out];
        if force {
            args.push("--force");
        }
        skyforge(&args, tmp.path())
    };
    // A directory of the user's: refused without --force and with it.
    std::fs::create_dir(tmp.path().join("mine")).unwrap();
    std::fs::write(tmp.path().join("mine/keep.txt"), "x").unwrap();
    for force in [false, true] {
        let o = run("mine", force);
        assert_eq!(o.status.code(), Some(2), "{}", text(&o));
        assert!(tmp.path().join("mine/keep.txt").exists());
    }
    // SkyForge's own output: replaced with --force.
    assert!(run("out", false).status.success());
    let o = run("out", false);
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    let o = run("out", true);
    assert!(o.status.success(), "{}", text(&o));
    assert!(tmp.path().join("out/truth.h5").exists());
    // ... unless something else was put into it.
    std::fs::write(tmp.path().join("out/notes.txt"), "mine").unwrap();
    let o = run("out", true);
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(text(&o).contains("notes.txt"), "{}", text(&o));
    assert!(tmp.path().join("out/notes.txt").exists());
}

/// `--force` on `.`, `..` or `dir/.` (issue #11: these deleted the working directory's or
/// the parent's contents) is refused with nothing deleted.
#[test]
fn force_never_replaces_dot_dot_dot_or_a_parent() {
    let tmp = tempfile::tempdir().unwrap();
    let work = tmp.path().join("work");
    std::fs::create_dir_all(work.join("victim")).unwrap();
    std::fs::write(tmp.path().join("sibling.txt"), "x").unwrap();
    std::fs::write(work.join("victim/data.txt"), "x").unwrap();
    let scenario = short_scenario(&work, "thesis-leo", 10);
    for out in [
        ".",
        "..",
        "victim/.",
        "victim/..",
        tmp.path().to_str().unwrap(),
    ] {
        let o = skyforge(
            &["run", scenario.to_str().unwrap(), "--out", out, "--force"],
            &work,
        );
        assert_eq!(o.status.code(), Some(2), "--out {out}: {}", text(&o));
        assert!(tmp.path().join("sibling.txt").exists(), "--out {out}");
        assert!(work.join("victim/data.txt").exists(), "--out {out}");
        assert!(scenario.exists(), "--out {out}");
    }
}

#[test]
fn scenarios_list_and_show() {
    let tmp = tempfile::tempdir().unwrap();
    let o = skyforge(&["scenarios", "list"], tmp.path());
    assert!(o.status.success());
    for name in [
        "thesis-leo",
        "thesis/v-1.2.1",
        "thesis/t-3.2",
        "ground-static",
    ] {
        assert!(text(&o).contains(name), "{name} missing from {}", text(&o));
    }
    let o = skyforge(&["scenarios", "show", "no-such"], tmp.path());
    assert_eq!(o.status.code(), Some(2));
    assert!(text(&o).contains("thesis-leo"));
}

#[test]
fn validate_thesis_writes_every_row_of_both_tables() {
    let tmp = tempfile::tempdir().unwrap();
    // A file of a bundled table scenario's name in the working directory is not read.
    std::fs::create_dir(tmp.path().join("thesis")).unwrap();
    std::fs::write(tmp.path().join("thesis/t-3.2"), "not a scenario").unwrap();
    let o = skyforge(
        &[
            "validate",
            "thesis",
            "--only",
            "V-1.2.1",
            "--only",
            "T-3.2",
            "--out",
            "v",
            "--data",
            "no-data-here",
        ],
        tmp.path(),
    );
    assert!(o.status.success(), "{}", text(&o));
    let rows = results_json(&tmp.path().join("v"));
    let count = |table: &str| rows.iter().filter(|r| r["table"] == table).count();
    // V-1.2.1: GPS, BD, GPS+BD x (max, min, mean) with BDS-3, plus BD and GPS+BD with BDS-2.
    assert_eq!(count("V-1.2.1"), 15);
    // T-3.2: 25 components, 2 dynamics rows, 20 totals.
    assert_eq!(count("T-3.2"), 47);
    for r in &rows {
        for key in [
            "table",
            "row",
            "quantity",
            "unit",
            "thesis",
            "ours",
            "tolerance",
            "verdict",
            "note",
        ] {
            assert!(r.get(key).is_some(), "{key} missing in {r}");
        }
        assert!(["reproduced", "deviates", "explained"].contains(&r["verdict"].as_str().unwrap()));
    }
    // The component values are formulas of the thesis: all of them must match.
    for r in rows
        .iter()
        .filter(|r| r["quantity"] == "phase error component")
    {
        assert_eq!(r["verdict"], "reproduced", "{r}");
    }
    // The provenance: the commit, no plan, the bundled scenarios' text.
    let file = results_file(&tmp.path().join("v"));
    let p = &file["provenance"];
    let commit = p["commit"].as_str().unwrap();
    assert!(
        commit == "unknown"
            || (commit.len() == 40 && commit.chars().all(|c| c.is_ascii_hexdigit())),
        "{commit}"
    );
    assert!(p["plan"].is_null());
    assert_eq!(p["tables"], serde_json::json!(["V-1.2.1", "T-3.2"]));
    // Neither table computes a thesis figure: no curves.json.
    assert!(!tmp.path().join("v/curves.json").exists());
    let names: Vec<&str> = p["scenarios"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| s["name"].as_str().unwrap())
        .collect();
    assert_eq!(names, ["thesis/v-1.2.1", "thesis/t-3.2"]);
    for s in p["scenarios"].as_array().unwrap() {
        assert_eq!(s["origin"], "bundled");
        assert!(s["text"].as_str().unwrap().contains("[time]"), "{s}");
    }
    let o = skyforge(&["validate", "thesis", "--only", "T-9.9"], tmp.path());
    assert_eq!(o.status.code(), Some(2));
    // --seed-base needs --seeds; --seeds 0 is refused.
    for args in [&["--seed-base", "3"][..], &["--seeds", "0"]] {
        let mut all = vec!["validate", "thesis", "--only", "T-3.2"];
        all.extend_from_slice(args);
        let o = skyforge(&all, tmp.path());
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", text(&o));
    }
}

#[test]
fn validate_thesis_over_seeds_gives_each_row_its_draws() {
    let tmp = tempfile::tempdir().unwrap();
    let o = skyforge(
        &[
            "validate",
            "thesis",
            "--only",
            "T-3.3-S",
            "--only",
            "T-3.2",
            "--seeds",
            "3",
            "--seed-base",
            "5",
            "--out",
            "v",
        ],
        tmp.path(),
    );
    assert!(o.status.success(), "{}", text(&o));
    let file = results_file(&tmp.path().join("v"));
    assert_eq!(
        file["provenance"]["plan"],
        serde_json::json!({"draws": 3, "base": 5})
    );
    let rows = file["rows"].as_array().unwrap();
    let mut per_run = 0;
    for r in rows {
        if r["table"] == "T-3.2" {
            assert!(r.get("over_seeds").is_none(), "{r}");
            assert!(
                r["note"].as_str().unwrap().starts_with("no random draw"),
                "{r}"
            );
            continue;
        }
        let over = &r["over_seeds"];
        assert_eq!(over["draws"], 3, "{r}");
        assert_eq!(over["base"], 5, "{r}");
        let f = over["in_tolerance"].as_f64().unwrap();
        let verdict = r["verdict"].as_str().unwrap();
        assert_eq!(verdict == "reproduced", f >= 0.5, "{r}");
        if let Some(ours) = r["ours"].as_f64() {
            assert_eq!(ours, over["mean"].as_f64().unwrap(), "{r}");
            let (lo, hi) = (over["min"].as_f64().unwrap(), over["max"].as_f64().unwrap());
            assert!(lo <= ours && ours <= hi, "{r}");
        }
        per_run += 1;
    }
    assert!(per_run > 10, "{per_run} rows of T-3.3-S");
    // T-3.3-S's figures 3.3-10/3.3-11 (on the registered seed, a unit test checks).
    let curves: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(tmp.path().join("v/curves.json")).unwrap())
            .unwrap();
    let figures: Vec<&str> = curves["curves"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| c["figure"].as_str().unwrap())
        .collect();
    assert_eq!(figures, ["3.3-10", "3.3-10", "3.3-11", "3.3-11"]);
    assert!(text(&o).contains("curves.json"), "{}", text(&o));
    // The printed table shows each row's fraction of draws in tolerance.
    assert!(text(&o).contains(" of 3"), "{}", text(&o));
    // Two runs side by side (here the same twice: every row agrees with itself).
    let o = skyforge(&["validate", "agree", "v", "v/results.json"], tmp.path());
    assert!(o.status.success(), "{}", text(&o));
    assert!(
        text(&o).contains(&format!("{per_run} rows over seeds in both;"))
            && text(&o).contains("0 of them with other verdicts"),
        "{}",
        text(&o)
    );
    let o = skyforge(&["validate", "agree", "v", "nowhere"], tmp.path());
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(text(&o).contains("nowhere"), "{}", text(&o));
}

#[test]
fn synthesis_is_bit_identical_for_any_thread_count_and_chunk_size_and_follows_the_seed() {
    let tmp = tempfile::tempdir().unwrap();
    short_scenario(tmp.path(), "interop-gps-static", 3);
    let run = |threads: &str, seed: &str, out: &str, chunk: &str| {
        let o = Command::new(env!("CARGO_BIN_EXE_skyforge"))
            .args(["synth", "short.toml", "--out", out, "--seed", seed])
            .args(["--chunk-epochs", chunk])
            .env("RAYON_NUM_THREADS", threads)
            .current_dir(tmp.path())
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", text(&o));
    };
    run("1", "5", "one", "10");
    run("2", "5", "two", "10");
    run("2", "5", "chunk1", "1");
    run("1", "5", "chunk2", "2");
    run("2", "6", "other", "10");
    let names: Vec<String> = std::fs::read_dir(tmp.path().join("one"))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    assert!(
        names.iter().any(|n| n.ends_with(".sigmf-data")) && names.iter().any(|n| n == "truth.h5")
    );
    for name in &names {
        let a = std::fs::read(tmp.path().join("one").join(name)).unwrap();
        for (other, what) in [
            ("two", "1 and 2 threads"),
            ("chunk1", "chunks of 10 and 1 epochs"),
            ("chunk2", "chunks of 10 and 2 epochs"),
        ] {
            let path = tmp.path().join(other).join(name);
            if name == "truth.h5" && other != "two" {
                // HDF5 places chunks in the order they were written: equal content,
                // different bytes. Compare every dataset instead.
                let (x, y) = (
                    h5_contents(&tmp.path().join("one").join(name)),
                    h5_contents(&path),
                );
                assert!(!x.is_empty() && x == y, "{name} differs between {what}");
            } else {
                let b = std::fs::read(path).unwrap();
                assert!(a == b, "{name} differs between {what}");
            }
        }
    }
    let meta: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(tmp.path().join("one/ant1.gps-l1ca.sigmf-meta")).unwrap(),
    )
    .unwrap();
    // 2023-03-12T00:00:00 GPST is 18 s earlier in UTC.
    assert_eq!(
        meta["captures"][0]["core:datetime"],
        "2023-03-11T23:59:42.000000000Z"
    );
    assert_eq!(meta["global"]["core:datatype"], "ci8");
    assert_eq!(meta["captures"][0]["core:frequency"], 1575.42e6);
    let a = std::fs::read(tmp.path().join("one/ant1.gps-l1ca.sigmf-data")).unwrap();
    let c = std::fs::read(tmp.path().join("other/ant1.gps-l1ca.sigmf-data")).unwrap();
    assert_eq!(a.len(), 3 * 4_000_000 * 2);
    assert!(a != c, "a different seed must give different noise");
}

#[test]
fn synthesis_writes_signal_truth_at_one_kilohertz() {
    let tmp = tempfile::tempdir().unwrap();
    short_scenario(tmp.path(), "interop-gps-static", 2);
    let o = skyforge(&["synth", "short.toml", "--out", "out"], tmp.path());
    assert!(o.status.success(), "{}", text(&o));
    let file = hdf5::File::open(tmp.path().join("out/truth.h5")).unwrap();
    let g = file.group("antennas/ant1").unwrap();
    let s = g.group("signal").unwrap();
    let t: Vec<f64> = dataset(&s, "t_s");
    let sat: Vec<u16> = dataset(&s, "sat_index");
    let pr: Vec<f64> = dataset(&s, "pseudorange_m");
    let phase: Vec<f64> = dataset(&s, "carrier_phase_cycles");
    let iono: Vec<f64> = dataset(&s, "iono_m");
    let tropo: Vec<f64> = dataset(&s, "tropo_m");
    // A site at 50 m under the default Saastamoinen troposphere: 2.3 m at the zenith, about
    // 25 m at 5 deg.
    assert!(
        tropo.iter().all(|&d| (2.2..30.0).contains(&d)),
        "tropo {:?}",
        &tropo[..3]
    );
    // A ground site under the default Klobuchar ionosphere: metres of delay.
    assert!(
        iono.iter().all(|&i| (0.5..50.0).contains(&i)),
        "iono {:?}",
        &iono[..3]
    );
    // Geometry at 1 Hz: the links visible at t = 0 and 1 s.
    let epochs: Vec<u32> = dataset(&g, "epoch_index");
    let gsat: Vec<u16> = dataset(&g, "sat_index");
    let range: Vec<f64> = dataset(&g, "range_m");
    let clock: Vec<f64> = dataset(&g, "sat_clock_s");
    let links_at = |k: u32| epochs.iter().filter(|&&e| e == k).count();
    // One record per visible link and millisecond of [0, 2) s.
    assert_eq!(t.len(), 1000 * (links_at(0) + links_at(1)));
    let lambda = 299_792_458.0 / 1575.42e6;
    for (i, (&ti, &si)) in t.iter().zip(&sat).enumerate() {
        // Code delayed, carrier advanced by the ionosphere; every other term (troposphere
        // here) is common to both.
        assert!((phase[i] * lambda - (pr[i] - 2.0 * iono[i])).abs() < 1e-6);
        if ti == 1.0 {
            let j = (0..epochs.len())
                .find(|&j| epochs[j] == 1 && gsat[j] == si)
                .unwrap();
            let expected = range[j] - 299_792_458.0 * clock[j] + iono[i] + tropo[i];
            assert!((pr[i] - expected).abs() < 1e-6, "{} vs {expected}", pr[i]);
        }
    }
}

#[test]
fn link_budget_and_per_antenna_clocks_reach_the_signal_truth() {
    let tmp = tempfile::tempdir().unwrap();
    let path = short_scenario(tmp.path(), "interop-gps-static", 1);
    let extra = "\n[[antennas]]\nname = \"ant2\"\nposition_body_m = [0.0, 0.0, 0.0]\n\
                 boresight_body = [0.0, 0.0, -1.0]\nelevation_mask_deg = 5.0\n\n\
                 [signal.link_budget]\nsystem_noise_temperature_k = 290.0\n\n\
                 [errors.receiver_clock]\npreset = \"tcxo\"\nbias_s = 2e-4\nper_antenna = true\n";
    let toml = std::fs::read_to_string(&path).unwrap() + extra;
    std::fs::write(&path, toml).unwrap();
    let o = skyforge(&["synth", "short.toml", "--out", "out"], tmp.path());
    assert!(o.status.success(), "{}", text(&o));
    let file = hdf5::File::open(tmp.path().join("out/truth.h5")).unwrap();
    let read = |ant: &str, name: &str| -> Vec<f64> {
        dataset(&file, &format!("antennas/{ant}/signal/{name}"))
    };
    // C/N0 from the budget: default GPS EIRP, free-space loss over the link's range,
    // 0 dBi (no gain pattern), kT at 290 K.
    let eirp = skyforge_signals::errors::default_gps_eirp_dbw();
    let k_t = 10.0 * (1.380_649e-23f64 * 290.0).log10();
    let (pr, cn0, rx, sat_clock, iono, tropo) = (
        read("ant1", "pseudorange_m"),
        read("ant1", "cn0_dbhz"),
        read("ant1", "rx_clock_m"),
        read("ant1", "sat_clock_m"),
        read("ant1", "iono_m"),
        read("ant1", "tropo_m"),
    );
    let lambda = 299_792_458.0 / 1575.42e6;
    for i in 0..pr.len() {
        let range = pr[i] - rx[i] + sat_clock[i] - iono[i] - tropo[i];
        let fspl = 20.0 * (4.0 * std::f64::consts::PI * range / lambda).log10();
        let expected = eirp - fspl - k_t;
        assert!((cn0[i] - expected).abs() < 0.01, "{} vs {expected}", cn0[i]);
    }
    // Ranges of 20 200 km (zenith) to 25 200 km (5 deg): 47.4 to 45.5 dB-Hz.
    let (lo, hi) = cn0
        .iter()
        .fold((f64::MAX, f64::MIN), |(l, h), c| (l.min(*c), h.max(*c)));
    assert!(lo > 45.3 && hi < 47.5, "C/N0 {lo}..{hi}");
    // Two independent oscillators started at the same bias: equal at t = 0, apart later;
    // each shared by all satellites of its antenna.
    let (t1, t2, rx2) = (
        read("ant1", "t_s"),
        read("ant2", "t_s"),
        read("ant2", "rx_clock_m"),
    );
    let at = |t: &[f64], rx: &[f64], when: f64| -> Vec<f64> {
        t.iter()
            .zip(rx)
            .filter(|(t, _)| **t == when)
            .map(|(_, r)| *r)
            .collect()
    };
    let (a0, b0) = (at(&t1, &rx, 0.0), at(&t2, &rx2, 0.0));
    assert!((a0[0] - 2e-4 * 299_792_458.0).abs() < 1e-9 && (b0[0] - a0[0]).abs() < 1e-9);
    let (a, b) = (at(&t1, &rx, 0.999), at(&t2, &rx2, 0.999));
    assert!(a.iter().all(|x| *x == a[0]) && b.iter().all(|x| *x == b[0]));
    assert!(
        a[0] != b[0],
        "independent oscillators: {} vs {}",
        a[0],
        b[0]
    );
}

/// A reflecting surface of the scenario reaches the signal truth through the body geometry:
/// a ground plane 1.5 m below a static antenna (body = NED at zero attitude) reflects each
/// satellite with the textbook extra path 2 h sin(elevation), and the truth's multipath
/// errors follow from that path by the closed forms of a two-path channel, computed here
/// from the elevation alone.
#[test]
fn ground_plane_surface_multipath_reaches_the_signal_truth() {
    let tmp = tempfile::tempdir().unwrap();
    let path = short_scenario(tmp.path(), "interop-gps-static", 1);
    let (h, a, phase_deg): (f64, f64, f64) = (1.5, 0.4, 180.0);
    let extra = format!(
        "\n[[errors.multipath.surfaces]]\nname = \"ground\"\npoint_body_m = [0.0, 0.0, {h}]\n\
         normal_body = [0.0, 0.0, -1.0]\nreflection_coefficient = {a}\nphase_deg = {phase_deg}\n"
    );
    let toml = std::fs::read_to_string(&path).unwrap() + &extra;
    std::fs::write(&path, toml).unwrap();
    let o = skyforge(&["synth", "short.toml", "--out", "out"], tmp.path());
    assert!(o.status.success(), "{}", text(&o));
    let file = hdf5::File::open(tmp.path().join("out/truth.h5")).unwrap();
    let f64s = |name: &str| -> Vec<f64> { dataset(&file, name) };
    let u16s = |name: &str| -> Vec<u16> { dataset(&file, name) };
    let u32s = |name: &str| -> Vec<u32> { dataset(&file, name) };
    // Elevation of each satellite at t = 0 (geometry epoch 0).
    let (epoch, sat, el) = (
        u32s("antennas/ant1/epoch_index"),
        u16s("antennas/ant1/sat_index"),
        f64s("antennas/ant1/elevation_rad"),
    );
    let el0: std::collections::HashMap<u16, f64> = (0..epoch.len())
        .filter(|&k| epoch[k] == 0)
        .map(|k| (sat[k], el[k]))
        .collect();
    let (t, sig_sat, code, carrier) = (
        f64s("antennas/ant1/signal/t_s"),
        u16s("antennas/ant1/signal/sat_index"),
        f64s("antennas/ant1/signal/multipath_code_m"),
        f64s("antennas/ant1/signal/multipath_carrier_m"),
    );
    let lambda = 299_792_458.0 / 1575.42e6;
    let chip_m = 299_792_458.0 / 1.023e6;
    let mut checked = 0;
    for k in (0..t.len()).filter(|&k| t[k] == 0.0) {
        let e = el0[&sig_sat[k]];
        let delay = 2.0 * h * e.sin();
        // Relative phase of the reflected path: the surface's shift, minus the carrier
        // phase of the extra path.
        let theta = phase_deg.to_radians() - std::f64::consts::TAU * delay / lambda;
        // Carrier: the prompt correlator on the direct path sees the reflection at the
        // C/A correlation triangle, a (1 - delay / chip); the composite phasor
        // 1 + a' e^{j theta} lags the direct one by its argument (a range error).
        let a_prompt = a * (1.0 - delay / chip_m);
        let expected_carrier = -(a_prompt * theta.sin()).atan2(1.0 + a_prompt * theta.cos())
            * lambda
            / std::f64::consts::TAU;
        // Non-coherent early-minus-late DLL, delay << chip: delay (a^2 + a cos) / |1 + a e^j|^2.
        let expected_code =
            delay * (a * a + a * theta.cos()) / (1.0 + a * a + 2.0 * a * theta.cos());
        assert!(
            (carrier[k] - expected_carrier).abs() < 1e-6,
            "el {:.1} deg: carrier {} m, two-path {} m",
            e.to_degrees(),
            carrier[k],
            expected_carrier
        );
        assert!(
            (code[k] - expected_code).abs() < 1e-3 * delay,
            "el {:.1} deg: code {} m, two-path {} m",
            e.to_degrees(),
            code[k],
            expected_code
        );
        checked += 1;
    }
    assert!(checked >= 8, "only {checked} links at t = 0");
}

/// A short GPS recording: synth `interop-gps-static` shortened to `duration_s` into
/// `dir/sim`.
fn short_gps_recording(dir: &Path, duration_s: u32) {
    let scenario = short_scenario(dir, "interop-gps-static", duration_s);
    let o = skyforge(&["synth", scenario.to_str().unwrap(), "--out", "sim"], dir);
    assert!(o.status.success(), "{}", text(&o));
}

/// `receive <inputs> --assist sim/nav.rnx --out rx` in `dir` on a 15 s `interop-gps-static`
/// recording: the 11 satellites above the mask at 45 dB-Hz are tracked and timed by a
/// subframe, and fixes are written. Returns the command's output.
fn receive_tracks_all_and_fixes(dir: &Path, inputs: &[&str]) -> String {
    let mut args = vec!["receive"];
    args.extend_from_slice(inputs);
    args.extend_from_slice(&["--assist", "sim/nav.rnx", "--out", "rx"]);
    let o = skyforge(&args, dir);
    let out = text(&o);
    assert!(o.status.success(), "{out}");
    assert!(out.contains("tracked 11"), "{out}");
    let fixes = std::fs::read_to_string(dir.join("rx/pvt.csv")).unwrap();
    assert!(fixes.lines().count() >= 3, "{out}\n{fixes}");
    out
}

#[test]
fn receive_tracks_decodes_and_fixes_on_a_short_recording() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path();
    short_gps_recording(dir, 15);
    let out = receive_tracks_all_and_fixes(dir, &["sim/ant1.gps-l1ca.sigmf-meta"]);
    let rinex = std::fs::read_to_string(dir.join("rx/ant1.obs.rnx")).unwrap();
    let epochs = rinex.lines().filter(|l| l.starts_with('>')).count();
    assert!(epochs >= 2, "{epochs} epochs:\n{out}");
    assert!(rinex.contains("SKYFORGE RECEIVER"));
    assert!(dir.join("rx/receiver.h5").is_file() && dir.join("rx/ant1.nmea").is_file());
}

/// `bytes` bytes of noise (a multiplicative hash of the index) as `dir/noise.bin`.
fn write_noise(dir: &Path, bytes: u32) -> Vec<u8> {
    let noise: Vec<u8> = (0..bytes)
        .map(|i| (i.wrapping_mul(2_654_435_761) >> 24) as u8)
        .collect();
    std::fs::write(dir.join("noise.bin"), &noise).unwrap();
    noise
}

/// `receive` with `args` in `dir` must exit 2 with a message containing every `needle`
/// and leave no output directory.
fn receive_refuses(dir: &Path, args: &[&str], needles: &[&str]) {
    let mut all = vec!["receive"];
    all.extend_from_slice(args);
    all.extend_from_slice(&["--out", "rx"]);
    let o = skyforge(&all, dir);
    let out = text(&o);
    assert_eq!(o.status.code(), Some(2), "{out}");
    for n in needles {
        assert!(out.contains(n), "missing {n:?} in:\n{out}");
    }
    assert!(!out.contains("panicked"), "{out}");
    assert!(!dir.join("rx").exists(), "output written:\n{out}");
}

#[test]
fn receive_refuses_bad_input_with_one_message_and_writes_nothing() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path();
    // Noise only: no satellite anywhere.
    let noise = write_noise(dir, 800_000);
    let mut args = vec!["noise.bin"];
    args.extend_from_slice(&RAW_CI8_4MSPS_GPS);
    receive_refuses(dir, &args, &["no signal found", "noise.bin", "searches"]);
    // Too short for one search.
    std::fs::write(dir.join("short.bin"), &noise[..1000]).unwrap();
    let mut args = vec!["short.bin"];
    args.extend_from_slice(&RAW_CI8_4MSPS_GPS);
    receive_refuses(dir, &args, &["500 common samples", "a search needs"]);
    // A raw file without its description.
    receive_refuses(dir, &["noise.bin"], &["noise.bin", "--format"]);
    // A missing file, an unknown signal, a bad configuration value and field.
    receive_refuses(
        dir,
        &["gone.sigmf-meta"],
        &["gone.sigmf-meta", "no such file"],
    );
    let mut args = vec!["noise.bin"];
    args.extend_from_slice(&["--format", "ci8", "--fs", "4e6", "--signal", "gal-e6"]);
    receive_refuses(dir, &args, &["--signal", "gal-e6", "gps-l1ca, bds-b1i"]);
    // A signal SkyForge knows from observation files but does not track.
    let mut args = vec!["noise.bin"];
    args.extend_from_slice(&["--format", "ci8", "--fs", "4e6", "--signal", "gps-l2"]);
    receive_refuses(
        dir,
        &args,
        &["--signal gps-l2", "not received", "gps-l1ca, bds-b1i"],
    );
    std::fs::write(dir.join("rx.toml"), "[observables]\nrate_hz = 500.0\n").unwrap();
    let mut args = vec!["noise.bin", "--config", "rx.toml"];
    args.extend_from_slice(&RAW_CI8_4MSPS_GPS);
    receive_refuses(
        dir,
        &args,
        &["rx.toml", "observables.rate_hz", "500", "[1, 100] Hz"],
    );
    std::fs::write(dir.join("rx.toml"), "[tracking]\npll_bw = 5.0\n").unwrap();
    receive_refuses(dir, &args, &["rx.toml", "line 2", "pll_bw"]);
}

#[test]
fn receive_refuses_recordings_that_do_not_share_a_sample_clock() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path();
    short_gps_recording(dir, 1);
    // A second antenna's recording at another sample rate.
    let meta = std::fs::read_to_string(dir.join("sim/ant1.gps-l1ca.sigmf-meta")).unwrap();
    let other = meta
        .replace("\"ant1\"", "\"ant2\"")
        .replace("4000000.0", "2000000.0");
    assert_ne!(meta, other);
    std::fs::write(dir.join("sim/ant2.gps-l1ca.sigmf-meta"), other).unwrap();
    std::fs::copy(
        dir.join("sim/ant1.gps-l1ca.sigmf-data"),
        dir.join("sim/ant2.gps-l1ca.sigmf-data"),
    )
    .unwrap();
    receive_refuses(
        dir,
        &[
            "sim/ant1.gps-l1ca.sigmf-meta",
            "sim/ant2.gps-l1ca.sigmf-meta",
        ],
        &["ant2", "2000000", "4000000"],
    );
}

/// A raw file as gps-sdr-sim writes one (16-bit I/Q at 2.6 Msps, no metadata): described on
/// the command line, tracked and decoded like a SigMF recording.
#[test]
fn receive_reads_a_raw_ci16_file_at_2_6_msps() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path();
    let scenario = short_scenario(dir, "interop-gps-static", 15);
    let toml = std::fs::read_to_string(&scenario)
        .unwrap()
        .replacen("sample_rate_hz = 4.0e6", "sample_rate_hz = 2.6e6", 1)
        .replacen("format = \"ci8\"", "format = \"ci16\"", 1)
        .replacen("bits = 8", "bits = 16", 1);
    std::fs::write(&scenario, toml).unwrap();
    let o = skyforge(&["synth", scenario.to_str().unwrap(), "--out", "sim"], dir);
    assert!(o.status.success(), "{}", text(&o));
    std::fs::rename(
        dir.join("sim/ant1.gps-l1ca.sigmf-data"),
        dir.join("capture.bin"),
    )
    .unwrap();
    receive_tracks_all_and_fixes(
        dir,
        &[
            "capture.bin",
            "--format",
            "ci16",
            "--fs",
            "2.6e6",
            "--signal",
            "gps-l1ca",
        ],
    );
}

/// The configuration example in docs/receiver.md is a valid receiver configuration: the
/// run gets past it and stops only because the file holds no signal.
#[test]
fn the_documented_receiver_configuration_is_accepted() {
    let doc = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/../docs/receiver.md"))
        .unwrap();
    let start = doc.find("```toml\n").expect("a toml block") + "```toml\n".len();
    let end = start + doc[start..].find("```").expect("its end");
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path();
    std::fs::write(dir.join("receiver.toml"), &doc[start..end]).unwrap();
    write_noise(dir, 400_000);
    let mut args = vec!["noise.bin", "--config", "receiver.toml"];
    args.extend_from_slice(&RAW_CI8_4MSPS_GPS);
    receive_refuses(dir, &args, &["no signal found"]);
}
