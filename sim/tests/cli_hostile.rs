//! Issue #11's reproductions, each run under a 4 GB address-space limit (`ulimit -v`):
//! --force on directories SkyForge did not write, antenna names that would become paths,
//! absurd sizes (part 1-3), and truncated or garbage input read as data (part 5). Each
//! gives one clear message (naming the file where there is one), exit code 2, and nothing
//! written (no output directory, no staging directory, no parent directory the run
//! created).

mod support;

use skyforge_orbits::fixtures::RINEX3_GPS_NAV;
use std::path::Path;
use support::{
    MEMORY_LIMIT_BYTES, RAW_CI8_4MSPS_GPS, listing, short_scenario, skyforge, skyforge_limited,
    text,
};

/// `receive` of the raw recording `noise.bin` (4 Msps ci8 GPS L1 C/A).
fn receive_noise() -> Vec<&'static str> {
    [&["receive", "noise.bin"][..], &RAW_CI8_4MSPS_GPS].concat()
}

/// `skyforge args` in `dir`, under the 4 GB address-space limit, must exit 2 with one
/// `error:` message holding every needle and leave `dir` as it was.
fn refused(dir: &Path, args: &[&str], needles: &[&str]) -> String {
    let before = listing(dir);
    let o = skyforge_limited(args, dir, MEMORY_LIMIT_BYTES);
    let out = text(&o);
    assert_eq!(o.status.code(), Some(2), "{args:?}:\n{out}");
    assert_eq!(
        out.matches("error:").count(),
        1,
        "{args:?}: one message:\n{out}"
    );
    for n in needles {
        assert!(out.contains(n), "{args:?}: missing {n:?} in:\n{out}");
    }
    assert_eq!(listing(dir), before, "{args:?} wrote something:\n{out}");
    out
}

/// A 2 s `interop-gps-static` recording in `dir/sim` (4 Msps ci8, 16 MB): long enough to
/// track, too short to decode a subframe.
fn two_second_recording(dir: &Path) {
    let scenario = short_scenario(dir, "interop-gps-static", 2);
    let o = skyforge(&["synth", scenario.to_str().unwrap(), "--out", "sim"], dir);
    assert!(o.status.success(), "{}", text(&o));
    std::fs::remove_file(scenario).unwrap();
}

/// A copy of the recording's metadata with `core:datetime` replaced (`None`: removed) as
/// `dir/sim/<name>.sigmf-meta`, its data a copy of the first `bytes` bytes.
fn edited_copy(dir: &Path, name: &str, datetime: Option<&str>, bytes: usize) -> String {
    let sim = dir.join("sim");
    let meta = std::fs::read_to_string(sim.join("ant1.gps-l1ca.sigmf-meta")).unwrap();
    let mut json: serde_json::Value = serde_json::from_str(&meta).unwrap();
    let capture = json["captures"][0].as_object_mut().unwrap();
    match datetime {
        Some(t) => capture.insert("core:datetime".into(), t.into()),
        None => capture.remove("core:datetime"),
    };
    json["global"]["skyforge:antenna"] = name.into();
    std::fs::write(sim.join(format!("{name}.sigmf-meta")), json.to_string()).unwrap();
    let data = std::fs::read(sim.join("ant1.gps-l1ca.sigmf-data")).unwrap();
    std::fs::write(sim.join(format!("{name}.sigmf-data")), &data[..bytes]).unwrap();
    format!("sim/{name}.sigmf-meta")
}

/// Before: exit 0 and an output directory with 0 epochs for a recording too short for a
/// subframe (whole, 100 ms, half of it), one without `core:datetime`, random bytes; an odd
/// trailing byte dropped silently; a 1900 or 9999 `core:datetime` gave epochs in 1899.
#[test]
fn recordings_without_an_epoch_or_with_partial_samples_write_nothing() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path();
    two_second_recording(dir);
    let whole = 16_000_000;
    let no_epoch = [
        "no observation epoch",
        "0 timed",
        "subframe",
        "What was read",
    ];
    refused(
        dir,
        &["receive", "sim/ant1.gps-l1ca.sigmf-meta", "--out", "rx"],
        &no_epoch,
    );
    for (name, datetime, bytes) in [
        ("ms100", Some("2023-03-11T23:59:42Z"), 800_000),
        ("half", Some("2023-03-11T23:59:42Z"), whole / 2),
        ("undated", None, whole),
    ] {
        let meta = edited_copy(dir, name, datetime, bytes);
        let out = refused(dir, &["receive", &meta, "--out", "rx"], &[]);
        assert!(
            out.contains("no observation epoch") || out.contains("no signal found"),
            "{name}: {out}"
        );
    }
    // An odd trailing byte: the file, its size and the sample size.
    let meta = edited_copy(dir, "odd", Some("2023-03-11T23:59:42Z"), whole / 2 + 1);
    refused(
        dir,
        &["receive", &meta, "--out", "rx"],
        &[
            "odd.sigmf-data",
            "8000001 bytes",
            "ci8 samples (2 bytes each)",
            "1 byte(s) after the last whole sample",
        ],
    );
    // Start times out of the supported range.
    for t in [
        "1900-01-01T00:00:00Z",
        "9999-12-31T00:00:00Z",
        "1980-01-05T23:59:59Z",
    ] {
        let meta = edited_copy(dir, "dated", Some(t), 800_000);
        refused(
            dir,
            &["receive", &meta, "--out", "rx"],
            &[
                "dated.sigmf-meta",
                "core:datetime",
                t,
                "1980-01-06",
                "2100-01-01",
            ],
        );
    }
    // Random bytes, raw: whatever the acquisition makes of them, no epoch.
    let mut x: u64 = 0x9E37_79B9_7F4A_7C15;
    let noise: Vec<u8> = (0..whole)
        .map(|_| {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            (x >> 56) as u8
        })
        .collect();
    std::fs::write(dir.join("random.bin"), &noise).unwrap();
    let mut args = vec!["receive", "random.bin", "--out", "rx"];
    args.extend_from_slice(&RAW_CI8_4MSPS_GPS);
    let out = refused(dir, &args, &["random.bin"]);
    assert!(
        out.contains("no observation epoch") || out.contains("no signal found"),
        "{out}"
    );
    // A ci16 file of an odd length.
    std::fs::write(dir.join("odd16.bin"), &noise[..4001]).unwrap();
    let args = [
        "receive",
        "odd16.bin",
        "--format",
        "ci16",
        "--fs",
        "4e6",
        "--signal",
        "gps-l1ca",
        "--out",
        "rx",
    ];
    refused(
        dir,
        &args,
        &["odd16.bin", "4001 bytes", "ci16_le samples (4 bytes each)"],
    );
}

/// Before: `--out a/b/c` left `a/` and `a/b/` behind when the run failed after staging.
/// Only the parents the run created go, and only when empty.
#[test]
fn a_failed_run_removes_the_parent_directories_it_created() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path();
    two_second_recording(dir);
    std::fs::create_dir(dir.join("keep")).unwrap();
    for out in ["a/b/c", "keep/x/y"] {
        refused(
            dir,
            &["receive", "sim/ant1.gps-l1ca.sigmf-meta", "--out", out],
            &["no observation epoch"],
        );
    }
    assert!(dir.join("keep").is_dir());
    assert!(listing(&dir.join("keep")).is_empty());
}

/// Before: a navigation file cut inside a record was read with its missing fields as 0
/// (`run` and `receive --assist` accepted it, `synth` failed with exit 1 and the message
/// twice, without file or line); `/dev/zero` or a directory was "does not exist".
#[test]
fn a_cut_navigation_file_a_directory_and_a_device_are_refused_everywhere() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path();
    let cut = RINEX3_GPS_NAV.trim_end().rsplit_once('\n').unwrap().0;
    std::fs::write(dir.join("cut.rnx"), cut).unwrap();
    std::fs::create_dir(dir.join("navdir")).unwrap();
    // The recording for `receive --assist`: noise, as the navigation file is read first.
    std::fs::write(dir.join("noise.bin"), vec![0u8; 400_000]).unwrap();
    let o = skyforge(&["scenarios", "show", "interop-gps-static"], dir);
    let scenario = String::from_utf8(o.stdout).unwrap();
    let scenario = scenario
        .replace(
            "source = \"embedded\"",
            "source = \"rinex\"\nnav_file = \"NAV\"",
        )
        .replace("2023-03-12T00:00:00 GPST", "2022-01-01T00:30:00 GPST")
        .replace("duration_s = 90.0", "duration_s = 1.0");
    for (nav, says) in [
        ("cut.rnx", "cut.rnx:9: record cut short: it has 7 lines"),
        ("navdir", "is a directory, not a navigation file"),
        ("/dev/zero", "more than 256 MiB: not a navigation file"),
    ] {
        std::fs::write(dir.join("s.toml"), scenario.replace("NAV", nav)).unwrap();
        for command in ["run", "synth"] {
            refused(
                dir,
                &[command, "s.toml", "--out", "out"],
                &["s.toml:", "gnss.gps.nav_file", says],
            );
        }
        let args = [&receive_noise()[..], &["--assist", nav, "--out", "rx"]].concat();
        let out = refused(dir, &args, &[says]);
        assert!(!out.contains("does not exist"), "{out}");
    }
}

/// Parts 1-3: `--force` on `.`, `..` and `victim/.`; antenna names that would become
/// paths; a sample rate of 1e15 Hz (option and SigMF), a 1 MHz PLL, `--assist /dev/zero`.
#[test]
fn force_names_and_sizes_are_refused_under_the_memory_limit() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("work");
    std::fs::create_dir(&dir).unwrap();
    two_second_recording(&dir);
    let scenario = short_scenario(&dir, "interop-gps-static", 1);
    std::fs::create_dir(dir.join("victim")).unwrap();
    std::fs::write(dir.join("victim/keep.txt"), "not skyforge's").unwrap();
    let s = scenario.to_str().unwrap();
    let above = listing(tmp.path());
    for out in [".", "..", "victim/."] {
        refused(&dir, &["run", s, "--out", out, "--force"], &["--force"]);
    }
    assert_eq!(listing(tmp.path()), above);
    assert_eq!(listing(&dir.join("victim")), ["keep.txt"]);
    let toml = std::fs::read_to_string(&scenario).unwrap();
    for name in ["../prev/ant1", "/tmp/skyforge-absolute", "two\\nlines"] {
        let named = toml.replacen("name = \"ant1\"", &format!("name = \"{name}\""), 1);
        std::fs::write(dir.join("named.toml"), named).unwrap();
        refused(
            &dir,
            &["synth", "named.toml", "--out", "out"],
            &["antennas[0].name"],
        );
        std::fs::remove_file(dir.join("named.toml")).unwrap();
    }
    assert!(!Path::new("/tmp/skyforge-absolute").exists());
    let raw = [
        "receive",
        "sim/ant1.gps-l1ca.sigmf-data",
        "--format",
        "ci8",
        "--signal",
        "gps-l1ca",
    ];
    refused(
        &dir,
        &[&raw[..], &["--fs", "1e15", "--out", "rx"]].concat(),
        &["sample rate"],
    );
    std::fs::write(
        dir.join("wide.toml"),
        "[tracking]\npll_bandwidth_hz = 1e6\n",
    )
    .unwrap();
    let wide = [
        &raw[..],
        &["--fs", "4e6", "--config", "wide.toml", "--out", "rx"],
    ]
    .concat();
    refused(&dir, &wide, &["wide.toml: tracking.pll_bandwidth_hz"]);
    std::fs::remove_file(dir.join("wide.toml")).unwrap();
    let assisted = [
        &raw[..],
        &["--fs", "4e6", "--assist", "/dev/zero", "--out", "rx"],
    ]
    .concat();
    refused(&dir, &assisted, &["/dev/zero", "256 MiB"]);
    let meta = std::fs::read_to_string(dir.join("sim/ant1.gps-l1ca.sigmf-meta")).unwrap();
    let mut json: serde_json::Value = serde_json::from_str(&meta).unwrap();
    json["global"]["core:sample_rate"] = 1e20.into();
    std::fs::write(dir.join("sim/ant1.gps-l1ca.sigmf-meta"), json.to_string()).unwrap();
    refused(
        &dir,
        &["receive", "sim/ant1.gps-l1ca.sigmf-meta", "--out", "rx"],
        &["sample rate"],
    );
}

/// Every kind of input file is read with a size limit: `/dev/zero` given as a scenario, a
/// SigMF metadata file, a receiver or attitude configuration, a geometry file or RINEX
/// observations is refused once its limit is passed (before: read until memory ran out),
/// and a directory is named as one.
#[test]
fn devices_and_directories_are_refused_as_every_kind_of_input() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path();
    let zero = |name: &str| std::os::unix::fs::symlink("/dev/zero", dir.join(name)).unwrap();
    for name in [
        "s.toml",
        "z.sigmf-meta",
        "z.obs.rnx",
        "geometry.toml",
        "config.toml",
    ] {
        zero(name);
    }
    std::fs::create_dir(dir.join("d.toml")).unwrap();
    refused(
        dir,
        &["run", "s.toml", "--out", "out"],
        &["s.toml", "more than 1 MiB: not a scenario file"],
    );
    refused(
        dir,
        &["run", "d.toml", "--out", "out"],
        &["is a directory, not a scenario file"],
    );
    refused(
        dir,
        &["receive", "z.sigmf-meta", "--out", "rx"],
        &[
            "z.sigmf-meta",
            "more than 16 MiB: not a SigMF metadata file",
        ],
    );
    std::fs::write(dir.join("noise.bin"), vec![0u8; 400_000]).unwrap();
    let raw = receive_noise();
    refused(
        dir,
        &[&raw[..], &["--config", "config.toml", "--out", "rx"]].concat(),
        &["config.toml", "not a receiver configuration"],
    );
    let attitude = [
        "attitude",
        "z.obs.rnx",
        "z.obs.rnx",
        "--nav",
        "d.toml",
        "--out",
        "att",
    ];
    refused(
        dir,
        &[&attitude[..], &["--geometry", "geometry.toml"]].concat(),
        &["geometry.toml"],
    );
    let obs = [
        "validate",
        "obs",
        "--truth",
        "z.obs.rnx",
        "--estimate",
        "z.obs.rnx",
    ];
    refused(dir, &obs, &["z.obs.rnx"]);
}

/// Issue #33 (13): `--seed-base 18446744073709551615` gave no draw and exit 0 with no
/// row; a plan past the largest offset is refused before any table runs.
#[test]
fn a_seed_plan_past_the_largest_offset_is_refused() {
    let tmp = tempfile::tempdir().unwrap();
    for (seeds, base) in [("1", "18446744073709551615"), ("2", "9999")] {
        refused(
            tmp.path(),
            &[
                "validate",
                "thesis",
                "--only",
                "T-3.2",
                "--seeds",
                seeds,
                "--seed-base",
                base,
            ],
            &[
                &format!("--seeds {seeds} --seed-base {base}"),
                "seed-base + seeds <= 10000",
            ],
        );
    }
}

/// Issue #33 (14): these exited 1, and the SigMF antenna names with a message naming
/// neither the file nor the key; each is the user's input: exit 2, the file and the field
/// named, nothing written.
#[test]
fn bad_input_beyond_the_scenario_exits_2_naming_the_file_and_field() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    two_second_recording(d);
    let sim = d.join("sim");
    std::fs::hard_link(
        sim.join("ant1.gps-l1ca.sigmf-data"),
        sim.join("x.sigmf-data"),
    )
    .unwrap();
    std::fs::hard_link(sim.join("ant1.gps-l1ca.sigmf-data"), d.join("raw.bin")).unwrap();
    let meta: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(sim.join("ant1.gps-l1ca.sigmf-meta")).unwrap(),
    )
    .unwrap();
    let long = "a".repeat(10_000);
    for name in ["../../evil", "/abs", "a/b", "", ".", &long, "a\0b", "a\nb"] {
        let mut json = meta.clone();
        json["global"]["skyforge:antenna"] = name.into();
        std::fs::write(sim.join("x.sigmf-meta"), json.to_string()).unwrap();
        refused(
            d,
            &["receive", "sim/x.sigmf-meta", "--out", "rx"],
            &[
                "sim/x.sigmf-meta: global skyforge:antenna is",
                "an antenna name",
            ],
        );
    }

    // A sample rate out of the receiver's range names the file and the key.
    let mut json = meta.clone();
    json["global"]["core:sample_rate"] = 1e15.into();
    std::fs::write(sim.join("x.sigmf-meta"), json.to_string()).unwrap();
    refused(
        d,
        &["receive", "sim/x.sigmf-meta", "--out", "rx"],
        &["sim/x.sigmf-meta: the sample rate (core:sample_rate or --fs) is 1000000000000000 Hz"],
    );

    // A negative IF is a value (clap read it as an option), checked against the rate.
    refused(
        d,
        &[
            "receive", "raw.bin", "--format", "ci8", "--fs", "4e6", "--signal", "gps-l1ca", "--if",
            "-3e6", "--out", "rx",
        ],
        &["--if", "-3000000", "fs / 2"],
    );

    // An orbit that decays during the run: the scenario's platform.leo, located.
    let scenario = short_scenario(d, "thesis-leo", 3000);
    let text = std::fs::read_to_string(&scenario).unwrap();
    let decaying = text
        .replace(
            "semi_major_axis_km = 6971.593",
            "semi_major_axis_km = 6528.137",
        )
        .replace("eccentricity = 0.000846", "eccentricity = 0.0")
        .replace("area_m2 = 1.0 ", "area_m2 = 10.0 ");
    assert_ne!(decaying, text);
    std::fs::write(&scenario, decaying).unwrap();
    refused(
        d,
        &["run", "short.toml", "--out", "decayed"],
        &["short.toml:", "platform.leo", "orbit decayed"],
    );
    std::fs::remove_file(&scenario).unwrap();

    // A scenario too short to calibrate on: its duration, located.
    let scenario = short_scenario(d, "interop-gps-static", 5);
    refused(
        d,
        &["calibrate", "short.toml", "--out", "cal"],
        &["short.toml:", "time.duration_s = 5", "at least 20 s"],
    );
    std::fs::remove_file(&scenario).unwrap();

    // A study's output directory below a file.
    support::small_study(d, 1);
    std::fs::write(d.join("afile"), "").unwrap();
    for command in ["run", "slurm"] {
        let mut args = vec!["study", command, "small.toml", "--out", "afile/x"];
        if command == "slurm" {
            args.extend(["--shards", "2"]);
        }
        refused(
            d,
            &args,
            &["cannot create", "afile is a file, not a directory"],
        );
    }
}

/// Issue #33 item 11: a SigMF metadata file that gives a key twice (JSON readers keep
/// either value, serde_json the last) is refused, naming the file and the key.
#[test]
fn a_sigmf_key_given_twice_is_refused_naming_the_file_and_the_key() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path();
    std::fs::write(
        dir.join("twice.sigmf-meta"),
        r#"{"global": {"core:datatype": "ci8", "core:version": "1.0.0",
  "core:sample_rate": 4000000.0,
  "core:sample_rate": 8000000.0},
 "captures": [{"core:sample_start": 0, "core:frequency": 1575420000.0}],
 "annotations": []}"#,
    )
    .unwrap();
    std::fs::write(dir.join("twice.sigmf-data"), [0u8; 64]).unwrap();
    refused(
        dir,
        &["receive", "twice.sigmf-meta", "--out", "rx"],
        &[
            "twice.sigmf-meta",
            "\"core:sample_rate\" given twice",
            "line 3",
        ],
    );
}
