//! Why BeiDou GEO pseudoranges carry metre-level biases at a static receiver
//! (docs/integrity.md, "What the GEO biases are"): the GEOs cross-correlate with each
//! other. Their relative Doppler is a few mHz and their D2 messages send mostly the same
//! bits in step, so the small cross-correlation of their codes does not average out: it
//! acts as a weak multipath at a fixed delay. Between moving satellites it averages out
//! within a second. The test checks this reading: with all five GEOs, GEO code errors
//! exceed the other satellites'; with C03 the only GEO left, C03's error is like theirs.

mod support;

use support::{json_file, skyforge_ok};

/// PRN and mean pseudorange error (m, relative to the system's satellites) of every
/// satellite the receiver kept, for `interop-bds-static` cut to 30 s with `prns` (all
/// when `None`).
fn code_biases(dir: &std::path::Path, name: &str, prns: Option<&str>) -> Vec<(u32, f64)> {
    let scenario = skyforge_ok(&["scenarios", "show", "interop-bds-static"], dir);
    // assumed: 30 s, long enough for the loops to settle and short enough for the suite.
    let mut short = scenario.replacen("duration_s = 90.0", "duration_s = 30.0", 1);
    if let Some(list) = prns {
        short = short.replacen(
            "embedded_set = \"bds2\"",
            &format!("embedded_set = \"bds2\"\nprns = [{list}]"),
            1,
        );
    }
    assert!(short.contains("duration_s = 30.0"));
    std::fs::write(dir.join(format!("{name}.toml")), short).unwrap();
    skyforge_ok(
        &["synth", &format!("{name}.toml"), "--out", name, "--receive"],
        dir,
    );
    let truth = format!("{name}/ant1.obs.rnx");
    let estimate = format!("{name}/receive/ant1.obs.rnx");
    let json = format!("{name}.json");
    skyforge_ok(
        &[
            "validate",
            "obs",
            "--truth",
            &truth,
            "--estimate",
            &estimate,
            "--json",
            &json,
        ],
        dir,
    );
    json_file(&dir.join(json))["pseudorange_m"]["per_satellite"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| {
            let prn = s["sat"].as_str().unwrap()[1..].parse().unwrap();
            (prn, s["mean"].as_f64().unwrap())
        })
        .collect()
}

/// BeiDou-2 GEOs are PRN 1-5.
fn is_geo(prn: u32) -> bool {
    prn <= 5
}

#[test]
fn geo_code_biases_come_from_the_other_geos() {
    let tmp = tempfile::tempdir().unwrap();
    let all = code_biases(tmp.path(), "all", None);
    let worst = |pick: fn(u32) -> bool, v: &[(u32, f64)]| {
        v.iter()
            .filter(|(p, _)| pick(*p))
            .map(|(_, b)| b.abs())
            .fold(0.0, f64::max)
    };
    let geo = worst(is_geo, &all);
    let other = worst(|p| !is_geo(p), &all);
    assert_eq!(all.iter().filter(|(p, _)| is_geo(*p)).count(), 5, "{all:?}");
    assert!(
        geo > 0.4 && other < 0.3,
        "GEO {geo} m, others {other} m: {all:?}"
    );

    let alone = code_biases(tmp.path(), "alone", Some("3, 6, 7, 9, 10, 12, 14, 16"));
    let c03 = alone.iter().find(|(p, _)| *p == 3).expect("C03 tracked").1;
    assert!(c03.abs() < 0.25, "C03 alone: {c03} m: {alone:?}");
}
