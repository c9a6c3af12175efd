//! One file written whole or not at all, outside a staged output directory: the bytes go
//! to a new file beside the target (`.NAME.partial-PID`, never an existing one), renamed
//! over the target when complete. A failure removes only the file this call created.
//! Before anything is made, [`check_target`] applies the rules of every output: nothing
//! replaced that SkyForge did not write, `--force` to replace what it did.

use crate::bad_input::BadInput;
pub use skyforge_orbits::bounded_read::starts_with;
use std::io::Write;
use std::path::Path;

/// Whether `target` may be written: its directory exists, and it is absent or a file
/// SkyForge wrote (`ours`, told what it is: `what`, e.g. "a report") replaced with
/// `force`. Checked before any work, so that a refusal costs nothing and leaves nothing.
pub fn check_target(
    target: &Path,
    force: bool,
    what: &str,
    ours: impl FnOnce(&Path) -> bool,
) -> Result<(), BadInput> {
    let refuse = |why: &str| Err(BadInput(format!("{}: {why}", target.display())));
    let parent = target
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    if !parent.is_dir() {
        return refuse(&format!(
            "cannot write it: {} is not a directory",
            parent.display()
        ));
    }
    let Ok(meta) = std::fs::symlink_metadata(target) else {
        return Ok(());
    };
    if meta.is_dir() {
        return refuse("is a directory; give the path of a file");
    }
    if !meta.is_file() || !ours(target) {
        return refuse(&format!(
            "exists and is not {what} skyforge wrote; remove it yourself if it should go"
        ));
    }
    if !force {
        return refuse(&format!("exists ({what}); give --force to replace it"));
    }
    Ok(())
}

/// Write `bytes` to `target` through a new file beside it, renamed when complete.
pub fn write(target: &Path, bytes: &[u8]) -> std::io::Result<()> {
    let name = target.file_name().map(|n| n.to_string_lossy().into_owned());
    let partial = target.with_file_name(format!(
        ".{}.partial-{}",
        name.unwrap_or_default(),
        std::process::id()
    ));
    let written = std::fs::OpenOptions::new()
        .write(true)
        .create_new(true)
        .open(&partial)
        .and_then(|mut f| f.write_all(bytes).and_then(|()| f.sync_all()));
    match written.and_then(|()| std::fs::rename(&partial, target)) {
        Ok(()) => Ok(()),
        Err(e) => {
            // Only a file this call created is removed.
            if partial.exists() && e.kind() != std::io::ErrorKind::AlreadyExists {
                let _ = std::fs::remove_file(&partial);
            }
            Err(e)
        }
    }
}
