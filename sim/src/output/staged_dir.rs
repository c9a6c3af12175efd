//! An output directory that appears only when complete: files are written into a sibling
//! staging directory, which replaces the target on [`StagedDir::commit`] and is removed
//! if the run fails (on drop), with the parent directories the run created for it (when
//! empty). Every committed directory carries a [`manifest`] of its
//! files; `--force` replaces only such a directory holding nothing else, and the old
//! directory stays in place until the new one is complete.

use super::{interrupt, manifest};
use crate::bad_input::BadInput;
use anyhow::Context;
use nix::fcntl::{AT_FDCWD, RenameFlags, renameat2};
use std::path::{Path, PathBuf};

/// A staging directory for `target`.
#[derive(Debug)]
pub struct StagedDir {
    target: PathBuf,
    staging: PathBuf,
    /// Whether an existing output may be replaced.
    force: bool,
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

/// A regular file among `dir` and its ancestors (create_dir_all would only say "File
/// exists" or "Not a directory").
fn file_on_the_way(dir: &Path) -> Option<&Path> {
    dir.ancestors().find(|a| a.is_file())
}

/// Create `dir` with its parents, for outputs written into it without staging (a study's
/// directory, shared by its shards and resumed into). A path through a file, or one that
/// cannot be created (permissions, a read-only file system), is the user's input.
pub fn create_shared(dir: &Path) -> Result<(), BadInput> {
    let cannot = |reason: String| BadInput(format!("cannot create {}: {reason}", dir.display()));
    if let Some(file) = file_on_the_way(dir) {
        return Err(cannot(format!(
            "{} is a file, not a directory",
            file.display()
        )));
    }
    std::fs::create_dir_all(dir).map_err(|e| cannot(e.to_string()))
}

/// `--force` replaces only what skyforge wrote: bad input otherwise.
fn refuse_foreign(target: &Path) -> anyhow::Result<()> {
    match manifest::refuse_replacing(target) {
        Some(reason) => Err(BadInput(format!(
            "--force will not replace {}: {reason}",
            target.display()
        ))
        .into()),
        None => Ok(()),
    }
}

/// Where a replaced output waits while the new one moves in (file systems that cannot
/// exchange): `.NAME.partial-PID.old`, the name [`interrupt::remove_stale`] recognises.
/// (`Path::with_extension` would give `.NAME.old`: the PID is the "extension".)
fn aside_name(staging: &Path) -> PathBuf {
    let mut name = staging.as_os_str().to_owned();
    name.push(".old");
    PathBuf::from(name)
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
        if target.exists() {
            refuse_foreign(target)?;
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
        if let Some(file) = file_on_the_way(parent) {
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
            force,
            created_parents,
            committed: false,
        })
    }

    /// Where `path`, inside this process's staging directories (a vehicle's output
    /// staged within its run's), will be once they are committed: each
    /// `.NAME.partial-PID` component named `NAME`. For the lines a command prints.
    pub fn final_path(path: &Path) -> PathBuf {
        let suffix = format!(".partial-{}", std::process::id());
        path.components()
            .map(|c| {
                let text = c.as_os_str().to_string_lossy();
                match text.strip_prefix('.').and_then(|t| t.strip_suffix(&suffix)) {
                    Some(name) => std::ffi::OsString::from(name),
                    None => c.as_os_str().to_os_string(),
                }
            })
            .collect()
    }

    /// Path of a file inside the staging directory.
    pub fn file(&self, name: &str) -> PathBuf {
        self.staging.join(name)
    }

    /// Write the manifest and move the finished directory into place. An existing one
    /// (checked in [`Self::create`], and again here) is exchanged with it atomically, so
    /// that the target always holds a complete output, then removed; where the file
    /// system cannot exchange, it is moved aside first and put back if the move fails (a
    /// process killed in between leaves it aside, and the next run puts it back:
    /// [`interrupt::remove_stale`]). An output that appeared meanwhile without `--force`
    /// is never replaced.
    pub fn commit(mut self) -> anyhow::Result<PathBuf> {
        manifest::write(&self.staging)
            .with_context(|| format!("cannot write the manifest in {}", self.staging.display()))?;
        let replaced = interrupt::exclusive(|registered| self.move_into_place(registered))?;
        self.committed = true;
        if let Some(old) = replaced {
            std::fs::remove_dir_all(&old)
                .with_context(|| format!("cannot remove the replaced {}", old.display()))?;
            interrupt::unregister(&old);
        }
        interrupt::unregister(&self.staging);
        Ok(self.target.clone())
    }

    /// The renames of [`Self::commit`]; returns where the replaced output went (a path
    /// in `registered`, the directories removed on interrupt).
    fn move_into_place(
        &self,
        registered: &mut interrupt::Registered,
    ) -> anyhow::Result<Option<PathBuf>> {
        let cannot = || format!("cannot move the output into {}", self.target.display());
        if !self.force || !self.target.exists() {
            return match std::fs::rename(&self.staging, &self.target) {
                Ok(()) => Ok(None),
                Err(e) if self.target.is_dir() => Err(BadInput(format!(
                    "output directory {} appeared while this run was writing (another run?) \
                     and was left as it is ({e}); pass --force to replace it",
                    self.target.display()
                ))
                .into()),
                Err(e) => Err(anyhow::Error::new(e).context(cannot())),
            };
        }
        refuse_foreign(&self.target)?;
        let exchanged = renameat2(
            AT_FDCWD,
            &self.staging,
            AT_FDCWD,
            &self.target,
            RenameFlags::RENAME_EXCHANGE,
        );
        if exchanged.is_ok() {
            return Ok(Some(self.staging.clone()));
        }
        let old = aside_name(&self.staging);
        std::fs::rename(&self.target, &old)
            .with_context(|| format!("cannot replace {}", self.target.display()))?;
        registered.push((old.clone(), Vec::new()));
        if let Err(e) = std::fs::rename(&self.staging, &self.target) {
            let _ = std::fs::rename(&old, &self.target);
            registered.retain(|(d, _)| *d != old);
            return Err(e).with_context(cannot);
        }
        Ok(Some(old))
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_aside_name_keeps_the_staging_pid() {
        let aside = aside_name(Path::new("dir/.out.partial-123"));
        assert_eq!(aside, Path::new("dir/.out.partial-123.old"));
        let nested = Path::new("runs")
            .join(format!(".pair.partial-{}", std::process::id()))
            .join("chaser");
        assert_eq!(
            StagedDir::final_path(&nested),
            Path::new("runs/pair/chaser")
        );
        let other = Path::new("runs/.pair.partial-1/chaser");
        assert_eq!(StagedDir::final_path(other), other);
    }
}
