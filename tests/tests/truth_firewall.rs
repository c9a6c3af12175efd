//! The receiver must never read simulator truth (DESIGN.md, "The truth firewall"): the
//! receiver crate may not depend on the crates that produce or compare truth, and of
//! `skyforge-signals` its library code may use only what every receiver has: the signal
//! definitions, the ranging codes, the navigation-message formats, the sample-file formats,
//! the NCO helpers and the observation vocabulary (records and RINEX observation files).

use std::path::{Path, PathBuf};

fn dependencies(manifest: &Path) -> Vec<String> {
    let text = std::fs::read_to_string(manifest).unwrap();
    let doc: toml::Table = toml::from_str(&text).unwrap();
    ["dependencies", "build-dependencies"]
        .iter()
        .filter_map(|k| doc.get(*k).and_then(|d| d.as_table()))
        .flat_map(|t| t.keys().cloned())
        .collect()
}

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// Every `skyforge_signals::<module>` a source text names.
fn signals_modules(text: &str) -> Vec<String> {
    let key = "skyforge_signals::";
    let mut found = Vec::new();
    let mut rest = text;
    while let Some(at) = rest.find(key) {
        rest = &rest[at + key.len()..];
        let module: String = rest
            .chars()
            .take_while(|c| c.is_alphanumeric() || *c == '_' || *c == '{')
            .collect();
        found.push(module);
    }
    found
}

/// The modules of `skyforge-signals` the receiver's library code may use.
const ALLOWED: [&str; 6] = [
    "signal",
    "codes",
    "navmsg",
    "sample_format",
    "nco",
    "observation",
];

#[test]
fn receiver_does_not_depend_on_truth_producers() {
    let manifest = Path::new(env!("CARGO_MANIFEST_DIR")).join("../receiver/Cargo.toml");
    let deps = dependencies(&manifest);
    for forbidden in ["skyforge-validate", "skyforge-scenarios", "skyforge-sim"] {
        assert!(
            !deps.iter().any(|d| d == forbidden),
            "receiver depends on {forbidden}: {deps:?}"
        );
    }
}

#[test]
fn receiver_uses_only_codes_and_message_formats_of_signals() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("../receiver/src");
    let mut files = Vec::new();
    rust_files(&src, &mut files);
    assert!(!files.is_empty(), "no sources under {}", src.display());
    for file in files {
        let text = std::fs::read_to_string(&file).unwrap();
        // Unit tests may build test signals; the library code may not look at truth.
        let library = text.split("#[cfg(test)]").next().unwrap_or("");
        for module in signals_modules(library) {
            assert!(
                ALLOWED.contains(&module.as_str()),
                "{} uses skyforge_signals::{module}: only {ALLOWED:?} are allowed",
                file.display()
            );
        }
        assert!(
            !library.contains("use skyforge_signals;") && !library.contains("skyforge_signals::*"),
            "{}: glob use of skyforge_signals",
            file.display()
        );
    }
}

#[test]
fn the_source_scan_sees_forbidden_paths() {
    let modules = signals_modules(
        "use skyforge_signals::codes::gps_ca;\nlet t = skyforge_signals::truth::x;\nuse skyforge_signals::{codes, synth};",
    );
    assert_eq!(modules, ["codes", "truth", "{codes"]);
}
