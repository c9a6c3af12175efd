//! The manifest SkyForge writes into every output directory it creates
//! ([`MANIFEST`]: one relative path per line of every file it wrote), so that `--force`
//! replaces only a directory SkyForge wrote and that holds nothing else: never `.`, `..`,
//! `/`, the home directory, an ancestor of the working directory, or a directory with a
//! file the manifest does not list.

use std::path::{Path, PathBuf};

/// File name of the manifest.
pub const MANIFEST: &str = ".skyforge-manifest";
/// First line of the manifest.
const HEADER: &str =
    "# files written by skyforge; --force replaces this directory only while it holds nothing else";

/// Every regular file below `dir` (relative paths, sorted), or what cannot be read.
fn files_below(dir: &Path) -> Result<Vec<PathBuf>, String> {
    let mut out = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        let entries =
            std::fs::read_dir(&d).map_err(|e| format!("cannot read {}: {e}", d.display()))?;
        for entry in entries {
            let entry = entry.map_err(|e| format!("cannot read {}: {e}", d.display()))?;
            let path = entry.path();
            let kind = entry
                .file_type()
                .map_err(|e| format!("cannot read {}: {e}", path.display()))?;
            if kind.is_dir() {
                stack.push(path);
            } else if let Ok(rel) = path.strip_prefix(dir) {
                out.push(rel.to_path_buf());
            }
        }
    }
    out.sort();
    Ok(out)
}

/// Write the manifest of the files now in `dir`.
pub fn write(dir: &Path) -> std::io::Result<()> {
    let files = files_below(dir).map_err(std::io::Error::other)?;
    let mut text = format!("{HEADER}\n");
    for f in files {
        text.push_str(&f.to_string_lossy());
        text.push('\n');
    }
    std::fs::write(dir.join(MANIFEST), text)
}

/// List `file` (a path relative to `dir`) in `dir`'s manifest when `dir` has one that
/// does not list it yet: a file SkyForge adds to a directory it wrote earlier. A
/// directory without a manifest stays without one.
pub fn add(dir: &Path, file: &Path) -> std::io::Result<()> {
    let path = dir.join(MANIFEST);
    let Ok(text) = std::fs::read_to_string(&path) else {
        return Ok(());
    };
    let line = file.to_string_lossy();
    if text.lines().any(|l| l == line) {
        return Ok(());
    }
    let mut text = text;
    if !text.ends_with('\n') {
        text.push('\n');
    }
    text.push_str(&line);
    text.push('\n');
    std::fs::write(path, text)
}

/// Why `target` may not be replaced, or `None` when it may: it is a directory that
/// SkyForge wrote (its manifest is there) and every file in it is one the manifest lists.
pub fn refuse_replacing(target: &Path) -> Option<String> {
    if let Some(reason) = protected(target) {
        return Some(reason);
    }
    let Ok(text) = std::fs::read_to_string(target.join(MANIFEST)) else {
        return Some(format!(
            "it was not written by skyforge (no {MANIFEST}); remove it yourself if it should go"
        ));
    };
    if text.lines().next() != Some(HEADER) {
        return Some(format!("its {MANIFEST} is not one skyforge wrote"));
    }
    let listed: Vec<&str> = text.lines().skip(1).collect();
    let files = match files_below(target) {
        Ok(f) => f,
        Err(e) => return Some(e),
    };
    let foreign: Vec<String> = files
        .iter()
        .map(|f| f.to_string_lossy().into_owned())
        .filter(|f| f != MANIFEST && !listed.contains(&f.as_str()))
        .collect();
    (!foreign.is_empty()).then(|| {
        format!(
            "it holds files skyforge did not write ({}); move them out first",
            foreign.join(", ")
        )
    })
}

/// Paths `--force` never replaces, whatever they hold.
fn protected(target: &Path) -> Option<String> {
    // As written: `Path::components` drops a trailing `.`.
    let text = target.to_string_lossy();
    let trimmed = text.trim_end_matches('/');
    let last = trimmed.rsplit('/').next().unwrap_or("");
    if trimmed.is_empty() || last == "." || last == ".." {
        return Some("a path that ends in '.' or '..', or the root, is never replaced".into());
    }
    let canonical = target.canonicalize().ok()?;
    if canonical.parent().is_none() {
        return Some("the root directory is never replaced".into());
    }
    let home = std::env::var_os("HOME").map(PathBuf::from);
    if home.and_then(|h| h.canonicalize().ok()).as_ref() == Some(&canonical) {
        return Some("the home directory is never replaced".into());
    }
    let cwd = std::env::current_dir().ok()?.canonicalize().ok()?;
    cwd.starts_with(&canonical)
        .then(|| "the working directory or one of its parents is never replaced".into())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn only_a_directory_holding_what_its_manifest_lists_may_be_replaced() {
        let tmp = tempfile::tempdir().unwrap();
        let out = tmp.path().join("out");
        std::fs::create_dir_all(out.join("sub")).unwrap();
        std::fs::write(out.join("a.txt"), "a").unwrap();
        std::fs::write(out.join("sub/b.txt"), "b").unwrap();
        assert!(
            refuse_replacing(&out)
                .unwrap()
                .contains("not written by skyforge")
        );
        write(&out).unwrap();
        assert_eq!(refuse_replacing(&out), None);
        std::fs::write(out.join("sub/mine.txt"), "user data").unwrap();
        let why = refuse_replacing(&out).unwrap();
        assert!(why.contains("sub/mine.txt"), "{why}");
        std::fs::write(out.join(MANIFEST), "hand-written\n").unwrap();
        assert!(
            refuse_replacing(&out)
                .unwrap()
                .contains("not one skyforge wrote")
        );
    }

    #[test]
    fn dot_dot_dot_and_root_are_never_replaced() {
        for p in [".", "..", "/", "some/dir/.", "some/.."] {
            assert!(protected(Path::new(p)).is_some(), "{p}");
        }
    }
}
