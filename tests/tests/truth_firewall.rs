//! The receiver and the navigation estimators must never read simulator truth (DESIGN.md,
//! "The truth firewall"). The firewall is a missing Cargo edge: nothing the receiver and
//! navigation crates depend on, directly or
//! through another crate, and none of its test or bench dependencies, is a crate that
//! produces or compares truth. Of the simulator's side it may use only the GNSS vocabulary
//! (`skyforge-gnss`: signals, codes, navigation-message, sample and observation formats).
//! The check walks the workspace's dependency graph as `cargo metadata` reads it from the
//! manifests, so no import alias or re-export can pass it.

use serde_json::Value;
use std::collections::{BTreeSet, HashMap};
use std::path::Path;
use std::process::Command;

/// The crates that produce or compare truth.
const TRUTH_CRATES: [&str; 7] = [
    "skyforge-signals",
    "skyforge-formats",
    "skyforge-scenarios",
    "skyforge-runner",
    "skyforge-validate",
    "skyforge-sim",
    "skyforge-studies",
];

/// `cargo metadata --no-deps`: the workspace's own packages with their declared
/// dependencies, read from the manifests (no registry needed).
fn metadata() -> Value {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let out = Command::new(cargo)
        .args([
            "metadata",
            "--format-version",
            "1",
            "--no-deps",
            "--offline",
        ])
        .current_dir(root)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    serde_json::from_slice(&out.stdout).unwrap()
}

/// Each workspace package's dependencies on other workspace packages: (name, kind), kind
/// `None` for normal, `Some("dev")` or `Some("build")`.
fn workspace_edges(meta: &Value) -> HashMap<String, Vec<(String, Option<String>)>> {
    let packages = meta["packages"].as_array().unwrap();
    let members: BTreeSet<&str> = packages
        .iter()
        .map(|p| p["name"].as_str().unwrap())
        .collect();
    packages
        .iter()
        .map(|p| {
            let deps = p["dependencies"]
                .as_array()
                .unwrap()
                .iter()
                .map(|d| {
                    let name = d["name"].as_str().unwrap().to_owned();
                    (name, d["kind"].as_str().map(str::to_owned))
                })
                .filter(|(name, _)| members.contains(name.as_str()))
                .collect();
            (p["name"].as_str().unwrap().to_owned(), deps)
        })
        .collect()
}

/// Every workspace package reachable from `root`, following normal and build edges and,
/// for `root` itself, dev edges too (its tests and benches).
fn reachable(meta: &Value, root: &str) -> BTreeSet<String> {
    let edges = workspace_edges(meta);
    assert!(
        edges.contains_key(root),
        "{root} is not a workspace package"
    );
    let mut seen = BTreeSet::new();
    let mut stack = vec![(root.to_owned(), true)];
    while let Some((name, is_root)) = stack.pop() {
        if !seen.insert(name.clone()) {
            continue;
        }
        for (dep, kind) in &edges[&name] {
            if is_root || kind.as_deref() != Some("dev") {
                stack.push((dep.clone(), false));
            }
        }
    }
    seen
}

#[test]
fn the_receiver_reaches_no_crate_that_holds_truth() {
    let meta = metadata();
    let reach = reachable(&meta, "skyforge-receiver");
    assert!(
        reach.contains("skyforge-gnss"),
        "the graph walk found no vocabulary: {reach:?}"
    );
    for forbidden in TRUTH_CRATES {
        assert!(
            !reach.contains(forbidden),
            "skyforge-receiver reaches {forbidden}: {reach:?}"
        );
    }
}

#[test]
fn navigation_and_the_vocabulary_reach_no_crate_that_holds_truth() {
    let meta = metadata();
    for krate in ["skyforge-navigation", "skyforge-gnss"] {
        let reach = reachable(&meta, krate);
        for forbidden in TRUTH_CRATES {
            assert!(
                !reach.contains(forbidden),
                "{krate} reaches {forbidden}: {reach:?}"
            );
        }
    }
}

#[test]
fn the_graph_walk_sees_the_simulator_where_it_is() {
    // The check must be able to fail: the validation crate does reach the simulator.
    let reach = reachable(&metadata(), "skyforge-validate");
    assert!(reach.contains("skyforge-signals"), "{reach:?}");
    assert!(reach.contains("skyforge-receiver"), "{reach:?}");
}
