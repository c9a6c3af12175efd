//! The real-data test tier's folder (DESIGN.md "Reference material"): `SKYFORGE_DATA`,
//! else `shared/data` beside the workspace. The real-data tests of every crate find their
//! files through [`require_dir`].

use std::path::PathBuf;

/// Environment variable naming the real-data folder.
pub const ENV: &str = "SKYFORGE_DATA";

/// The real-data folder; panics with a loud message when it does not exist (the tier was
/// asked for explicitly, so a missing folder is a failure, not a skip).
pub fn require_dir() -> PathBuf {
    let dir = std::env::var_os(ENV).map(PathBuf::from).unwrap_or_else(|| {
        PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../../shared/data"))
    });
    assert!(
        dir.is_dir(),
        "\n\n*** REAL-DATA FOLDER MISSING: {} ***\n*** set {ENV} to the shared/data folder ***\n",
        dir.display()
    );
    dir
}

/// The `system` broadcast ephemerides of the real-data navigation file `rel` (a path
/// inside [`require_dir`]); panics on a read error, as the tier's tests want.
pub fn ephemerides(
    rel: &str,
    system: crate::ephemeris::System,
) -> Vec<crate::ephemeris::BroadcastEphemeris> {
    let path = require_dir().join(rel);
    crate::ephemeris::rinex_nav::read_nav_file(&path)
        .unwrap_or_else(|e| panic!("{e}"))
        .into_iter()
        .filter(|e| e.sat.system == system)
        .collect()
}
