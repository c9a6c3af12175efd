//! One file written whole or not at all, outside a staged output directory: the bytes go
//! to a new file beside the target (`.NAME.partial-PID`, never an existing one), renamed
//! over the target when complete. A failure removes only the file this call created.

use std::io::Write;
use std::path::Path;

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
