//! `skyforge synth --receive`: the receiver reads the samples as they are rendered, with no
//! recording in between. It must see exactly what it would read from the recordings: the
//! same scenario received from the files of `synth` gives byte-identical receiver outputs.
//! Two bands and four antennas exercise the stream's demultiplexing (the synthesiser
//! interleaves eight sources; the receiver reads them in its own rhythm).

mod support;

use std::path::Path;
use support::{skyforge, skyforge_ok, text};

/// Bundled scenario `name` with every `(from, to)` of `edits` replaced (each edit must
/// take), written to `d/file`.
fn edited_scenario(d: &Path, name: &str, edits: &[(&str, &str)], file: &str) {
    let mut scenario = skyforge_ok(&["scenarios", "show", name], d);
    for (from, to) in edits {
        scenario = scenario.replace(from, to);
    }
    assert!(edits.iter().all(|(_, to)| scenario.contains(to)));
    std::fs::write(d.join(file), &scenario).unwrap();
}

#[test]
fn receiving_while_synthesising_gives_what_receiving_the_recordings_gives() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    // assumed: 15 s (two navigation subframes: the receiver times its channels), GPS L1
    // C/A and BeiDou B1I, the lab's four antennas at the signal level.
    edited_scenario(
        d,
        "integrity-lab",
        &[
            ("duration_s = 1800.0", "duration_s = 15.0"),
            ("level = \"observation\"", "level = \"signal\""),
        ],
        "lab.toml",
    );

    let printed = skyforge_ok(&["synth", "lab.toml", "--out", "streamed", "--receive"], d);
    assert!(printed.contains("received as rendered"), "{printed}");
    let streamed = d.join("streamed");
    assert!(
        std::fs::read_dir(&streamed).unwrap().all(|e| !e
            .unwrap()
            .file_name()
            .to_string_lossy()
            .contains("sigmf")),
        "no recording is written"
    );

    skyforge_ok(&["synth", "lab.toml", "--out", "files"], d);
    let mut args = vec!["receive".to_string()];
    for band in ["gps-l1ca", "bds-b1i"] {
        for a in ["A", "B", "C", "D"] {
            args.push(format!("files/{a}.{band}.sigmf-meta"));
        }
    }
    args.extend(
        [
            "--assist",
            "files/nav.rnx",
            "--config",
            "files/receiver.toml",
            "--out",
            "files/receive",
        ]
        .map(String::from),
    );
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    skyforge_ok(&args, d);

    let mut compared = 0;
    for name in [
        "A.obs.rnx",
        "B.obs.rnx",
        "C.obs.rnx",
        "D.obs.rnx",
        "pvt.csv",
        "A.nmea",
    ] {
        let a = std::fs::read(streamed.join("receive").join(name)).unwrap();
        let b = std::fs::read(d.join("files/receive").join(name)).unwrap();
        assert!(
            a == b,
            "receive/{name} differs between streamed and recorded samples"
        );
        compared += a.len();
    }
    let obs = std::fs::read_to_string(streamed.join("receive/C.obs.rnx")).unwrap();
    assert!(
        obs.contains("G") && obs.contains("C0"),
        "both systems observed:\n{obs}"
    );
    assert!(
        compared > 10_000,
        "outputs hold observations ({compared} bytes)"
    );
    // The truth products are those of a plain synth.
    for name in ["nav.rnx", "A.obs.rnx", "receiver.toml", "geometry.toml"] {
        assert_eq!(
            std::fs::read(streamed.join(name)).unwrap(),
            std::fs::read(d.join("files").join(name)).unwrap(),
            "{name}"
        );
    }
}

#[test]
fn a_receiver_that_finds_nothing_fails_the_run_and_nothing_is_written() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    // 8 s at 10 dB-Hz: nothing to detect.
    edited_scenario(
        d,
        "interop-bds-static",
        &[
            ("duration_s = 90.0", "duration_s = 8.0"),
            ("cn0_dbhz = 45.0", "cn0_dbhz = 10.0"),
        ],
        "faint.toml",
    );
    let o = skyforge(&["synth", "faint.toml", "--out", "out", "--receive"], d);
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(text(&o).contains("no signal found"), "{}", text(&o));
    assert!(!d.join("out").exists(), "nothing half-written");

    let lab = skyforge_ok(&["scenarios", "show", "integrity-lab"], d);
    std::fs::write(d.join("obs.toml"), lab).unwrap();
    let o = skyforge(&["synth", "obs.toml", "--out", "out", "--receive"], d);
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(text(&o).contains("--receive needs samples"), "{}", text(&o));
    assert!(!d.join("out").exists());
}
