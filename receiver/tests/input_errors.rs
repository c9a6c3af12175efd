//! Every way input can be wrong ends in a message that says exactly what is wrong (or, when
//! reading can work around it, a finding in the report), never a panic.

use proptest::prelude::*;
use serde_json::{Value, json};
use skyforge_receiver::input::{BlockReader, Finding, InputError, InputParams, Recording};
use std::path::{Path, PathBuf};

/// SigMF metadata as SkyForge writes it (ci8, 4.092 Msps, GPS L1 at baseband).
fn meta_json(antenna: &str) -> Value {
    json!({
        "global": {
            "core:datatype": "ci8",
            "core:sample_rate": 4.092e6,
            "core:version": "1.0.0",
            "core:num_channels": 1,
            "core:extensions": [{"name": "skyforge", "version": "1.0.0", "optional": true}],
            "skyforge:antenna": antenna,
            "skyforge:antenna_position_body_m": [0.0, 0.0, 0.0],
            "skyforge:if_hz": 0.0,
        },
        "captures": [{
            "core:sample_start": 0,
            "core:frequency": 1575.42e6,
            "core:datetime": "2023-03-12T00:00:00.000000000Z",
        }],
        "annotations": [],
    })
}

/// Writes `<dir>/<antenna>.sigmf-meta` and `n_bytes` bytes of samples (byte k = k mod 251);
/// returns the metadata path.
fn write(dir: &Path, antenna: &str, meta: &Value, n_bytes: usize) -> PathBuf {
    let data: Vec<u8> = (0..n_bytes).map(|k| (k % 251) as u8).collect();
    std::fs::write(dir.join(format!("{antenna}.sigmf-data")), data).unwrap();
    let path = dir.join(format!("{antenna}.sigmf-meta"));
    std::fs::write(&path, meta.to_string()).unwrap();
    path
}

fn open(path: &Path) -> Result<Recording, InputError> {
    Recording::open(path, &InputParams::default())
}

fn err(r: Result<Recording, InputError>) -> String {
    r.unwrap_err().to_string()
}

fn open_reader(recs: &[Recording]) -> String {
    BlockReader::open(recs, 4092).unwrap_err().to_string()
}

#[test]
fn missing_and_unreadable_files_are_named() {
    let dir = tempfile::tempdir().unwrap();
    let p = dir.path().join("nothere.sigmf-meta");
    assert_eq!(err(open(&p)), format!("{}: no such file", p.display()));
    // Metadata without its data file: found when the reader opens it.
    let meta = write(dir.path(), "a", &meta_json("a"), 0);
    std::fs::remove_file(dir.path().join("a.sigmf-data")).unwrap();
    let rec = open(&meta).unwrap();
    assert_eq!(
        open_reader(&[rec]),
        format!(
            "{}: no such file",
            dir.path().join("a.sigmf-data").display()
        )
    );
    // A directory where the metadata should be: unreadable, with the system's reason.
    let d = dir.path().join("b.sigmf-meta");
    std::fs::create_dir(&d).unwrap();
    let e = err(open(&d));
    assert!(
        e.starts_with(&format!("{}: cannot read: ", d.display())),
        "{e}"
    );
    // Not JSON; JSON without "global".
    let bad = dir.path().join("c.sigmf-meta");
    std::fs::write(&bad, "{ not json").unwrap();
    let e = err(open(&bad));
    assert!(
        e.starts_with(&format!(
            "{}: not SigMF metadata: invalid JSON: ",
            bad.display()
        )),
        "{e}"
    );
    std::fs::write(&bad, "[1, 2]").unwrap();
    assert_eq!(
        err(open(&bad)),
        format!(
            "{}: not SigMF metadata: no \"global\" object",
            bad.display()
        )
    );
}

#[test]
fn metadata_without_required_fields_names_the_field() {
    let dir = tempfile::tempdir().unwrap();
    for (key, why) in [
        ("core:datatype", "the sample format; or give --format"),
        (
            "core:sample_rate",
            "the receiver needs the sample rate; or give --fs",
        ),
    ] {
        let mut m = meta_json("a");
        m["global"].as_object_mut().unwrap().remove(key);
        let p = write(dir.path(), "a", &m, 8);
        assert_eq!(
            err(open(&p)),
            format!(
                "{}: the metadata has no global {key} (required: {why})",
                p.display()
            )
        );
    }
    // The command line can supply what is missing.
    let rec = Recording::open(
        &dir.path().join("a.sigmf-data"),
        &InputParams {
            sample_rate_hz: Some(2e6),
            ..InputParams::default()
        },
    )
    .unwrap();
    assert_eq!(rec.sample_rate_hz, 2e6);
}

#[test]
fn bad_field_values_say_what_was_expected() {
    let dir = tempfile::tempdir().unwrap();
    let cases: [(&str, &str, Value, String); 6] = [
        (
            "global",
            "core:datatype",
            json!("ci16_be"),
            "unknown sample datatype \"ci16_be\"; allowed: ci8, ci16_le (or ci16), cf32_le (or cf32), ri8 (all little-endian)".into(),
        ),
        (
            "global",
            "core:sample_rate",
            json!("fast"),
            "global core:sample_rate is \"fast\"; expected a number".into(),
        ),
        (
            "global",
            "core:num_channels",
            json!(2),
            "global core:num_channels is 2; expected 1 (multi-channel datasets are not supported: give one file per antenna)".into(),
        ),
        (
            "capture",
            "core:datetime",
            json!("12/03/2023"),
            "captures[] core:datetime is \"12/03/2023\"; expected an ISO-8601 UTC time such as 2023-03-12T00:00:00.000Z".into(),
        ),
        (
            "capture",
            "core:sample_start",
            json!(-4),
            "captures[] core:sample_start is -4; expected a non-negative integer".into(),
        ),
        (
            "global",
            "core:sample_rate",
            json!(-1.0),
            "the sample rate (core:sample_rate or --fs) is -1; expected a positive number of samples per second".into(),
        ),
    ];
    for (section, key, value, want) in cases {
        let mut m = meta_json("a");
        match section {
            "global" => m["global"][key] = value,
            _ => m["captures"][0][key] = value,
        }
        let p = write(dir.path(), "a", &m, 8);
        assert_eq!(err(open(&p)), format!("{}: {want}", p.display()));
    }
}

#[test]
fn unknown_command_line_values_list_the_allowed_ones() {
    let e = skyforge_receiver::input::parse_format("i8", "--format").unwrap_err();
    assert_eq!(
        e.to_string(),
        "--format: unknown sample datatype \"i8\"; allowed: ci8, ci16_le (or ci16), cf32_le (or cf32), ri8 (all little-endian)"
    );
    let dir = tempfile::tempdir().unwrap();
    let raw = dir.path().join("x.bin");
    std::fs::write(&raw, [0u8; 8]).unwrap();
    assert_eq!(
        err(open(&raw)),
        format!(
            "{}: not a .sigmf-meta/.sigmf-data recording; a raw sample file needs --format and --fs (and --if, --signal)",
            raw.display()
        )
    );
    // Real samples need an IF inside Nyquist.
    let params = InputParams {
        format: Some(skyforge_receiver::input::parse_format("ri8", "--format").unwrap()),
        sample_rate_hz: Some(4e6),
        ..InputParams::default()
    };
    assert_eq!(
        err(Recording::open(&raw, &params)),
        format!(
            "{}: the IF (skyforge:if_hz, carrier - core:frequency, or --if) is 0; expected 0 < IF < 2000000 Hz for real (ri8) samples: give --if",
            raw.display()
        )
    );
    let params = InputParams {
        if_hz: Some(2.5e6),
        ..params
    };
    assert_eq!(
        err(Recording::open(&raw, &params)),
        format!(
            "{}: the IF (skyforge:if_hz, carrier - core:frequency, or --if) is 2500000; expected |IF| < fs / 2 = 2000000 Hz",
            raw.display()
        )
    );
}

#[test]
fn antennas_that_cannot_share_a_clock_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let a = open(&write(dir.path(), "a", &meta_json("a"), 80)).unwrap();
    // Each antenna differs from `a` in one way: (name, edit of its metadata, the refusal).
    type Edit = fn(&mut Value);
    let cases: [(&str, Edit, &str); 4] = [
        (
            "b",
            |m| m["global"]["core:sample_rate"] = json!(4.0e6),
            "is sampled at 4000000 Hz but antenna a at 4092000 Hz: all antennas must share one sample clock",
        ),
        (
            "c",
            |m| m["global"]["core:datatype"] = json!("ci16_le"),
            "holds ci16_le samples but antenna a holds ci8: all antennas must use one datatype",
        ),
        (
            "d",
            |m| {
                m["global"]["skyforge:if_hz"] = json!(1000.0);
                m["captures"][0]["core:frequency"] = json!(1575.42e6 - 1000.0);
            },
            "has the signal at IF 1000 Hz but antenna a at 0 Hz: complex recordings processed together must share one IF",
        ),
        (
            "e",
            |m| m["captures"][0]["core:frequency"] = json!(1561.098e6),
            "records bds-b1i but antenna a records gps-l1ca: process one band per run",
        ),
    ];
    for (name, edit, refusal) in cases {
        let mut m = meta_json(name);
        edit(&mut m);
        let other = open(&write(dir.path(), name, &m, 80)).unwrap();
        let data = dir.path().join(format!("{name}.sigmf-data"));
        assert_eq!(
            open_reader(&[a.clone(), other]),
            format!("antenna {name} ({}) {refusal}", data.display())
        );
    }
    assert_eq!(open_reader(&[]), "no sample files given");
}

#[test]
fn truncated_and_short_files_are_reported_and_the_common_part_is_read() {
    let dir = tempfile::tempdir().unwrap();
    let data = |n: &str| dir.path().join(format!("{n}.sigmf-data"));
    // Issue #11: 1000 samples + 1 stray byte was read with the byte dropped silently.
    let odd = open(&write(dir.path(), "odd", &meta_json("odd"), 2001)).unwrap();
    assert_eq!(
        open_reader(&[odd]),
        format!(
            "{} (antenna odd): 2001 bytes of samples are not a whole number of ci8 samples (2 bytes each): 1 byte(s) after the last whole sample (a truncated or corrupted file)",
            data("odd").display()
        )
    );
    // a: 1000 samples; b: 600 samples.
    let a = open(&write(dir.path(), "a", &meta_json("a"), 2000)).unwrap();
    let b = open(&write(dir.path(), "b", &meta_json("b"), 1200)).unwrap();
    let (mut reader, report) = BlockReader::open(&[a, b], 256).unwrap();
    assert_eq!(report.common_samples, 600);
    assert_eq!(
        report.findings,
        [Finding::Shorter {
            antenna: "b".into(),
            path: data("b"),
            missing_samples: 400,
            missing_s: 400.0 / 4.092e6,
            longest: "a".into(),
            common_samples: 600,
        },]
    );
    assert_eq!(
        report.findings[0].to_string(),
        format!(
            "antenna b ({}) is {} samples ({} s) shorter than antenna a's file: only the 600 samples all files share are processed",
            data("b").display(),
            400,
            400.0 / 4.092e6
        )
    );
    let text = report.to_string();
    assert!(
        text.starts_with(&format!(
            "2 antenna(s), GPS L1 C/A, 4092000 samples/s: 600 common samples ({} s)\n  first sample at ",
            600.0 / 4.092e6
        )),
        "{text}"
    );
    for f in &report.findings {
        assert!(text.contains(&format!("\n  note: {f}\n")), "{text}");
    }
    let mut bufs = reader.buffers();
    let mut total = 0;
    while let Some(block) = reader.read_block(&mut bufs).unwrap() {
        total += block.len;
        // Both files hold the same byte pattern, so the antennas agree sample by sample.
        assert_eq!(bufs[0], bufs[1]);
    }
    assert_eq!(total, 600);
    // A file without a whole sample, and a file that shrinks while being read.
    let c = open(&write(dir.path(), "c", &meta_json("c"), 0)).unwrap();
    assert_eq!(
        open_reader(&[c]),
        format!(
            "no samples to process: antenna c ({}) holds no whole sample",
            data("c").display()
        )
    );
    // d: 500 000 samples, cut to 50 bytes after the first block (whatever the reader had
    // buffered still arrives; then the cut is found).
    let d = open(&write(dir.path(), "d", &meta_json("d"), 1_000_000)).unwrap();
    let (mut reader, _) = BlockReader::open(&[d], 4092).unwrap();
    let mut bufs = reader.buffers();
    reader.read_block(&mut bufs).unwrap();
    std::fs::File::options()
        .write(true)
        .open(data("d"))
        .unwrap()
        .set_len(50)
        .unwrap();
    let failed_at = loop {
        let at = reader.position();
        match reader.read_block(&mut bufs) {
            Ok(Some(_)) => assert!(at < 500_000),
            Ok(None) => panic!("the cut was not noticed"),
            Err(e) => break (at, e.to_string()),
        }
    };
    assert_eq!(
        failed_at.1,
        format!(
            "{}: ended in the block starting at sample {} of the 500000 to be read (the file shrank while being read)",
            data("d").display(),
            failed_at.0
        )
    );
    assert_eq!(
        reader.read_block(&mut []).unwrap_err().to_string(),
        "0 block buffers given for 1 antennas"
    );
}

#[test]
fn start_times_and_global_indices_align_the_antennas() {
    let dir = tempfile::tempdir().unwrap();
    // b starts 100 samples (100 / 4.092 MHz) after a: a's first 100 samples are skipped,
    // so byte pattern offsets line up with b's.
    let a = open(&write(dir.path(), "a", &meta_json("a"), 2000)).unwrap();
    let mut m = meta_json("b");
    m["captures"][0]["core:datetime"] = json!("2023-03-12T00:00:00.000024438Z");
    let b = open(&write(dir.path(), "b", &m, 2000)).unwrap();
    let (mut reader, report) = BlockReader::open(&[a.clone(), b], 64).unwrap();
    assert_eq!(report.antennas[0].skipped_samples, 100);
    assert_eq!(report.common_samples, 900);
    assert_eq!(
        report.findings[0].to_string(),
        format!(
            "antenna a ({}) starts 100 samples ({} s) before the latest-starting file: its first 100 samples are skipped to align the antennas",
            dir.path().join("a.sigmf-data").display(),
            100.0 / 4.092e6
        )
    );
    // a starts earlier with as many samples, so it also ends earlier.
    assert_eq!(
        report.findings[1],
        Finding::Shorter {
            antenna: "a".into(),
            path: dir.path().join("a.sigmf-data"),
            missing_samples: 100,
            missing_s: 100.0 / 4.092e6,
            longest: "b".into(),
            common_samples: 900,
        }
    );
    // 24.438 us is 99.9997 samples: whole within the tolerance, so no fractional finding.
    assert_eq!(report.findings.len(), 2);
    let mut bufs = reader.buffers();
    reader.read_block(&mut bufs).unwrap();
    // Byte k = k mod 251: a's first delivered sample holds bytes 200, 201; b's 0, 1.
    assert_eq!(bufs[0][0].re * 128.0, f32::from(200u8 as i8));
    assert_eq!(bufs[1][0].re * 128.0, 0.0);
    // Global indices win over times: c is 10 samples behind a.
    let with_index = |name: &str, index: u64| {
        let mut m = meta_json(name);
        m["captures"][0]["core:global_index"] = json!(index);
        open(&write(dir.path(), name, &m, 2000)).unwrap()
    };
    let (a, c) = (with_index("a2", 5), with_index("c", 15));
    let (_, report) = BlockReader::open(&[a, c], 64).unwrap();
    assert_eq!(report.antennas[0].skipped_samples, 10);
    assert_eq!(report.antennas[1].skipped_samples, 0);
    // Unknown start on one antenna only: said so.
    let mut m = meta_json("e");
    m["captures"][0]
        .as_object_mut()
        .unwrap()
        .remove("core:datetime");
    let e = open(&write(dir.path(), "e", &m, 2000)).unwrap();
    let (_, report) = BlockReader::open(&[a_clone(&dir), e], 64).unwrap();
    assert_eq!(
        report.findings[0].to_string(),
        "antennas e give no start time or global sample index: all files are assumed to start at the same sample"
    );
}

#[test]
fn header_bytes_sample_start_and_trailing_bytes_are_skipped() {
    let dir = tempfile::tempdir().unwrap();
    let mut m = meta_json("h");
    m["captures"][0]["core:header_bytes"] = json!(3);
    m["captures"][0]["core:sample_start"] = json!(10);
    m["global"]["core:trailing_bytes"] = json!(5);
    // 3 header bytes, 100 samples, 5 trailing bytes: 90 samples from byte 3 + 20.
    let rec = open(&write(dir.path(), "h", &m, 3 + 200 + 5)).unwrap();
    let (mut reader, report) = BlockReader::open(&[rec], 1000).unwrap();
    assert!(report.findings.is_empty(), "{report}");
    assert_eq!(report.common_samples, 90);
    let mut bufs = reader.buffers();
    let block = reader.read_block(&mut bufs).unwrap().unwrap();
    assert_eq!(block.len, 90);
    // Byte k = k mod 251.
    for (j, v) in bufs[0].iter().enumerate() {
        let k = 23 + 2 * j;
        assert_eq!(v.re * 128.0, f32::from(k as u8 as i8));
        assert_eq!(v.im * 128.0, f32::from((k + 1) as u8 as i8));
    }
    assert_eq!(reader.read_block(&mut bufs).unwrap(), None);
}

fn a_clone(dir: &tempfile::TempDir) -> Recording {
    open(&dir.path().join("a.sigmf-meta")).unwrap()
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// Arbitrary bytes as metadata and as samples: errors or findings, never a panic.
    #[test]
    fn arbitrary_files_never_panic(
        meta in prop::collection::vec(any::<u8>(), 0..300),
        data in prop::collection::vec(any::<u8>(), 0..300),
    ) {
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(dir.path().join("x.sigmf-meta"), &meta).unwrap();
        std::fs::write(dir.path().join("x.sigmf-data"), &data).unwrap();
        let _ = open(&dir.path().join("x.sigmf-meta"));
        let rec = open(&write(dir.path(), "y", &meta_json("y"), 0)).unwrap();
        std::fs::write(dir.path().join("y.sigmf-data"), &data).unwrap();
        if let Ok((mut reader, _)) = BlockReader::open(&[rec], 7) {
            let mut bufs = reader.buffers();
            while reader.read_block(&mut bufs).unwrap().is_some() {}
        }
    }

    /// Metadata whose fields have arbitrary JSON values: errors, never a panic.
    #[test]
    fn arbitrary_field_values_never_panic(
        key in prop::sample::select(vec![
            "core:datatype", "core:sample_rate", "core:num_channels", "skyforge:if_hz",
            "skyforge:antenna", "skyforge:antenna_position_body_m", "core:trailing_bytes",
        ]),
        capture_key in prop::sample::select(vec![
            "core:sample_start", "core:frequency", "core:datetime", "core:global_index",
            "core:header_bytes",
        ]),
        value in prop_oneof![
            any::<f64>().prop_map(|x| json!(x)),
            any::<i64>().prop_map(|x| json!(x)),
            ".{0,12}".prop_map(|s| json!(s)),
            Just(json!(null)),
            Just(json!([1, "a"])),
            Just(json!(u64::MAX)),
        ],
    ) {
        let dir = tempfile::tempdir().unwrap();
        for (k, section) in [(key, "global"), (capture_key, "captures")] {
            let mut m = meta_json("z");
            match section {
                "global" => m["global"][k] = value.clone(),
                _ => m["captures"][0][k] = value.clone(),
            }
            let p = write(dir.path(), "z", &m, 64);
            if let Ok(rec) = open(&p)
                && let Ok((mut reader, _)) = BlockReader::open(&[rec], 5)
            {
                let mut bufs = reader.buffers();
                while let Ok(Some(_)) = reader.read_block(&mut bufs) {}
            }
        }
    }
}
