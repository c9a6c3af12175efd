//! Issue #11: the memory and disk a synthesis needs. `synth --dry-run` writes nothing and
//! prints each recording's exact size and bounds of the rest; a run at a high sample rate
//! stays within the printed memory bound, far below one second of its samples (which the
//! renderer used to hold, twice), and the largest allowed rate runs under a 4 GB
//! address-space limit (`ulimit -v`).

mod support;

use nix::sys::resource::{UsageWho, getrusage};
use std::path::Path;
use support::{MEMORY_LIMIT_BYTES, skyforge_limited, skyforge_ok, text};

/// The bundled GPS ground scenario, `duration_s` long, at `fs_hz` with `format` samples.
fn scenario(dir: &Path, duration_s: u32, fs_hz: f64, format: &str, bits: u32) -> String {
    let path = support::short_scenario(dir, "interop-gps-static", duration_s);
    let toml = std::fs::read_to_string(&path).unwrap();
    let toml = toml
        .replace(
            "sample_rate_hz = 4.0e6",
            &format!("sample_rate_hz = {fs_hz:e}"),
        )
        .replace("format = \"ci8\"", &format!("format = \"{format}\""))
        .replace("bits = 8", &format!("bits = {bits}"));
    std::fs::write(&path, toml).unwrap();
    path.display().to_string()
}

/// The byte count of the dry-run line starting with `label` (the `(N bytes)` figure).
fn figure(dry_run: &str, label: &str) -> u64 {
    let line = dry_run
        .lines()
        .find(|l| l.starts_with(label))
        .unwrap_or_else(|| panic!("no {label} line in:\n{dry_run}"));
    let open = line.find('(').expect("a (N bytes) figure") + 1;
    let bytes = line[open..].split_whitespace().next().unwrap();
    bytes.parse().unwrap_or_else(|_| panic!("{line}"))
}

/// The largest peak resident set of this test binary's children so far (bytes).
fn children_peak_rss() -> u64 {
    let usage = getrusage(UsageWho::RUSAGE_CHILDREN).expect("getrusage");
    usage.max_rss() as u64 * 1024
}

#[test]
fn dry_run_writes_nothing_and_gives_the_sizes_of_the_run() {
    let dir = tempfile::tempdir().unwrap();
    let s = scenario(dir.path(), 3, 4.0e6, "ci8", 8);
    let dry = skyforge_ok(&["synth", &s, "--out", "out", "--dry-run"], dir.path());
    assert!(!dir.path().join("out").exists(), "a dry run wrote out/");
    skyforge_ok(&["synth", &s, "--out", "out"], dir.path());
    let size = |name: &str| {
        std::fs::metadata(dir.path().join("out").join(name))
            .unwrap()
            .len()
    };
    let recording = size("ant1.gps-l1ca.sigmf-data");
    assert_eq!(
        recording,
        figure(&dry, "recording  ant1.gps-l1ca.sigmf-data")
    );
    assert_eq!(recording, 3 * 4_000_000 * 2, "3 s of 4 Msps ci8");
    let truth = size("truth.h5");
    assert!(
        truth <= figure(&dry, "truth.h5"),
        "truth.h5 {truth} B:\n{dry}"
    );
    let rinex = size("ant1.obs.rnx");
    assert!(
        rinex <= figure(&dry, "RINEX obs"),
        "RINEX {rinex} B:\n{dry}"
    );
}

#[test]
fn memory_stays_within_the_dry_run_bound_at_a_high_sample_rate() {
    let dir = tempfile::tempdir().unwrap();
    let s = scenario(dir.path(), 1, 5.0e7, "ci16", 16);
    let dry = skyforge_ok(&["synth", &s, "--out", "out", "--dry-run"], dir.path());
    let bound = figure(&dry, "memory");
    let one_second = figure(&dry, "recording  ant1.gps-l1ca.sigmf-data");
    assert_eq!(one_second, 50_000_000 * 4);
    let o = skyforge_limited(
        &["synth", &s, "--out", "out"],
        dir.path(),
        MEMORY_LIMIT_BYTES,
    );
    assert!(o.status.success(), "{}", text(&o));
    let peak = children_peak_rss();
    println!("peak RSS {peak} B, dry-run bound {bound} B, one second of samples {one_second} B");
    assert!(
        peak <= bound,
        "peak {peak} B above the printed bound {bound} B"
    );
    assert!(
        peak < one_second,
        "peak {peak} B: the renderer holds a whole second"
    );
}

#[test]
#[ignore = "acceptance tier: writes 2 GB (1 s at the largest sample rate)"]
fn the_largest_sample_rate_runs_under_a_4_gb_address_space_limit() {
    let dir = tempfile::tempdir().unwrap();
    let s = scenario(dir.path(), 1, 1.0e9, "ci8", 8);
    let o = skyforge_limited(
        &["synth", &s, "--out", "out"],
        dir.path(),
        MEMORY_LIMIT_BYTES,
    );
    assert!(o.status.success(), "{}", text(&o));
    let data = dir.path().join("out/ant1.gps-l1ca.sigmf-data");
    assert_eq!(std::fs::metadata(data).unwrap().len(), 2_000_000_000);
}

/// The largest scenario the checks allow (366 days, 64 antennas, GPS + BeiDou, 1 GHz
/// cf32, signal truth at 1 kHz) gets its figures without an arithmetic overflow (a panic
/// in this debug build): 128 recordings of 2.5e17 bytes pass 64-bit byte counts.
#[test]
fn the_largest_allowed_scenario_gets_its_figures() {
    let dir = tempfile::tempdir().unwrap();
    let base = skyforge_ok(&["scenarios", "show", "thesis-leo"], dir.path());
    let antennas: String = (0..61)
        .map(|i| format!("\n[[antennas]]\nname = \"x{i}\"\nposition_body_m = [0.0, 0.0, {i}.0]\n"))
        .collect();
    let toml = base.replace("duration_s = 86400.0", "duration_s = 31622400.0")
        + &antennas
        + "\n[signal]\nsample_rate_hz = 1.0e9\nformat = \"cf32\"\ntruth_rate_hz = 1000\n";
    std::fs::write(dir.path().join("max.toml"), toml).unwrap();
    let dry = skyforge_ok(
        &["synth", "max.toml", "--out", "out", "--dry-run"],
        dir.path(),
    );
    let one = 31_622_400u64 * 1_000_000_000 * 8;
    assert_eq!(figure(&dry, "recording  x60.bds-b1i.sigmf-data"), one);
    assert!(dry.contains("disk       more than"), "{dry}");
    assert!(!dir.path().join("out").exists());
}

/// The channel-samples figure of the dry run's `time` line.
fn channel_samples(dry_run: &str) -> f64 {
    let line = dry_run
        .lines()
        .find(|l| l.starts_with("time "))
        .unwrap_or_else(|| panic!("no time line in:\n{dry_run}"));
    let open = line.find('(').expect("a (N channel-samples) figure") + 1;
    line[open..]
        .split_whitespace()
        .next()
        .unwrap()
        .parse()
        .unwrap()
}

/// Issue #33 (6): 5000 multipath taps on 2 s of signal ran for minutes, and `--dry-run`
/// said nothing about time. The taps are bounded (64), and the dry run's time estimate
/// counts every reflected path as one more channel: 64 taps on every link make it 65
/// times the direct paths' work.
#[test]
fn multipath_taps_are_bounded_and_the_dry_run_counts_them() {
    let dir = tempfile::tempdir().unwrap();
    let s = scenario(dir.path(), 2, 4.0e6, "ci8", 8);
    let plain = std::fs::read_to_string(&s).unwrap();
    let direct = channel_samples(&skyforge_ok(
        &["synth", &s, "--out", "out", "--dry-run"],
        dir.path(),
    ));
    let with_taps = |n: usize| {
        let taps = "\n[[errors.multipath.taps]]\ndelay_m = 5.0\nrelative_amplitude = 0.1\n";
        std::fs::write(&s, format!("{plain}{}", taps.repeat(n))).unwrap();
    };
    with_taps(64);
    let dry = skyforge_ok(&["synth", &s, "--out", "out", "--dry-run"], dir.path());
    // Printed to four figures.
    let ratio = channel_samples(&dry) / direct;
    assert!((ratio - 65.0).abs() < 65.0e-3, "{ratio}: {dry}");
    assert!(dry.contains("at most about"), "{dry}");
    with_taps(65);
    let o = skyforge_limited(
        &["synth", &s, "--out", "out", "--dry-run"],
        dir.path(),
        MEMORY_LIMIT_BYTES,
    );
    assert_eq!(o.status.code(), Some(2), "{}", text(&o));
    assert!(
        text(&o).contains("errors.multipath.taps") && text(&o).contains("at most 64"),
        "{}",
        text(&o)
    );
    assert!(!dir.path().join("out").exists());
}
