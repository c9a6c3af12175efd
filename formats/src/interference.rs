//! `interference.csv`: the jamming monitor's verdict at every observation epoch
//! (`skyforge jamming`): satellites tracked and referenced, the median C/N0 change
//! against the references, the alarm threshold and the alarm. Writer and reader together.

use crate::FormatError;
use crate::csv::{Fields, read_csv, require_columns};
use skyforge_navigation::interference::JammingEpoch;
use std::io::Write;
use std::path::Path;

/// The file's name in an output directory.
pub const INTERFERENCE_CSV: &str = "interference.csv";

/// The columns, in order.
const COLUMNS: [&str; 6] = [
    "time_gpst",
    "tracked",
    "referenced",
    "change_db",
    "threshold_db",
    "alarm",
];

/// Writes `epochs` as [`INTERFERENCE_CSV`] at `path` (an unset change or threshold, NaN,
/// is left empty).
pub fn write_interference_csv(path: &Path, epochs: &[JammingEpoch]) -> std::io::Result<()> {
    let mut w = std::io::BufWriter::new(std::fs::File::create(path)?);
    writeln!(w, "{}", COLUMNS.join(","))?;
    let number = |x: f64| match x.is_finite() {
        true => format!("{x:.3}"),
        false => String::new(),
    };
    for e in epochs {
        writeln!(
            w,
            "{},{},{},{},{},{}",
            e.t,
            e.tracked,
            e.referenced,
            number(e.change_db),
            number(e.threshold_db),
            u8::from(e.alarm)
        )?;
    }
    w.flush()
}

/// Every row of [`INTERFERENCE_CSV`] at `path`, times increasing.
pub fn read_interference_csv(path: &Path) -> Result<Vec<JammingEpoch>, FormatError> {
    let mut rows: Vec<JammingEpoch> = Vec::new();
    let columns: Vec<String> = COLUMNS.iter().map(|c| c.to_string()).collect();
    read_csv(
        path,
        |header| require_columns(path, header, &columns),
        |header, line, text| {
            let f = Fields::new(path, line, header, text)?;
            let count = |c: &str| f.parse::<usize>(c, "a count");
            let t = f.epoch("time_gpst")?;
            if rows.last().is_some_and(|r| r.t >= t) {
                return Err(f.error("time_gpst does not increase".into()));
            }
            rows.push(JammingEpoch {
                t,
                tracked: count("tracked")?,
                referenced: count("referenced")?,
                change_db: f.number("change_db")?.unwrap_or(f64::NAN),
                threshold_db: f.number("threshold_db")?.unwrap_or(f64::NAN),
                alarm: f.flag("alarm")?,
            });
            Ok(())
        },
    )?;
    Ok(rows)
}

#[cfg(test)]
mod tests {
    use super::*;
    use hifitime::Epoch;

    /// What is written reads back, an unset change as NaN.
    #[test]
    fn rows_round_trip() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join(INTERFERENCE_CSV);
        let t = Epoch::from_gpst_seconds(1e9);
        let rows = vec![
            JammingEpoch {
                t,
                tracked: 3,
                referenced: 2,
                change_db: f64::NAN,
                threshold_db: f64::NAN,
                alarm: false,
            },
            JammingEpoch {
                t: t + hifitime::Duration::from_seconds(1.0),
                tracked: 9,
                referenced: 9,
                change_db: -9.5,
                threshold_db: -1.25,
                alarm: true,
            },
        ];
        write_interference_csv(&path, &rows).unwrap();
        let back = read_interference_csv(&path).unwrap();
        assert_eq!(back.len(), 2);
        assert!(back[0].change_db.is_nan() && !back[0].alarm && back[0].tracked == 3);
        assert_eq!(back[1], rows[1]);
    }
}
