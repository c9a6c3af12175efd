//! What the RINEX 3/4 reader checks itself before and after the `rinex` crate reads a
//! file. Before: the header (a version the readers read, the observation file type, an
//! `INTERVAL` the crate can take: it panics on `inf`), and its `MARKER NAME`. After: the
//! crate drops what it cannot parse without a word and keeps some epochs it should not (a
//! year 0 is read as 2000), so the body is scanned here too: every epoch line
//! (RINEX 3.04 table A3: `> yyyy mm dd hh mm ss.sssssss  f nnn`) is checked, and so is
//! every line, which must be an epoch line, one of the satellite lines its epoch line
//! announces, or one of an event's header records. What fails is left out and reported
//! ([`Dropped`]); a file that loses more than [`MAX_DROPPED_PERCENT`] of its epochs and
//! lines, or every epoch, is refused.
//!
//! Hatanaka-compressed files (`CRINEX`) are read by the crate alone past the header:
//! their epoch lines are differences.

use super::read_error::{EpochFields, ObsReadError, marker_name};
use super::record::{Dropped, list_dropped};
use skyforge_orbits::rinex_header::{label, supported_major, version_and_type};
use std::collections::BTreeMap;
use std::path::Path;

/// A file that loses more than this share of its epochs and lines (in percent) is
/// refused rather than read with a warning: at that rate the file is damaged, not
/// touched by an odd fault.
pub(crate) const MAX_DROPPED_PERCENT: usize = 10;

/// Largest `INTERVAL` (s): a day.
const MAX_INTERVAL_S: f64 = 86_400.0;

/// The calendar fields of a time tag as hifitime gives them back (`to_gregorian`):
/// year, month, day, hour, minute, second, nanosecond.
pub(crate) type Calendar = (i32, u8, u8, u8, u8, u8, u32);

/// One epoch line the scan found good, with flag 0 or 1 (observations).
#[derive(Debug)]
pub(crate) struct ScannedEpoch {
    pub line: usize,
    /// The line of each satellite (`G05`) of the epoch.
    pub sat_lines: BTreeMap<String, usize>,
}

/// What the scan found.
#[derive(Debug, Default)]
pub(crate) struct Scan {
    pub marker: Option<String>,
    /// The body's good epochs with observations, by time tag; `None` for a Hatanaka file
    /// (not scanned).
    pub epochs: Option<BTreeMap<Calendar, ScannedEpoch>>,
    /// Epoch lines and lines that are not read.
    pub dropped: Vec<Dropped>,
    /// Epoch lines and lines outside any epoch: what [`MAX_DROPPED_PERCENT`] is of.
    pub records: usize,
}

fn at(source: &Path, line: usize, message: impl Into<String>) -> ObsReadError {
    ObsReadError::Syntax {
        path: source.to_path_buf(),
        line,
        message: message.into(),
    }
}

/// Check the header of RINEX 3/4 (or Hatanaka) observation `text` and scan its body.
pub(crate) fn scan(text: &str, source: &Path) -> Result<Scan, ObsReadError> {
    let mut lines = text.lines().enumerate().map(|(i, l)| (i + 1, l));
    let mut out = Scan::default();
    let mut hatanaka = false;
    let mut version_seen = false;
    let mut ended = false;
    for (n, line) in lines.by_ref() {
        match label(line) {
            "CRINEX VERS   / TYPE" => hatanaka = true,
            "RINEX VERSION / TYPE" => {
                let (version, kind) = version_and_type(line).map_err(|m| at(source, n, m))?;
                supported_major(version).map_err(|m| at(source, n, m))?;
                if kind != "O" {
                    return Err(ObsReadError::NotObservation(source.to_path_buf()));
                }
                version_seen = true;
            }
            "INTERVAL" => {
                let text = line.get(..10).unwrap_or("").trim();
                let value: f64 = text.parse().map_err(|_| {
                    at(
                        source,
                        n,
                        format!("INTERVAL {text:?} is not a number (F10.3)"),
                    )
                })?;
                if !(0.0..=MAX_INTERVAL_S).contains(&value) {
                    return Err(at(
                        source,
                        n,
                        format!("INTERVAL {value}: allowed 0 to {MAX_INTERVAL_S} s"),
                    ));
                }
            }
            "MARKER NAME" => out.marker = marker_name(line),
            "END OF HEADER" => {
                ended = true;
                break;
            }
            _ => {}
        }
        if !version_seen && !hatanaka {
            return Err(at(
                source,
                n,
                "not a RINEX file: no RINEX VERSION / TYPE line",
            ));
        }
    }
    if !ended {
        return Err(at(source, 0, "no END OF HEADER"));
    }
    if hatanaka {
        return Ok(out);
    }
    let mut epochs = BTreeMap::new();
    let mut body = lines.peekable();
    while let Some((n, line)) = body.next() {
        if line.trim().is_empty() {
            continue;
        }
        out.records += 1;
        if !line.starts_with('>') {
            out.dropped.push(Dropped {
                line: n,
                reason: "neither an epoch line ('>') nor a satellite line its epoch announced"
                    .into(),
            });
            continue;
        }
        // The lines that follow: satellites (flags 0, 1, 6) or an event's header records.
        let (mut following, mut count) = (BTreeMap::new(), 0);
        while let Some((m, next)) = body.next_if(|(_, l)| !l.starts_with('>')) {
            if !next.trim().is_empty() {
                following.insert(next.get(..3).unwrap_or(next).to_string(), m);
                count += 1;
            }
        }
        match epoch_line(line, count) {
            Ok(Some(calendar)) => {
                epochs.insert(
                    calendar,
                    ScannedEpoch {
                        line: n,
                        sat_lines: following,
                    },
                );
            }
            Ok(None) => {}
            Err(reason) => out.dropped.push(Dropped { line: n, reason }),
        }
    }
    out.epochs = Some(epochs);
    Ok(out)
}

/// The time tag of epoch line `line` when it holds observations (flag 0 or 1), `None`
/// for an event or a cycle-slip record, or why it is no epoch line; `following` lines
/// come after it before the next epoch line.
fn epoch_line(line: &str, following: usize) -> Result<Option<Calendar>, String> {
    let field = |from: usize, to: usize| line.get(from..to.min(line.len())).unwrap_or("").trim();
    let int = |from: usize, to: usize, what: &str| {
        let text = field(from, to);
        text.parse::<u16>().map_err(|_| {
            format!(
                "epoch {what} {text:?} (columns {}-{to}) is not a number",
                from + 1
            )
        })
    };
    let flag = int(31, 32, "flag")?;
    if flag > 6 {
        return Err(format!("epoch flag {flag}: allowed 0 to 6"));
    }
    let count = int(32, 35, "number of satellites or records")?;
    if usize::from(count) != following {
        return Err(format!(
            "{count} satellites or records announced, {following} lines follow"
        ));
    }
    if flag > 1 {
        return Ok(None);
    }
    let small = |from: usize, to: usize, what: &str| {
        int(from, to, what).and_then(|v| u8::try_from(v).map_err(|_| format!("epoch {what} {v}")))
    };
    let seconds_text = field(18, 29);
    let fields = EpochFields {
        year: i32::from(int(2, 6, "year")?),
        month: small(7, 9, "month")?,
        day: small(10, 12, "day")?,
        hour: small(13, 15, "hour")?,
        minute: small(16, 18, "minute")?,
        seconds: seconds_text.parse().map_err(|_| {
            format!("epoch seconds {seconds_text:?} (columns 19-29) is not a number")
        })?,
    };
    fields.check()?;
    let (whole, ns) = fields.whole_and_ns();
    Ok(Some((
        fields.year,
        fields.month,
        fields.day,
        fields.hour,
        fields.minute,
        whole,
        ns,
    )))
}

impl Scan {
    /// The epoch lines the crate did not deliver (`delivered`: their time tags) join the
    /// dropped ones; then more than [`MAX_DROPPED_PERCENT`] dropped, or no epoch left
    /// where the file had some, is an error.
    pub(crate) fn settle(
        &mut self,
        delivered: &std::collections::BTreeSet<Calendar>,
        source: &Path,
    ) -> Result<(), ObsReadError> {
        let Some(epochs) = &self.epochs else {
            return Ok(());
        };
        for (calendar, e) in epochs {
            if !delivered.contains(calendar) {
                self.dropped.push(Dropped {
                    line: e.line,
                    reason: "the epoch could not be read".into(),
                });
            }
        }
        self.dropped.sort_by_key(|d| d.line);
        let left = delivered.len();
        let too_many = self.dropped.len() * 100 > MAX_DROPPED_PERCENT * self.records;
        if self.dropped.is_empty() || (left > 0 && !too_many) {
            return Ok(());
        }
        Err(ObsReadError::Read {
            path: source.to_path_buf(),
            message: format!(
                "{} of {} epochs and lines cannot be read ({}; a file that loses more than {MAX_DROPPED_PERCENT} % of them, or every epoch, is refused): {}",
                self.dropped.len(),
                self.records,
                match left {
                    0 => "no epoch left".to_string(),
                    _ => format!("{left} epochs left"),
                },
                list_dropped(&self.dropped)
            ),
        })
    }
}
