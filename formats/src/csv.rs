//! Reading SkyForge's CSV tables: a file read whole under a size cap, its header's column
//! names, every data line split on commas and its fields looked up by name, every error
//! naming the file and the line.

use hifitime::Epoch;
use skyforge_orbits::bounded_read::read_text;
use skyforge_orbits::time::parse_epoch;
use std::path::{Path, PathBuf};

/// Largest CSV file read (bytes): a day of 1 Hz epochs of `ambiguities.csv` with two
/// baselines and 40 double differences is about 200 MB.
pub(crate) const MAX_CSV_BYTES: u64 = 1 << 30;

/// Why one of SkyForge's files could not be read. Every variant names the file.
#[derive(Debug, thiserror::Error)]
pub enum FormatError {
    /// The file is missing, unreadable, too large or not what it should be.
    #[error("{path}: {message}")]
    File { path: PathBuf, message: String },
    /// A line of a table is malformed (`line` counts from 1, the header's).
    #[error("{path}:{line}: {message}")]
    Row {
        path: PathBuf,
        line: usize,
        message: String,
    },
}

impl FormatError {
    pub fn file(path: &Path, message: impl Into<String>) -> Self {
        Self::File {
            path: path.to_path_buf(),
            message: message.into(),
        }
    }

    pub fn row(path: &Path, line: usize, message: impl Into<String>) -> Self {
        Self::Row {
            path: path.to_path_buf(),
            line,
            message: message.into(),
        }
    }
}

/// `path` read whole, size-capped: `header` checks its header (the column names), `each`
/// gets every data line with its 1-based line number.
pub(crate) fn read_csv(
    path: &Path,
    header: impl FnOnce(&[&str]) -> Result<(), FormatError>,
    mut each: impl FnMut(&[&str], usize, &str) -> Result<(), FormatError>,
) -> Result<(), FormatError> {
    let text = read_text(path, MAX_CSV_BYTES, "CSV file")
        .map_err(|e| FormatError::file(path, e.to_string()))?;
    let mut lines = text.lines();
    let Some(first) = lines.next() else {
        return Err(FormatError::file(path, "empty file: no header line"));
    };
    let names: Vec<&str> = first.split(',').map(str::trim).collect();
    header(&names)?;
    for (i, line) in lines.enumerate() {
        let number = i + 2;
        if line.trim().is_empty() {
            continue;
        }
        each(&names, number, line)?;
    }
    Ok(())
}

/// The header of `path` must name every one of `columns`.
pub(crate) fn require_columns(
    path: &Path,
    header: &[&str],
    columns: &[String],
) -> Result<(), FormatError> {
    match columns.iter().find(|c| !header.contains(&c.as_str())) {
        Some(c) => Err(FormatError::row(
            path,
            1,
            format!("the header has no column {c}"),
        )),
        None => Ok(()),
    }
}

/// One data line split on commas, its fields looked up by header name.
pub(crate) struct Fields<'a> {
    path: &'a Path,
    line: usize,
    header: &'a [&'a str],
    fields: Vec<&'a str>,
}

impl<'a> Fields<'a> {
    pub(crate) fn new(
        path: &'a Path,
        line: usize,
        header: &'a [&'a str],
        text: &'a str,
    ) -> Result<Self, FormatError> {
        let fields: Vec<&str> = text.split(',').map(str::trim).collect();
        let f = Self {
            path,
            line,
            header,
            fields,
        };
        if f.fields.len() != header.len() {
            return Err(f.error(format!(
                "{} fields; the header has {}",
                f.fields.len(),
                header.len()
            )));
        }
        Ok(f)
    }

    pub(crate) fn error(&self, message: String) -> FormatError {
        FormatError::row(self.path, self.line, message)
    }

    /// Whether the header names `column`.
    pub(crate) fn has(&self, column: &str) -> bool {
        self.header.contains(&column)
    }

    pub(crate) fn text(&self, column: &str) -> Result<&'a str, FormatError> {
        self.header
            .iter()
            .position(|h| *h == column)
            .and_then(|i| self.fields.get(i).copied())
            .ok_or_else(|| self.error(format!("no column {column}")))
    }

    /// A number, `None` when the field is empty.
    pub(crate) fn number(&self, column: &str) -> Result<Option<f64>, FormatError> {
        let t = self.text(column)?;
        if t.is_empty() {
            return Ok(None);
        }
        match t.parse::<f64>() {
            Ok(v) if v.is_finite() => Ok(Some(v)),
            _ => Err(self.error(format!("{column} = {t:?} is not a finite number"))),
        }
    }

    pub(crate) fn parse<T: std::str::FromStr>(
        &self,
        column: &str,
        what: &str,
    ) -> Result<T, FormatError> {
        let t = self.text(column)?;
        t.parse()
            .map_err(|_| self.error(format!("{column} = {t:?} is not {what}")))
    }

    /// A flag written `0` or `1`.
    pub(crate) fn flag(&self, column: &str) -> Result<bool, FormatError> {
        match self.text(column)? {
            "0" => Ok(false),
            "1" => Ok(true),
            t => Err(self.error(format!("{column} = {t:?}: 0 or 1"))),
        }
    }

    pub(crate) fn epoch(&self, column: &str) -> Result<Epoch, FormatError> {
        let t = self.text(column)?;
        parse_epoch(t).map_err(|e| self.error(format!("{column}: {e}")))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn csv(dir: &Path, name: &str, text: &str) -> PathBuf {
        let p = dir.join(name);
        std::fs::write(&p, text).unwrap();
        p
    }

    #[test]
    fn csv_rows_name_file_and_line() {
        let dir = tempfile::tempdir().unwrap();
        let p = csv(
            dir.path(),
            "a.csv",
            "time_gpst,n\n2023-03-12T00:00:00 GPST,1\nx\n",
        );
        let mut seen = Vec::new();
        let e = read_csv(
            &p,
            |_| Ok(()),
            |h, line, text| {
                let f = Fields::new(&p, line, h, text)?;
                seen.push(f.number("n")?);
                Ok(())
            },
        )
        .unwrap_err()
        .to_string();
        assert_eq!(seen, [Some(1.0)]);
        assert!(e.contains("a.csv:3: 1 fields; the header has 2"), "{e}");
        let p = csv(
            dir.path(),
            "b.csv",
            "time_gpst,n\n2023-03-12T00:00:00 GPST,nan\n",
        );
        let e = read_csv(
            &p,
            |_| Ok(()),
            |h, line, text| Fields::new(&p, line, h, text)?.number("n").map(|_| ()),
        )
        .unwrap_err()
        .to_string();
        assert!(
            e.contains("b.csv:2: n = \"nan\" is not a finite number"),
            "{e}"
        );
        let e = read_csv(&dir.path().join("none.csv"), |_| Ok(()), |_, _, _| Ok(()))
            .unwrap_err()
            .to_string();
        assert!(e.contains("none.csv"), "{e}");
    }
}
