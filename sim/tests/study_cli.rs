//! `skyforge study`: a study run whole, as shards, and interrupted then resumed gives the
//! same merged file, byte for byte, at the observation and at the signal level; bad study
//! files and arguments get one located error.

mod support;

use std::path::Path;
use support::{HOSTILE_DIRS, short_scenario, skyforge, skyforge_ok, small_study, text};

/// Whether the `study.h5` files of output directories `a` and `b` in `d` hold the same
/// bytes.
fn same_study(d: &Path, a: &str, b: &str) -> bool {
    let read = |dir: &str| std::fs::read(d.join(dir).join("study.h5")).unwrap();
    read(a) == read(b)
}

/// `study run <study>` as `n` shards into `d/sharded`, then `study merge`: the merged
/// file must be the bytes of the whole run in `d/whole`. Returns what each shard printed.
fn shards_merge_to_the_whole(d: &Path, study: &str, n: u32) -> Vec<String> {
    let printed = (1..=n)
        .map(|i| {
            let shard = format!("{i}/{n}");
            let args = ["study", "run", study, "--out", "sharded", "--shard", &shard];
            skyforge_ok(&args, d)
        })
        .collect();
    skyforge_ok(&["study", "merge", "sharded"], d);
    assert!(
        same_study(d, "whole", "sharded"),
        "merged shards differ from the whole run"
    );
    printed
}

/// `skyforge args` in `d` must exit 2; returns what it printed.
fn refused(d: &Path, args: &[&str]) -> String {
    let o = skyforge(args, d);
    let said = text(&o);
    assert_eq!(o.status.code(), Some(2), "{said}");
    said
}

#[test]
fn a_study_run_whole_and_as_three_shards_merges_to_the_same_bytes() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    small_study(d, 3);
    let whole = skyforge_ok(&["study", "run", "small.toml", "--out", "whole"], d);
    assert!(whole.contains("2 points x 3 seeds = 6 runs"), "{whole}");
    assert!(whole.contains("signal.cn0_dbhz = 45.0"), "{whole}");
    for (i, printed) in (1..).zip(shards_merge_to_the_whole(d, "small.toml", 3)) {
        assert!(
            printed.contains(&format!("shard      {i}/3: 2 runs")),
            "{printed}"
        );
    }

    // The merged file holds every run and per-point summaries of what the runs measured.
    let f = hdf5::File::open(d.join("whole/study.h5")).unwrap();
    let runs: Vec<u64> = support::dataset(&f, "runs/run");
    assert_eq!(runs, [0, 1, 2, 3, 4, 5]);
    let fix: Vec<f64> = support::dataset(&f, "runs/fix_rate");
    assert!(fix.iter().all(|v| (0.0..=1.0).contains(v)), "{fix:?}");
    let mean: Vec<f64> = support::dataset(&f, "summary/pseudorange_rms_m/mean");
    assert_eq!(mean.len(), 2);
    // At 40 dB-Hz the code is noisier than at 45 (the calibrated model).
    assert!(mean[0] > mean[1] && mean[1] > 0.0, "{mean:?}");
    // So is the carrier phase, at millimetres (the PLL's thermal noise) where the code is
    // at decimetres.
    let phase: Vec<f64> = support::dataset(&f, "summary/phase_rms_m/mean");
    assert!(phase[0] > phase[1] && phase[1] > 0.0, "{phase:?}");
    assert!(
        phase[0] < 0.01 && phase[0] < mean[0] / 50.0,
        "{phase:?} vs {mean:?}"
    );

    // A missing shard is named.
    std::fs::remove_file(d.join("sharded/shard-2-of-3.h5")).unwrap();
    let said = refused(d, &["study", "merge", "sharded", "--out", "m.h5"]);
    assert!(
        said.contains("2 of 6 runs are missing (the first: run 1"),
        "{said}"
    );
    assert!(!d.join("m.h5").exists());
}

#[test]
fn a_signal_level_study_run_whole_and_as_two_shards_merges_to_the_same_bytes() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    // assumed: interop-gps-static is at the signal level, one antenna, GPS L1 C/A at
    // 4 Msps. 18 s: the receiver times its satellites on the first whole navigation
    // subframe (6 to 12 s) and observes from 13 s on.
    short_scenario(d, "interop-gps-static", 18);
    std::fs::write(
        d.join("signal.toml"),
        "name = \"signal\"\nscenario = \"short.toml\"\nseed = 3\nseeds = 2\n\
         metrics = [\"pseudorange_rms_m\", \"phase_rms_m\", \"position_rms_m\"]\n\
         \n[[parameters]]\nkey = \"signal.cn0_dbhz\"\nvalues = [42.0, 48.0]\n",
    )
    .unwrap();
    let whole = skyforge_ok(&["study", "run", "signal.toml", "--out", "whole"], d);
    assert!(whole.contains("2 points x 2 seeds = 4 runs"), "{whole}");
    shards_merge_to_the_whole(d, "signal.toml", 2);

    // Every run is measured, from what the receiver made of its own samples: code at
    // decimetres, phase at millimetres, fixes at metres, each falling with the noise
    // (6 dB: half the thermal noise), and each seed drawing its own noise.
    let f = hdf5::File::open(d.join("whole/study.h5")).unwrap();
    let per_run = |m: &str| -> Vec<f64> { support::dataset(&f, &format!("runs/{m}")) };
    let mean = |m: &str| -> Vec<f64> { support::dataset(&f, &format!("summary/{m}/mean")) };
    let (code, phase, position) = (
        per_run("pseudorange_rms_m"),
        per_run("phase_rms_m"),
        per_run("position_rms_m"),
    );
    for (c, (p, x)) in code.iter().zip(phase.iter().zip(&position)) {
        assert!((0.05..3.0).contains(c), "code {code:?}");
        assert!(*p > 0.0 && *p < 0.005 && *p < c / 50.0, "phase {phase:?}");
        assert!((0.05..10.0).contains(x), "position {position:?}");
    }
    assert!(code[0] != code[1] && position[2] != position[3]);
    for m in ["pseudorange_rms_m", "phase_rms_m", "position_rms_m"] {
        let at = mean(m);
        assert!(at[0] > 1.4 * at[1], "{m}: {at:?} at 42 and 48 dB-Hz");
    }
}

#[test]
fn an_interrupted_study_resumes_with_only_the_missing_runs() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    small_study(d, 12);
    skyforge_ok(&["study", "run", "small.toml", "--out", "straight"], d);

    let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_skyforge"))
        .args(["study", "run", "small.toml", "--out", "killed"])
        .current_dir(d)
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn()
        .unwrap();
    let journal = d.join("killed/shard-1-of-1.runs.jsonl");
    let started = std::time::Instant::now();
    // Head line plus at least three runs, then kill.
    while std::fs::read_to_string(&journal).map_or(0, |t| t.lines().count()) < 4 {
        assert!(
            started.elapsed().as_secs() < 300,
            "no run finished in 5 min"
        );
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    child.kill().unwrap();
    child.wait().unwrap();
    let done = std::fs::read_to_string(&journal).unwrap().lines().count() - 1;
    assert!(done < 24, "killed before the end ({done} runs done)");
    assert!(!d.join("killed/study.h5").exists());

    let printed = skyforge_ok(&["study", "run", "small.toml", "--out", "killed"], d);
    assert!(
        printed.contains(&format!("{done} already done, {} to make", 24 - done)),
        "{printed}"
    );
    assert!(
        same_study(d, "straight", "killed"),
        "the resumed study differs from the straight one"
    );
}

/// A control character in a path or option of `study slurm` (a newline in `--out` once
/// ran the rest of the path as a command when the job ran), or a backslash in the log
/// path (Slurm's "no patterns"), is refused, exit 2, nothing written.
#[test]
fn study_slurm_refuses_control_characters_and_writes_nothing() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    small_study(d, 2);
    let cases: [(&[&str], &str, &str); 4] = [
        (&["--out", "x\ntouch PWNED"], "--out", "control character"),
        (
            &["--out", "x", "--sbatch", "--comment=a\u{1b}b"],
            "--sbatch",
            "control character",
        ),
        (&["--out", "x\ry"], "--out", "control character"),
        (&["--out", "a\\b"], "--out", "backslash"),
    ];
    for (extra, what, why) in cases {
        let mut args = vec!["study", "slurm", "small.toml", "--shards", "3"];
        args.extend_from_slice(extra);
        let said = refused(d, &args);
        assert!(said.contains(what) && said.contains(why), "{said}");
        let mut left: Vec<_> = std::fs::read_dir(d)
            .unwrap()
            .map(|e| e.unwrap().file_name())
            .collect();
        left.sort();
        assert_eq!(left, ["small.toml", "t-5.4-3.toml"], "{said}");
    }
}

/// The generated scripts are valid bash whatever the output path holds, and the array
/// task hands the program exactly the paths it was given (a stand-in binary records its
/// arguments): nothing in a path runs.
#[test]
fn study_slurm_scripts_carry_hostile_paths_intact() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    small_study(d, 2);
    let stand_in = d.join("record-args");
    std::fs::write(
        &stand_in,
        "#!/bin/sh\nfor a in \"$@\"; do printf '%s\\n' \"$a\"; done > \"$ARGS_FILE\"\n",
    )
    .unwrap();
    std::process::Command::new("chmod")
        .arg("+x")
        .arg(&stand_in)
        .status()
        .unwrap();
    for name in HOSTILE_DIRS {
        let out = d.join(name);
        let stand_in = stand_in.to_str().unwrap();
        let out_arg = out.to_str().unwrap();
        skyforge_ok(
            &[
                "study",
                "slurm",
                "small.toml",
                "--out",
                out_arg,
                "--shards",
                "3",
                "--skyforge",
                stand_in,
                "--sbatch",
                "--comment=a b $(touch PWNED3)",
            ],
            d,
        );
        let slurm = out.join("slurm");
        for script in ["array.sbatch", "merge.sbatch", "submit.sh"] {
            let checked = std::process::Command::new("bash")
                .arg("-n")
                .arg(slurm.join(script))
                .output()
                .unwrap();
            assert!(
                checked.status.success(),
                "{name:?}/{script}: {}",
                String::from_utf8_lossy(&checked.stderr)
            );
        }
        let args_file = d.join("args.txt");
        for (script, task) in [("array.sbatch", Some("2")), ("merge.sbatch", None)] {
            let mut run = std::process::Command::new("bash");
            run.arg(slurm.join(script))
                .env("ARGS_FILE", &args_file)
                .current_dir(d);
            if let Some(t) = task {
                run.env("SLURM_ARRAY_TASK_ID", t);
            }
            assert!(run.status().unwrap().success(), "{name:?}/{script}");
            let args = std::fs::read_to_string(&args_file).unwrap();
            let want = match task {
                Some(_) => format!(
                    "study\nrun\n{}\n--out\n{out_arg}\n--shard\n2/3\n",
                    d.join("small.toml").display()
                ),
                None => format!("study\nmerge\n{out_arg}\n"),
            };
            assert_eq!(args, want, "{name:?}/{script}");
        }
        for pwned in ["PWNED", "PWNED2", "PWNED3"] {
            assert!(!d.join(pwned).exists(), "{name:?} ran {pwned}");
        }
    }
}

/// Every study output follows `run`'s rules: a file skyforge did not write is never
/// replaced, `--force` or not; another study's file only with `--force`; the study's own
/// is rewritten by a rerun; a directory in the place of a file is refused with nothing
/// left beside it. (Each was overwritten or left `.partial` before.)
#[test]
fn study_outputs_replace_nothing_skyforge_did_not_write() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    small_study(d, 1);
    let precious = "precious\n";
    let kept = |path: &str| {
        assert_eq!(
            std::fs::read_to_string(d.join(path)).unwrap(),
            precious,
            "{path} was replaced"
        );
    };
    let refused_twice = |args: &[&str], path: &str| {
        let mut forced = args.to_vec();
        forced.push("--force");
        for a in [args, &forced] {
            let said = refused(d, a);
            assert!(
                said.contains(path) && said.contains("not a study file skyforge wrote")
                    || said.contains("not a Slurm script skyforge wrote"),
                "{said}"
            );
        }
        kept(path);
    };

    // study run into a user's folder holding a study.h5 of their own.
    std::fs::create_dir(d.join("u")).unwrap();
    std::fs::write(d.join("u/study.h5"), precious).unwrap();
    refused_twice(&["study", "run", "small.toml", "--out", "u"], "u/study.h5");
    assert!(!d.join("u/shard-1-of-1.runs.jsonl").exists());

    // A study run twice rewrites its own files; the shards merge into a user's file never.
    skyforge_ok(&["study", "run", "small.toml", "--out", "s"], d);
    skyforge_ok(&["study", "run", "small.toml", "--out", "s"], d);
    std::fs::write(d.join("m.h5"), precious).unwrap();
    refused_twice(&["study", "merge", "s", "--out", "m.h5"], "m.h5");
    std::fs::write(d.join("s/study.h5"), precious).unwrap();
    refused_twice(&["study", "merge", "s"], "s/study.h5");
    std::fs::remove_file(d.join("s/study.h5")).unwrap();
    skyforge_ok(&["study", "merge", "s"], d);
    skyforge_ok(&["study", "merge", "s"], d);

    // Another study's merged file is replaced only with --force.
    let other = std::fs::read_to_string(d.join("small.toml"))
        .unwrap()
        .replace("seed = 11", "seed = 12");
    std::fs::write(d.join("other.toml"), other).unwrap();
    skyforge_ok(&["study", "run", "other.toml", "--out", "o"], d);
    let said = refused(d, &["study", "merge", "s", "--out", "o/study.h5"]);
    assert!(
        said.contains("o/study.h5: the file of another study; give --force"),
        "{said}"
    );
    skyforge_ok(
        &["study", "merge", "s", "--out", "o/study.h5", "--force"],
        d,
    );

    // A directory in the place of the merged file: refused, nothing left beside it.
    std::fs::create_dir(d.join("m-dir")).unwrap();
    let said = refused(d, &["study", "merge", "s", "--out", "m-dir"]);
    assert!(
        said.contains("m-dir") && said.contains("is a directory"),
        "{said}"
    );
    let partial = std::fs::read_dir(d)
        .unwrap()
        .filter_map(Result::ok)
        .filter(|e| e.file_name().to_string_lossy().contains("partial"))
        .count();
    assert_eq!(partial, 0);

    // study slurm: a user's submit.sh stays; its own scripts are replaced with --force.
    std::fs::create_dir_all(d.join("c/slurm")).unwrap();
    std::fs::write(d.join("c/slurm/submit.sh"), precious).unwrap();
    let slurm = [
        "study",
        "slurm",
        "small.toml",
        "--out",
        "c",
        "--shards",
        "2",
    ];
    refused_twice(&slurm, "c/slurm/submit.sh");
    assert!(!d.join("c/slurm/array.sbatch").exists());
    std::fs::remove_file(d.join("c/slurm/submit.sh")).unwrap();
    skyforge_ok(&slurm, d);
    let said = refused(d, &slurm);
    assert!(said.contains("give --force"), "{said}");
    let mut forced = slurm.to_vec();
    forced.push("--force");
    skyforge_ok(&forced, d);
}

/// A second run of a shard while another process holds it (a requeued Slurm task
/// overlapping the first) exits 2 naming the holder, and makes and writes nothing.
#[test]
fn a_shard_held_by_another_process_is_refused() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    small_study(d, 1);
    std::fs::create_dir(d.join("s")).unwrap();
    let lock = std::fs::File::create(d.join("s/shard-2-of-2.lock")).unwrap();
    lock.try_lock().unwrap();
    std::fs::write(d.join("s/shard-2-of-2.lock"), "host node7, process 4242\n").unwrap();
    let said = refused(
        d,
        &["study", "run", "small.toml", "--out", "s", "--shard", "2/2"],
    );
    assert!(
        said.contains("shard 2/2 is being made by another process (host node7, process 4242)"),
        "{said}"
    );
    assert!(!d.join("s/shard-2-of-2.runs.jsonl").exists());
    assert!(!d.join("s/shard-2-of-2.h5").exists());
    drop(lock);
    skyforge_ok(
        &["study", "run", "small.toml", "--out", "s", "--shard", "2/2"],
        d,
    );
}

#[test]
fn bad_study_files_get_one_located_error_and_nothing_is_run() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    let good = small_study(d, 2);
    let cases = [
        (
            good.replace("seeds = 2", "seeds = 2\ncolour = 1"),
            "small.toml:5:1: colour",
            "unknown field",
        ),
        (
            good.replace("\"fix_rate\"", "\"fixrate\""),
            "small.toml:5:12: metrics[0] = fixrate",
            "one of pseudorange_rms_m",
        ),
        (
            good.replace("seeds = 2", "seeds = 0"),
            "small.toml:4:9: seeds = 0",
            "at least 1",
        ),
        (
            good.replace("[40.0, 45.0]", "[40.0, -500.0]"),
            "small.toml:13:10: parameters[1].values",
            "the scenario rejects this point",
        ),
        (
            good.replace("signal.cn0_dbhz", "signal.cn0_dbz"),
            "parameters[1].values",
            "unknown field",
        ),
        (
            good.replace("t-5.4-3.toml\"", "nowhere.toml\""),
            "small.toml:2:12: scenario = nowhere.toml",
            "bundled scenario",
        ),
        (
            good.replace("t-5.4-3.toml\"", "interop-gps-static\""),
            "small.toml:5:11: metrics = fix_rate",
            "needs two antennas or more (the scenario has 1)",
        ),
        (
            // A parameter may not add a table: this one made every run signal-level.
            good.replace("t-5.4-3.toml\"", "ground-static\""),
            "small.toml:13:10: parameters[1].values",
            "the base scenario has no [signal] table",
        ),
        (
            // Without the C/N0 parameter.
            good.replace("t-5.4-3.toml\"", "ground-static\"")
                .split("\n[[parameters]]\nkey = \"signal.")
                .next()
                .unwrap()
                .to_string(),
            "small.toml:5:11: metrics = fix_rate",
            "needs a [signal] table",
        ),
    ];
    for (text_of, place, what) in cases {
        std::fs::write(d.join("small.toml"), &text_of).unwrap();
        let said = refused(d, &["study", "run", "small.toml", "--out", "out"]);
        assert!(
            said.contains(place) && said.contains(what),
            "want {place} .. {what}:\n{said}"
        );
        assert!(!d.join("out").exists(), "{said}");
    }
    std::fs::write(d.join("small.toml"), &good).unwrap();
    let said = refused(
        d,
        &[
            "study",
            "run",
            "small.toml",
            "--out",
            "out",
            "--shard",
            "4/3",
        ],
    );
    assert!(said.contains("1 <= i <= n"), "{said}");

    // A directory holding another study's journal is not overwritten.
    skyforge_ok(&["study", "run", "small.toml", "--out", "out"], d);
    std::fs::write(d.join("small.toml"), good.replace("seed = 11", "seed = 12")).unwrap();
    let said = refused(d, &["study", "run", "small.toml", "--out", "out"]);
    assert!(said.contains("another study"), "{said}");
}
