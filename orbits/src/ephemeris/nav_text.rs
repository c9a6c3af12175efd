//! The text of a navigation or orbit file (RINEX navigation, SP3), read with a size limit
//! and gunzipped when compressed.

use super::NavError;
use crate::bounded_read::{read_bytes, read_limited, too_large};
use std::path::Path;

/// Largest navigation file read, compressed or after decompression (bytes): a day of
/// every constellation's broadcast ephemerides (RINEX 4 BRD4 files) is about 15 MB.
pub const NAV_FILE_MAX_BYTES: u64 = 256 * 1024 * 1024;

/// Read a whole text file, gunzipping it when it starts with the gzip magic bytes; a
/// directory, or more than [`NAV_FILE_MAX_BYTES`] (a device such as `/dev/zero`), is an
/// error before memory runs out.
pub(crate) fn read_text_maybe_gz(path: &Path) -> Result<String, NavError> {
    const KIND: &str = "navigation file";
    let io_err = |source| NavError::Io {
        path: path.display().to_string(),
        source,
    };
    let raw = read_bytes(path, NAV_FILE_MAX_BYTES, KIND).map_err(io_err)?;
    let bytes = if raw.starts_with(&[0x1f, 0x8b]) {
        read_limited(
            flate2::read::MultiGzDecoder::new(raw.as_slice()),
            NAV_FILE_MAX_BYTES,
        )
        .map_err(io_err)?
        .ok_or_else(|| io_err(too_large(NAV_FILE_MAX_BYTES, KIND)))?
    } else {
        raw
    };
    Ok(String::from_utf8_lossy(&bytes).into_owned())
}
