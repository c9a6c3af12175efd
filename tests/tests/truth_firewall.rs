//! The receiver and the navigation estimators must never read simulator truth (DESIGN.md,
//! "The truth firewall"). The firewall is a missing Cargo edge: nothing the receiver and
//! navigation crates depend on, directly or
//! through another crate, and none of its test or bench dependencies, is a crate that
//! produces or compares truth. Of the simulator's side it may use only the GNSS vocabulary
//! (`skyforge-gnss`: signals, codes, navigation-message, sample and observation formats).
//! The check reads the resolved dependency graph of `cargo metadata`, so no import alias
//! or re-export can pass it.

use serde_json::Value;
use std::collections::{BTreeSet, HashMap};
use std::path::Path;
use std::process::Command;

/// The crates that produce or compare truth.
const TRUTH_CRATES: [&str; 5] = [
    "skyforge-signals",
    "skyforge-scenarios",
    "skyforge-validate",
    "skyforge-sim",
    "skyforge-studies",
];

/// `cargo metadata` of the workspace.
fn metadata() -> Value {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let out = Command::new(cargo)
        .args(["metadata", "--format-version", "1", "--offline"])
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

/// Package names by package id.
fn names(meta: &Value) -> HashMap<String, String> {
    meta["packages"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| {
            (
                p["id"].as_str().unwrap().to_owned(),
                p["name"].as_str().unwrap().to_owned(),
            )
        })
        .collect()
}

/// Every package reachable from `root` in the resolved graph, following normal, build and
/// (for `root` itself) dev edges.
fn reachable(meta: &Value, root: &str) -> BTreeSet<String> {
    let names = names(meta);
    let nodes: HashMap<&str, &Value> = meta["resolve"]["nodes"]
        .as_array()
        .unwrap()
        .iter()
        .map(|n| (n["id"].as_str().unwrap(), n))
        .collect();
    let root_id = names
        .iter()
        .find(|(_, n)| *n == root)
        .map(|(id, _)| id.clone())
        .unwrap();
    let mut seen = BTreeSet::new();
    let mut stack = vec![(root_id, true)];
    while let Some((id, is_root)) = stack.pop() {
        if !seen.insert(names[&id].clone()) {
            continue;
        }
        for dep in nodes[id.as_str()]["deps"].as_array().unwrap() {
            let kinds: Vec<Option<&str>> = dep["dep_kinds"]
                .as_array()
                .unwrap()
                .iter()
                .map(|k| k["kind"].as_str())
                .collect();
            let follow = kinds.iter().any(|k| *k != Some("dev")) || is_root;
            if follow {
                stack.push((dep["pkg"].as_str().unwrap().to_owned(), false));
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
