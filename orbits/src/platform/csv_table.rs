//! Numeric CSV tables (trajectory and attitude inputs): comma-separated numbers, `#`
//! starts a comment (whole line or trailing), blank lines are skipped, and an optional
//! header line is allowed before the first data row (recognised by a first field that is
//! not a number). The first column is time, strictly increasing. Every error names the
//! file and the 1-based line.

use super::PlatformError;
use crate::bounded_read::read_text;
use std::path::Path;

/// Largest CSV table read (a year at 1 Hz of a trajectory is about 2.5 GB; tables that
/// large should be resampled).
const CSV_MAX_BYTES: u64 = 512 << 20;

/// One data row with its 1-based line number.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct NumericRow {
    pub line: usize,
    pub values: Vec<f64>,
}

/// Reads `path` as rows of numbers. `columns` names every possible column in order and
/// `allowed_counts` lists the accepted column counts; all rows must have the same count.
/// At least two rows are required and the first column must strictly increase.
pub(crate) fn read_numeric_csv(
    path: &Path,
    columns: &[&str],
    allowed_counts: &[usize],
) -> Result<Vec<NumericRow>, PlatformError> {
    let shown = path.display().to_string();
    let text = read_text(path, CSV_MAX_BYTES, "CSV table").map_err(|e| PlatformError::Csv {
        path: shown.clone(),
        line: 0,
        message: format!("cannot read the file: {e}"),
    })?;
    parse_numeric_csv(&text, &shown, columns, allowed_counts)
}

/// [`read_numeric_csv`] on text already in memory; `shown` names it in errors.
pub(crate) fn parse_numeric_csv(
    text: &str,
    shown: &str,
    columns: &[&str],
    allowed_counts: &[usize],
) -> Result<Vec<NumericRow>, PlatformError> {
    let error = |line: usize, message: String| PlatformError::Csv {
        path: shown.to_string(),
        line,
        message,
    };
    let expected = || {
        let forms: Vec<String> = allowed_counts
            .iter()
            .map(|&n| columns[..n].join(","))
            .collect();
        forms.join(" or ")
    };
    let mut rows: Vec<NumericRow> = Vec::new();
    let mut header_allowed = true;
    for (index, raw) in text.lines().enumerate() {
        let line = index + 1;
        let content = raw.split('#').next().unwrap_or("").trim();
        if content.is_empty() {
            continue;
        }
        let fields: Vec<&str> = content.split(',').map(str::trim).collect();
        if header_allowed && fields[0].parse::<f64>().is_err() {
            header_allowed = false;
            continue;
        }
        header_allowed = false;
        if !allowed_counts.contains(&fields.len()) {
            return Err(error(
                line,
                format!("{} columns, expected {}", fields.len(), expected()),
            ));
        }
        if let Some(first) = rows.first()
            && first.values.len() != fields.len()
        {
            return Err(error(
                line,
                format!(
                    "{} columns, but line {} has {}; all rows need the same columns",
                    fields.len(),
                    first.line,
                    first.values.len()
                ),
            ));
        }
        let mut values = Vec::with_capacity(fields.len());
        for (k, field) in fields.iter().enumerate() {
            match field.parse::<f64>() {
                Ok(v) if v.is_finite() => values.push(v),
                _ => {
                    return Err(error(
                        line,
                        format!("{} = {field:?} is not a finite number", columns[k]),
                    ));
                }
            }
        }
        if let Some(prev) = rows.last()
            && values[0] <= prev.values[0]
        {
            return Err(error(
                line,
                format!(
                    "{} = {} does not increase (line {} has {}); times must be strictly increasing",
                    columns[0], values[0], prev.line, prev.values[0]
                ),
            ));
        }
        rows.push(NumericRow { line, values });
    }
    if rows.len() < 2 {
        return Err(error(
            rows.last().map_or(0, |r| r.line),
            format!(
                "{} data rows, at least 2 needed ({})",
                rows.len(),
                expected()
            ),
        ));
    }
    Ok(rows)
}

#[cfg(test)]
mod tests {
    use super::*;

    const COLS: [&str; 4] = ["t_s", "a", "b", "c"];

    fn parse(text: &str) -> Result<Vec<NumericRow>, PlatformError> {
        parse_numeric_csv(text, "x.csv", &COLS, &[2, 4])
    }

    fn line_and_message(r: Result<Vec<NumericRow>, PlatformError>) -> (usize, String) {
        match r {
            Err(PlatformError::Csv {
                path,
                line,
                message,
            }) => {
                assert_eq!(path, "x.csv");
                (line, message)
            }
            other => panic!("expected a CSV error, got {other:?}"),
        }
    }

    #[test]
    fn header_comments_and_blank_lines() {
        let rows = parse("# made by hand\n t_s, a \n\n0, 1.5 # start\n1,2\n").unwrap_or_default();
        assert_eq!(
            rows,
            vec![
                NumericRow {
                    line: 4,
                    values: vec![0.0, 1.5]
                },
                NumericRow {
                    line: 5,
                    values: vec![1.0, 2.0]
                }
            ]
        );
    }

    #[test]
    fn errors_name_the_line() {
        let (line, msg) = line_and_message(parse("t_s,a\n0,1\n1,x\n"));
        assert_eq!(line, 3);
        assert!(msg.contains("a = \"x\""), "{msg}");
        let (line, msg) = line_and_message(parse("0,1\n1,2\n1,3\n"));
        assert_eq!(line, 3);
        assert!(msg.contains("strictly increasing"), "{msg}");
        let (line, msg) = line_and_message(parse("0,1\n1,2,3\n"));
        assert_eq!(line, 2);
        assert!(msg.contains("t_s,a or t_s,a,b,c"), "{msg}");
        let (line, _) = line_and_message(parse("0,1\n1,2,3,4\n"));
        assert_eq!(line, 2);
        let (line, msg) = line_and_message(parse("t_s,a\n5,1\n"));
        assert_eq!(line, 2);
        assert!(msg.contains("at least 2"), "{msg}");
        let (_, msg) = line_and_message(parse("0,1\n1,inf\n"));
        assert!(msg.contains("finite"), "{msg}");
        // Only one header line, and only before the data.
        let (line, _) = line_and_message(parse("0,1\nt_s,a\n"));
        assert_eq!(line, 2);
    }

    #[test]
    fn missing_file_is_reported() {
        let r = read_numeric_csv(Path::new("/nonexistent/skyforge.csv"), &COLS, &[2]);
        let Err(PlatformError::Csv { path, line, .. }) = r else {
            panic!("expected an error")
        };
        assert_eq!((path.as_str(), line), ("/nonexistent/skyforge.csv", 0));
    }
}
