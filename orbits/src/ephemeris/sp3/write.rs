//! The SP3-c writer: every vehicle's states at the union of their epochs, positions in
//! km and, where given, velocities in dm/s (the `V` flag), in GPS time.
//!
//! Layout (SP3-c specification, checked against a real file's header in the tests):
//! line 1 `#c`, the P/V flag, the first epoch, the number of epochs, data used,
//! coordinate system, orbit type, agency; line 2 `##`, GPS week, seconds of week, epoch
//! interval, MJD and its fraction; at least five `+` lines of 17 identifiers and as many
//! `++` accuracy lines; two `%c`, `%f`, `%i` lines; at least four `/*` comment lines;
//! then per epoch a `*` line and the data lines; `EOF`.

use super::{CLOCK_MISSING_US, Sp3State};
use crate::time::gpst_week_sow;
use hifitime::{Epoch, TimeScale, Unit};
use std::collections::BTreeSet;
use std::io::{self, Write};

/// Identifiers per `+` line.
const IDS_PER_LINE: usize = 17;
/// The SP3-c minimum of `+` (and `++`) lines, and of comment lines.
const MIN_ID_LINES: usize = 5;
const MIN_COMMENT_LINES: usize = 4;
/// Comment text per line (SP3-c: columns 4-60).
const COMMENT_CHARS: usize = 57;
/// MJD of the GPS week 0 epoch (1980-01-06).
const MJD_GPS_WEEK_0: f64 = 44_244.0;

/// The header fields a writer chooses.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sp3Header<'a> {
    /// Data used (5 characters at most), e.g. `u` (undifferenced code), `u+U`.
    pub data_used: &'a str,
    /// Coordinate system (5 at most), e.g. `WGS84`, `IGb20`.
    pub coordinate_system: &'a str,
    /// Orbit type (3 at most): `FIT`, `EXT`, `BCT`, `HLM`; `EST` for a filter's estimate.
    pub orbit_type: &'a str,
    /// Agency (4 at most).
    pub agency: &'a str,
    /// File type letter of the `%c` line: `L` (LEO), `M` (mixed), `G` (GPS).
    pub file_type: char,
    /// Free text, cut into comment lines.
    pub comment: &'a str,
}

/// One vehicle's states in time order.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sp3Series<'a> {
    /// Three characters: a system letter and a two-digit number (`L01`).
    pub id: &'a str,
    pub states: &'a [Sp3State],
}

/// Why a file could not be written.
fn invalid(message: String) -> io::Error {
    io::Error::new(io::ErrorKind::InvalidInput, message)
}

/// `text` cut or padded to `n` characters, right-aligned.
fn field(text: &str, n: usize) -> String {
    let t: String = text.chars().take(n).collect();
    format!("{t:>n$}")
}

/// Write `series` as an SP3-c file to `w`. Every vehicle appears at every epoch of the
/// union (absent states as the format's zero position); the epoch interval is the
/// smallest step between epochs (0 for one epoch).
pub fn write_sp3(w: &mut impl Write, header: &Sp3Header, series: &[Sp3Series]) -> io::Result<()> {
    for s in series {
        if s.id.len() != 3 || !s.id.is_ascii() {
            return Err(invalid(format!(
                "SP3 vehicle identifier {:?}: must be 3 ASCII characters (L01)",
                s.id
            )));
        }
    }
    let epochs: Vec<Epoch> = series
        .iter()
        .flat_map(|s| s.states.iter().map(|x| x.epoch))
        .collect::<BTreeSet<_>>()
        .into_iter()
        .collect();
    let Some(&first) = epochs.first() else {
        return Err(invalid("SP3: no states to write".into()));
    };
    let interval_s = epochs
        .windows(2)
        .map(|p| (p[1] - p[0]).to_seconds())
        .fold(f64::INFINITY, f64::min);
    let interval_s = if interval_s.is_finite() {
        interval_s
    } else {
        0.0
    };
    let velocity = series
        .iter()
        .any(|s| s.states.iter().any(|x| x.v_ecef_mps.is_some()));
    write_header(w, header, series, first, epochs.len(), interval_s, velocity)?;
    let mut cursors = vec![0usize; series.len()];
    for t in &epochs {
        writeln!(w, "*  {}", calendar(*t))?;
        for (s, cursor) in series.iter().zip(cursors.iter_mut()) {
            let state = s.states.get(*cursor).filter(|x| x.epoch == *t);
            if state.is_some() {
                *cursor += 1;
            }
            write_state(w, s.id, state, velocity)?;
        }
    }
    writeln!(w, "EOF")
}

/// `2020  6 25  0  0  0.00000000` (GPS time), rounded to the 10 ns the seconds field
/// holds first (so 59.999999996 s is the next minute, not `60.00000000`).
fn calendar(t: Epoch) -> String {
    let (y, mo, d, h, mi, s, ns) = t.round(Unit::Nanosecond * 10).to_gregorian(TimeScale::GPST);
    let sec = f64::from(s) + f64::from(ns) * 1e-9;
    format!("{y:4} {mo:2} {d:2} {h:2} {mi:2} {sec:11.8}")
}

fn write_header(
    w: &mut impl Write,
    h: &Sp3Header,
    series: &[Sp3Series],
    first: Epoch,
    n_epochs: usize,
    interval_s: f64,
    velocity: bool,
) -> io::Result<()> {
    let flag = if velocity { 'V' } else { 'P' };
    writeln!(
        w,
        "#c{flag}{} {n_epochs:7} {} {} {} {}",
        calendar(first),
        field(h.data_used, 5),
        field(h.coordinate_system, 5),
        field(h.orbit_type, 3),
        field(h.agency, 4)
    )?;
    let (week, sow) = gpst_week_sow(first);
    let mjd = MJD_GPS_WEEK_0 + 7.0 * f64::from(week) + sow / 86_400.0;
    writeln!(
        w,
        "## {week:4} {sow:15.8} {interval_s:14.8} {:5} {:15.13}",
        mjd.floor() as i64,
        mjd - mjd.floor()
    )?;
    let lines = series.len().div_ceil(IDS_PER_LINE).max(MIN_ID_LINES);
    for line in 0..lines {
        let ids: String = (0..IDS_PER_LINE)
            .map(|k| series.get(line * IDS_PER_LINE + k).map_or("  0", |s| s.id))
            .collect();
        if line == 0 {
            writeln!(w, "+  {:3}   {ids}", series.len())?;
        } else {
            writeln!(w, "+        {ids}")?;
        }
    }
    for _ in 0..lines {
        // Accuracy exponents: 0, unknown.
        writeln!(w, "++       {}", "  0".repeat(IDS_PER_LINE))?;
    }
    writeln!(
        w,
        "%c {}  cc GPS ccc cccc cccc cccc cccc ccccc ccccc ccccc ccccc",
        h.file_type
    )?;
    writeln!(
        w,
        "%c cc cc ccc ccc cccc cccc cccc cccc ccccc ccccc ccccc ccccc"
    )?;
    for _ in 0..2 {
        writeln!(
            w,
            "%f  0.0000000  0.000000000  0.00000000000  0.000000000000000"
        )?;
    }
    for _ in 0..2 {
        writeln!(
            w,
            "%i    0    0    0    0      0      0      0      0         0"
        )?;
    }
    let text: Vec<char> = h
        .comment
        .chars()
        .filter(|c| c.is_ascii() && !c.is_control())
        .collect();
    let mut comments: Vec<String> = text
        .chunks(COMMENT_CHARS)
        .map(|c| c.iter().collect())
        .collect();
    comments.resize(comments.len().max(MIN_COMMENT_LINES), String::new());
    for c in comments {
        writeln!(w, "/* {c}")?;
    }
    Ok(())
}

/// The `P` line (and with `velocity` the `V` line) of one vehicle at one epoch.
fn write_state(
    w: &mut impl Write,
    id: &str,
    state: Option<&Sp3State>,
    velocity: bool,
) -> io::Result<()> {
    let missing = CLOCK_MISSING_US + 0.999_999;
    let r_km = state.map_or([0.0; 3], |s| (s.r_ecef_m * 1e-3).into());
    let clock_us = state.and_then(|s| s.clock_s).map_or(missing, |c| c * 1e6);
    writeln!(
        w,
        "P{id}{:14.6}{:14.6}{:14.6}{clock_us:14.6}",
        r_km[0], r_km[1], r_km[2]
    )?;
    if velocity {
        let v_dm_s = state
            .and_then(|s| s.v_ecef_mps)
            .map_or([0.0; 3], |v| (v * 10.0).into());
        writeln!(
            w,
            "V{id}{:14.6}{:14.6}{:14.6}{missing:14.6}",
            v_dm_s[0], v_dm_s[1], v_dm_s[2]
        )?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::super::read::parse_sp3_vehicle;
    use super::*;
    use crate::Vec3;

    fn states(n: usize, velocity: bool) -> Vec<Sp3State> {
        let t0 = Epoch::from_gregorian(2020, 6, 25, 0, 0, 0, 0, TimeScale::GPST);
        (0..n)
            .map(|k| Sp3State {
                epoch: t0 + Unit::Second * (10 * k) as i64,
                r_ecef_m: Vec3::new(6_871_000.123 + k as f64, -12_345.678, 1_000.0),
                v_ecef_mps: velocity.then(|| Vec3::new(1.2345, 7600.1234 - k as f64, -3.5)),
                clock_s: (k == 1).then_some(1.5e-6),
            })
            .collect()
    }

    const HEADER: Sp3Header = Sp3Header {
        data_used: "u",
        coordinate_system: "WGS84",
        orbit_type: "EST",
        agency: "SKYF",
        file_type: 'L',
        comment: "skyforge od: the position filter's estimate",
    };

    fn write(series: &[Sp3Series]) -> String {
        let mut out = Vec::new();
        write_sp3(&mut out, &HEADER, series).unwrap();
        String::from_utf8(out).unwrap()
    }

    /// The header lines have the columns of a real file's (GRG0MGXFIN_20201770000's
    /// first two lines, `#cP2020  6 25  0  0  0.00000000      96 TRACK IGb14 FIT GRGS`
    /// and `## 2111 345600.00000000   900.00000000 59025 0.0000000000000`): the same
    /// epoch, week, seconds of week and MJD where they describe the same instant.
    #[test]
    fn header_columns_match_a_real_file() {
        let s = states(3, false);
        let text = write(&[Sp3Series {
            id: "L01",
            states: &s,
        }]);
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(
            lines[0],
            "#cP2020  6 25  0  0  0.00000000       3     u WGS84 EST SKYF"
        );
        assert_eq!(
            lines[1],
            "## 2111 345600.00000000    10.00000000 59025 0.0000000000000"
        );
        assert_eq!(&lines[2][..12], "+    1   L01");
        assert_eq!(lines[2].len(), 60);
        assert_eq!(lines.iter().filter(|l| l.starts_with("++")).count(), 5);
        assert_eq!(lines.iter().filter(|l| l.starts_with("/*")).count(), 4);
        assert!(lines.contains(&"*  2020  6 25  0  0 10.00000000"));
        assert_eq!(lines.last(), Some(&"EOF"));
    }

    /// An epoch a few nanoseconds before a whole minute is written as that minute.
    #[test]
    fn epochs_round_to_the_seconds_field() {
        let t = Epoch::from_gregorian(2023, 3, 12, 0, 0, 0, 0, TimeScale::GPST);
        assert_eq!(
            calendar(t - Unit::Nanosecond * 4),
            "2023  3 12  0  0  0.00000000"
        );
        assert_eq!(
            calendar(t + Unit::Millisecond * 1500),
            "2023  3 12  0  0  1.50000000"
        );
    }

    /// What the writer writes, the reader reads back: positions to the format's 1 mm,
    /// velocities to its 1e-7 m/s, clocks to 1 ps, missing clocks missing.
    #[test]
    fn states_read_back_within_the_format_resolution() {
        let (a, b) = (states(4, true), states(2, true));
        let text = write(&[
            Sp3Series {
                id: "L01",
                states: &a,
            },
            Sp3Series {
                id: "L02",
                states: &b,
            },
        ]);
        assert!(text.starts_with("#cV"));
        for (id, written) in [("L01", &a), ("L02", &b)] {
            let read = parse_sp3_vehicle(&text, "t.sp3", id).unwrap();
            assert_eq!(read.len(), written.len(), "{id}");
            for (r, w) in read.iter().zip(written.iter()) {
                assert_eq!(r.epoch, w.epoch);
                assert!((r.r_ecef_m - w.r_ecef_m).norm() < 1e-3);
                let (rv, wv) = (r.v_ecef_mps.unwrap(), w.v_ecef_mps.unwrap());
                assert!((rv - wv).norm() < 1e-6);
                match (r.clock_s, w.clock_s) {
                    (Some(x), Some(y)) => assert!((x - y).abs() < 1e-12),
                    (x, y) => assert_eq!(x, y),
                }
            }
        }
        // L02 has no state at the last two epochs: zero positions, read as absent.
        assert_eq!(text.matches("PL02      0.000000").count(), 2);
    }

    #[test]
    fn bad_identifiers_and_nothing_to_write_are_refused() {
        let s = states(1, false);
        let mut out = Vec::new();
        for id in ["L1", "LEO1", "L\u{e9}"] {
            let e = write_sp3(&mut out, &HEADER, &[Sp3Series { id, states: &s }]);
            assert!(e.is_err(), "{id}");
        }
        assert!(write_sp3(&mut out, &HEADER, &[]).is_err());
    }
}
