//! Output failures of `skyforge synth`: an output path that cannot be written and a disk
//! that fills up mid-run give one clear message naming the path, a non-zero exit code,
//! and leave no partial files behind.

mod support;

use std::process::{Command, Output};
use support::{Tmpfs, is_root, listing, short_scenario, skyforge};

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// The scenario the tests shorten: 4 Msps ci8, 16 MB per second.
const SCENARIO: &str = "interop-gps-static";

#[test]
fn an_output_path_below_a_regular_file_is_refused_and_nothing_is_written() {
    let tmp = tempfile::tempdir().expect("temp dir");
    short_scenario(tmp.path(), SCENARIO, 1);
    std::fs::write(tmp.path().join("afile"), "keep").expect("write file");
    // ENOTDIR fails for root too (root ignores permission bits, not file types).
    for (out, reason) in [
        ("afile/out", "afile is a file, not a directory"),
        ("afile/deeper/out", "afile is a file, not a directory"),
    ] {
        let o = skyforge(&["synth", "short.toml", "--out", out], tmp.path());
        assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
        let msg = stderr(&o);
        assert_eq!(msg.lines().count(), 1, "one message: {msg}");
        assert!(
            msg.contains(&format!("output directory {out}")) && msg.contains(reason),
            "{msg}"
        );
    }
    // The file itself as the output directory, even with --force.
    let o = skyforge(
        &["synth", "short.toml", "--out", "afile", "--force"],
        tmp.path(),
    );
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("output directory afile: it exists and is not a directory"),
        "{}",
        stderr(&o)
    );
    assert_eq!(listing(tmp.path()), ["afile", "short.toml"]);
    assert_eq!(
        std::fs::read_to_string(tmp.path().join("afile")).expect("read file"),
        "keep"
    );
}

/// Run as a user directory permissions bind (`nobody` when the suite runs as root).
#[test]
fn a_read_only_parent_is_refused_and_nothing_is_written() {
    use std::os::unix::fs::PermissionsExt;
    let tmp = tempfile::tempdir().expect("temp dir");
    // Root ignores directory permissions: as root the command runs as `nobody`, who
    // must be able to enter the scratch folder and read the scenario.
    std::fs::set_permissions(tmp.path(), std::fs::Permissions::from_mode(0o755)).expect("chmod");
    short_scenario(tmp.path(), SCENARIO, 1);
    let ro = tmp.path().join("ro");
    std::fs::create_dir(&ro).expect("create dir");
    std::fs::set_permissions(&ro, std::fs::Permissions::from_mode(0o555)).expect("chmod");
    let args = ["synth", "short.toml", "--out", "ro/out"];
    let o = if is_root() {
        Command::new("setpriv")
            .args(["--reuid=65534", "--regid=65534", "--clear-groups"])
            .arg(env!("CARGO_BIN_EXE_skyforge"))
            .args(args)
            .current_dir(tmp.path())
            .output()
            .expect("run setpriv (util-linux)")
    } else {
        skyforge(&args, tmp.path())
    };
    std::fs::set_permissions(&ro, std::fs::Permissions::from_mode(0o755)).expect("chmod");
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    let msg = stderr(&o);
    assert!(
        msg.contains("output directory ro/out") && msg.contains("Permission denied"),
        "{msg}"
    );
    assert!(listing(&ro).is_empty());
}

#[test]
fn a_full_disk_fails_clearly_and_removes_the_partial_output() {
    let tmp = tempfile::tempdir().expect("temp dir");
    // 2 s of 4 Msps ci8 is 16 MB: the 2 MB file system fills up during the run.
    short_scenario(tmp.path(), SCENARIO, 2);
    let disk = Tmpfs::mount(&tmp.path().join("small"), "2m");
    let o = skyforge(&["synth", "short.toml", "--out", "small/out"], tmp.path());
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let msg = stderr(&o);
    println!("{msg}");
    assert!(msg.contains("No space left on device"), "{msg}");
    // The file that could not be written is named (the sample file fills the disk).
    assert!(
        msg.contains("cannot write ") && msg.contains(".sigmf-data"),
        "{msg}"
    );
    assert!(
        msg.contains("output directory small/out was not written")
            && msg.contains("partial files were removed"),
        "{msg}"
    );
    // No staging directory, no partial files.
    assert!(
        listing(&disk.0).is_empty(),
        "left behind: {:?}",
        listing(&disk.0)
    );
    drop(disk);
    assert_eq!(listing(tmp.path()), ["short.toml", "small"]);
}

/// Interrupted runs (issue #11): SIGINT or SIGTERM during `synth` removes the staging
/// directory and exits 130 or 143 with a message; a staging directory left by a killed
/// process is removed by the next run writing beside it.
#[test]
fn an_interrupted_run_leaves_nothing_and_stale_staging_is_cleared() {
    let tmp = tempfile::tempdir().expect("temp dir");
    short_scenario(tmp.path(), SCENARIO, 60);
    for (signal, code) in [("-INT", 130), ("-TERM", 143)] {
        let child = Command::new(env!("CARGO_BIN_EXE_skyforge"))
            .args(["synth", "short.toml", "--out", "out"])
            .current_dir(tmp.path())
            .stderr(std::process::Stdio::piped())
            .spawn()
            .expect("start skyforge");
        let staging = tmp.path().join(format!(".out.partial-{}", child.id()));
        let deadline = std::time::Instant::now() + std::time::Duration::from_secs(30);
        while !staging.join("truth.h5").exists() && std::time::Instant::now() < deadline {
            std::thread::sleep(std::time::Duration::from_millis(20));
        }
        assert!(staging.exists(), "the run never started writing");
        let killed = Command::new("kill")
            .args([signal, &child.id().to_string()])
            .status()
            .expect("kill");
        assert!(killed.success());
        let out = child.wait_with_output().expect("wait");
        assert_eq!(out.status.code(), Some(code), "{}", stderr(&out));
        assert!(stderr(&out).contains("interrupted"), "{}", stderr(&out));
        assert!(!staging.exists(), "{signal}: staging directory left");
        assert_eq!(listing(tmp.path()), ["short.toml"], "{signal}");
    }
    // A staging directory of a process that is gone (PID 4294967295 never runs).
    let stale = tmp.path().join(".out.partial-4294967295");
    std::fs::create_dir(&stale).expect("stale dir");
    std::fs::write(stale.join("ant1.gps-l1ca.sigmf-data"), vec![0u8; 1024]).expect("write");
    short_scenario(tmp.path(), SCENARIO, 1);
    let o = skyforge(&["synth", "short.toml", "--out", "out"], tmp.path());
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(!stale.exists(), "stale staging directory left");
}

/// Issue #11: absurd but parseable receiver input (a sample rate of 1e15 Hz, 1 Hz, a 1 MHz
/// PLL) allocated gigabytes or aborted; now each is one message, exit 2, nothing written.
#[test]
fn absurd_receiver_settings_are_refused_before_allocating() {
    let tmp = tempfile::tempdir().expect("temp dir");
    std::fs::write(tmp.path().join("capture.bin"), vec![0u8; 400_000]).expect("write");
    std::fs::write(
        tmp.path().join("wide.toml"),
        "[tracking]\npll_bandwidth_hz = 1e6\n",
    )
    .expect("write");
    let raw = [
        "receive",
        "capture.bin",
        "--format",
        "ci16",
        "--signal",
        "gps-l1ca",
    ];
    for (extra, expected) in [
        (&["--fs", "1e15"][..], "sample rate"),
        (&["--fs", "1"][..], "sample rate"),
        (
            &["--fs", "4e6", "--config", "wide.toml"][..],
            "pll_bandwidth_hz",
        ),
    ] {
        let mut args = raw.to_vec();
        args.extend_from_slice(extra);
        args.extend_from_slice(&["--out", "rx"]);
        let o = skyforge(&args, tmp.path());
        assert_eq!(o.status.code(), Some(2), "{extra:?}: {}", stderr(&o));
        assert!(stderr(&o).contains(expected), "{extra:?}: {}", stderr(&o));
        assert_eq!(
            listing(tmp.path()),
            ["capture.bin", "wide.toml"],
            "{extra:?}: something was written"
        );
    }
}

/// Issue #33 (15): a full disk under `receive` (HDF5's error buried the path) and under
/// `validate thesis` ("No space left on device" alone) names the file that could not be
/// written.
#[test]
fn a_full_disk_under_receive_and_validate_names_the_file() {
    let tmp = tempfile::tempdir().expect("temp dir");
    let d = tmp.path();
    // 15 s: long enough for the receiver to time its satellites and write epochs.
    short_scenario(d, SCENARIO, 15);
    let o = skyforge(&["synth", "short.toml", "--out", "sim"], d);
    assert!(o.status.success(), "{}", stderr(&o));
    let disk = Tmpfs::mount(&d.join("small"), "64k");
    let o = skyforge(
        &[
            "receive",
            "sim/ant1.gps-l1ca.sigmf-meta",
            "--out",
            "small/rx",
        ],
        d,
    );
    let msg = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{msg}");
    let first = msg.lines().next().unwrap_or_default();
    assert!(
        first.starts_with("error: cannot write small/.rx.partial-")
            && msg.contains("No space left"),
        "{msg}"
    );
    assert!(listing(&disk.0).is_empty(), "{:?}", listing(&disk.0));
    // One page: results.json does not fit.
    let tiny = Tmpfs::mount(&d.join("tiny"), "4k");
    let o = skyforge(
        &["validate", "thesis", "--only", "T-3.2", "--out", "tiny/v"],
        d,
    );
    let msg = stderr(&o);
    assert_eq!(o.status.code(), Some(1), "{msg}");
    assert!(
        msg.contains("error: cannot write tiny/.v.partial-")
            && msg.contains("/results.json: No space left on device"),
        "{msg}"
    );
    assert!(listing(&tiny.0).is_empty(), "{:?}", listing(&tiny.0));
}
