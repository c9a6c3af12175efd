//! The IMU text files, reader and writer of each: SkyForge's IMU CSV and the increment
//! file of KF-GINS (Wuhan University's open GNSS/INS package).
//!
//! * SkyForge's CSV: `#` comment lines at the top, then the header [`CSV_HEADER`], then
//!   one record per line: GPS week, seconds of week and interval of `t_end`, the angle
//!   increments (rad) and the velocity increments (m/s), body axes front-right-down,
//!   numbers written in Rust's shortest form that reads back to the same `f64`.
//! * KF-GINS's IMU text file (its README, section 2.2 "Data format"): whitespace-separated
//!   columns, 1 the GNSS seconds of week, 2-4 the X-Y-Z angle increments (rad), 5-7 the
//!   X-Y-Z velocity increments (m/s), IMU axes forward-right-down; KF-GINS reads the first
//!   `imudatalen` columns, so columns after the seventh are ignored here. The file holds
//!   neither the week nor the intervals: the reader is given the week of the first record
//!   (a record whose seconds fall more than half a week below the previous one's starts
//!   the next week) and the first record's interval; every later interval is the time
//!   since the previous record. The writer therefore refuses records that do not follow
//!   each other without a gap, and returns the week the reader needs.
//!
//! Every reader error names the file, the line, the field, its value and what is allowed;
//! lines are read at most [`MAX_LINE_BYTES`] at a time, so no input allocates more than
//! the records it holds.

use super::ImuIncrement;
use hifitime::Epoch;
use skyforge_orbits::Vec3;
use skyforge_orbits::check::{Allowed, shown};
use skyforge_orbits::time::{
    SECONDS_PER_WEEK, SUPPORTED_RANGE, epoch_from_gpst, gpst_week_sow, in_supported_range,
};
use std::io::{BufRead, BufReader, Read, Write};
use std::path::{Path, PathBuf};

/// The header line of SkyForge's IMU CSV.
pub const CSV_HEADER: &str =
    "gps_week,tow_s,dt_s,dtheta_x_rad,dtheta_y_rad,dtheta_z_rad,dv_x_mps,dv_y_mps,dv_z_mps";

/// The longest line either reader accepts (bytes): a record of nine shortest-form `f64`
/// values takes under 250.
pub const MAX_LINE_BYTES: usize = 4096;

/// The most records [`read_csv`] and [`read_kf_gins`] collect: ten hours at 1 kHz (about
/// 2.6 GB in memory). Longer files are read record by record with [`CsvReader`] or
/// [`KfGinsReader`].
pub const MAX_RECORDS: usize = 36_000_000;

/// The interval of one record (s): positive, at most 1 s (IMUs deliver 1 Hz to a few kHz).
pub const DT_S: Allowed = Allowed::above(0.0, 1.0, "s");

/// An angle increment component (rad): at most half a turn per interval, beyond which a
/// rotation vector is ambiguous.
pub const DTHETA_RAD: Allowed = Allowed::closed(-std::f64::consts::PI, std::f64::consts::PI, "rad");

/// A velocity increment component (m/s): a specific force of up to 1000 g over a 1-s
/// interval.
pub const DV_MPS: Allowed = Allowed::closed(-1e4, 1e4, "m/s");

/// The increment columns after the time columns, in file order.
const INCREMENT_NAMES: [&str; 6] = [
    "dtheta_x_rad",
    "dtheta_y_rad",
    "dtheta_z_rad",
    "dv_x_mps",
    "dv_y_mps",
    "dv_z_mps",
];

/// Why an IMU text file could not be read or written.
#[derive(Debug, thiserror::Error)]
pub enum ImuTextError {
    /// The file could not be opened or read.
    #[error("{path}: {message}")]
    Read { path: PathBuf, message: String },
    /// The file is not well formed at `line` (1-based).
    #[error("{path}:{line}: {message}")]
    Syntax {
        path: PathBuf,
        line: usize,
        message: String,
    },
    /// Record `index` (0-based) given to a writer cannot be written as the format holds it.
    #[error("IMU record {index}: {message}")]
    Record { index: usize, message: String },
    /// The output could not be written.
    #[error("writing the IMU file: {0}")]
    Write(#[from] std::io::Error),
}

/// Lines of a text file, at most [`MAX_LINE_BYTES`] each, counted from 1.
struct Lines<R> {
    reader: R,
    path: PathBuf,
    line: usize,
}

impl<R: BufRead> Lines<R> {
    fn new(reader: R, path: &Path) -> Self {
        Self {
            reader,
            path: path.to_path_buf(),
            line: 0,
        }
    }

    /// The error at the current line.
    fn error(&self, message: impl Into<String>) -> ImuTextError {
        ImuTextError::Syntax {
            path: self.path.clone(),
            line: self.line,
            message: message.into(),
        }
    }

    /// The next line without its line ending, `None` at the end of the file.
    fn next_line(&mut self) -> Result<Option<String>, ImuTextError> {
        let mut bytes = Vec::new();
        let limit = MAX_LINE_BYTES as u64 + 1;
        let n = (&mut self.reader)
            .take(limit)
            .read_until(b'\n', &mut bytes)
            .map_err(|e| ImuTextError::Read {
                path: self.path.clone(),
                message: e.to_string(),
            })?;
        if n == 0 {
            return Ok(None);
        }
        self.line += 1;
        if bytes.last() == Some(&b'\n') {
            bytes.pop();
        }
        if bytes.len() > MAX_LINE_BYTES {
            return Err(self.error(format!(
                "line longer than {MAX_LINE_BYTES} bytes: not an IMU file"
            )));
        }
        if bytes.last() == Some(&b'\r') {
            bytes.pop();
        }
        String::from_utf8(bytes)
            .map(Some)
            .map_err(|_| self.error("not UTF-8 text: not an IMU file"))
    }

    /// The next line that is not blank.
    fn next_nonblank(&mut self) -> Result<Option<String>, ImuTextError> {
        while let Some(line) = self.next_line()? {
            if !line.trim().is_empty() {
                return Ok(Some(line));
            }
        }
        Ok(None)
    }
}

/// The file at `path` for reading, or why not.
fn open(path: &Path) -> Result<BufReader<std::fs::File>, ImuTextError> {
    let error = |message: String| ImuTextError::Read {
        path: path.to_path_buf(),
        message,
    };
    if path.is_dir() {
        return Err(error("is a directory, not an IMU file".into()));
    }
    std::fs::File::open(path)
        .map(BufReader::new)
        .map_err(|e| error(e.to_string()))
}

/// `text` of column `name` as a number inside `allowed`.
fn number(name: &str, text: &str, allowed: Allowed) -> Result<f64, String> {
    let value: f64 = text
        .trim()
        .parse()
        .map_err(|_| format!("{name} = {text:?}: not a number; must be in {allowed}"))?;
    allowed
        .check(name, value)
        .map(|()| value)
        .map_err(|e| e.to_string())
}

/// Seconds of week of column `name`: in `[0, 604800)`.
fn seconds_of_week(name: &str, text: &str) -> Result<f64, String> {
    let week = f64::from(SECONDS_PER_WEEK);
    let value: f64 = text
        .trim()
        .parse()
        .map_err(|_| format!("{name} = {text:?}: not a number"))?;
    if (0.0..week).contains(&value) {
        Ok(value)
    } else {
        Err(format!(
            "{name} = {}: must be in [0, {SECONDS_PER_WEEK}) s",
            shown(value)
        ))
    }
}

/// The six increment columns (angle x, y, z, then velocity x, y, z).
fn increments(fields: &[&str]) -> Result<(Vec3, Vec3), String> {
    let mut values = [0.0; 6];
    for (k, (name, text)) in INCREMENT_NAMES.iter().zip(fields).enumerate() {
        let allowed = if k < 3 { DTHETA_RAD } else { DV_MPS };
        values[k] = number(name, text, allowed)?;
    }
    Ok((
        Vec3::new(values[0], values[1], values[2]),
        Vec3::new(values[3], values[4], values[5]),
    ))
}

/// Why `t_end` cannot follow `previous`: times must increase strictly.
fn check_increasing(previous: Option<Epoch>, t_end: Epoch) -> Result<(), String> {
    match previous {
        Some(p) if t_end <= p => Err(format!(
            "time {t_end} is not after the previous record's {p}: times must increase strictly"
        )),
        _ => Ok(()),
    }
}

/// Why `t_end` is no time an IMU file can hold.
fn check_supported(t_end: Epoch) -> Result<(), String> {
    if in_supported_range(t_end) {
        Ok(())
    } else {
        Err(format!("time {t_end}: must lie {SUPPORTED_RANGE}"))
    }
}

/// Reads SkyForge's IMU CSV record by record (see the module documentation).
#[derive(Debug)]
pub struct CsvReader<R> {
    lines: Lines<R>,
    header_seen: bool,
    previous: Option<Epoch>,
    failed: bool,
}

impl<R> std::fmt::Debug for Lines<R> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}:{}", self.path.display(), self.line)
    }
}

impl CsvReader<BufReader<std::fs::File>> {
    /// The reader of the file at `path`.
    pub fn open(path: &Path) -> Result<Self, ImuTextError> {
        Ok(Self::new(open(path)?, path))
    }
}

impl<R: BufRead> CsvReader<R> {
    /// The reader of `reader`, whose errors name `path`.
    pub fn new(reader: R, path: &Path) -> Self {
        Self {
            lines: Lines::new(reader, path),
            header_seen: false,
            previous: None,
            failed: false,
        }
    }

    /// Skips the comments and checks the header; the first data line, if any.
    fn first_record_line(&mut self) -> Result<Option<String>, ImuTextError> {
        while let Some(line) = self.lines.next_nonblank()? {
            if line.trim_start().starts_with('#') {
                continue;
            }
            if line.trim() != CSV_HEADER {
                return Err(self.lines.error(format!(
                    "header {:?}: must be {CSV_HEADER:?} (after any '#' comment lines)",
                    line.trim()
                )));
            }
            self.header_seen = true;
            return self.lines.next_nonblank();
        }
        Err(self.lines.error(format!(
            "no header line {CSV_HEADER:?}: not a SkyForge IMU CSV"
        )))
    }

    /// One record line as an increment.
    fn record(&mut self, line: &str) -> Result<ImuIncrement, String> {
        if line.trim_start().starts_with('#') {
            return Err("comment line after the header: comments go above it".into());
        }
        let fields: Vec<&str> = line.split(',').collect();
        if fields.len() != 9 {
            return Err(format!("{} fields: must be 9 ({CSV_HEADER})", fields.len()));
        }
        let week: u32 = fields[0].trim().parse().map_err(|_| {
            format!(
                "gps_week = {:?}: must be a whole number of weeks from 0",
                fields[0]
            )
        })?;
        let tow = seconds_of_week("tow_s", fields[1])?;
        let dt_s = number("dt_s", fields[2], DT_S)?;
        let (dtheta_rad, dv_mps) = increments(&fields[3..])?;
        let t_end = epoch_from_gpst(week, tow);
        check_supported(t_end).map_err(|e| format!("gps_week = {week}, tow_s = {tow}: {e}"))?;
        check_increasing(self.previous, t_end)?;
        self.previous = Some(t_end);
        Ok(ImuIncrement {
            t_end,
            dt_s,
            dtheta_rad,
            dv_mps,
        })
    }

    fn next_record(&mut self) -> Result<Option<ImuIncrement>, ImuTextError> {
        let line = if self.header_seen {
            self.lines.next_nonblank()?
        } else {
            self.first_record_line()?
        };
        line.map(|l| self.record(&l).map_err(|m| self.lines.error(m)))
            .transpose()
    }
}

impl<R: BufRead> Iterator for CsvReader<R> {
    type Item = Result<ImuIncrement, ImuTextError>;

    /// The next record; after an error, none.
    fn next(&mut self) -> Option<Self::Item> {
        let next = (!self.failed).then(|| self.next_record())?;
        self.failed = next.is_err();
        next.transpose()
    }
}

/// Reads KF-GINS's IMU text file record by record (see the module documentation).
#[derive(Debug)]
pub struct KfGinsReader<R> {
    lines: Lines<R>,
    week: u32,
    first_dt_s: f64,
    previous: Option<Epoch>,
    failed: bool,
}

impl KfGinsReader<BufReader<std::fs::File>> {
    /// The reader of the file at `path`; see [`KfGinsReader::new`].
    pub fn open(path: &Path, gps_week: u32, first_dt_s: f64) -> Result<Self, ImuTextError> {
        Self::new(open(path)?, path, gps_week, first_dt_s)
    }
}

impl<R: BufRead> KfGinsReader<R> {
    /// The reader of `reader`, whose errors name `path`: `gps_week` is the GPS week of
    /// the first record, `first_dt_s` its interval (in [`DT_S`]; KF-GINS takes it from
    /// its `imudatarate` setting).
    pub fn new(
        reader: R,
        path: &Path,
        gps_week: u32,
        first_dt_s: f64,
    ) -> Result<Self, ImuTextError> {
        let read_error = |message: String| ImuTextError::Read {
            path: path.to_path_buf(),
            message,
        };
        DT_S.check("first interval", first_dt_s)
            .map_err(|e| read_error(e.to_string()))?;
        check_supported(epoch_from_gpst(gps_week, 0.0))
            .map_err(|e| read_error(format!("GPS week {gps_week}: {e}")))?;
        Ok(Self {
            lines: Lines::new(reader, path),
            week: gps_week,
            first_dt_s,
            previous: None,
            failed: false,
        })
    }

    /// The epoch of seconds of week `sow`: in the current week, or in the next when the
    /// seconds fall back by more than half a week (a week rollover).
    fn epoch(&mut self, sow: f64) -> Epoch {
        if let Some(p) = self.previous {
            let (_, previous_sow) = gpst_week_sow(p);
            if previous_sow - sow > f64::from(SECONDS_PER_WEEK) / 2.0 {
                self.week += 1;
            }
        }
        epoch_from_gpst(self.week, sow)
    }

    /// One record line as an increment.
    fn record(&mut self, line: &str) -> Result<ImuIncrement, String> {
        let fields: Vec<&str> = line.split_whitespace().collect();
        if fields.len() < 7 {
            return Err(format!(
                "{} columns: must be at least 7 (seconds of week, 3 angle increments in rad, \
                 3 velocity increments in m/s)",
                fields.len()
            ));
        }
        let sow = seconds_of_week("seconds of week (column 1)", fields[0])?;
        let (dtheta_rad, dv_mps) = increments(&fields[1..7])?;
        let t_end = self.epoch(sow);
        check_supported(t_end)?;
        check_increasing(self.previous, t_end)?;
        let dt_s = match self.previous {
            None => self.first_dt_s,
            Some(p) => {
                let dt = (t_end - p).to_seconds();
                DT_S.check("interval since the previous record", dt)
                    .map_err(|e| e.to_string())?;
                dt
            }
        };
        self.previous = Some(t_end);
        Ok(ImuIncrement {
            t_end,
            dt_s,
            dtheta_rad,
            dv_mps,
        })
    }

    fn next_record(&mut self) -> Result<Option<ImuIncrement>, ImuTextError> {
        let line = self.lines.next_nonblank()?;
        line.map(|l| self.record(&l).map_err(|m| self.lines.error(m)))
            .transpose()
    }
}

impl<R: BufRead> Iterator for KfGinsReader<R> {
    type Item = Result<ImuIncrement, ImuTextError>;

    /// The next record; after an error, none.
    fn next(&mut self) -> Option<Self::Item> {
        let next = (!self.failed).then(|| self.next_record())?;
        self.failed = next.is_err();
        next.transpose()
    }
}

/// Every record of `reader`, at most [`MAX_RECORDS`].
fn collect(
    reader: impl Iterator<Item = Result<ImuIncrement, ImuTextError>>,
    path: &Path,
) -> Result<Vec<ImuIncrement>, ImuTextError> {
    let mut out = Vec::new();
    for record in reader {
        if out.len() == MAX_RECORDS {
            return Err(ImuTextError::Read {
                path: path.to_path_buf(),
                message: format!(
                    "more than {MAX_RECORDS} records: read it record by record instead"
                ),
            });
        }
        out.push(record?);
    }
    Ok(out)
}

/// Every record of SkyForge's IMU CSV at `path`.
pub fn read_csv(path: &Path) -> Result<Vec<ImuIncrement>, ImuTextError> {
    collect(CsvReader::open(path)?, path)
}

/// Every record of KF-GINS's IMU text file at `path`, the first in GPS week `gps_week`
/// with interval `first_dt_s` ([`KfGinsReader::new`]).
pub fn read_kf_gins(
    path: &Path,
    gps_week: u32,
    first_dt_s: f64,
) -> Result<Vec<ImuIncrement>, ImuTextError> {
    collect(KfGinsReader::open(path, gps_week, first_dt_s)?, path)
}

/// Why `inc` cannot be written: its interval or increments outside [`DT_S`],
/// [`DTHETA_RAD`], [`DV_MPS`], its time outside SkyForge's range or not after `previous`.
fn check_record(inc: &ImuIncrement, previous: Option<Epoch>) -> Result<(), String> {
    DT_S.check("dt_s", inc.dt_s).map_err(|e| e.to_string())?;
    let values = inc.dtheta_rad.iter().chain(inc.dv_mps.iter());
    for (k, (name, value)) in INCREMENT_NAMES.iter().zip(values).enumerate() {
        let allowed = if k < 3 { DTHETA_RAD } else { DV_MPS };
        allowed.check(name, *value).map_err(|e| e.to_string())?;
    }
    check_supported(inc.t_end)?;
    check_increasing(previous, inc.t_end)
}

/// Every record of `increments` checked in order; the first that cannot be written is the
/// error.
fn check_records(increments: &[ImuIncrement]) -> Result<(), ImuTextError> {
    let mut previous = None;
    for (index, inc) in increments.iter().enumerate() {
        check_record(inc, previous).map_err(|message| ImuTextError::Record { index, message })?;
        previous = Some(inc.t_end);
    }
    Ok(())
}

/// Writes SkyForge's IMU CSV record by record: the comments and the header at creation,
/// then one line per [`CsvWriter::push`], each record checked against the previous one.
#[derive(Debug)]
pub struct CsvWriter<W> {
    out: W,
    previous: Option<Epoch>,
    index: usize,
}

impl<W: Write> CsvWriter<W> {
    /// Writes each line of `comments` as a `#` line, then the header.
    pub fn new(mut out: W, comments: &str) -> Result<Self, ImuTextError> {
        for line in comments.lines() {
            writeln!(out, "# {line}")?;
        }
        writeln!(out, "{CSV_HEADER}")?;
        Ok(Self {
            out,
            previous: None,
            index: 0,
        })
    }

    /// Writes `inc`; refuses (writing nothing) a record out of range or not after the
    /// previous one.
    pub fn push(&mut self, inc: &ImuIncrement) -> Result<(), ImuTextError> {
        check_record(inc, self.previous).map_err(|message| ImuTextError::Record {
            index: self.index,
            message,
        })?;
        let (week, tow) = gpst_week_sow(inc.t_end);
        let (a, v) = (inc.dtheta_rad, inc.dv_mps);
        writeln!(
            self.out,
            "{week},{tow},{},{},{},{},{},{},{}",
            inc.dt_s, a.x, a.y, a.z, v.x, v.y, v.z
        )?;
        self.previous = Some(inc.t_end);
        self.index += 1;
        Ok(())
    }

    /// Flushes the output.
    pub fn finish(mut self) -> Result<W, ImuTextError> {
        self.out.flush()?;
        Ok(self.out)
    }
}

/// Writes `increments` as SkyForge's IMU CSV: each line of `comments` as a `#` line, the
/// header, one record per line. Nothing is written when a record is out of range or its
/// time does not follow the previous one's.
pub fn write_csv(
    out: impl Write,
    increments: &[ImuIncrement],
    comments: &str,
) -> Result<(), ImuTextError> {
    check_records(increments)?;
    let mut writer = CsvWriter::new(out, comments)?;
    for inc in increments {
        writer.push(inc)?;
    }
    writer.finish().map(drop)
}

/// The largest difference between a record's interval and the time since the previous
/// record that [`write_kf_gins`] accepts (s): the file keeps only the times.
pub const KF_GINS_GAP_S: f64 = 1e-6;

/// Why record `index`, `inc`, cannot follow `previous` in KF-GINS's file: its interval
/// is not the time since the previous record.
fn check_gap(
    previous: &ImuIncrement,
    inc: &ImuIncrement,
    index: usize,
) -> Result<(), ImuTextError> {
    let since = (inc.t_end - previous.t_end).to_seconds();
    if (since - inc.dt_s).abs() > KF_GINS_GAP_S {
        return Err(ImuTextError::Record {
            index,
            message: format!(
                "dt_s = {} but {since} s since the previous record: KF-GINS's file keeps \
                 only the times, so records must follow each other without gaps",
                inc.dt_s
            ),
        });
    }
    Ok(())
}

/// Writes KF-GINS's IMU text file record by record, each checked against the previous
/// one as [`write_kf_gins`] checks them.
#[derive(Debug)]
pub struct KfGinsWriter<W> {
    out: W,
    previous: Option<ImuIncrement>,
    first_week: Option<u32>,
    index: usize,
}

impl<W: Write> KfGinsWriter<W> {
    /// A writer to `out` (the file has no header).
    pub fn new(out: W) -> Self {
        Self {
            out,
            previous: None,
            first_week: None,
            index: 0,
        }
    }

    /// Writes `inc`; refuses (writing nothing) a record out of range, not after the
    /// previous one, or with a gap before it.
    pub fn push(&mut self, inc: &ImuIncrement) -> Result<(), ImuTextError> {
        let index = self.index;
        check_record(inc, self.previous.map(|p| p.t_end))
            .map_err(|message| ImuTextError::Record { index, message })?;
        if let Some(previous) = &self.previous {
            check_gap(previous, inc, index)?;
        }
        let (week, sow) = gpst_week_sow(inc.t_end);
        let (a, v) = (inc.dtheta_rad, inc.dv_mps);
        writeln!(
            self.out,
            "{sow} {} {} {} {} {} {}",
            a.x, a.y, a.z, v.x, v.y, v.z
        )?;
        self.first_week.get_or_insert(week);
        self.previous = Some(*inc);
        self.index += 1;
        Ok(())
    }

    /// Flushes the output; the GPS week of the first record (none without records),
    /// which the file does not hold and [`read_kf_gins`] needs.
    pub fn finish(mut self) -> Result<Option<u32>, ImuTextError> {
        self.out.flush()?;
        Ok(self.first_week)
    }
}

/// Writes `increments` as KF-GINS's IMU text file and returns the GPS week of the first
/// record, which the file does not hold ([`read_kf_gins`] needs it). Nothing is written
/// when a record is out of range, does not follow the previous one, or its interval
/// differs from the time since the previous record by more than [`KF_GINS_GAP_S`] (the
/// reader takes the intervals from the times).
pub fn write_kf_gins(
    out: impl Write,
    increments: &[ImuIncrement],
) -> Result<Option<u32>, ImuTextError> {
    check_records(increments)?;
    for (index, pair) in increments.windows(2).enumerate() {
        check_gap(&pair[0], &pair[1], index + 1)?;
    }
    let mut writer = KfGinsWriter::new(out);
    for inc in increments {
        writer.push(inc)?;
    }
    writer.finish()
}

#[cfg(test)]
mod tests {
    use super::*;
    use hifitime::Duration;
    use proptest::prelude::*;

    fn record(t_end: Epoch, dt_s: f64, k: f64) -> ImuIncrement {
        ImuIncrement {
            t_end,
            dt_s,
            dtheta_rad: Vec3::new(1e-4 * k, -2.5e-5, 3.0e-7 / 3.0),
            dv_mps: Vec3::new(0.098_065_5, -1e-3 * k, -9.81e-2),
        }
    }

    /// `n` records at `dt_ns` spacing ending at `start + dt`, `start + 2 dt`, ...
    fn records(start: Epoch, dt_ns: i64, n: usize) -> Vec<ImuIncrement> {
        let dt = Duration::from_total_nanoseconds(i128::from(dt_ns));
        (1..=n)
            .map(|k| record(start + dt * k as i64, dt.to_seconds(), k as f64))
            .collect()
    }

    fn csv_text(increments: &[ImuIncrement], comments: &str) -> String {
        let mut out = Vec::new();
        write_csv(&mut out, increments, comments).unwrap();
        String::from_utf8(out).unwrap()
    }

    fn read_csv_text(text: &str) -> Result<Vec<ImuIncrement>, ImuTextError> {
        CsvReader::new(text.as_bytes(), Path::new("imu.csv")).collect()
    }

    fn kf_gins_text(increments: &[ImuIncrement]) -> (String, Option<u32>) {
        let mut out = Vec::new();
        let week = write_kf_gins(&mut out, increments).unwrap();
        (String::from_utf8(out).unwrap(), week)
    }

    fn read_kf_gins_text(
        text: &str,
        week: u32,
        first_dt_s: f64,
    ) -> Result<Vec<ImuIncrement>, ImuTextError> {
        KfGinsReader::new(text.as_bytes(), Path::new("imu.txt"), week, first_dt_s)?.collect()
    }

    fn start() -> Epoch {
        epoch_from_gpst(2300, 345_600.0)
    }

    #[test]
    fn csv_layout_and_round_trip() {
        let recs = records(start(), 10_000_000, 3);
        let text = csv_text(&recs, "IMU of run 7\nnavigation grade");
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines[0], "# IMU of run 7");
        assert_eq!(lines[1], "# navigation grade");
        assert_eq!(lines[2], CSV_HEADER);
        assert_eq!(
            lines[3],
            "2300,345600.01,0.01,0.0001,-0.000025,0.0000001,0.0980655,-0.001,-0.0981"
        );
        assert_eq!(read_csv_text(&text).unwrap(), recs);
        // Files on disk read the same; CRLF line ends and blank lines are fine.
        let tmp = tempfile::tempdir().unwrap();
        let path = tmp.path().join("imu.csv");
        std::fs::write(&path, text.replace('\n', "\r\n\r\n")).unwrap();
        assert_eq!(read_csv(&path).unwrap(), recs);
    }

    #[test]
    fn kf_gins_layout_and_round_trip() {
        let recs = records(start(), 5_000_000, 4);
        let (text, week) = kf_gins_text(&recs);
        assert_eq!(week, Some(2300));
        assert_eq!(
            text.lines().next().unwrap(),
            "345600.005 0.0001 -0.000025 0.0000001 0.0980655 -0.001 -0.0981"
        );
        assert_eq!(read_kf_gins_text(&text, 2300, 0.005).unwrap(), recs);
        // Columns after the seventh (an odometer, say) are ignored as KF-GINS does.
        let wider: String = text.lines().map(|l| format!("{l}\t12.5\n")).collect();
        assert_eq!(read_kf_gins_text(&wider, 2300, 0.005).unwrap(), recs);
        let tmp = tempfile::tempdir().unwrap();
        let path = tmp.path().join("imu.txt");
        std::fs::write(&path, &text).unwrap();
        assert_eq!(read_kf_gins(&path, 2300, 0.005).unwrap(), recs);
        assert_eq!(kf_gins_text(&[]), (String::new(), None));
    }

    #[test]
    fn kf_gins_week_rollover() {
        let recs = records(epoch_from_gpst(2300, 604_799.98), 10_000_000, 5);
        let (text, week) = kf_gins_text(&recs);
        assert_eq!(week, Some(2300));
        assert!(text.lines().nth(1).unwrap().starts_with("0 "));
        let back = read_kf_gins_text(&text, 2300, 0.01).unwrap();
        assert_eq!(back, recs);
        assert_eq!(gpst_week_sow(back[4].t_end).0, 2301);
    }

    fn syntax(e: ImuTextError) -> (usize, String) {
        match e {
            ImuTextError::Syntax { line, message, .. } => (line, message),
            other => panic!("not a syntax error: {other}"),
        }
    }

    #[test]
    fn csv_errors_name_line_field_value_and_what_is_allowed() {
        let good = csv_text(&records(start(), 10_000_000, 2), "");
        let header_at = 1;
        let with = |line: usize, text: &str| {
            let mut lines: Vec<String> = good.lines().map(str::to_string).collect();
            lines[line] = text.to_string();
            read_csv_text(&lines.join("\n")).unwrap_err()
        };
        let e = with(header_at - 1, "week,tow");
        assert_eq!(syntax(e).0, 1);
        let e = with(1, "2300,345600.01,0,0,0,0,0,0,0");
        let (line, message) = syntax(e);
        assert_eq!(line, 2);
        assert_eq!(message, "dt_s = 0: must be in (0, 1] s");
        let e = with(1, "2300,345600.01,0.01,NaN,0,0,0,0,0");
        assert_eq!(
            syntax(e).1,
            "dtheta_x_rad = NaN: must be in [-3.141592653589793, 3.141592653589793] rad"
        );
        let e = with(1, "2300,345600.01,0.01,0,0,0,0,0,abc");
        assert_eq!(
            syntax(e).1,
            "dv_z_mps = \"abc\": not a number; must be in [-10000, 10000] m/s"
        );
        let e = with(1, "2300,604800,0.01,0,0,0,0,0,0");
        assert_eq!(syntax(e).1, "tow_s = 604800: must be in [0, 604800) s");
        let e = with(1, "-1,0.5,0.01,0,0,0,0,0,0");
        assert!(
            syntax(e)
                .1
                .starts_with("gps_week = \"-1\": must be a whole number")
        );
        let e = with(1, "9999,0.5,0.01,0,0,0,0,0,0");
        assert!(syntax(e).1.contains("must lie from the GPS epoch"));
        let e = with(1, "2300,0.5,0.01,0,0,0,0,0");
        assert_eq!(syntax(e).1, format!("8 fields: must be 9 ({CSV_HEADER})"));
        let e = with(2, "2300,345600.01,0.01,0,0,0,0,0,0");
        let (line, message) = syntax(e);
        assert_eq!(line, 3);
        assert!(message.contains("must increase strictly"), "{message}");
        let e = with(2, "# late comment");
        assert!(syntax(e).1.contains("comments go above"));
        let e = read_csv_text("# only a comment\n").unwrap_err();
        assert!(syntax(e).1.starts_with("no header line"));
        assert_eq!(
            e_string(read_csv_text(&format!("{CSV_HEADER}\n1,2\n"))),
            format!("imu.csv:2: 2 fields: must be 9 ({CSV_HEADER})")
        );
    }

    fn e_string<T: std::fmt::Debug>(r: Result<T, ImuTextError>) -> String {
        r.unwrap_err().to_string()
    }

    #[test]
    fn kf_gins_errors() {
        let (good, _) = kf_gins_text(&records(start(), 10_000_000, 3));
        let mut lines: Vec<String> = good.lines().map(str::to_string).collect();
        lines[1] = "345600.02 0 0 0 0 0".into();
        let e = read_kf_gins_text(&lines.join("\n"), 2300, 0.01).unwrap_err();
        assert_eq!(
            e.to_string(),
            "imu.txt:2: 6 columns: must be at least 7 (seconds of week, 3 angle increments \
             in rad, 3 velocity increments in m/s)"
        );
        lines[1] = "345601.5 0 0 0 0 0 0".into();
        let e = read_kf_gins_text(&lines.join("\n"), 2300, 0.01).unwrap_err();
        assert_eq!(
            syntax(e).1,
            "interval since the previous record = 1.49: must be in (0, 1] s"
        );
        lines[1] = "345500 0 0 0 0 0 0".into();
        let e = read_kf_gins_text(&lines.join("\n"), 2300, 0.01).unwrap_err();
        assert!(syntax(e).1.contains("must increase strictly"));
        let e = read_kf_gins_text(&good, 2300, -1.0).unwrap_err();
        assert_eq!(
            e.to_string(),
            "imu.txt: first interval = -1: must be in (0, 1] s"
        );
        let e = read_kf_gins_text(&good, 99_999, 0.01).unwrap_err();
        assert!(e.to_string().starts_with("imu.txt: GPS week 99999: time"));
    }

    #[test]
    fn hostile_input_is_refused_without_panics_or_large_allocations() {
        let e = CsvReader::new(BufReader::new(std::io::repeat(b'1')), Path::new("/dev/x"))
            .next()
            .unwrap()
            .unwrap_err();
        assert_eq!(
            e.to_string(),
            "/dev/x:1: line longer than 4096 bytes: not an IMU file"
        );
        let e = read_csv_text("\u{0}\u{ff}").unwrap_err();
        assert!(e.to_string().starts_with("imu.csv:1: header"), "{e}");
        let bytes = [b'#', 0xff, 0xfe, b'\n'];
        let e = CsvReader::new(&bytes[..], Path::new("f"))
            .next()
            .unwrap()
            .unwrap_err();
        assert_eq!(e.to_string(), "f:1: not UTF-8 text: not an IMU file");
        let tmp = tempfile::tempdir().unwrap();
        let e = read_csv(tmp.path()).unwrap_err();
        assert!(e.to_string().ends_with("is a directory, not an IMU file"));
        assert!(read_kf_gins(&tmp.path().join("missing"), 2300, 0.01).is_err());
        assert_eq!(read_kf_gins_text("", 2300, 0.01).unwrap(), vec![]);
        assert_eq!(read_csv_text(&format!("{CSV_HEADER}\n")).unwrap(), vec![]);
    }

    #[test]
    fn writers_refuse_what_their_readers_would() {
        let mut recs = records(start(), 10_000_000, 3);
        recs[1].dt_s = f64::INFINITY;
        let e = write_csv(Vec::new(), &recs, "").unwrap_err();
        assert_eq!(
            e.to_string(),
            "IMU record 1: dt_s = inf: must be in (0, 1] s"
        );
        let mut recs = records(start(), 10_000_000, 3);
        recs[2].t_end = recs[1].t_end;
        let e = write_kf_gins(Vec::new(), &recs).unwrap_err();
        assert!(e.to_string().starts_with("IMU record 2: time"));
        let mut recs = records(start(), 10_000_000, 3);
        recs[2].dt_s = 0.005;
        let e = write_kf_gins(Vec::new(), &recs).unwrap_err();
        assert!(e.to_string().contains("without gaps"), "{e}");
        assert!(write_csv(Vec::new(), &recs, "").is_ok());
        let mut recs = records(start(), 10_000_000, 1);
        recs[0].dv_mps.y = -2e4;
        let e = write_csv(Vec::new(), &recs, "").unwrap_err();
        assert_eq!(
            e.to_string(),
            "IMU record 0: dv_y_mps = -20000: must be in [-10000, 10000] m/s"
        );
    }

    fn component(allowed: Allowed) -> impl Strategy<Value = f64> {
        prop_oneof![
            Just(0.0),
            Just(allowed.lo),
            Just(allowed.hi),
            allowed.lo..allowed.hi
        ]
    }

    fn vec3(allowed: Allowed) -> impl Strategy<Value = Vec3> {
        (component(allowed), component(allowed), component(allowed))
            .prop_map(|(x, y, z)| Vec3::new(x, y, z))
    }

    proptest! {
        #[test]
        fn both_formats_round_trip(
            week in 0u32..6000,
            sow_ns in prop_oneof![0i64..604_800_000_000_000, 604_799_000_000_000i64..604_800_000_000_000],
            dt_ns in 1i64..=1_000_000_000,
            parts in proptest::collection::vec((vec3(DTHETA_RAD), vec3(DV_MPS)), 1..20),
        ) {
            let first = epoch_from_gpst(week, 0.0)
                + Duration::from_total_nanoseconds(i128::from(sow_ns));
            let dt = Duration::from_total_nanoseconds(i128::from(dt_ns));
            let recs: Vec<ImuIncrement> = parts
                .iter()
                .enumerate()
                .map(|(k, (a, v))| ImuIncrement {
                    t_end: first + dt * k as i64,
                    dt_s: dt.to_seconds(),
                    dtheta_rad: *a,
                    dv_mps: *v,
                })
                .collect();
            prop_assert_eq!(&read_csv_text(&csv_text(&recs, "c")).unwrap(), &recs);
            let (text, first_week) = kf_gins_text(&recs);
            prop_assert_eq!(first_week, Some(week));
            let back = read_kf_gins_text(&text, week, dt.to_seconds()).unwrap();
            prop_assert_eq!(&back, &recs);
        }

        #[test]
        fn any_text_is_an_error_or_records_never_a_panic(text in ".{0,300}") {
            let _ = read_csv_text(&text);
            let _ = read_csv_text(&format!("{CSV_HEADER}\n{text}"));
            let _ = read_kf_gins_text(&text, 2300, 0.01);
        }
    }
}
