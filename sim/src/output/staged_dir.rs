//! An output directory that appears only when complete: files are written into a sibling
//! staging directory, which replaces the target on [`StagedDir::commit`] and is removed
//! if the run fails (on drop).

use crate::BadInput;
use anyhow::Context;
use std::path::{Path, PathBuf};

/// A staging directory for `target`.
#[derive(Debug)]
pub struct StagedDir {
    target: PathBuf,
    staging: PathBuf,
    committed: bool,
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
        std::fs::create_dir_all(parent)
            .map_err(|e| unwritable(format!("cannot create {}: {e}", parent.display())))?;
        let staging = parent.join(format!(".{name}.partial-{}", std::process::id()));
        if staging.exists() {
            std::fs::remove_dir_all(&staging)
                .with_context(|| format!("cannot clear {}", staging.display()))?;
        }
        std::fs::create_dir(&staging)
            .map_err(|e| unwritable(format!("cannot create {}: {e}", staging.display())))?;
        Ok(Self {
            target: target.to_path_buf(),
            staging,
            committed: false,
        })
    }

    /// Path of a file inside the staging directory.
    pub fn file(&self, name: &str) -> PathBuf {
        self.staging.join(name)
    }

    /// Move the finished directory into place (replacing an existing one).
    pub fn commit(mut self) -> anyhow::Result<PathBuf> {
        if self.target.exists() {
            std::fs::remove_dir_all(&self.target)
                .with_context(|| format!("cannot replace {}", self.target.display()))?;
        }
        std::fs::rename(&self.staging, &self.target)
            .with_context(|| format!("cannot move output into {}", self.target.display()))?;
        self.committed = true;
        Ok(self.target.clone())
    }
}

impl Drop for StagedDir {
    fn drop(&mut self) {
        if !self.committed {
            let _ = std::fs::remove_dir_all(&self.staging);
        }
    }
}
