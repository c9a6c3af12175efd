//! Reading a settings file (TOML) of a navigation stage: size-limited, checked by the
//! stage's own parser, every error naming the file.

use skyforge_orbits::bounded_read::read_text;
use std::path::Path;

/// Largest settings file read (bytes).
const MAX_CONFIG_BYTES: u64 = 1 << 20;

/// The settings at `path` (`what` names the kind in a size or read error), parsed and
/// checked by `parse`; errors name the file.
pub(crate) fn read_settings<T>(
    path: &Path,
    what: &str,
    parse: impl FnOnce(&str) -> Result<T, String>,
) -> Result<T, String> {
    let text = read_text(path, MAX_CONFIG_BYTES, what).map_err(|e| e.to_string())?;
    parse(&text).map_err(|e| format!("{}: {e}", path.display()))
}
