//! Issue #11 fault suite (interoperability tier): `synth` and `receive` are killed with
//! SIGINT, SIGTERM and SIGKILL at random points while replacing an earlier output
//! (`--force`); two runs race for one `--out`; a disk fills up under `receive`. After each,
//! the output directory holds a complete output (the earlier one, or the new one when the
//! signal came after the commit), nothing partial is visible under its name, and the next
//! run succeeds and clears what a killed process left behind.

mod support;

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::collections::BTreeMap;
use std::hash::{DefaultHasher, Hasher};
use std::os::unix::process::ExitStatusExt;
use std::path::Path;
use std::process::{Command, ExitStatus, Stdio};
use std::time::{Duration, Instant};
use support::{Tmpfs, listing, short_scenario, skyforge, skyforge_ok, text};

/// Kill points per command and signal.
const POINTS: usize = 3;
/// Seed of the kill points. # assumed: any fixed seed; chosen before the first run.
const KILL_SEED: u64 = 11;

/// `v` as string slices.
fn as_str(v: &[String]) -> Vec<&str> {
    v.iter().map(String::as_str).collect()
}

/// Every file below `dir`: relative path -> hash of its bytes.
fn snapshot(dir: &Path) -> BTreeMap<String, u64> {
    let mut files = BTreeMap::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).expect("read dir").flatten() {
            let path = e.path();
            if path.is_dir() {
                stack.push(path);
            } else {
                let mut h = DefaultHasher::new();
                h.write(&std::fs::read(&path).expect("read file"));
                let rel = path.strip_prefix(dir).unwrap().display().to_string();
                files.insert(rel, h.finish());
            }
        }
    }
    files
}

/// Run `skyforge args` in `cwd`, send `signal` after `delay`, and return how it ended
/// with its standard error.
fn killed_run(args: &[&str], cwd: &Path, signal: &str, delay: Duration) -> (ExitStatus, String) {
    let child = Command::new(env!("CARGO_BIN_EXE_skyforge"))
        .args(args)
        .current_dir(cwd)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("start skyforge");
    std::thread::sleep(delay);
    // The run may have finished already: then kill fails, which is fine.
    let _ = Command::new("kill")
        .args([signal, &child.id().to_string()])
        .stderr(Stdio::null())
        .status();
    let out = child.wait_with_output().expect("wait");
    (
        out.status,
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// Whether `status` is how a run ends under `signal`: finished (signal too late), or the
/// signal's exit (130/143 through the handler; killed by the signal itself before the
/// handler is installed or for SIGKILL).
fn ended_as_expected(status: ExitStatus, signal: &str) -> bool {
    let (code, number) = match signal {
        "-INT" => (Some(130), 2),
        "-TERM" => (Some(143), 15),
        _ => (None, 9),
    };
    status.success() || (code.is_some() && status.code() == code) || status.signal() == Some(number)
}

/// `short.toml` synthesised with seeds 1 and 2 into `ref1/` and `ref2/`: their snapshots.
fn seed_outputs(cwd: &Path) -> Vec<BTreeMap<String, u64>> {
    ["1", "2"]
        .iter()
        .map(|seed| {
            let dir = format!("ref{seed}");
            skyforge_ok(&["synth", "short.toml", "--out", &dir, "--seed", seed], cwd);
            snapshot(&cwd.join(dir))
        })
        .collect()
}

/// Hidden entries of `dir` (staging directories and replaced outputs are hidden).
fn hidden(dir: &Path) -> Vec<String> {
    listing(dir)
        .into_iter()
        .filter(|n| n.starts_with('.'))
        .collect()
}

/// Time one complete run of `args` (the span the kill points are drawn from).
fn timed(args: &[&str], cwd: &Path) -> Duration {
    let t = Instant::now();
    skyforge_ok(args, cwd);
    t.elapsed()
}

/// Kill `args` (which replaces `out` in `cwd` with `--force`) at random points; `out` must
/// always equal `before` or `after`, nothing partial may be visible, and `restore` (a
/// complete run writing `before`) must then succeed and leave no staging directory.
fn kill_at_random_points(
    cwd: &Path,
    args: &[&str],
    restore: &[&str],
    (out, before, after): (&str, &BTreeMap<String, u64>, &BTreeMap<String, u64>),
    rng: &mut ChaCha8Rng,
) {
    let span = timed(args, cwd);
    skyforge_ok(restore, cwd);
    let names_before = listing(cwd);
    for signal in ["-INT", "-TERM", "-KILL"] {
        for _ in 0..POINTS {
            let delay = span.mul_f64(rng.random_range(0.0..1.2));
            let (status, stderr) = killed_run(args, cwd, signal, delay);
            println!("{args:?} {signal} after {delay:?}: {status}");
            assert!(ended_as_expected(status, signal), "{status}: {stderr}");
            let now = snapshot(&cwd.join(out));
            assert!(
                now == *before || now == *after,
                "{signal} after {delay:?}: {out} is neither the earlier nor the new output"
            );
            let visible: Vec<String> = listing(cwd)
                .into_iter()
                .filter(|n| !n.starts_with('.'))
                .collect();
            let expected: Vec<&String> = names_before
                .iter()
                .filter(|n| !n.starts_with('.'))
                .collect();
            assert_eq!(visible.iter().collect::<Vec<_>>(), expected, "{signal}");
            if signal != "-KILL" {
                assert_eq!(hidden(cwd), Vec::<String>::new(), "{signal}: staging left");
            }
        }
    }
    skyforge_ok(restore, cwd);
    assert_eq!(snapshot(&cwd.join(out)), *before);
    assert_eq!(hidden(cwd), Vec::<String>::new(), "left after the next run");
}

#[test]
#[ignore = "fault suite (interoperability tier): many runs killed at random points"]
fn killed_runs_never_damage_the_previous_output() {
    let tmp = tempfile::tempdir().expect("temp dir");
    let cwd = tmp.path();
    short_scenario(cwd, "interop-gps-static", 20);
    let mut rng = ChaCha8Rng::seed_from_u64(KILL_SEED);
    // synth: seed 1 is in place; seed 2 replaces it.
    let synth = |seed: &str| -> Vec<String> {
        [
            "synth",
            "short.toml",
            "--out",
            "out",
            "--force",
            "--seed",
            seed,
        ]
        .map(String::from)
        .to_vec()
    };
    let refs = seed_outputs(cwd);
    let (s2, s1) = (synth("2"), synth("1"));
    kill_at_random_points(
        cwd,
        &as_str(&s2),
        &as_str(&s1),
        ("out", &refs[0], &refs[1]),
        &mut rng,
    );

    // receive: the seed-1 recording's output is in place; the seed-2 recording replaces it.
    let receive = |rec: &str| -> Vec<String> {
        [
            "receive",
            &format!("{rec}/ant1.gps-l1ca.sigmf-meta"),
            "--assist",
            &format!("{rec}/nav.rnx"),
            "--out",
            "rx",
            "--force",
        ]
        .map(String::from)
        .to_vec()
    };
    let rx_refs: Vec<BTreeMap<String, u64>> = ["ref1", "ref2"]
        .iter()
        .map(|rec| {
            let dir = format!("rx-{rec}");
            let mut args = receive(rec);
            args[5] = dir.clone();
            skyforge_ok(&as_str(&args), cwd);
            snapshot(&cwd.join(dir))
        })
        .collect();
    let (r2, r1) = (receive("ref2"), receive("ref1"));
    kill_at_random_points(
        cwd,
        &as_str(&r2),
        &as_str(&r1),
        ("rx", &rx_refs[0], &rx_refs[1]),
        &mut rng,
    );
}

#[test]
#[ignore = "fault suite (interoperability tier)"]
fn two_runs_racing_for_one_output_leave_one_complete_output() {
    let tmp = tempfile::tempdir().expect("temp dir");
    let cwd = tmp.path();
    short_scenario(cwd, "interop-gps-static", 6);
    let refs = seed_outputs(cwd);
    for force in [false, true] {
        let mut args = vec!["synth", "short.toml", "--out", "race"];
        if force {
            args.push("--force");
        }
        let start = |seed: &str| {
            let mut a = args.clone();
            a.extend(["--seed", seed]);
            Command::new(env!("CARGO_BIN_EXE_skyforge"))
                .args(a)
                .current_dir(cwd)
                .stdout(Stdio::null())
                .stderr(Stdio::piped())
                .spawn()
                .expect("start skyforge")
        };
        let (a, b) = (start("1"), start("2"));
        let (a, b) = (a.wait_with_output().unwrap(), b.wait_with_output().unwrap());
        let ok = [a.status.success(), b.status.success()];
        println!("force {force}: {ok:?}\n{}{}", text(&a), text(&b));
        if force {
            assert_eq!(ok, [true, true], "both replace a skyforge output");
        } else {
            assert_eq!(ok.iter().filter(|&&s| s).count(), 1, "exactly one run wins");
            let loser = if ok[0] { &b } else { &a };
            assert_eq!(loser.status.code(), Some(2), "{}", text(loser));
        }
        let now = snapshot(&cwd.join("race"));
        assert!(
            now == refs[0] || now == refs[1],
            "force {force}: race/ is incomplete or mixed"
        );
        assert_eq!(
            hidden(cwd),
            Vec::<String>::new(),
            "force {force}: left behind"
        );
    }
}

#[test]
#[ignore = "fault suite (interoperability tier): mounts a tmpfs"]
fn a_disk_that_fills_up_under_receive_keeps_the_previous_output() {
    let tmp = tempfile::tempdir().expect("temp dir");
    let cwd = tmp.path();
    short_scenario(cwd, "interop-gps-static", 20);
    skyforge_ok(&["synth", "short.toml", "--out", "rec"], cwd);
    let disk = Tmpfs::mount(&cwd.join("small"), "16m");
    let receive = |force: bool| {
        let args = [
            "receive",
            "rec/ant1.gps-l1ca.sigmf-meta",
            "--assist",
            "rec/nav.rnx",
        ];
        let out: &[&str] = if force {
            &["--out", "small/rx", "--force"]
        } else {
            &["--out", "small/rx"]
        };
        skyforge(&[&args[..], out].concat(), cwd)
    };
    let o = receive(false);
    assert!(o.status.success(), "{}", text(&o));
    let previous = snapshot(&disk.0.join("rx"));
    // Fill what is left of the disk.
    let mut filler = std::fs::File::create(disk.0.join("filler")).unwrap();
    while std::io::Write::write_all(&mut filler, &[0u8; 4096]).is_ok() {}
    drop(filler);
    let o = receive(true);
    let msg = text(&o);
    println!("{msg}");
    assert!(!o.status.success());
    assert!(msg.contains("No space left on device"), "{msg}");
    assert_eq!(listing(&disk.0), ["filler", "rx"]);
    assert_eq!(
        snapshot(&disk.0.join("rx")),
        previous,
        "the previous output changed"
    );
    // With the room back (a replacement needs room for both outputs) the next run succeeds.
    std::fs::remove_file(disk.0.join("filler")).unwrap();
    let o = receive(true);
    assert!(o.status.success(), "the next run: {}", text(&o));
    assert_eq!(snapshot(&disk.0.join("rx")), previous);
    assert_eq!(listing(&disk.0), ["rx"]);
}
