//! RINEX navigation files, versions 2 (GPS), 3 (mixed) and 4 (message types), plain or
//! gzip-compressed. Only GPS LNAV and BeiDou D1/D2 records are kept; others are skipped.

use super::{NavError, broadcast::BroadcastEphemeris};
use std::path::Path;

/// Read every GPS LNAV and BeiDou D1/D2 ephemeris in the file.
pub fn read_nav_file(path: &Path) -> Result<Vec<BroadcastEphemeris>, NavError> {
    todo!("{path:?}")
}
