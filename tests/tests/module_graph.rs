//! The module graph of the library crates: no source files import each other, in pairs or
//! around a longer cycle (issue #31). A file imports another when its code outside the unit tests names a path into
//! it (`crate::a::b`, `super::c`); a folder's `mod.rs` or a crate's `lib.rs` declaring its
//! children is not an import. Configuration types sit in files the stages import, shared
//! types where both users reach them, so a pair of files that need each other says that a
//! concept has no home of its own.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

const LIBRARIES: [&str; 11] = [
    "orbits",
    "gnss",
    "signals",
    "scenarios",
    "receiver",
    "navigation",
    "formats",
    "runner",
    "validate",
    "studies",
    "sim",
];

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

/// The module path of `file` below `src` (`a/b.rs` and `a/b/mod.rs` are `[a, b]`).
fn module_of(src: &Path, file: &Path) -> Vec<String> {
    let rel = file.strip_prefix(src).unwrap().with_extension("");
    let mut parts: Vec<String> = rel
        .iter()
        .map(|p| p.to_string_lossy().into_owned())
        .collect();
    if matches!(
        parts.last().map(String::as_str),
        Some("mod" | "lib" | "main")
    ) {
        parts.pop();
    }
    parts
}

/// The file that holds module `parts` (or its longest existing prefix).
fn file_of(src: &Path, parts: &[String]) -> Option<PathBuf> {
    (1..=parts.len()).rev().find_map(|k| {
        let base = parts[..k].iter().fold(src.to_path_buf(), |p, s| p.join(s));
        let file = base.with_extension("rs");
        let module = base.join("mod.rs");
        [file, module].into_iter().find(|p| p.is_file())
    })
}

/// The code of `text` a reader of the library sees: before the unit tests, without comments.
fn library_code(text: &str) -> String {
    let code = text.split("#[cfg(test)]").next().unwrap_or("");
    code.lines()
        .filter(|l| !l.trim_start().starts_with("//"))
        .collect::<Vec<_>>()
        .join("\n")
}

/// Every `crate::...` or `super::...` path in `code`, as its head and its segments.
fn paths(code: &str) -> Vec<(usize, Option<usize>, Vec<String>)> {
    let mut found = Vec::new();
    let bytes = code.as_bytes();
    for (at, _) in code
        .match_indices("crate::")
        .chain(code.match_indices("super::"))
    {
        if at > 0 && (bytes[at - 1].is_ascii_alphanumeric() || bytes[at - 1] == b'_') {
            continue;
        }
        let rest = &code[at..];
        let mut segments: Vec<String> = Vec::new();
        let mut supers = 0;
        let mut is_crate = false;
        for seg in rest.split("::") {
            let name: String = seg
                .chars()
                .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
                .collect();
            match name.as_str() {
                "super" if segments.is_empty() && !is_crate => supers += 1,
                "crate" if segments.is_empty() && supers == 0 => is_crate = true,
                n if !n.is_empty() && n.starts_with(|c: char| c.is_ascii_lowercase()) => {
                    segments.push(name.clone());
                    if name.len() != seg.len() {
                        break;
                    }
                }
                _ => break,
            }
        }
        // A `super::` run is found again at each of its `super`s: keep the first.
        if !is_crate && at >= 7 && &code[at - 7..at] == "super::" {
            continue;
        }
        found.push((at, (!is_crate).then_some(supers), segments));
    }
    found
}

/// Each file's imports of other files of the same crate.
fn imports(src: &Path) -> BTreeMap<PathBuf, BTreeSet<PathBuf>> {
    let mut files = Vec::new();
    rust_files(src, &mut files);
    let mut graph = BTreeMap::new();
    for file in files {
        let module = module_of(src, &file);
        let code = library_code(&std::fs::read_to_string(&file).unwrap());
        let mut targets = BTreeSet::new();
        for (_, supers, segments) in paths(&code) {
            let parts: Vec<String> = match supers {
                None => segments,
                Some(n) => {
                    let keep = module.len().saturating_sub(n);
                    module[..keep].iter().cloned().chain(segments).collect()
                }
            };
            if let Some(target) = file_of(src, &parts).filter(|t| *t != file) {
                targets.insert(target);
            }
        }
        graph.insert(file, targets);
    }
    graph
}

fn is_parent(file: &Path) -> bool {
    matches!(
        file.file_name().and_then(|n| n.to_str()),
        Some("mod.rs" | "lib.rs" | "main.rs")
    )
}

/// The files `from` reaches through imports, none of them a module's parent.
fn reachable(graph: &BTreeMap<PathBuf, BTreeSet<PathBuf>>, from: &Path) -> BTreeSet<PathBuf> {
    let mut seen = BTreeSet::new();
    let mut next: Vec<&PathBuf> = graph[from].iter().filter(|f| !is_parent(f)).collect();
    while let Some(f) = next.pop() {
        if seen.insert(f.clone()) {
            next.extend(graph[f].iter().filter(|g| !is_parent(g)));
        }
    }
    seen
}

/// Groups of files (none a module's parent) that import each other, directly or around a
/// cycle through the group; each group sorted, the groups in order.
fn import_cycles(src: &Path) -> Vec<Vec<PathBuf>> {
    let graph = imports(src);
    let reach: BTreeMap<&PathBuf, BTreeSet<PathBuf>> = graph
        .keys()
        .filter(|f| !is_parent(f))
        .map(|f| (f, reachable(&graph, f)))
        .collect();
    let mut grouped = BTreeSet::new();
    let mut cycles = Vec::new();
    for (a, from_a) in &reach {
        if grouped.contains(*a) {
            continue;
        }
        let group: Vec<PathBuf> = from_a
            .iter()
            .filter(|b| reach.get(b).is_some_and(|from_b| from_b.contains(*a)))
            .cloned()
            .collect();
        if group.len() >= 2 {
            grouped.extend(group.iter().cloned());
            cycles.push(group);
        }
    }
    cycles
}

#[test]
fn no_files_import_each_other() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let mut cycles = Vec::new();
    for krate in LIBRARIES {
        cycles.extend(import_cycles(&root.join(krate).join("src")));
    }
    assert!(
        cycles.is_empty(),
        "files that import each other: {cycles:#?}"
    );
}

#[test]
fn the_scan_finds_pairs_and_longer_cycles() {
    let dir = tempfile::tempdir().unwrap();
    let src = dir.path();
    std::fs::create_dir_all(src.join("stage")).unwrap();
    std::fs::write(src.join("lib.rs"), "pub mod stage;\n").unwrap();
    std::fs::write(
        src.join("stage/mod.rs"),
        "pub mod config;\npub mod kalman;\n",
    )
    .unwrap();
    std::fs::write(
        src.join("stage/config.rs"),
        "use super::kalman::Kalman;\n// crate::nothing::here\n",
    )
    .unwrap();
    std::fs::write(
        src.join("stage/kalman.rs"),
        "use crate::stage::config::Config;\n#[cfg(test)]\nmod tests { use super::super::config; }\n",
    )
    .unwrap();
    let (config, kalman) = (src.join("stage/config.rs"), src.join("stage/kalman.rs"));
    assert_eq!(import_cycles(src), [vec![config.clone(), kalman.clone()]]);
    // Without the back edge there is no cycle.
    std::fs::write(&config, "pub struct Config;\n").unwrap();
    assert!(import_cycles(src).is_empty());
    // config -> reverse -> kalman -> config: a cycle of three, found whole.
    std::fs::write(
        src.join("stage/mod.rs"),
        "pub mod config;\npub mod kalman;\npub mod reverse;\n",
    )
    .unwrap();
    std::fs::write(&config, "use super::reverse::Reverse;\n").unwrap();
    let reverse = src.join("stage/reverse.rs");
    std::fs::write(&reverse, "use crate::stage::kalman::Kalman;\n").unwrap();
    assert_eq!(import_cycles(src), [vec![config, kalman, reverse]]);
}
