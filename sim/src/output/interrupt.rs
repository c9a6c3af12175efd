//! Interrupted runs leave nothing behind: the staging directories of this process are
//! registered here, and on SIGINT or SIGTERM a watcher thread removes them, says so and
//! exits with 128 + the signal (130, 143). Staging directories of processes that died
//! without that chance (SIGKILL, a crash) are removed by the next run writing beside them
//! ([`remove_stale`]).

use std::path::{Path, PathBuf};
use std::sync::{Mutex, Once};

/// Staging directories this process is writing, each with the parent directories the
/// run created for it (deepest first).
static STAGING: Mutex<Registered> = Mutex::new(Vec::new());
static WATCHER: Once = Once::new();

/// The staging directory `dir` is being written: remove it if the run is interrupted,
/// and then the parents in `created_parents` that are empty.
pub fn register(dir: &Path, created_parents: &[PathBuf]) {
    WATCHER.call_once(start_watcher);
    STAGING
        .lock()
        .unwrap_or_else(|e| e.into_inner())
        .push((dir.to_path_buf(), created_parents.to_vec()));
}

/// `dir` was committed or removed.
pub fn unregister(dir: &Path) {
    STAGING
        .lock()
        .unwrap_or_else(|e| e.into_inner())
        .retain(|(d, _)| d != dir);
}

/// Registered directories, each with the parents its run created.
pub type Registered = Vec<(PathBuf, Vec<PathBuf>)>;

/// Run `f` with the interrupt watcher held off: a SIGINT/SIGTERM arriving meanwhile
/// removes the registered directories only after `f` (a commit's renames) is done. `f`
/// registers and unregisters through the list it is given.
pub fn exclusive<T>(f: impl FnOnce(&mut Registered) -> T) -> T {
    let mut held = STAGING.lock().unwrap_or_else(|e| e.into_inner());
    f(&mut held)
}

fn start_watcher() {
    use signal_hook::consts::{SIGINT, SIGTERM};
    let Ok(mut signals) = signal_hook::iterator::Signals::new([SIGINT, SIGTERM]) else {
        eprintln!(
            "warning: cannot watch for interrupts; an interrupted run may leave a staging directory"
        );
        return;
    };
    std::thread::spawn(move || {
        if let Some(signal) = signals.forever().next() {
            let dirs = STAGING.lock().unwrap_or_else(|e| e.into_inner()).clone();
            for (d, parents) in &dirs {
                let _ = std::fs::remove_dir_all(d);
                super::staged_dir::remove_created(parents);
            }
            let name = if signal == SIGINT {
                "SIGINT"
            } else {
                "SIGTERM"
            };
            eprintln!("error: interrupted by {name}; partial output removed, nothing written");
            std::process::exit(128 + signal);
        }
    });
}

/// The process id in a staging directory name `.NAME.partial-PID` (or its `.old` twin
/// from a replacement), for `name`.
fn staging_pid(entry: &str, name: &str) -> Option<u32> {
    let rest = entry.strip_prefix(&format!(".{name}.partial-"))?;
    rest.strip_suffix(".old").unwrap_or(rest).parse().ok()
}

/// Remove the staging directories for output `name` in `parent` left by processes that
/// no longer run (`/proc/PID` gone). Only names of SkyForge's own pattern are touched. A
/// replaced output moved aside (`.old`) by a process killed before its new output took
/// its place is put back when the output is missing.
pub fn remove_stale(parent: &Path, name: &str) {
    let Ok(entries) = std::fs::read_dir(parent) else {
        return;
    };
    let me = std::process::id();
    for entry in entries.flatten() {
        let file_name = entry.file_name();
        let Some(pid) = staging_pid(&file_name.to_string_lossy(), name) else {
            continue;
        };
        let alive = pid == me || Path::new("/proc").join(pid.to_string()).exists();
        if alive || !entry.file_type().is_ok_and(|t| t.is_dir()) {
            continue;
        }
        let target = parent.join(name);
        let aside = file_name.to_string_lossy().ends_with(".old");
        if !(aside && !target.exists() && std::fs::rename(entry.path(), &target).is_ok()) {
            let _ = std::fs::remove_dir_all(entry.path());
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn staging_names_are_recognised_and_only_dead_owners_cleared() {
        assert_eq!(staging_pid(".out.partial-123", "out"), Some(123));
        assert_eq!(staging_pid(".out.partial-123.old", "out"), Some(123));
        assert_eq!(staging_pid(".out.partial-x", "out"), None);
        assert_eq!(staging_pid(".other.partial-123", "out"), None);
        let tmp = tempfile::tempdir().unwrap();
        // PID 1 is always alive; u32::MAX never is.
        for d in [".out.partial-1", ".out.partial-4294967295", "keep"] {
            std::fs::create_dir(tmp.path().join(d)).unwrap();
        }
        remove_stale(tmp.path(), "out");
        assert!(tmp.path().join(".out.partial-1").exists());
        assert!(!tmp.path().join(".out.partial-4294967295").exists());
        assert!(tmp.path().join("keep").exists());
    }

    #[test]
    fn an_output_moved_aside_by_a_dead_process_is_put_back() {
        let tmp = tempfile::tempdir().unwrap();
        let aside = tmp.path().join(".out.partial-4294967295.old");
        std::fs::create_dir(&aside).unwrap();
        std::fs::write(aside.join("a"), "previous").unwrap();
        remove_stale(tmp.path(), "out");
        assert_eq!(
            std::fs::read_to_string(tmp.path().join("out/a")).unwrap(),
            "previous"
        );
        assert!(!aside.exists());
        // With the output in place, an aside copy is only removed.
        std::fs::create_dir(&aside).unwrap();
        remove_stale(tmp.path(), "out");
        assert!(!aside.exists());
        assert!(tmp.path().join("out/a").exists());
    }
}
