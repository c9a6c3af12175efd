//! Galileo through the CLI: `run` writes its satellites into the truth, `synth` says
//! plainly that Galileo signals are not synthesised yet (exit 2, nothing written).

mod support;

use skyforge_formats::truth::TruthFile;

/// The bundled static ground site with `[gnss.galileo]`, `duration_s` long.
fn scenario(dir: &std::path::Path, duration_s: f64, signal: bool) -> String {
    let text = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../scenarios/bundled/ground-static.toml"),
    )
    .expect("bundled scenario");
    let mut text = text
        .replacen(
            "[platform.ground]",
            "[gnss.galileo]\n\n[platform.ground]",
            1,
        )
        .replacen(
            "duration_s = 3600.0",
            &format!("duration_s = {duration_s}"),
            1,
        );
    if signal {
        text.push_str("\n[signal]\nsample_rate_hz = 20.46e6\nformat = \"ci8\"\ncn0_dbhz = 45.0\n");
    }
    let path = dir.join("galileo.toml");
    std::fs::write(&path, text).expect("write scenario");
    path.to_string_lossy().into_owned()
}

#[test]
fn run_writes_galileo_truth() {
    let dir = tempfile::tempdir().expect("tempdir");
    let path = scenario(dir.path(), 600.0, false);
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
fn synth_refuses_galileo_until_its_signals_exist() {
    let dir = tempfile::tempdir().expect("tempdir");
    let path = scenario(dir.path(), 2.0, true);
    let out = dir.path().join("out");
    let o = support::skyforge(
        &["synth", &path, "--out", out.to_str().unwrap()],
        dir.path(),
    );
    assert_eq!(o.status.code(), Some(2), "{}", support::text(&o));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("gnss.galileo") && err.contains("not synthesised yet"),
        "{err}"
    );
    assert!(!out.exists(), "synth left {}", out.display());
}
