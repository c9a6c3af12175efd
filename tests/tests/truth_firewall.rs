//! The receiver must never read simulator truth (DESIGN.md, "The truth firewall"): the
//! receiver crate may not depend on the crate that produces truth.

use std::path::Path;

fn dependencies(manifest: &Path) -> Vec<String> {
    let text = std::fs::read_to_string(manifest).unwrap();
    let doc: toml::Table = toml::from_str(&text).unwrap();
    ["dependencies", "build-dependencies"]
        .iter()
        .filter_map(|k| doc.get(*k).and_then(|d| d.as_table()))
        .flat_map(|t| t.keys().cloned())
        .collect()
}

#[test]
fn receiver_does_not_depend_on_truth_producers() {
    let manifest = Path::new(env!("CARGO_MANIFEST_DIR")).join("../receiver/Cargo.toml");
    let deps = dependencies(&manifest);
    assert!(!deps.is_empty() || manifest.exists());
    for forbidden in [
        "skyforge-signals",
        "skyforge-validate",
        "skyforge-scenarios",
        "skyforge-sim",
    ] {
        assert!(
            !deps.iter().any(|d| d == forbidden),
            "receiver depends on {forbidden}: {deps:?}"
        );
    }
}
