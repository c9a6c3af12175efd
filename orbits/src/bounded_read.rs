//! Reading a whole input file with a size limit for its kind (issue #11): a device such as
//! `/dev/zero`, a named pipe that never ends or a file far larger than its kind can be is
//! refused once the limit is passed, before memory runs out, and a directory is named as
//! one. File metadata cannot do this: a device reports a size of 0.

use std::io::{Error, ErrorKind, Read};
use std::path::Path;

/// At most `limit` bytes of `reader`, or `None` when it holds more.
pub fn read_limited(reader: impl Read, limit: u64) -> std::io::Result<Option<Vec<u8>>> {
    let mut out = Vec::new();
    reader.take(limit.saturating_add(1)).read_to_end(&mut out)?;
    Ok((out.len() as u64 <= limit).then_some(out))
}

/// The error for input beyond `limit` bytes of a `kind` (e.g. "navigation file").
pub fn too_large(limit: u64, kind: &str) -> Error {
    Error::new(
        ErrorKind::FileTooLarge,
        format!("more than {}: not a {kind}", size_text(limit)),
    )
}

/// The bytes of the file at `path`, at most `limit` of them; the errors say what the path
/// is instead (a directory, more than the limit) in terms of `kind`.
pub fn read_bytes(path: &Path, limit: u64, kind: &str) -> std::io::Result<Vec<u8>> {
    if path.is_dir() {
        return Err(Error::new(
            ErrorKind::IsADirectory,
            format!("is a directory, not a {kind}"),
        ));
    }
    let file = std::fs::File::open(path)?;
    read_limited(file, limit)?.ok_or_else(|| too_large(limit, kind))
}

/// [`read_bytes`] as UTF-8 text.
pub fn read_text(path: &Path, limit: u64, kind: &str) -> std::io::Result<String> {
    String::from_utf8(read_bytes(path, limit, kind)?).map_err(|_| {
        Error::new(
            ErrorKind::InvalidData,
            format!("not UTF-8 text, so not a {kind}"),
        )
    })
}

/// `bytes` in MiB when whole, else in bytes.
fn size_text(bytes: u64) -> String {
    const MIB: u64 = 1 << 20;
    if bytes >= MIB && bytes.is_multiple_of(MIB) {
        format!("{} MiB", bytes / MIB)
    } else {
        format!("{bytes} bytes")
    }
}

/// Whether the file at `path` begins with `prefix` (only that many bytes are read,
/// whatever the file's size): how a writer recognises a file it wrote.
pub fn starts_with(path: &Path, prefix: &[u8]) -> bool {
    let mut head = Vec::with_capacity(prefix.len());
    std::fs::File::open(path)
        .and_then(|f| f.take(prefix.len() as u64).read_to_end(&mut head))
        .is_ok_and(|_| head == prefix)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn devices_directories_and_large_files_are_named_for_what_they_are() {
        let tmp = tempfile::tempdir().unwrap();
        let e = read_text(tmp.path(), 10, "scenario file").unwrap_err();
        assert_eq!(e.to_string(), "is a directory, not a scenario file");
        let e = read_bytes(Path::new("/dev/zero"), 1 << 20, "scenario file").unwrap_err();
        assert_eq!(e.to_string(), "more than 1 MiB: not a scenario file");
        let file = tmp.path().join("f");
        std::fs::write(&file, "0123456789").unwrap();
        assert_eq!(read_text(&file, 10, "x").unwrap(), "0123456789");
        let e = read_text(&file, 9, "CSV table").unwrap_err();
        assert_eq!(e.to_string(), "more than 9 bytes: not a CSV table");
        std::fs::write(&file, [0xff, 0xfe]).unwrap();
        let e = read_text(&file, 10, "scenario file").unwrap_err();
        assert_eq!(e.to_string(), "not UTF-8 text, so not a scenario file");
        let e = read_text(&tmp.path().join("missing"), 10, "x").unwrap_err();
        assert_eq!(e.kind(), ErrorKind::NotFound);
    }
}
