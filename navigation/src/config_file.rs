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

/// Each `(name, value, max)` finite and in `(0, max]`: the first that is not, as `name =
/// value: must be in (0, max]`.
pub(crate) fn check_positive(values: &[(&str, f64, f64)]) -> Result<(), String> {
    for &(name, v, max) in values {
        if !(v.is_finite() && v > 0.0 && v <= max) {
            return Err(format!("{name} = {v}: must be in (0, {max}]"));
        }
    }
    Ok(())
}
