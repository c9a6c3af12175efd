//! Records the commit SkyForge is built from (`SKYFORGE_COMMIT`), for the provenance of
//! `validate thesis`'s `results.json`; nothing when the source is not a git checkout.

use std::process::Command;

fn main() {
    for watched in ["../.git/HEAD", "../.git/refs/heads", "../.git/packed-refs"] {
        println!("cargo:rerun-if-changed={watched}");
    }
    let commit = Command::new("git")
        .args(["rev-parse", "HEAD"])
        .output()
        .ok()
        .filter(|o| o.status.success())
        .and_then(|o| String::from_utf8(o.stdout).ok())
        .map(|s| s.trim().to_string())
        .filter(|s| !s.is_empty());
    if let Some(commit) = commit {
        println!("cargo:rustc-env=SKYFORGE_COMMIT={commit}");
    }
}
