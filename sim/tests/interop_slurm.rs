//! `skyforge study slurm` on a real Slurm cluster: Debian's slurm-wlm and munge brought up
//! as a single-node cluster on this machine (scripts/slurm-local.sh), the study submitted
//! as a four-task job array plus a dependent merge job, and the merged file compared with
//! a local whole run, byte for byte.

mod support;

use std::path::{Path, PathBuf};
use std::process::Command;
use support::{HOSTILE_DIRS, skyforge_ok, small_study};

/// The cluster, stopped when the test ends however it ends.
struct Cluster(PathBuf);

impl Drop for Cluster {
    fn drop(&mut self) {
        let _ = Command::new(script()).arg("stop").arg(&self.0).status();
    }
}

fn script() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../scripts/slurm-local.sh")
}

#[test]
#[ignore = "interoperability tier: needs root, slurm-wlm and munge (scripts/deps.sh slurm-wlm munge)"]
fn a_study_run_as_a_slurm_job_array_merges_to_the_bytes_of_a_local_run() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    small_study(d, 3);
    let state = d.join("cluster");
    let started = Command::new(script())
        .arg("start")
        .arg(&state)
        .output()
        .unwrap();
    assert!(
        started.status.success(),
        "slurm-local start:\n{}{}",
        String::from_utf8_lossy(&started.stdout),
        String::from_utf8_lossy(&started.stderr)
    );
    let _cluster = Cluster(state.clone());
    let conf = state.join("slurm.conf");

    // sbatch accepts the scripts whatever the output path holds.
    for name in HOSTILE_DIRS {
        let out = d.join("test-only").join(name);
        skyforge_ok(
            &[
                "study",
                "slurm",
                "small.toml",
                "--out",
                out.to_str().unwrap(),
                "--shards",
                "4",
                "--sbatch",
                "--comment=a b $(touch PWNED)",
            ],
            d,
        );
        for script in ["array.sbatch", "merge.sbatch"] {
            let tested = Command::new("sbatch")
                .arg("--test-only")
                .arg(out.join("slurm").join(script))
                .env("SLURM_CONF", &conf)
                .current_dir(d)
                .output()
                .unwrap();
            assert!(
                tested.status.success(),
                "sbatch --test-only {name:?}/{script}: {}",
                String::from_utf8_lossy(&tested.stderr)
            );
        }
    }

    // The study itself runs in a directory whose name holds a space, both quotes, `$()`,
    // backquotes, `#` and `%`: its logs must land in its slurm/ folder.
    let out_name = "cluster out it's \"q\" $(x) `y` #z 50%";
    let printed = skyforge_ok(
        &[
            "study",
            "slurm",
            "small.toml",
            "--out",
            out_name,
            "--shards",
            "4",
        ],
        d,
    );
    assert!(printed.contains("6 runs in 4 array tasks"), "{printed}");
    let submitted = Command::new("bash")
        .arg(d.join(out_name).join("slurm/submit.sh"))
        .env("SLURM_CONF", &conf)
        .current_dir(d)
        .output()
        .unwrap();
    let said = String::from_utf8_lossy(&submitted.stdout).into_owned()
        + &String::from_utf8_lossy(&submitted.stderr);
    assert!(submitted.status.success(), "submit.sh:\n{said}");
    assert!(
        said.contains("array job") && said.contains("merge job"),
        "{said}"
    );

    // The merge job writes study.h5 once every array task has succeeded.
    let merged = d.join(out_name).join("study.h5");
    let logs = || {
        std::fs::read_dir(d.join(out_name).join("slurm"))
            .unwrap()
            .filter_map(Result::ok)
            .filter(|e| e.path().extension().is_some_and(|x| x == "log"))
            .map(|e| {
                format!(
                    "{}:\n{}",
                    e.path().display(),
                    std::fs::read_to_string(e.path()).unwrap_or_default()
                )
            })
            .collect::<Vec<_>>()
            .join("\n")
    };
    let t0 = std::time::Instant::now();
    while !(merged.exists()
        && std::fs::read_to_string(d.join(out_name).join("slurm/merge.log"))
            .is_ok_and(|l| l.contains("wrote")))
    {
        assert!(
            t0.elapsed().as_secs() < 600,
            "no merged file after 10 min:\n{}",
            logs()
        );
        std::thread::sleep(std::time::Duration::from_millis(200));
    }
    for i in 1..=4 {
        assert!(
            d.join(out_name).join(format!("shard-{i}-of-4.h5")).exists(),
            "{}",
            logs()
        );
    }

    skyforge_ok(&["study", "run", "small.toml", "--out", "local"], d);
    let a = std::fs::read(d.join("local/study.h5")).unwrap();
    let b = std::fs::read(&merged).unwrap();
    assert!(
        a == b,
        "the Slurm-merged file differs from the local run\n{}",
        logs()
    );
}
