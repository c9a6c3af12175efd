//! An output directory that appears only when complete: files are written into a sibling
//! staging directory, which replaces the target on [`StagedDir::commit`] and is removed
//! if the run fails (on drop), with the parent directories the run created for it (when
//! empty). Every committed directory carries a [`manifest`] of its
//! files; `--force` replaces only such a directory holding nothing else, and the old
//! directory stays in place until the new one is complete.

use super::{interrupt, manifest};
use crate::BadInput;
use anyhow::Context;
use std::path::{Path, PathBuf};

/// A staging directory for `target`.
#[derive(Debug)]
pub struct StagedDir {
    target: PathBuf,
    staging: PathBuf,
    /// Parent directories this run created for `target`, deepest first: removed (when
    /// empty) with the staging directory if the run fails.
    created_parents: Vec<PathBuf>,
    committed: bool,
}

/// The ancestors of `dir` (itself included) that do not exist, deepest first.
fn missing_ancestors(dir: &Path) -> Vec<PathBuf> {
    dir.ancestors()
        .filter(|a| !a.as_os_str().is_empty())
        .take_while(|a| std::fs::symlink_metadata(a).is_err())
        .map(Path::to_path_buf)
        .collect()
}

/// Remove the directories in `created` (deepest first) that are empty; stop at the first
/// that is not (something else now lives there).
pub(super) fn remove_created(created: &[PathBuf]) {
    for dir in created {
        if std::fs::remove_dir(dir).is_err() {
            break;
        }
    }
}

impl StagedDir {
    /// Check `target` (must not exist unless `force`, must be creatable) and create the
    /// staging directory. An output path that cannot be written (below a regular file, in
    /// a read-only directory, an existing file in its place) is bad input: one message
    /// naming `target` and the reason, and nothing is left behind.
    pub fn create(target: &Path, force: bool) -> anyhow::Result<Self> {
        let unwritable = |reason: String| {
            BadInput(format!(
                "cannot write the output directory {}: {reason}",
                target.display()
            ))
        };
        if target.exists() && !force {
            return Err(BadInput(format!(
                "output directory {} already exists; pass --force to replace it",
                target.display()
            ))
            .into());
        }
        if target.exists() && !target.is_dir() {
            return Err(unwritable("it exists and is not a directory".into()).into());
        }
        if target.exists()
            && let Some(reason) = manifest::refuse_replacing(target)
        {
            return Err(BadInput(format!(
                "--force will not replace {}: {reason}",
                target.display()
            ))
            .into());
        }
        let name = target
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_else(|| "out".into());
        let parent = target
            .parent()
            .filter(|p| !p.as_os_str().is_empty())
            .unwrap_or(Path::new("."));
        // create_dir_all reports "File exists" when a path component is a regular file.
        if let Some(file) = parent.ancestors().find(|a| a.is_file()) {
            return Err(
                unwritable(format!("{} is a file, not a directory", file.display())).into(),
            );
        }
        let created_parents = missing_ancestors(parent);
        let undo = |e: anyhow::Error| {
            remove_created(&created_parents);
            e
        };
        std::fs::create_dir_all(parent)
            .map_err(|e| unwritable(format!("cannot create {}: {e}", parent.display())).into())
            .map_err(undo)?;
        interrupt::remove_stale(parent, &name);
        let staging = parent.join(format!(".{name}.partial-{}", std::process::id()));
        if staging.exists() {
            std::fs::remove_dir_all(&staging)
                .with_context(|| format!("cannot clear {}", staging.display()))?;
        }
        std::fs::create_dir(&staging)
            .map_err(|e| unwritable(format!("cannot create {}: {e}", staging.display())).into())
            .map_err(undo)?;
        interrupt::register(&staging, &created_parents);
        Ok(Self {
            target: target.to_path_buf(),
            staging,
            created_parents,
            committed: false,
        })
    }

    /// Path of a file inside the staging directory.
    pub fn file(&self, name: &str) -> PathBuf {
        self.staging.join(name)
    }

    /// Write the manifest and move the finished directory into place. An existing one
    /// (checked in [`Self::create`]) is first moved aside and removed only once the new
    /// one is in place; if the move fails it is put back.
    pub fn commit(mut self) -> anyhow::Result<PathBuf> {
        manifest::write(&self.staging)
            .with_context(|| format!("cannot write the manifest in {}", self.staging.display()))?;
        let old = self
            .target
            .exists()
            .then(|| self.staging.with_extension("old"));
        if let Some(old) = &old {
            std::fs::rename(&self.target, old)
                .with_context(|| format!("cannot replace {}", self.target.display()))?;
        }
        if let Err(e) = std::fs::rename(&self.staging, &self.target) {
            if let Some(old) = &old {
                let _ = std::fs::rename(old, &self.target);
            }
            return Err(e)
                .with_context(|| format!("cannot move output into {}", self.target.display()));
        }
        self.committed = true;
        interrupt::unregister(&self.staging);
        if let Some(old) = old {
            std::fs::remove_dir_all(&old)
                .with_context(|| format!("cannot remove the replaced {}", old.display()))?;
        }
        Ok(self.target.clone())
    }
}

impl Drop for StagedDir {
    fn drop(&mut self) {
        if !self.committed {
            let _ = std::fs::remove_dir_all(&self.staging);
            remove_created(&self.created_parents);
            interrupt::unregister(&self.staging);
        }
    }
}
