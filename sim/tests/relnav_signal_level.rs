//! Relative navigation at the signal level: two spacecraft of one scenario
//! (`[[vehicles]]`) rendered as I/Q, each recording received by the bundled receiver, and
//! `skyforge relnav` on the two receivers' RINEX files against the relative truth. Each
//! recording's SigMF metadata names its vehicle. The chaser's receiver also runs the
//! relnav stage (`receive --relnav`) against the target's observations.

mod support;

use std::path::Path;

/// 90 s of GPS L1 C/A at 4 Msps (as interop-leo-gps), today's satellite errors, a TCXO
/// per receiver.
const HEAD: &str = r#"
name = "pair-iq"
seed = 1
[time]
start = "2023-03-12T00:00:00 GPST"
duration_s = 90.0
[gnss.beidou]
enabled = false
[signal]
sample_rate_hz = 4.0e6
if_hz = 0.0
format = "ci8"
bits = 8
cn0_dbhz = 45.0
[errors.satellite]
model = "modern"
[errors.receiver_clock]
preset = "tcxo"
"#;

/// The bundled receiver on `vehicle`'s recording, with `extra` arguments; what it printed.
fn receive(d: &Path, vehicle: &str, extra: &[&str]) -> String {
    let dir = format!("pair/{vehicle}");
    let (meta, nav, config, out) = (
        format!("{dir}/ant1.gps-l1ca.sigmf-meta"),
        format!("{dir}/nav.rnx"),
        format!("{dir}/receiver.toml"),
        format!("rx-{vehicle}"),
    );
    let mut args = vec![
        "receive", &meta, "--assist", &nav, "--config", &config, "--out", &out,
    ];
    args.extend_from_slice(extra);
    support::skyforge_ok(&args, d)
}

/// A chaser 32 km behind the target, each receiver on its own samples: relative DGPS
/// from the receivers' observations within 5 m (3-D RMS, after 30 s of fixes; # assumed
/// bar: the satellites' errors cancel, the two receivers' code noise through the
/// geometry remains) and the separation recovered to 10 m at every epoch.
#[test]
fn two_spacecraft_from_their_samples() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let text = format!(
        "{HEAD}{}{}",
        support::leo_vehicle("target", 0.0),
        support::leo_vehicle("chaser", -0.2667)
    );
    std::fs::write(d.join("pair.toml"), text).unwrap();
    support::skyforge_ok(&["synth", "pair.toml", "--out", "pair"], d);
    // Each recording names its vehicle: with the scenario and its seed, what reproduces it.
    for vehicle in ["target", "chaser"] {
        let meta = support::json_file(&d.join(format!("pair/{vehicle}/ant1.gps-l1ca.sigmf-meta")));
        assert_eq!(meta["global"]["skyforge:vehicle"], vehicle, "{meta}");
        assert_eq!(meta["global"]["skyforge:seed"], 1, "{meta}");
    }
    receive(d, "target", &[]);
    // The chaser's receiver with the relnav stage against the target's observations.
    let printed = receive(d, "chaser", &["--relnav", "rx-target/ant1.obs.rnx"]);
    assert!(printed.contains("position-difference"), "{printed}");
    support::skyforge_ok(
        &[
            "relnav",
            "rx-target/ant1.obs.rnx",
            "rx-chaser/ant1.obs.rnx",
            "--nav",
            "pair/target/nav.rnx",
            "--out",
            "rel",
        ],
        d,
    );
    support::skyforge_ok(
        &[
            "validate",
            "relnav",
            "--truth",
            "pair",
            "--relnav",
            "rel",
            "--settle-s",
            "30",
            "--json",
            "rel.json",
        ],
        d,
    );
    let v = support::json_file(&d.join("rel.json"));
    let rms = v["position_m"]["rms_3d"].as_f64().unwrap();
    let worst = (0..3)
        .map(|i| v["position_m"]["max_abs"][i].as_f64().unwrap())
        .fold(0.0, f64::max);
    let compared = v["compared"].as_u64().unwrap();
    eprintln!(
        "relative DGPS from samples: {rms:.3} m RMS, {worst:.3} m worst axis, {compared} epochs"
    );
    assert!(compared >= 30, "{v}");
    assert!(rms < 5.0, "{v}");
    assert!(worst < 10.0, "{v}");
    // The stage's estimates are the files' within what the RINEX file's rounding of the
    // chaser's observations moves them (bar # assumed: 1 cm).
    let read = |p: &str| skyforge_formats::relative::read_relative_csv(&d.join(p)).unwrap();
    let (stage, files) = (read("rx-chaser/relnav.csv"), read("rel/relnav.csv"));
    assert_eq!(stage.len(), files.len());
    let largest = (stage.iter().zip(&files))
        .map(|(a, b)| (a.position_m - b.position_m).amax())
        .fold(0.0, f64::max);
    eprintln!("relnav stage against the files: {largest:.2e} m at most");
    assert!(largest < 0.01, "{largest} m");
    // Bad input to the stage: one clear error, exit code 2, nothing written.
    std::fs::write(d.join("bad.toml"), "mode = \"kalman\"\n").unwrap();
    let meta = "pair/chaser/ant1.gps-l1ca.sigmf-meta";
    for (extra, expected) in [
        (
            vec!["--relnav", "rx-target/ant1.obs.rnx"],
            "--relnav needs --assist",
        ),
        (
            vec![
                "--assist",
                "pair/chaser/nav.rnx",
                "--relnav",
                "rx-target/ant1.obs.rnx",
                "--relnav-config",
                "bad.toml",
            ],
            "kalman",
        ),
        (
            vec!["--assist", "pair/chaser/nav.rnx", "--relnav", "none.obs"],
            "none.obs",
        ),
    ] {
        let mut args = vec!["receive", meta, "--out", "bad"];
        args.extend(extra);
        let o = support::skyforge(&args, d);
        let err = support::text(&o);
        assert_eq!(o.status.code(), Some(2), "{err}");
        assert!(err.contains(expected), "{err}");
        assert!(!d.join("bad").exists());
    }
}
