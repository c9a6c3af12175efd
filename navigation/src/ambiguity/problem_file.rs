//! A float ambiguity vector and its covariance read from a file, by extension:
//!
//! - `.json`: `{"a_hat": [a1, ..., an], "q": [[q11, ..., q1n], ..., [qn1, ..., qnn]]}`;
//! - `.csv`: the first data line is `a_hat` (n comma-separated numbers), the next n
//!   lines are the rows of `Q`. Blank lines and lines starting with `#` are skipped.
//!
//! At most [`MAX_FILE_BYTES`] bytes and [`super::MAX_DIMENSION`] ambiguities; the
//! content (symmetry, positive definiteness) is checked by [`super::lambda`].

use super::MAX_DIMENSION;
use nalgebra::{DMatrix, DVector};
use std::io::Read;
use std::path::Path;

/// Largest problem file read (4 MiB).
pub const MAX_FILE_BYTES: u64 = 4 << 20;

/// A float solution and its covariance.
#[derive(Debug, Clone, PartialEq)]
pub struct Problem {
    pub a_hat: DVector<f64>,
    pub q: DMatrix<f64>,
}

/// Why a problem file could not be read: the file, the place when there is one, and what
/// is wrong and allowed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{file}{}: {message}", location(.line, .column))]
pub struct ProblemFileError {
    pub file: String,
    /// 1-based line, when the error has one.
    pub line: Option<usize>,
    /// 1-based column (JSON: character; CSV: comma-separated field).
    pub column: Option<usize>,
    pub message: String,
}

fn location(line: &Option<usize>, column: &Option<usize>) -> String {
    match (*line, *column) {
        (Some(l), Some(c)) => format!(":{l}:{c}"),
        (Some(l), None) => format!(":{l}"),
        _ => String::new(),
    }
}

/// A parse error before the file name is attached.
type Located = (Option<usize>, Option<usize>, String);

fn at(line: Option<usize>, column: Option<usize>, message: impl Into<String>) -> Located {
    (line, column, message.into())
}

/// Read `path` (`.json` or `.csv`).
pub fn read_problem(path: &Path) -> Result<Problem, ProblemFileError> {
    let file = path.display().to_string();
    let fail = |(line, column, message): Located| ProblemFileError {
        file: file.clone(),
        line,
        column,
        message,
    };
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    let parse: fn(&str) -> Result<Problem, Located> = match ext.as_deref() {
        Some("json") => parse_json,
        Some("csv") => parse_csv,
        other => {
            return Err(fail(at(
                None,
                None,
                format!(
                    "unknown extension {:?}: allowed are .json and .csv",
                    other.unwrap_or("")
                ),
            )));
        }
    };
    let text = read_bounded(path).map_err(|m| fail(at(None, None, m)))?;
    parse(&text).map_err(fail)
}

/// The file's text, refusing directories, files over the limit and non-UTF-8 content.
fn read_bounded(path: &Path) -> Result<String, String> {
    let meta = std::fs::metadata(path).map_err(|e| format!("cannot read: {e}"))?;
    if meta.is_dir() {
        return Err("is a directory, not a problem file".into());
    }
    if meta.len() > MAX_FILE_BYTES {
        return Err(format!(
            "{} bytes exceed the limit of {MAX_FILE_BYTES} bytes",
            meta.len()
        ));
    }
    let mut bytes = Vec::new();
    std::fs::File::open(path)
        .and_then(|f| f.take(MAX_FILE_BYTES + 1).read_to_end(&mut bytes))
        .map_err(|e| format!("cannot read: {e}"))?;
    if bytes.len() as u64 > MAX_FILE_BYTES {
        return Err(format!("more than the limit of {MAX_FILE_BYTES} bytes"));
    }
    String::from_utf8(bytes)
        .map_err(|e| format!("not UTF-8 text (byte {})", e.utf8_error().valid_up_to()))
}

#[derive(serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct JsonProblem {
    a_hat: Vec<f64>,
    q: Vec<Vec<f64>>,
}

/// Parse the JSON layout.
fn parse_json(text: &str) -> Result<Problem, Located> {
    let p: JsonProblem = serde_json::from_str(text).map_err(|e| {
        at(
            Some(e.line()),
            Some(e.column()),
            format!("{e} (expected {{\"a_hat\": [numbers], \"q\": [[numbers], ...]}})"),
        )
    })?;
    let n = check_n(p.a_hat.len()).map_err(|m| at(None, None, format!("a_hat: {m}")))?;
    if p.q.len() != n {
        return Err(at(
            None,
            None,
            format!(
                "q has {} rows but a_hat has {n} entries: q must be {n} x {n}",
                p.q.len()
            ),
        ));
    }
    if let Some((i, row)) = p.q.iter().enumerate().find(|(_, r)| r.len() != n) {
        return Err(at(
            None,
            None,
            format!("q[{i}] has {} entries: q must be {n} x {n}", row.len()),
        ));
    }
    Ok(Problem {
        a_hat: DVector::from_vec(p.a_hat),
        q: DMatrix::from_fn(n, n, |i, j| p.q[i][j]),
    })
}

fn check_n(n: usize) -> Result<usize, String> {
    if n == 0 {
        Err("no ambiguities (at least 1 is needed)".into())
    } else if n > MAX_DIMENSION {
        Err(format!(
            "{n} ambiguities exceed the limit of {MAX_DIMENSION}"
        ))
    } else {
        Ok(n)
    }
}

/// One CSV data line: finite numbers separated by commas.
fn csv_numbers(line_no: usize, line: &str) -> Result<Vec<f64>, Located> {
    line.split(',')
        .enumerate()
        .map(|(i, field)| {
            let f = field.trim();
            match f.parse::<f64>() {
                Ok(v) if v.is_finite() => Ok(v),
                _ => Err(at(
                    Some(line_no),
                    Some(i + 1),
                    format!("field {} is {f:?}: a finite number is expected", i + 1),
                )),
            }
        })
        .collect()
}

/// Parse the CSV layout.
fn parse_csv(text: &str) -> Result<Problem, Located> {
    let mut data = text
        .lines()
        .enumerate()
        .map(|(i, l)| (i + 1, l.trim()))
        .filter(|(_, l)| !l.is_empty() && !l.starts_with('#'));
    let Some((first_no, first)) = data.next() else {
        return Err(at(None, None, "no data: the first data line must be a_hat"));
    };
    // Count the fields before parsing them, so the size is known before allocating.
    let n = check_n(first.split(',').count())
        .map_err(|m| at(Some(first_no), None, format!("a_hat: {m}")))?;
    let a_hat = csv_numbers(first_no, first)?;
    let mut q = DMatrix::zeros(n, n);
    let mut rows = 0;
    for (no, line) in data {
        if rows == n {
            return Err(at(
                Some(no),
                None,
                format!("extra line: a_hat has {n} entries, so exactly {n} rows of Q follow it"),
            ));
        }
        let fields = line.split(',').count();
        if fields != n {
            return Err(at(
                Some(no),
                None,
                format!(
                    "row {} of Q has {fields} fields, expected {n} (Q must be {n} x {n})",
                    rows + 1
                ),
            ));
        }
        for (j, v) in csv_numbers(no, line)?.into_iter().enumerate() {
            q[(rows, j)] = v;
        }
        rows += 1;
    }
    if rows < n {
        return Err(at(
            None,
            None,
            format!("Q has {rows} rows, expected {n} (one line per row after a_hat)"),
        ));
    }
    Ok(Problem {
        a_hat: DVector::from_vec(a_hat),
        q,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn json_and_csv_give_the_same_problem() {
        let j = parse_json(r#"{"a_hat": [1.5, -2], "q": [[2, 0.5], [0.5, 1]]}"#).unwrap();
        let c = parse_csv("# float solution\n1.5, -2\n\n2,0.5\n0.5 ,1\n").unwrap();
        assert_eq!(j, c);
        assert_eq!(j.q[(0, 1)], 0.5);
        assert_eq!(j.a_hat[1], -2.0);
    }

    #[test]
    fn errors_name_the_place() {
        let (l, c, m) = parse_csv("1,2\n3,x\n4,5\n").unwrap_err();
        assert_eq!((l, c), (Some(2), Some(2)), "{m}");
        let (l, _, m) = parse_csv("1,2\n3,4\n4,5\n6,7\n").unwrap_err();
        assert_eq!(l, Some(4), "{m}");
        let (l, c, m) = parse_json("{\"a_hat\": [1, 2],\n \"q\": [[1, \"a\"]]}").unwrap_err();
        assert_eq!(l, Some(2), "{m}");
        assert!(c.is_some());
        let (_, _, m) = parse_json(r#"{"a_hat": [1, 2], "q": [[1, 0], [0]]}"#).unwrap_err();
        assert!(m.contains("q[1] has 1 entries"), "{m}");
        let (_, _, m) = parse_json(r#"{"a_hat": [], "q": []}"#).unwrap_err();
        assert!(m.contains("at least 1"), "{m}");
        let big = vec!["0"; MAX_DIMENSION + 1].join(",");
        let (l, _, m) = parse_csv(&big).unwrap_err();
        assert_eq!(l, Some(1));
        assert!(m.contains("limit of 500"), "{m}");
    }
}
