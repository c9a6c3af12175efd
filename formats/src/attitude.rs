//! What the attitude chain writes (`skyforge attitude`, `skyforge receive --geometry`):
//! one [`EpochValues`] per master epoch, a row of [`ATTITUDE_CSV`] and of [`ATTITUDE_H5`]
//! (schema in docs/attitude.md), and the fixed integers as rows of [`AMBIGUITIES_CSV`];
//! the writers ([`EpochFiles`], [`write_h5`]) and the readers of the two CSV files
//! ([`read_attitude_csv`], [`read_ambiguities_csv`]).

use crate::csv::{Fields, FormatError, read_csv, require_columns};
use crate::h5::{append_rows, create_epoch_file, create_rows};
use hifitime::Epoch;
use skyforge_gnss::signal::Signal;
use skyforge_navigation::relative::{AmbiguityStatus, EpochOutcome, FixMethod};
use skyforge_orbits::ephemeris::SatId;
use std::fs::File;
use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};

/// Every epoch's solution, one row each.
pub const ATTITUDE_CSV: &str = "attitude.csv";
/// The same as columns of numbers.
pub const ATTITUDE_H5: &str = "attitude.h5";
/// The fixed integers, one row per double difference.
pub const AMBIGUITIES_CSV: &str = "ambiguities.csv";

/// The columns of `ambiguities.csv`: the required ones, then `method` (what SkyForge
/// writes; another program's file may leave it out).
const AMBIGUITY_COLUMNS: [&str; 6] = [
    "time_gpst",
    "baseline",
    "signal",
    "sat",
    "reference",
    "integer",
];

/// What became of an epoch's ambiguities; its index is the code in `attitude.h5`'s
/// `status` dataset.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Status {
    /// No solution.
    None = 0,
    Float = 1,
    Partial = 2,
    Fixed = 3,
}

impl Status {
    const ALL: [Status; 4] = [Status::None, Status::Float, Status::Partial, Status::Fixed];

    /// The word in `attitude.csv`.
    pub fn name(self) -> &'static str {
        match self {
            Status::None => "none",
            Status::Float => "float",
            Status::Partial => "partial",
            Status::Fixed => "fixed",
        }
    }
}

impl std::str::FromStr for Status {
    type Err = ();
    fn from_str(s: &str) -> Result<Self, ()> {
        Status::ALL.into_iter().find(|x| x.name() == s).ok_or(())
    }
}

/// A fixed baseline in the master's NED frame and its standard deviations (m).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NedBaseline {
    pub ned_m: [f64; 3],
    /// Standard deviations, where the solver gives them.
    pub sigma_m: Option<[f64; 3]>,
}

/// The attitude stage's state: yaw, pitch, roll (deg), standard deviations, rates.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AttitudeValues {
    pub angles_deg: [f64; 3],
    /// Standard deviations, where the solver gives them.
    pub std_deg: Option<[f64; 3]>,
    /// Filters only.
    pub rates_dps: Option<[f64; 3]>,
}

/// What one epoch gave, as numbers.
#[derive(Debug, Clone, PartialEq)]
pub struct EpochValues {
    pub time: Epoch,
    pub status: Status,
    /// What decided the integers (`None` where the epoch has no solution, or a solution
    /// read back does not say).
    pub method: Option<FixMethod>,
    pub ambiguities: usize,
    pub fixed_combinations: usize,
    pub held: usize,
    pub ratio: Option<f64>,
    pub success_rate: Option<f64>,
    /// Per baseline: ECEF x, y, z (fixed; float when not fixed).
    pub ecef_m: Vec<[f64; 3]>,
    /// Per baseline: fixed N, E, D and their standard deviations.
    pub ned_m: Option<Vec<NedBaseline>>,
    pub attitude: Option<AttitudeValues>,
    /// Why the configured constrained search did not decide and LAMBDA did (empty when
    /// it did not fall back).
    pub fallback: String,
    /// Why the reverse filter failed this epoch and restarts (its baselines are the
    /// epoch's own); empty when it did not.
    pub reverse_restart: String,
    /// Why there is no solution, or why the attitude stage skipped the epoch.
    pub note: String,
}

impl EpochValues {
    /// The values of `o` for `m` baselines.
    pub fn of(o: &EpochOutcome, m: usize) -> Self {
        let mut v = Self {
            time: o.time,
            status: Status::None,
            method: None,
            ambiguities: 0,
            fixed_combinations: 0,
            held: 0,
            ratio: None,
            success_rate: None,
            ecef_m: Vec::new(),
            ned_m: None,
            attitude: None,
            fallback: String::new(),
            reverse_restart: String::new(),
            note: String::new(),
        };
        let e = match &o.result {
            Ok(e) => e,
            Err(why) => {
                v.note = why.clone();
                return v;
            }
        };
        let r = &e.resolution;
        (v.status, v.fixed_combinations) = match r.status {
            AmbiguityStatus::Float => (Status::Float, 0),
            AmbiguityStatus::Partial { combinations } => (Status::Partial, combinations),
            AmbiguityStatus::Fixed => (Status::Fixed, e.float.ambiguities.len()),
        };
        v.method = Some(r.method);
        v.ambiguities = e.float.ambiguities.len();
        v.held = r.held;
        v.ratio = r.ratio;
        v.success_rate = Some(r.success_rate);
        let baselines = e
            .fixed
            .as_ref()
            .map_or(&e.float.baselines, |x| &x.baselines);
        v.ecef_m = (0..m)
            .map(|k| {
                let c = baselines.column(k);
                [c[0], c[1], c[2]]
            })
            .collect();
        v.ned_m = e.fixed_ned.as_ref().map(|ned| {
            let q = ned.covariance();
            (0..m)
                .map(|k| {
                    let b = ned.baselines()[k];
                    let s = |i: usize| q[(3 * k + i, 3 * k + i)].sqrt();
                    NedBaseline {
                        ned_m: [b.x, b.y, b.z],
                        sigma_m: Some([s(0), s(1), s(2)]),
                    }
                })
                .collect()
        });
        v.attitude = e.attitude.as_ref().map(|s| {
            let a = [s.angles.yaw_rad, s.angles.pitch_rad, s.angles.roll_rad];
            AttitudeValues {
                angles_deg: a.map(f64::to_degrees),
                std_deg: Some([0, 1, 2].map(|i| s.covariance[(i, i)].sqrt().to_degrees())),
                rates_dps: s
                    .rates_rad_s
                    .map(|r| [r[0], r[1], r[2]].map(f64::to_degrees)),
            }
        });
        v.fallback = r.fallback.clone().unwrap_or_default();
        v.reverse_restart = e.reverse_restarted.clone().unwrap_or_default();
        v.note = e.attitude_skipped.clone().unwrap_or_default();
        v
    }
}

/// The CSV header for `m` baselines.
fn csv_header(m: usize) -> String {
    let mut cols: Vec<String> = [
        "time_gpst",
        "status",
        "method",
        "ambiguities",
        "fixed_combinations",
        "held",
        "ratio",
        "success_rate",
    ]
    .map(String::from)
    .to_vec();
    for k in 1..=m {
        for c in [
            "x_m", "y_m", "z_m", "n_m", "e_m", "d_m", "sn_m", "se_m", "sd_m",
        ] {
            cols.push(format!("b{k}_{c}"));
        }
    }
    for suffix in ["deg", "std_deg", "rate_dps"] {
        for c in ["yaw", "pitch", "roll"] {
            cols.push(format!("{c}_{suffix}"));
        }
    }
    cols.extend(["fallback", "reverse_restart", "note"].map(String::from));
    cols.join(",")
}

/// One CSV row of `v` for `m` baselines (empty fields for what the epoch did not give).
fn csv_row(v: &EpochValues, m: usize) -> String {
    let fmt = |x: &[f64], digits: usize| x.iter().map(|v| format!("{v:.digits$}")).collect();
    let blank = |n: usize| vec![String::new(); n];
    let opt = |x: &Option<[f64; 3]>, digits: usize| match x {
        Some(x) => fmt(x, digits),
        None => blank(3),
    };
    let method = v.method.map_or("", FixMethod::name);
    let mut f = vec![v.time.to_string(), v.status.name().into(), method.into()];
    if v.status == Status::None {
        f.extend(blank(5 + 9 * m + 9));
    } else {
        f.push(v.ambiguities.to_string());
        f.push(v.fixed_combinations.to_string());
        f.push(v.held.to_string());
        f.push(v.ratio.map_or(String::new(), |r| format!("{r:.3}")));
        f.push(v.success_rate.map_or(String::new(), |s| format!("{s:.6}")));
        for k in 0..m {
            f.extend::<Vec<String>>(fmt(&v.ecef_m[k], 4));
            match &v.ned_m {
                Some(ned) => {
                    f.extend::<Vec<String>>(fmt(&ned[k].ned_m, 4));
                    f.extend::<Vec<String>>(opt(&ned[k].sigma_m, 5));
                }
                None => f.extend(blank(6)),
            }
        }
        match &v.attitude {
            Some(a) => {
                f.extend::<Vec<String>>(fmt(&a.angles_deg, 5));
                f.extend::<Vec<String>>(opt(&a.std_deg, 5));
                f.extend::<Vec<String>>(opt(&a.rates_dps, 5));
            }
            None => f.extend(blank(9)),
        }
    }
    for text in [&v.fallback, &v.reverse_restart, &v.note] {
        f.push(text.replace(',', ";"));
    }
    f.join(",")
}

/// The fixed integers of an epoch, one row each (baselines numbered from 1).
pub fn integer_rows(o: &EpochOutcome) -> Vec<IntegerRow> {
    let Ok(e) = &o.result else {
        return Vec::new();
    };
    let method = e.resolution.method;
    let ids: Vec<_> = e.float.model.layout.ambiguity_ids().collect();
    e.resolution
        .integers
        .iter()
        .enumerate()
        .filter_map(|(i, value)| {
            let (signal, sat, reference) = ids[i % ids.len()];
            Some(IntegerRow {
                time: o.time,
                baseline: i / ids.len() + 1,
                signal,
                sat,
                reference,
                integer: (*value)?,
                method: Some(method),
            })
        })
        .collect()
}

/// `attitude.csv` and `ambiguities.csv` in a directory, written as the epochs come.
#[derive(Debug)]
pub struct EpochFiles {
    /// Baselines (antennas - 1).
    m: usize,
    csv: BufWriter<File>,
    ints: BufWriter<File>,
    paths: [PathBuf; 2],
    /// The first write error, reported by [`Self::finish`].
    error: Option<io::Error>,
}

/// `e` with the file it happened on.
fn on(path: &Path, what: &str, e: io::Error) -> io::Error {
    io::Error::new(e.kind(), format!("cannot {what} {}: {e}", path.display()))
}

impl EpochFiles {
    /// Create both files in `dir` for `m` baselines and write their headers.
    pub fn create(dir: &Path, m: usize) -> io::Result<Self> {
        let paths = [dir.join(ATTITUDE_CSV), dir.join(AMBIGUITIES_CSV)];
        let create = |p: &Path| {
            File::create(p)
                .map(BufWriter::new)
                .map_err(|e| on(p, "create", e))
        };
        let (mut csv, mut ints) = (create(&paths[0])?, create(&paths[1])?);
        writeln!(csv, "{}", csv_header(m)).map_err(|e| on(&paths[0], "write", e))?;
        writeln!(ints, "{},method", AMBIGUITY_COLUMNS.join(","))
            .map_err(|e| on(&paths[1], "write", e))?;
        Ok(Self {
            m,
            csv,
            ints,
            paths,
            error: None,
        })
    }

    /// One epoch's rows: its values `v` and its fixed integers.
    pub fn write(&mut self, v: &EpochValues, integers: &[IntegerRow]) {
        if self.error.is_some() {
            return;
        }
        let mut rows = || -> io::Result<()> {
            writeln!(self.csv, "{}", csv_row(v, self.m))
                .map_err(|e| on(&self.paths[0], "write", e))?;
            for r in integers {
                writeln!(self.ints, "{}", r.csv_line())
                    .map_err(|e| on(&self.paths[1], "write", e))?;
            }
            Ok(())
        };
        self.error = rows().err();
    }

    /// Flush and close both files; the first error of any write.
    pub fn finish(self) -> io::Result<()> {
        if let Some(e) = self.error {
            return Err(e);
        }
        for (w, p) in [(self.csv, &self.paths[0]), (self.ints, &self.paths[1])] {
            w.into_inner().map_err(|e| on(p, "write", e.into_error()))?;
        }
        Ok(())
    }
}

/// A row read back and its line in the file (1-based; the header is line 1).
#[derive(Debug, Clone, PartialEq)]
pub struct Line<T> {
    pub line: usize,
    pub row: T,
}

/// `attitude.csv` read back: numbers as printed (ECEF and NED baselines to 0.1 mm, their
/// sigmas to 10 um, angles to 1e-5 deg, the ratio to 1e-3, the success rate to 1e-6) and
/// commas of the note as semicolons.
#[derive(Debug, Clone, PartialEq)]
pub struct AttitudeCsv {
    /// Baselines, from the header's `b<k>_x_m` columns.
    pub baselines: usize,
    pub rows: Vec<Line<EpochValues>>,
}

/// Three numbers of a row, all present or none (also when the columns are absent); one or
/// two present is an error.
fn triple(f: &Fields<'_>, columns: [String; 3]) -> Result<Option<[f64; 3]>, FormatError> {
    let v = [0, 1, 2].map(|i| optional(f, &columns[i]));
    match v {
        [Ok(Some(a)), Ok(Some(b)), Ok(Some(c))] => Ok(Some([a, b, c])),
        [Ok(None), Ok(None), Ok(None)] => Ok(None),
        [a, b, c] => {
            a?;
            b?;
            c?;
            Err(f.error(format!("{} given in part", columns.join(", "))))
        }
    }
}

/// The columns every `attitude.csv` has for `m` baselines: what another program's solution
/// must give to be compared with the truth (`skyforge validate attitude`). The other
/// columns are read where present.
fn required_columns(m: usize) -> Vec<String> {
    let mut c: Vec<String> = [
        "time_gpst",
        "status",
        "yaw_deg",
        "pitch_deg",
        "roll_deg",
        "note",
    ]
    .map(String::from)
    .to_vec();
    for k in 1..=m {
        c.extend(["x", "y", "z", "n", "e", "d"].map(|a| format!("b{k}_{a}_m")));
    }
    c
}

/// A number of an optional column: `None` when the column or the value is absent.
fn optional(f: &Fields<'_>, column: &str) -> Result<Option<f64>, FormatError> {
    if f.has(column) {
        f.number(column)
    } else {
        Ok(None)
    }
}

/// The text of an optional column (empty when the column is absent).
fn text_or_empty(f: &Fields<'_>, column: &str) -> Result<String, FormatError> {
    match f.has(column) {
        true => Ok(f.text(column)?.to_string()),
        false => Ok(String::new()),
    }
}

/// The optional `method` column: `None` when absent or empty.
fn method_of(f: &Fields<'_>) -> Result<Option<FixMethod>, FormatError> {
    match text_or_empty(f, "method")?.as_str() {
        "" => Ok(None),
        m => m.parse().map(Some).map_err(|()| {
            f.error(format!(
                "method = {m:?}; expected none, held, lambda, geometry, length or partial"
            ))
        }),
    }
}

/// The values of one data line of `attitude.csv` with `m` baselines.
fn attitude_values(f: &Fields<'_>, m: usize) -> Result<EpochValues, FormatError> {
    let status = f.text("status")?;
    let status: Status = status.parse().map_err(|()| {
        f.error(format!(
            "status = {status:?}; expected fixed, partial, float or none"
        ))
    })?;
    let method = method_of(f)?;
    let mut v = EpochValues {
        time: f.epoch("time_gpst")?,
        status,
        method,
        ambiguities: 0,
        fixed_combinations: 0,
        held: 0,
        ratio: optional(f, "ratio")?,
        success_rate: optional(f, "success_rate")?,
        ecef_m: Vec::new(),
        ned_m: None,
        attitude: None,
        fallback: text_or_empty(f, "fallback")?,
        reverse_restart: text_or_empty(f, "reverse_restart")?,
        note: f.text("note")?.to_string(),
    };
    if v.status == Status::None {
        return Ok(v);
    }
    let count = |c: &str| match f.has(c) {
        true => f.parse(c, "a count"),
        false => Ok(0),
    };
    v.ambiguities = count("ambiguities")?;
    v.fixed_combinations = count("fixed_combinations")?;
    v.held = count("held")?;
    let axes = |k: usize, c: [&str; 3]| c.map(|c| format!("b{k}_{c}_m"));
    let mut ned = Vec::with_capacity(m);
    for k in 1..=m {
        let ecef = triple(f, axes(k, ["x", "y", "z"]))?
            .ok_or_else(|| f.error(format!("a solved epoch without baseline b{k}_x/y/z_m")))?;
        v.ecef_m.push(ecef);
        let sigma_m = triple(f, axes(k, ["sn", "se", "sd"]))?;
        let ned_m = triple(f, axes(k, ["n", "e", "d"]))?;
        ned.push(ned_m.map(|ned_m| NedBaseline { ned_m, sigma_m }));
    }
    v.ned_m = ned.into_iter().collect();
    let angles = |suffix: &str| ["yaw", "pitch", "roll"].map(|a| format!("{a}_{suffix}"));
    v.attitude = match triple(f, angles("deg"))? {
        Some(angles_deg) => Some(AttitudeValues {
            angles_deg,
            std_deg: triple(f, angles("std_deg"))?,
            rates_dps: triple(f, angles("rate_dps"))?,
        }),
        None => None,
    };
    Ok(v)
}

/// Read `attitude.csv` at `path`: the header names at least the required columns for its
/// baselines ([`required_columns`]; another program's solution may give only those),
/// every row's values parse.
pub fn read_attitude_csv(path: &Path) -> Result<AttitudeCsv, FormatError> {
    let baselines = std::cell::Cell::new(0);
    let mut rows = Vec::new();
    let check_header = |names: &[&str]| {
        let m = (1..)
            .take_while(|k| names.contains(&format!("b{k}_x_m").as_str()))
            .count();
        baselines.set(m);
        require_columns(path, names, &required_columns(m))
    };
    read_csv(path, check_header, |header, line, text| {
        let f = Fields::new(path, line, header, text)?;
        let row = attitude_values(&f, baselines.get())?;
        rows.push(Line { line, row });
        Ok(())
    })?;
    Ok(AttitudeCsv {
        baselines: baselines.get(),
        rows,
    })
}

/// One row of `ambiguities.csv`: a fixed double-difference integer.
#[derive(Debug, Clone, PartialEq)]
pub struct IntegerRow {
    pub time: Epoch,
    /// 1-based: antenna `baseline` (after the master) minus the master.
    pub baseline: usize,
    pub signal: Signal,
    pub sat: SatId,
    pub reference: SatId,
    pub integer: i64,
    /// What decided the epoch's integers (`None` where a file read back does not say).
    pub method: Option<FixMethod>,
}

impl IntegerRow {
    /// The row's line of `ambiguities.csv`.
    fn csv_line(&self) -> String {
        format!(
            "{},{},{},{},{},{},{}",
            self.time,
            self.baseline,
            self.signal.tag(),
            self.sat,
            self.reference,
            self.integer,
            self.method.map_or("", FixMethod::name)
        )
    }
}

/// Read `ambiguities.csv` at `path`.
pub fn read_ambiguities_csv(path: &Path) -> Result<Vec<Line<IntegerRow>>, FormatError> {
    let required = AMBIGUITY_COLUMNS.map(String::from);
    let mut rows = Vec::new();
    read_csv(
        path,
        |names| require_columns(path, names, &required),
        |header, line, text| {
            let f = Fields::new(path, line, header, text)?;
            let row = IntegerRow {
                time: f.epoch("time_gpst")?,
                baseline: f.parse("baseline", "a baseline number")?,
                signal: f.parse("signal", "a signal tag (gps-l1ca, bds-b1i)")?,
                sat: f.parse("sat", "a satellite (e.g. G05)")?,
                reference: f.parse("reference", "a satellite (e.g. G05)")?,
                integer: f.parse("integer", "an integer")?,
                method: method_of(&f)?,
            };
            rows.push(Line { line, row });
            Ok(())
        },
    )?;
    Ok(rows)
}

/// `attitude.h5`: every epoch's values as columns (NaN where the epoch gave none).
pub fn write_h5(path: &Path, epochs: &[EpochValues], m: usize) -> hdf5::Result<()> {
    let start = epochs.first().map(|v| v.time);
    let file = create_epoch_file(path, "skyforge attitude.h5 version 1", start)?;
    let root: &hdf5::Group = &file;
    let n = epochs.len();
    let chunk = n.clamp(1, 4096);
    let column = |name: &str, width: usize, unit: &str, what: &str, data: Vec<f64>| {
        let ds = create_rows::<f64>(root, name, width, chunk, unit, what)?;
        append_rows(&ds, 0, &data, width)
    };
    let per = |f: &dyn Fn(&EpochValues) -> Vec<f64>| epochs.iter().flat_map(f).collect();
    let nan = f64::NAN;
    column(
        "t_s",
        0,
        "s",
        "epoch time since start_gpst",
        per(&|v| vec![start.map_or(0.0, |s| (v.time - s).to_seconds())]),
    )?;
    // One code per epoch: `code(v)` of every epoch as a dataset of bytes.
    let codes = |name: &str, what: &str, code: &dyn Fn(&EpochValues) -> u8| {
        let data: Vec<u8> = epochs.iter().map(code).collect();
        let ds = create_rows::<u8>(root, name, 0, chunk, "-", what)?;
        append_rows(&ds, 0, &data, 0)
    };
    codes(
        "status",
        "0 no solution, 1 float, 2 partial, 3 fixed",
        &|v| v.status as u8,
    )?;
    codes(
        "method",
        "what decided the integers: 0 none, 1 held, 2 lambda, 3 geometry, 4 length, 5 partial",
        &|v| v.method.unwrap_or(FixMethod::None) as u8,
    )?;
    codes(
        "fallback",
        "1 where the configured constrained search did not decide and LAMBDA did",
        &|v| u8::from(!v.fallback.is_empty()),
    )?;
    codes(
        "reverse_restart",
        "1 where the reverse filter failed (the epoch's own baselines) and restarts",
        &|v| u8::from(!v.reverse_restart.is_empty()),
    )?;
    column(
        "ratio",
        0,
        "-",
        "second-best over best score of the integer search",
        per(&|v| vec![v.ratio.unwrap_or(nan)]),
    )?;
    column(
        "success_rate",
        0,
        "-",
        "bootstrapped success rate of the free ambiguities",
        per(&|v| vec![v.success_rate.unwrap_or(nan)]),
    )?;
    column(
        "baseline_ecef_m",
        3 * m,
        "m",
        "baselines (antenna k+1 minus the master), x y z per baseline; fixed, float when not",
        per(&|v| {
            let mut row: Vec<f64> = v.ecef_m.iter().flatten().copied().collect();
            row.resize(3 * m, nan);
            row
        }),
    )?;
    let ned = |pick: fn(&NedBaseline) -> Option<[f64; 3]>| {
        per(&move |v: &EpochValues| match &v.ned_m {
            Some(b) => b.iter().flat_map(|b| pick(b).unwrap_or([nan; 3])).collect(),
            None => vec![nan; 3 * m],
        })
    };
    column(
        "baseline_ned_m",
        3 * m,
        "m",
        "fixed baselines in the master's NED frame, n e d per baseline",
        ned(|b| Some(b.ned_m)),
    )?;
    column(
        "baseline_ned_sigma_m",
        3 * m,
        "m",
        "standard deviations of baseline_ned_m",
        ned(|b| b.sigma_m),
    )?;
    let attitude = |pick: fn(&AttitudeValues) -> Option<[f64; 3]>| {
        per(&move |v: &EpochValues| {
            v.attitude
                .as_ref()
                .and_then(pick)
                .unwrap_or([nan; 3])
                .to_vec()
        })
    };
    column(
        "attitude_deg",
        3,
        "deg",
        "yaw, pitch, roll from the master's NED frame (3-2-1)",
        attitude(|a| Some(a.angles_deg)),
    )?;
    column(
        "attitude_std_deg",
        3,
        "deg",
        "standard deviations of attitude_deg",
        attitude(|a| a.std_deg),
    )?;
    column(
        "attitude_rate_dps",
        3,
        "deg/s",
        "yaw, pitch, roll rates (filters only)",
        attitude(|a| a.rates_dps),
    )?;
    file.close()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn values(t_s: f64, fixed: bool) -> EpochValues {
        let time = Epoch::from_gpst_seconds(1.0e9 + t_s);
        EpochValues {
            time,
            status: if fixed { Status::Fixed } else { Status::Float },
            method: Some(if fixed {
                FixMethod::Geometry
            } else {
                FixMethod::None
            }),
            ambiguities: 20,
            fixed_combinations: if fixed { 20 } else { 0 },
            held: 0,
            ratio: Some(4.5),
            success_rate: Some(0.9999),
            ecef_m: vec![[1.0, 2.0, 3.0], [4.0, 5.0, 6.0]],
            ned_m: fixed.then(|| {
                vec![
                    NedBaseline {
                        ned_m: [0.1, 0.2, 0.3],
                        sigma_m: Some([1e-3; 3]),
                    };
                    2
                ]
            }),
            attitude: fixed.then_some(AttitudeValues {
                angles_deg: [10.0, 2.0, -1.0],
                std_deg: Some([0.01; 3]),
                rates_dps: None,
            }),
            fallback: String::new(),
            reverse_restart: String::new(),
            note: String::new(),
        }
    }

    #[test]
    fn h5_columns_hold_every_epoch_with_nan_where_none() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("attitude.h5");
        let mut epochs = [values(0.0, false), values(1.0, true)];
        epochs[0].fallback = "geometry search failed".into();
        epochs[1].reverse_restart = "reverse baseline filter: not finite".into();
        write_h5(&path, &epochs, 2).unwrap();
        let f = hdf5::File::open(&path).unwrap();
        let t: Vec<f64> = f.dataset("t_s").unwrap().read_raw().unwrap();
        assert_eq!(t, [0.0, 1.0]);
        let status: Vec<u8> = f.dataset("status").unwrap().read_raw().unwrap();
        assert_eq!(status, [1, 3]);
        let method: Vec<u8> = f.dataset("method").unwrap().read_raw().unwrap();
        assert_eq!(method, [0, 3]);
        let fallback: Vec<u8> = f.dataset("fallback").unwrap().read_raw().unwrap();
        assert_eq!(fallback, [1, 0]);
        let restart: Vec<u8> = f.dataset("reverse_restart").unwrap().read_raw().unwrap();
        assert_eq!(restart, [0, 1]);
        let ecef: Vec<f64> = f.dataset("baseline_ecef_m").unwrap().read_raw().unwrap();
        assert_eq!(ecef.len(), 12);
        assert_eq!(ecef[6..], [1.0, 2.0, 3.0, 4.0, 5.0, 6.0]);
        let ned: Vec<f64> = f.dataset("baseline_ned_m").unwrap().read_raw().unwrap();
        assert!(ned[..6].iter().all(|v| v.is_nan()));
        assert_eq!(ned[6..9], [0.1, 0.2, 0.3]);
        let att: Vec<f64> = f.dataset("attitude_deg").unwrap().read_raw().unwrap();
        assert!(att[..3].iter().all(|v| v.is_nan()));
        assert_eq!(att[3..], [10.0, 2.0, -1.0]);
        let rates: Vec<f64> = f.dataset("attitude_rate_dps").unwrap().read_raw().unwrap();
        assert!(rates.iter().all(|v| v.is_nan()));
    }

    /// Rows written by [`EpochFiles`] read back as they were: the same text when written
    /// again, the statuses, times, notes and integers exactly.
    #[test]
    fn csv_files_read_back_what_was_written() {
        let dir = tempfile::tempdir().unwrap();
        let mut none = values(2.0, false);
        (none.status, none.success_rate, none.ratio) = (Status::None, None, None);
        none.method = None;
        (none.ecef_m, none.note) = (Vec::new(), "no position: too few, of 4".into());
        let mut rated = values(3.0, true);
        rated.attitude.as_mut().unwrap().rates_dps = Some([0.5, -0.25, 1e-3]);
        rated.fallback = "geometry search failed: no candidate fits".into();
        rated.reverse_restart = "reverse baseline filter: x, y".into();
        let epochs = [values(0.0, false), values(1.0, true), none, rated];
        let integers = |v: &EpochValues| {
            (v.status == Status::Fixed)
                .then(|| IntegerRow {
                    time: v.time,
                    baseline: 2,
                    signal: Signal::BdsB1I,
                    sat: SatId::beidou(7),
                    reference: SatId::beidou(11),
                    integer: -123_456,
                    method: Some(FixMethod::Held),
                })
                .into_iter()
                .collect::<Vec<_>>()
        };
        let mut files = EpochFiles::create(dir.path(), 2).unwrap();
        for v in &epochs {
            files.write(v, &integers(v));
        }
        files.finish().unwrap();
        let read = read_attitude_csv(&dir.path().join(ATTITUDE_CSV)).unwrap();
        assert_eq!(read.baselines, 2);
        assert_eq!(read.rows.len(), epochs.len());
        for (k, (r, v)) in read.rows.iter().zip(&epochs).enumerate() {
            assert_eq!(r.line, k + 2);
            assert_eq!((r.row.time, r.row.status), (v.time, v.status));
            assert_eq!(r.row.method, v.method);
            assert_eq!(csv_row(&r.row, 2), csv_row(v, 2));
        }
        assert_eq!(read.rows[2].row.note, "no position: too few; of 4");
        let rated = &read.rows[3].row;
        assert_eq!(rated.method, Some(FixMethod::Geometry));
        assert_eq!(rated.fallback, "geometry search failed: no candidate fits");
        assert_eq!(rated.reverse_restart, "reverse baseline filter: x; y");
        assert_eq!(
            read.rows[3].row.attitude.unwrap().rates_dps,
            Some([0.5, -0.25, 1e-3])
        );
        let ints = read_ambiguities_csv(&dir.path().join(AMBIGUITIES_CSV)).unwrap();
        let written: Vec<IntegerRow> = epochs.iter().flat_map(integers).collect();
        assert_eq!(
            ints.iter().map(|l| l.row.clone()).collect::<Vec<_>>(),
            written
        );
        assert_eq!(ints.iter().map(|l| l.line).collect::<Vec<_>>(), [2, 3]);
        // Another program's integers need no method column.
        let other = dir.path().join("other.csv");
        std::fs::write(
            &other,
            "time_gpst,baseline,signal,sat,reference,integer\n2024-01-01T00:00:00 GPST,1,gps-l1ca,G05,G07,-3\n",
        )
        .unwrap();
        let read = read_ambiguities_csv(&other).unwrap();
        assert_eq!((read[0].row.integer, read[0].row.method), (-3, None));
    }

    /// A status the writer never writes, or a baseline given in part, is refused with its
    /// file and line.
    #[test]
    fn malformed_rows_are_refused_by_line() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join(ATTITUDE_CSV);
        let good = csv_row(&values(1.0, true), 2);
        let write = |row: String| {
            std::fs::write(&path, format!("{}\n{good}\n{row}\n", csv_header(2))).unwrap();
            read_attitude_csv(&path).unwrap_err().to_string()
        };
        let e = write(good.replacen(",fixed,", ",fixd,", 1));
        assert!(e.contains("attitude.csv:3: status = \"fixd\""), "{e}");
        let fields: Vec<&str> = good.split(',').collect();
        let header = csv_header(2);
        let y = header.split(',').position(|c| c == "b1_y_m").unwrap();
        let mut part = fields.clone();
        part[y] = "";
        let e = write(part.join(","));
        assert!(
            e.contains("attitude.csv:3: b1_x_m, b1_y_m, b1_z_m given in part"),
            "{e}"
        );
    }

    /// Another program's solution needs only the required columns: its rows read with
    /// what they give, the rest absent.
    #[test]
    fn a_table_of_the_required_columns_reads() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join(ATTITUDE_CSV);
        let text = "time_gpst,status,b1_x_m,b1_y_m,b1_z_m,b1_n_m,b1_e_m,b1_d_m,yaw_deg,pitch_deg,roll_deg,note\n\
                    2024-01-01T00:00:00 GPST,fixed,1.5,0.5,-0.25,0.1,1.2,0.3,,,,\n\
                    2024-01-01T00:00:01 GPST,none,,,,,,,,,,Q=5\n";
        std::fs::write(&path, text).unwrap();
        let read = read_attitude_csv(&path).unwrap();
        assert_eq!(read.baselines, 1);
        let (fixed, none) = (&read.rows[0].row, &read.rows[1].row);
        assert_eq!(fixed.status, Status::Fixed);
        assert_eq!(fixed.ecef_m, [[1.5, 0.5, -0.25]]);
        let ned = fixed.ned_m.as_ref().unwrap();
        assert_eq!((ned[0].ned_m, ned[0].sigma_m), ([0.1, 1.2, 0.3], None));
        assert_eq!((fixed.success_rate, fixed.attitude), (None, None));
        assert_eq!((none.status, none.note.as_str()), (Status::None, "Q=5"));
        std::fs::write(&path, text.replace("roll_deg,", "")).unwrap();
        let e = read_attitude_csv(&path).unwrap_err().to_string();
        assert!(
            e.contains("attitude.csv:1: the header has no column roll_deg"),
            "{e}"
        );
    }

    #[test]
    fn csv_row_has_a_field_per_header_column() {
        let header = csv_header(2);
        for v in [values(0.0, false), values(1.0, true)] {
            let row = csv_row(&v, 2);
            assert_eq!(row.split(',').count(), header.split(',').count(), "{row}");
        }
    }
}
