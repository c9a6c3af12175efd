//! RINEX navigation files, versions 2 (GPS), 3 (mixed) and 4 (message types), plain or
//! gzip-compressed. GPS LNAV, BeiDou D1/D2 and Galileo I/NAV and F/NAV records are kept;
//! others are skipped.
//!
//! Format facts used (RINEX 2.11, 3.05 and 4.00 specifications, "navigation message file"
//! tables for GPS and BDS):
//! - data records: an epoch line (satellite, epoch of clock `toc` in the system's time
//!   scale, af0/af1/af2) followed by seven "broadcast orbit" lines of four 19-character
//!   floating-point fields (Fortran `D` exponents allowed). Version 2 lines start with 3
//!   blanks, versions 3/4 with 4. Every field the orbit and clock models use (and the
//!   transmission time, which every complete record has) must be present: a record cut
//!   short (missing lines, a shortened line) is an error naming the file, line and field.
//!   Fields the models do not use (spares, codes on L2, L2 P flag, accuracy, TGD2, the GPS
//!   fit interval) may be blank or missing at the end of a line and read as zero.
//! - version 4 prefixes each record with a `> EPH G05 LNAV` / `> EPH C19 D1` line; other
//!   record types (STO, EOP, ION) and other message types (CNAV, CNV1..3) are skipped.
//! - GPS: toe is GPS week (continuous) + seconds of week; health is the 6-bit SV health;
//!   TGD is the L1/L2 P(Y) group delay; the fit interval is in hours.
//! - BeiDou: toe is BDT week + seconds of week; health is SatH1; TGD1 (B1I) is kept; the
//!   last line carries AODC.
//! - Galileo: the first orbit line carries IODnav (kept as IODE and IODC); the fifth
//!   carries the data sources, whose bit 1 marks an F/NAV record and bits 0 and 2 an I/NAV
//!   one (RINEX 3.05 Table A8; a record that claims both is an error; version 4 names the
//!   message on its `> EPH E05 INAV` line, which must agree); the week goes with toe and
//!   is the continuous GPS week (RINEX 3.05 §6.12, not the GST week, which is 1024 less);
//!   health is the SV health field (E1-B, E5a and E5b data validity and health bits);
//!   the group delay kept is the one of the message's clock pair: BGD(E1,E5b) for I/NAV,
//!   BGD(E1,E5a) for F/NAV ([`super::NavMessage`]).
//!
//! Choices (documented here, tested below):
//! - GPS fit interval: the field in hours; 0, missing, or a value below 4 (some writers put
//!   the 0/1 fit-interval *flag* there) means the standard 4 h.
//! - BeiDou fit interval: 6 h. The ICD gives none; BeiDou uploads a new set every hour
//!   with toe on the hour, so the store's nearest-toe rule picks the hourly set wherever
//!   the file has one, and the wider window only matters at the ends of a file (the last
//!   set of a daily file has toe 23:00). Measured on the bundled RINEX 4 file
//!   (`tests/real_data_ephemeris.rs`): a set used 1, 2, 3 h after its toe differs from the
//!   newer set by at most 4.7, 7.2, 10.0 m.
//! - Galileo fit interval: 4 h. The ICD gives none; Galileo uploads a new set every 10 min
//!   to 3 h (IODnav changes), and a set's nominal validity is 4 h (Galileo OS SDD).
//! - BeiDou GEO: classified by PRN (C01-C05 and C59-C63), not by the D1/D2 label.
//! - toe week: the week field goes with toe; if toe and toc then differ by more than half
//!   a week (a writer that put the transmission week), the week is corrected by one.
//! - Records whose orbit is physically impossible (sqrt(A) outside 1000..10000 m^1/2,
//!   e outside [0, 1), non-finite values) are format errors.

use super::nav_text::read_text_maybe_gz;
use super::rinex_nav_iono::{BroadcastIono, parse_iono};
use super::{
    NavError,
    broadcast::NavMessage,
    broadcast::{BroadcastEphemeris, ClockParams, HarmonicCorrections, KeplerElements, OrbitClass},
    sat_id::{SatId, System},
};
use crate::rinex_header::{label, supported_major, version_and_type};
use hifitime::{Epoch, TimeScale, Unit};
use std::path::Path;

/// Default GPS fit interval (s), IS-GPS-200 20.3.4.4 (fit interval flag 0).
const GPS_DEFAULT_FIT_S: f64 = 4.0 * 3600.0;
/// BeiDou validity interval (s), +-3 h about toe (see the module notes).
const BDS_FIT_S: f64 = 6.0 * 3600.0;
/// Galileo validity interval (s), +-2 h about toe (see the module notes).
const GAL_FIT_S: f64 = 4.0 * 3600.0;
/// Galileo data-sources bits (RINEX 3.05 Table A8): I/NAV E1-B, F/NAV E5a-I, I/NAV E5b-I.
const GAL_SOURCE_INAV_E1B: u32 = 1 << 0;
const GAL_SOURCE_FNAV: u32 = 1 << 1;
const GAL_SOURCE_INAV_E5B: u32 = 1 << 2;
/// Seconds per week.
const WEEK_S: f64 = crate::time::SECONDS_PER_WEEK as f64;

/// Read every GPS LNAV, BeiDou D1/D2 and Galileo I/NAV and F/NAV ephemeris in the file.
pub fn read_nav_file(path: &Path) -> Result<Vec<BroadcastEphemeris>, NavError> {
    let text = read_text_maybe_gz(path)?;
    parse_nav(&text, &path.display().to_string())
}

/// Read the ephemerides and the header's Klobuchar coefficients of a navigation file,
/// the file read once.
pub fn read_nav_file_with_iono(
    path: &Path,
) -> Result<(Vec<BroadcastEphemeris>, BroadcastIono), NavError> {
    let text = read_text_maybe_gz(path)?;
    parse_nav_with_iono(&text, &path.display().to_string())
}

/// Parse the text of a RINEX 2/3/4 navigation file. `source` names the file in errors.
pub fn parse_nav(text: &str, source: &str) -> Result<Vec<BroadcastEphemeris>, NavError> {
    parse_nav_with_iono(text, source).map(|(ephemerides, _)| ephemerides)
}

/// [`parse_nav`] with the header's Klobuchar coefficients.
fn parse_nav_with_iono(
    text: &str,
    source: &str,
) -> Result<(Vec<BroadcastEphemeris>, BroadcastIono), NavError> {
    let p = Parser { source };
    let lines: Vec<&str> = text.lines().map(|l| l.trim_end_matches('\r')).collect();
    let first = lines.first().ok_or_else(|| p.err(1, "empty file"))?;
    let (version, file_type) = version_and_type(first).map_err(|m| p.err(1, m))?;
    if file_type != "N" {
        return Err(p.err(
            1,
            format!("file type {file_type:?} is not a navigation file (N)"),
        ));
    }
    let end = lines
        .iter()
        .position(|l| label(l) == "END OF HEADER")
        .ok_or_else(|| p.err(lines.len(), "no END OF HEADER"))?;
    // The header's Klobuchar lines must read as numbers wherever the file is read (they
    // were ignored here and refused by the receiver's reader).
    let iono = parse_iono(text, source)?;
    let body = Body {
        lines: &lines,
        start: end + 1,
    };
    let ephemerides = match supported_major(version).map_err(|m| p.err(1, m))? {
        2 => p.parse_v2(&body),
        3 => p.parse_v3(&body),
        _ => p.parse_v4(&body),
    }?;
    Ok((ephemerides, iono))
}

/// The data section of the file (0-based index of its first line).
struct Body<'a> {
    lines: &'a [&'a str],
    start: usize,
}

/// One record: its lines with their 1-based line numbers.
type Record<'a> = Vec<(usize, &'a str)>;

struct Parser<'a> {
    source: &'a str,
}

/// The 31 numbers of a GPS/BeiDou record: clock line (3) + seven orbit lines (4 each),
/// `None` where the field is blank or beyond the end of its line (or its line is missing).
struct Fields {
    v: [Option<f64>; 31],
    /// 1-based file line of the epoch line and of orbit lines 1-7; a missing orbit line
    /// gets the record's last line.
    line_no: [usize; 8],
}

impl Fields {
    /// Orbit line `line` (1-7), field `k` (1-4); a blank or missing field reads 0 (only
    /// for fields the model does not need, see [`Self::need`]).
    fn orbit(&self, line: usize, k: usize) -> f64 {
        self.v[3 + (line - 1) * 4 + (k - 1)].unwrap_or(0.0)
    }

    /// Orbit line `line` (1-7), field `k` (1-4), which must be present: a record cut short
    /// (the file ends inside it, a line is shortened) is an error naming the field, never
    /// zeros.
    fn need(&self, p: &Parser, line: usize, k: usize, name: &str) -> Result<f64, NavError> {
        self.v[3 + (line - 1) * 4 + (k - 1)].ok_or_else(|| {
            p.err(
                self.line_no[line],
                format!(
                    "record cut short: broadcast orbit line {line} has no field {k} ({name}); \
                     every field the orbit and clock models use must be present"
                ),
            )
        })
    }

    /// Clock field `k` (0-2: af0, af1, af2) of the epoch line, which must be present.
    fn clock(&self, p: &Parser, k: usize) -> Result<f64, NavError> {
        const NAMES: [&str; 3] = ["af0", "af1", "af2"];
        self.v[k].ok_or_else(|| {
            p.err(
                self.line_no[0],
                format!(
                    "record cut short: the epoch line has no {} (clock field {})",
                    NAMES[k],
                    k + 1
                ),
            )
        })
    }
}

impl Parser<'_> {
    fn err(&self, line: usize, message: impl Into<String>) -> NavError {
        NavError::Format {
            path: self.source.to_string(),
            line,
            message: message.into(),
        }
    }

    /// RINEX 2: GPS only; a record starts with the PRN in columns 1-2.
    fn parse_v2(&self, body: &Body) -> Result<Vec<BroadcastEphemeris>, NavError> {
        let mut out = Vec::new();
        for rec in split_records(body, |l| !l.get(..2).unwrap_or(l).trim().is_empty()) {
            let (n0, l0) = rec[0];
            let head = l0
                .get(..22)
                .ok_or_else(|| self.err(n0, "epoch line too short"))?;
            let t: Vec<&str> = head.split_whitespace().collect();
            if t.len() != 7 {
                return Err(self.err(n0, "expected PRN and 6 epoch fields in columns 1-22"));
            }
            let prn: u8 = t[0].parse().map_err(|_| self.err(n0, "bad PRN"))?;
            let yy: i32 = t[1].parse().map_err(|_| self.err(n0, "bad year"))?;
            let year = if yy < 80 { 2000 + yy } else { 1900 + yy };
            let epoch = self.epoch(n0, year, &t[2..7], TimeScale::GPST)?;
            let fields = self.fields(&rec, 22, 3)?;
            out.push(self.ephemeris(
                n0,
                SatId::gps(self.prn(n0, System::Gps, prn)?),
                epoch,
                &fields,
            )?);
        }
        Ok(out)
    }

    /// RINEX 3: a record starts with the system letter in column 1.
    fn parse_v3(&self, body: &Body) -> Result<Vec<BroadcastEphemeris>, NavError> {
        let mut out = Vec::new();
        for rec in split_records(body, |l| l.starts_with(|c: char| c.is_ascii_alphabetic())) {
            if let Some(eph) = self.v3_record(&rec)? {
                out.push(eph);
            }
        }
        Ok(out)
    }

    /// RINEX 4: a record starts with a `>` line naming its type and message.
    fn parse_v4(&self, body: &Body) -> Result<Vec<BroadcastEphemeris>, NavError> {
        let mut out = Vec::new();
        for rec in split_records(body, |l| l.starts_with('>')) {
            let (n0, l0) = rec[0];
            let t: Vec<&str> = l0.split_whitespace().collect();
            // Every record type (EPH, STO, EOP, ION) has data lines: a `>` line alone is a
            // file cut after it (or inside it).
            if rec.len() < 2 {
                return Err(self.err(n0, "record cut short: a record line without data lines"));
            }
            let wanted = match t.as_slice() {
                [">", "EPH", sat, msg, ..] => {
                    (sat.starts_with('G') && *msg == "LNAV")
                        || (sat.starts_with('C') && (*msg == "D1" || *msg == "D2"))
                        || (sat.starts_with('E') && (*msg == "INAV" || *msg == "FNAV"))
                }
                [">", "EPH", ..] => {
                    return Err(self.err(n0, "EPH record line without satellite and message type"));
                }
                [">", ..] => false,
                _ => return Err(self.err(n0, "bad record type line")),
            };
            if !wanted {
                continue;
            }
            match self.v3_record(&rec[1..])? {
                Some(eph) if eph.sat.to_string() != t[2] => {
                    return Err(self.err(rec[1].0, "satellite differs from the > line"));
                }
                Some(eph)
                    if eph.sat.system == System::Galileo && galileo_label(eph.message) != t[3] =>
                {
                    return Err(self.err(
                        rec[1].0,
                        format!(
                            "the data sources say {} but the > line says {}",
                            galileo_label(eph.message),
                            t[3]
                        ),
                    ));
                }
                Some(eph) => out.push(eph),
                None => return Err(self.err(rec[1].0, "EPH data line is not GPS/BeiDou/Galileo")),
            }
        }
        Ok(out)
    }

    /// A RINEX 3/4 data record (epoch line + orbit lines); `None` for other systems.
    fn v3_record(&self, rec: &[(usize, &str)]) -> Result<Option<BroadcastEphemeris>, NavError> {
        let (n0, l0) = rec[0];
        let system = match l0.chars().next().and_then(System::from_letter) {
            Some(s) => s,
            None => return Ok(None),
        };
        let sat: SatId = l0
            .get(..3)
            .and_then(|s| s.parse().ok())
            .ok_or_else(|| self.err(n0, "bad satellite id in columns 1-3"))?;
        let head = l0
            .get(4..23)
            .ok_or_else(|| self.err(n0, "epoch line too short"))?;
        let t: Vec<&str> = head.split_whitespace().collect();
        if t.len() != 6 {
            return Err(self.err(n0, "expected 6 epoch fields in columns 5-23"));
        }
        let year: i32 = t[0].parse().map_err(|_| self.err(n0, "bad year"))?;
        let epoch = self.epoch(n0, year, &t[1..6], system.time_scale())?;
        let fields = self.fields(rec, 23, 4)?;
        self.ephemeris(n0, sat, epoch, &fields).map(Some)
    }

    fn prn(&self, line: usize, system: System, prn: u8) -> Result<u8, NavError> {
        if prn == 0 || prn > system.max_prn() {
            return Err(self.err(line, format!("PRN {prn} out of range")));
        }
        Ok(prn)
    }

    /// Month, day, hour, minute, second (may be fractional) in `scale`.
    fn epoch(
        &self,
        line: usize,
        year: i32,
        t: &[&str],
        scale: TimeScale,
    ) -> Result<Epoch, NavError> {
        let bad = || self.err(line, "bad epoch");
        let int = |s: &str| s.parse::<u8>().map_err(|_| bad());
        let sec: f64 = t[4].parse().map_err(|_| bad())?;
        if !(0.0..61.0).contains(&sec) {
            return Err(bad());
        }
        let whole = sec.floor();
        let nanos = ((sec - whole) * 1e9).round() as u32;
        Epoch::maybe_from_gregorian(
            year,
            int(t[0])?,
            int(t[1])?,
            int(t[2])?,
            int(t[3])?,
            whole as u8,
            nanos.min(999_999_999),
            scale,
        )
        .map_err(|_| bad())
    }

    /// The 31 numbers: 3 on the epoch line from column `first_col`, then 4 per orbit line
    /// from column `indent`. All eight lines are required (the last one may be shortened:
    /// which fields must be present is decided in [`Self::ephemeris`]).
    fn fields(
        &self,
        rec: &[(usize, &str)],
        first_col: usize,
        indent: usize,
    ) -> Result<Fields, NavError> {
        let last = rec.last().map_or(rec[0].0, |r| r.0);
        if rec.len() < 8 {
            return Err(self.err(
                last,
                format!(
                    "record cut short: it has {} lines (from line {}), a GPS/BeiDou/Galileo record has 8 \
                     (the epoch line and seven broadcast orbit lines)",
                    rec.len(),
                    rec[0].0
                ),
            ));
        }
        let mut v = [None; 31];
        let mut line_no = [last; 8];
        let (n0, l0) = rec[0];
        line_no[0] = n0;
        for (k, x) in v.iter_mut().take(3).enumerate() {
            *x = self.field(n0, l0, first_col + 19 * k)?;
        }
        for (j, &(n, l)) in rec.iter().skip(1).take(7).enumerate() {
            if l.get(..indent).is_none_or(|s| !s.trim().is_empty()) && !l.trim().is_empty() {
                return Err(self.err(n, "orbit line must start with blanks"));
            }
            line_no[j + 1] = n;
            for k in 0..4 {
                v[3 + 4 * j + k] = self.field(n, l, indent + 19 * k)?;
            }
        }
        Ok(Fields { v, line_no })
    }

    /// One 19-character field starting at `col`; `None` when blank or beyond the line end.
    fn field(&self, line_no: usize, line: &str, col: usize) -> Result<Option<f64>, NavError> {
        if col >= line.len() {
            return Ok(None);
        }
        let s = line
            .get(col..(col + 19).min(line.len()))
            .ok_or_else(|| self.err(line_no, "non-ASCII text in a numeric field"))?
            .trim();
        if s.is_empty() {
            return Ok(None);
        }
        // Fields are right-justified in 19 columns: a number the line end cuts into was
        // shortened (a truncated file), and its digits would read as another value.
        if line.len() < col + 19 {
            return Err(self.err(
                line_no,
                format!(
                    "record cut short: the line ends at column {} inside the number {s:?} \
                     (a field spans columns {}-{})",
                    line.len(),
                    col + 1,
                    col + 19
                ),
            ));
        }
        let x: f64 = s
            .replace(['D', 'd'], "E")
            .parse()
            .map_err(|_| self.err(line_no, format!("bad number {s:?}")))?;
        if !x.is_finite() {
            return Err(self.err(line_no, format!("non-finite number {s:?}")));
        }
        Ok(Some(x))
    }

    /// Build the ephemeris from the record fields (RINEX 3.05 GPS, Galileo and BDS
    /// navigation message record tables; version 2 GPS records have the same layout).
    fn ephemeris(
        &self,
        line: usize,
        sat: SatId,
        toc: Epoch,
        f: &Fields,
    ) -> Result<BroadcastEphemeris, NavError> {
        // Galileo's RINEX week is the continuous GPS week (the module notes).
        let scale = match sat.system {
            System::Galileo => TimeScale::GPST,
            system => system.time_scale(),
        };
        let (week_name, iode_name) = match sat.system {
            System::Gps => ("GPS week", "IODE"),
            System::Beidou => ("BDT week", "AODE"),
            System::Galileo => ("GAL week", "IODnav"),
        };
        let need = |line, k, name| f.need(self, line, k, name);
        let toe_sow = need(3, 1, "toe")?;
        let week = need(5, 3, week_name)?;
        if !(0.0..=WEEK_S).contains(&toe_sow) {
            return Err(self.err(line, format!("toe {toe_sow} s outside the week")));
        }
        if !(0.0..100_000.0).contains(&week) || week.fract() != 0.0 {
            return Err(self.err(line, format!("bad {week_name} {week}")));
        }
        let mut toe = Epoch::from_time_of_week(week as u32, (toe_sow * 1e9).round() as u64, scale);
        let off_s = (toe - toc).to_seconds();
        if off_s > WEEK_S / 2.0 {
            toe -= Unit::Week * 1;
        } else if off_s < -WEEK_S / 2.0 {
            toe += Unit::Week * 1;
        }
        let sqrt_a = need(2, 4, "sqrt(A)")?;
        let e = need(2, 2, "e")?;
        if !(1000.0..10_000.0).contains(&sqrt_a) || !(0.0..1.0).contains(&e) {
            return Err(self.err(line, format!("implausible orbit sqrt(A)={sqrt_a} e={e}")));
        }
        let count = |x: f64| -> Result<u32, NavError> {
            if (0.0..=f64::from(u32::MAX)).contains(&x) {
                Ok(x.round() as u32)
            } else {
                Err(self.err(line, format!("bad issue-of-data/health value {x}")))
            }
        };
        // The transmission time is not used, but every complete record has it: without it
        // the record (the file) was cut after its sixth orbit line.
        need(7, 1, "transmission time")?;
        let mut message = NavMessage::default_for(sat.system);
        let mut tgd2_s = 0.0;
        let (class, tgd_s, iodc, fit_interval_s) = match sat.system {
            System::Galileo => {
                message = galileo_message(count(need(5, 2, "data sources")?)?)
                    .map_err(|m| self.err(f.line_no[5], m))?;
                let tgd_s = match message {
                    NavMessage::GalileoFnav => need(6, 3, "BGD E5a/E1")?,
                    _ => {
                        tgd2_s = need(6, 3, "BGD E5a/E1")?;
                        need(6, 4, "BGD E5b/E1")?
                    }
                };
                let iod = count(need(1, 1, iode_name)?)?;
                (OrbitClass::Standard, tgd_s, iod, GAL_FIT_S)
            }
            System::Gps => {
                let fit_h = f.orbit(7, 2);
                let fit_s = if fit_h < 4.0 {
                    GPS_DEFAULT_FIT_S
                } else {
                    fit_h * 3600.0
                };
                (
                    OrbitClass::Standard,
                    need(6, 3, "TGD")?,
                    count(need(6, 4, "IODC")?)?,
                    fit_s,
                )
            }
            System::Beidou => {
                let class = if sat.prn <= 5 || sat.prn >= 59 {
                    OrbitClass::BeidouGeo
                } else {
                    OrbitClass::Standard
                };
                (
                    class,
                    need(6, 3, "TGD1")?,
                    count(need(7, 2, "AODC")?)?,
                    BDS_FIT_S,
                )
            }
        };
        let orbit = KeplerElements {
            sqrt_a,
            e,
            i0: need(4, 1, "i0")?,
            omega0: need(3, 3, "OMEGA0")?,
            omega: need(4, 3, "omega")?,
            m0: need(1, 4, "M0")?,
            delta_n: need(1, 3, "Delta n")?,
            idot: need(5, 1, "IDOT")?,
            omega_dot: need(4, 4, "OMEGA DOT")?,
        };
        let harmonics = HarmonicCorrections {
            cuc: need(2, 1, "Cuc")?,
            cus: need(2, 3, "Cus")?,
            crc: need(4, 2, "Crc")?,
            crs: need(1, 2, "Crs")?,
            cic: need(3, 2, "Cic")?,
            cis: need(3, 4, "Cis")?,
        };
        let clock = ClockParams {
            af0: f.clock(self, 0)?,
            af1: f.clock(self, 1)?,
            af2: f.clock(self, 2)?,
            tgd_s,
            tgd2_s,
        };
        Ok(BroadcastEphemeris {
            toc,
            message,
            iode: count(need(1, 1, iode_name)?)?,
            iodc,
            health: count(need(6, 2, "health")?)?,
            ..BroadcastEphemeris::from_elements(
                sat,
                class,
                toe,
                orbit,
                harmonics,
                clock,
                fit_interval_s,
            )
        })
    }
}

/// The message of a Galileo record from its data-sources field (RINEX 3.05 Table A8).
fn galileo_message(sources: u32) -> Result<NavMessage, String> {
    let inav = sources & (GAL_SOURCE_INAV_E1B | GAL_SOURCE_INAV_E5B) != 0;
    match (inav, sources & GAL_SOURCE_FNAV != 0) {
        (true, false) => Ok(NavMessage::GalileoInav),
        (false, true) => Ok(NavMessage::GalileoFnav),
        (true, true) => Err(format!(
            "data sources {sources} claim both I/NAV (bits 0, 2) and F/NAV (bit 1)"
        )),
        (false, false) => Err(format!(
            "data sources {sources} name neither I/NAV (bits 0, 2) nor F/NAV (bit 1)"
        )),
    }
}

/// The RINEX 4 message label of a Galileo message (`INAV`, `FNAV`).
fn galileo_label(message: NavMessage) -> &'static str {
    match message {
        NavMessage::GalileoFnav => "FNAV",
        _ => "INAV",
    }
}

/// Split the body into records: a record is a line for which `starts` holds plus the
/// following lines for which it does not. Blank lines are dropped; lines before the first
/// record start are ignored.
fn split_records<'a>(body: &Body<'a>, starts: impl Fn(&str) -> bool) -> Vec<Record<'a>> {
    let mut out: Vec<Record<'a>> = Vec::new();
    for (i, &l) in body.lines.iter().enumerate().skip(body.start) {
        if l.trim().is_empty() {
            continue;
        }
        if starts(l) {
            out.push(vec![(i + 1, l)]);
        } else if let Some(last) = out.last_mut() {
            last.push((i + 1, l));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Issue #33 (12): an `IONOSPHERIC CORR` line that does not read as numbers was
    /// ignored by this reader (and refused by the receiver's); it is refused with its line.
    #[test]
    fn an_unreadable_ionosphere_header_line_is_refused() {
        let fixture = crate::fixtures::RINEX3_GPS_NAV;
        let good = "GPSA   1.1176E-08  1.4901E-08 -5.9605E-08 -1.1921E-07       IONOSPHERIC CORR\n";
        let bad = "GPSA   1.1176E-08  x.4901E-08 -5.9605E-08 -1.1921E-07       IONOSPHERIC CORR\n";
        let with = |line: &str| {
            fixture.replacen(
                "RINEX VERSION / TYPE\n",
                &format!("RINEX VERSION / TYPE\n{line}"),
                1,
            )
        };
        assert_eq!(parse_nav(&with(good), "nav.rnx").unwrap().len(), 1);
        let e = parse_nav(&with(bad), "nav.rnx").unwrap_err().to_string();
        assert!(e.starts_with("nav.rnx:2: "), "{e}");
    }

    /// Issue #11: `--assist /dev/zero` read until memory ran out, and a directory was
    /// reported as missing.
    #[test]
    fn an_endless_device_and_a_directory_are_refused_with_what_they_are() {
        let err = read_nav_file(Path::new("/dev/zero"))
            .unwrap_err()
            .to_string();
        assert!(
            err.contains("not a navigation file") && err.contains("MiB"),
            "{err}"
        );
        let dir = std::env::temp_dir();
        let err = read_nav_file(&dir).unwrap_err().to_string();
        assert!(err.contains("is a directory"), "{err}");
    }
    use proptest::prelude::*;

    const V2_HEADER: &str =
        "     2              NAVIGATION DATA                         RINEX VERSION / TYPE
                                                            END OF HEADER
";

    /// Two records from the IGS brdc0010.22n file (GPS, 2022-01-01); the second one edited
    /// (health 63, fit-interval field 0, a last line with four fields) to cover those cases.
    const V2_BODY: &str =
        " 1 22  1  1  0  0  0.0 0.469126738608D-03-0.100044417195D-10 0.000000000000D+00
    0.390000000000D+02-0.141125000000D+03 0.398838041777D-08-0.624294238235D+00
   -0.736303627491D-05 0.112181392033D-01 0.469572842121D-05 0.515367499542D+04
    0.518400000000D+06-0.316649675369D-07-0.103661124009D+01 0.195577740669D-06
    0.986418769490D+00 0.299750000000D+03 0.884087601569D+00-0.813355308085D-08
   -0.377872882780D-09 0.100000000000D+01 0.219000000000D+04 0.000000000000D+00
    0.200000000000D+01 0.000000000000D+00 0.512227416039D-08 0.390000000000D+02
    0.511218000000D+06 0.400000000000D+01
 2 22  1  1  0  0  0.0-0.647393986583D-03-0.113686837722D-11 0.000000000000D+00
    0.410000000000D+02-0.142718750000D+03 0.455626121514D-08-0.453245129719D+00
   -0.748783349991D-05 0.206388905644D-01 0.423192977905D-05 0.515366817474D+04
    0.518400000000D+06-0.258907675743D-06-0.112496293255D+01 0.122934579849D-06
    0.964744088915D+00 0.303625000000D+03-0.146476911829D+01-0.868964767299D-08
   -0.262153776900D-09 0.100000000000D+01 0.219000000000D+04 0.000000000000D+00
    0.200000000000D+01 0.630000000000D+02-0.176951289177D-07 0.410000000000D+02
    0.512376000000D+06 0.000000000000D+00 0.000000000000D+00 0.000000000000D+00
";

    const V3_HEADER: &str =
        "     3.05           NAVIGATION DATA     MIXED               RINEX VERSION / TYPE
                                                            END OF HEADER
";

    /// A GLONASS record (skipped) and a BeiDou GEO record from ESBC00DNK 2020-06-24/25.
    const V3_BODY: &str =
        "R01 2020 06 24 23 15 00 6.355904042721e-05 0.000000000000e+00 3.420000000000e+05
     1.090894238281e+04 1.407806396484e+00-1.862645149231e-09 0.000000000000e+00
    -2.885726074219e+03 2.795855522156e+00-0.000000000000e+00 1.000000000000e+00
     2.288353955078e+04-3.169984817505e-01-2.793967723846e-09 0.000000000000e+00
                         .999999999999e+09 1.500000000000e+01
C05 2020 06 24 22 00 00-5.154609680176e-04-6.708145150469e-11 0.000000000000e+00
     1.000000000000e+00-4.142968750000e+02-3.141559429989e-09-1.101749161212e+00
    -1.366203650832e-05 3.830116475001e-04-1.177610829473e-05 6.493378950119e+03
     3.384000000000e+05-6.146728992462e-08 2.697580724014e+00 6.146728992462e-08
     1.136268367853e-01 3.549843750000e+02-1.027125663175e+00 4.100527946305e-09
     3.321566928024e-10 0.000000000000e+00 7.550000000000e+02
     2.000000000000e+00 0.000000000000e+00 1.000000000000e-10-9.300000000000e-09
     3.384276000000e+05 0.000000000000e+00
";

    const V4_HEADER: &str =
        "     4.00           NAVIGATION DATA     M                   RINEX VERSION / TYPE
                                                            END OF HEADER
";

    /// STO, GPS LNAV, BeiDou D2 (GEO C01) and CNV1 records from BRD400DLR 2023-03-12.
    const V4_BODY: &str = "> STO C21 CNVX
    2023 03 12 00 20 00 BDGA
     2.286000000000e+03-2.502929419279e-08 2.664535259100e-14 6.776263578034e-21
> EPH G01 LNAV
G01 2023 03 12 00 00 00 2.037500962615e-04-3.865352482535e-12 0.000000000000e+00
     5.900000000000e+01-6.681250000000e+01 3.651580674421e-09 2.337063183399e+00
    -3.580003976822e-06 1.249682181515e-02 1.121312379837e-05 5.153656053543e+03
     0.000000000000e+00-2.980232238770e-08-2.635778779840e+00-2.421438694000e-07
     9.898042779154e-01 1.769375000000e+02 9.395220485102e-01-7.465310960167e-09
    -2.000083311498e-11 1.000000000000e+00 2.253000000000e+03 0.000000000000e+00
     2.000000000000e+00 0.000000000000e+00 4.656612873077e-09 5.900000000000e+01
    -7.182000000000e+03 4.000000000000e+00
> EPH C01 D2
C01 2023 03 12 00 00 00 9.050882654265e-04-2.618349981276e-12 0.000000000000e+00
     1.000000000000e+00-3.022187500000e+02-1.132904332870e-09 1.639863675133e+00
    -1.014024019241e-05 4.634374054149e-04 1.808675006032e-05 6.493325918198e+03
     0.000000000000e+00 2.887099981308e-08-2.843751285290e+00-8.102506399155e-08
     9.005722671926e-02-5.558125000000e+02-2.556429343966e+00 2.302953070096e-09
     4.485901141503e-10 0.000000000000e+00 8.970000000000e+02 0.000000000000e+00
     2.000000000000e+00 0.000000000000e+00-5.400000000000e-09-9.700000000000e-09
     0.000000000000e+00 0.000000000000e+00
> EPH C19 CNV1
C19 2023 03 12 00 00 00-8.956108940765e-04-9.041656312547e-13 0.000000000000e+00
    -2.287387847900e-03-5.843750000000e+00 3.871232680951e-09 8.650567350738e-01
";

    fn parse(text: &str) -> Result<Vec<BroadcastEphemeris>, NavError> {
        parse_nav(text, "test.rnx")
    }

    fn gpst(y: i32, mo: u8, d: u8, h: u8) -> Epoch {
        Epoch::from_gregorian(y, mo, d, h, 0, 0, 0, TimeScale::GPST)
    }

    /// A RINEX 4 file with one Galileo record under `label` (`INAV`, `FNAV`), its data
    /// sources `sources`.
    fn galileo_v4(label: &str, sources: f64) -> String {
        let record = [
            "E05 2023 03 12 00 00 00-8.700000000000e-05 3.600000000000e-12 0.000000000000e+00",
            "     0.000000000000e+00-5.400000000000e+01 3.500000000000e-09 1.600000000000e+00",
            "    -2.600000000000e-06 1.700000000000e-04 5.100000000000e-06 5.440600000000e+03",
            "     0.000000000000e+00 2.900000000000e-08-6.100000000000e-01 5.500000000000e-09",
            "     9.500000000000e-01 2.200000000000e+02-1.600000000000e+00-5.800000000000e-09",
        ];
        let mut text = format!(
            "{:>9}{:11}{:<20}{:<20}RINEX VERSION / TYPE\n{:60}END OF HEADER\n> EPH E05 {label}\n",
            "4.00", "", "NAVIGATION DATA", "M", ""
        );
        for line in record {
            text.push_str(line);
            text.push('\n');
        }
        text.push_str(&format!(
            "    -2.800000000000e-10{sources:19.12e} 2.253000000000e+03\n"
        ));
        text.push_str(
            "     3.120000000000e+00 0.000000000000e+00 3.200000000000e-09 3.700000000000e-09\n",
        );
        text.push_str("     6.640000000000e+02\n");
        text
    }

    #[test]
    fn rinex4_galileo_inav_and_fnav_records() {
        let inav = parse(&galileo_v4("INAV", 517.0)).unwrap();
        assert_eq!(inav.len(), 1);
        let e = &inav[0];
        assert_eq!(e.sat, SatId::galileo(5));
        assert_eq!(e.message, NavMessage::GalileoInav);
        // I/NAV: the E1/E5b clock's BGD(E1,E5b), and BGD(E1,E5a) beside it.
        assert_eq!((e.clock.tgd_s, e.clock.tgd2_s), (3.7e-9, 3.2e-9));
        // toc in GST; toe from week 2253 (continuous GPS week) + 0 s.
        assert_eq!(
            e.toc,
            Epoch::from_gregorian(2023, 3, 12, 0, 0, 0, 0, TimeScale::GST)
        );
        assert_eq!(e.toe, Epoch::from_time_of_week(2253, 0, TimeScale::GPST));
        assert_eq!(e.fit_interval_s, 4.0 * 3600.0);
        let fnav = parse(&galileo_v4("FNAV", 258.0)).unwrap();
        assert_eq!(fnav[0].message, NavMessage::GalileoFnav);
        assert_eq!((fnav[0].clock.tgd_s, fnav[0].clock.tgd2_s), (3.2e-9, 0.0));
        // The label and the data sources must agree.
        let err = parse(&galileo_v4("FNAV", 517.0)).unwrap_err().to_string();
        assert!(err.contains("say INAV but the > line says FNAV"), "{err}");
    }

    #[test]
    fn rinex2_gps_records() {
        let ephs = parse(&format!("{V2_HEADER}{V2_BODY}")).unwrap();
        assert_eq!(ephs.len(), 2);
        let g1 = &ephs[0];
        assert_eq!(g1.sat, SatId::gps(1));
        assert_eq!(g1.class, OrbitClass::Standard);
        assert_eq!(g1.toc, gpst(2022, 1, 1, 0));
        // toe = week 2190, 518400 s = Saturday 2022-01-01 00:00 GPST.
        assert_eq!(g1.toe, gpst(2022, 1, 1, 0));
        assert_eq!(g1.orbit.sqrt_a, 0.515367499542e4);
        assert_eq!(g1.orbit.e, 0.112181392033e-1);
        assert_eq!(g1.harmonics.crs, -0.141125e3);
        assert_eq!(g1.clock.af0, 0.469126738608e-3);
        assert_eq!(g1.clock.tgd_s, 0.512227416039e-8);
        assert_eq!((g1.iode, g1.iodc, g1.health), (39, 39, 0));
        assert_eq!(g1.fit_interval_s, 4.0 * 3600.0);
        // The second record: health 63, fit-interval field 0 -> 4 h.
        assert_eq!(ephs[1].health, 63);
        assert_eq!(ephs[1].fit_interval_s, 4.0 * 3600.0);
    }

    #[test]
    fn rinex3_mixed_skips_glonass_and_reads_beidou_geo() {
        let ephs = parse(&format!("{V3_HEADER}{V3_BODY}")).unwrap();
        assert_eq!(ephs.len(), 1);
        let c5 = &ephs[0];
        assert_eq!(c5.sat, SatId::beidou(5));
        assert_eq!(c5.class, OrbitClass::BeidouGeo);
        let bdt = |h| Epoch::from_gregorian(2020, 6, 24, h, 0, 0, 0, TimeScale::BDT);
        assert_eq!(c5.toc, bdt(22));
        // BDT week 755, sow 338400 = Wednesday 22:00 BDT.
        assert_eq!(c5.toe, bdt(22));
        assert_eq!(c5.clock.tgd_s, 1.0e-10);
        assert_eq!(c5.fit_interval_s, BDS_FIT_S);
        assert_eq!(c5.iode, 1);
    }

    #[test]
    fn rinex4_keeps_lnav_and_d2_only() {
        let ephs = parse(&format!("{V4_HEADER}{V4_BODY}")).unwrap();
        let sats: Vec<String> = ephs.iter().map(|e| e.sat.to_string()).collect();
        assert_eq!(sats, ["G01", "C01"]);
        assert_eq!(ephs[0].toe, gpst(2023, 3, 12, 0));
        assert_eq!(ephs[1].class, OrbitClass::BeidouGeo);
        assert_eq!(ephs[1].clock.tgd_s, -5.4e-9);
    }

    /// Longitude, latitude (deg) and radius (m) of an ECEF position.
    fn lon_lat_r(r: crate::Vec3) -> (f64, f64, f64) {
        let lon = r.y.atan2(r.x).to_degrees();
        (lon, (r.z / r.norm()).asin().to_degrees(), r.norm())
    }

    /// External oracle: the BDS-2 GEO on C05 is stationed at 58.75 deg E (BDS-2 GEO slots
    /// 58.75/80/110.5/140/160 deg E). Its D2 record (ESBC00DNK, 2020-06-24) evaluated
    /// with the GEO algorithm must stay there over a day, near the equator and at
    /// geostationary radius. A sign error in either GEO rotation would make it wander by
    /// +-10 deg in latitude or drift by 720 deg/day in longitude.
    #[test]
    fn beidou_geo_record_stays_at_its_slot() {
        let ephs = parse(&format!("{V3_HEADER}{V3_BODY}")).unwrap();
        let origin = crate::time::TimeOrigin::new(ephs[0].toe);
        let b = ephs[0].bind(&origin);
        for h in -12..=12 {
            let (lon, lat, r) = lon_lat_r(b.position_ecef(f64::from(h) * 3600.0));
            assert!((lon - 58.75).abs() < 0.5, "h={h} lon={lon}");
            assert!(lat.abs() < 3.0, "h={h} lat={lat}");
            assert!((r - 42_164e3).abs() < 50e3, "radius {r}");
        }
    }

    /// The 2023 C01 D2 record: stationary over a day (longitude spread < 0.2 deg) on the
    /// equator; its slot is 144.5 deg E since the 2019 replacement satellite (checked
    /// loosely: the real-data tier covers the slots with more records).
    #[test]
    fn beidou_geo_c01_is_stationary() {
        let ephs = parse(&format!("{V4_HEADER}{V4_BODY}")).unwrap();
        let origin = crate::time::TimeOrigin::new(ephs[1].toe);
        let b = ephs[1].bind(&origin);
        let lons: Vec<f64> = (-12..=12)
            .map(|h| lon_lat_r(b.position_ecef(f64::from(h) * 3600.0)))
            .inspect(|&(_, lat, _)| assert!(lat.abs() < 3.0, "lat={lat}"))
            .map(|(lon, _, _)| lon)
            .collect();
        let (lo, hi) = lons
            .iter()
            .fold((f64::MAX, f64::MIN), |(a, b), &x| (a.min(x), b.max(x)));
        assert!(hi - lo < 0.2, "spread {lo}..{hi}");
        assert!((lo - 144.5).abs() < 0.5, "{lo}");
    }

    #[test]
    fn malformed_records_report_file_and_line() {
        let bad = V2_BODY.replacen("0.515367499542D+04", "0.5153674995x2D+04", 1);
        match parse(&format!("{V2_HEADER}{bad}")) {
            Err(NavError::Format { path, line, .. }) => {
                assert_eq!(path, "test.rnx");
                assert_eq!(line, 5);
            }
            other => panic!("{other:?}"),
        }
        // A record cut after three lines: the error names the line it ends on.
        let cut: String = V2_BODY.lines().take(3).map(|l| format!("{l}\n")).collect();
        assert!(matches!(
            parse(&format!("{V2_HEADER}{cut}")),
            Err(NavError::Format { line: 5, .. })
        ));
        assert!(parse("").is_err());
        assert!(parse(V2_HEADER.lines().next().unwrap()).is_err());
    }

    /// `text` cut at every byte of its last record (from just after the record's first
    /// non-blank byte to the end) parses either to exactly the ephemerides of the whole text or to a
    /// format error on a line of that record, never to other values.
    fn assert_cuts_are_refused(text: &str, record_start: usize) {
        let whole = parse(text).unwrap();
        let first_line = text[..record_start].lines().count() + 1;
        let last_line = text.lines().count();
        let mut refused = 0;
        // From the record's first non-blank byte on (a blank line is no record yet).
        let first = record_start + text[record_start..].find(|c: char| c != ' ').unwrap();
        for cut in first + 1..text.len() {
            match parse(&text[..cut]) {
                Ok(ephs) => assert_eq!(ephs, whole, "cut at byte {cut} read other values"),
                Err(NavError::Format { line, message, .. }) => {
                    assert!(
                        (first_line..=last_line).contains(&line),
                        "cut at byte {cut}: line {line} outside {first_line}..={last_line}: {message}"
                    );
                    refused += 1;
                }
                Err(e) => panic!("cut at byte {cut}: {e}"),
            }
        }
        assert!(refused > 0);
    }

    /// Issue #11: a file cut inside a record read the missing fields as 0 (a record
    /// without its last line, or a line shortened inside a number, was accepted).
    #[test]
    fn a_record_cut_anywhere_is_an_error_never_zeros() {
        let v2 = format!("{V2_HEADER}{V2_BODY}");
        let second = v2.find("\n 2 22").unwrap() + 1;
        assert_cuts_are_refused(&v2, second);
        let v3 = format!("{V3_HEADER}{V3_BODY}");
        assert_cuts_are_refused(&v3, v3.find("C05 2020").unwrap());
        let v4 = format!("{V4_HEADER}{V4_BODY}");
        let v4 = &v4[..v4.find("> EPH C19").unwrap()];
        assert_cuts_are_refused(v4, v4.find("> EPH C01").unwrap());
        // The messages name the field or the cut.
        let without_last_line = v2.trim_end().rsplit_once('\n').unwrap().0;
        let err = parse(without_last_line).unwrap_err().to_string();
        assert!(
            err.starts_with("test.rnx:17: record cut short: it has 7 lines (from line 11)"),
            "{err}"
        );
        let err = parse(&v2[..v2.len() - 30]).unwrap_err().to_string();
        assert!(err.contains("inside the number"), "{err}");
        let v3_cut = v3.trim_end().trim_end_matches("0.000000000000e+00");
        let err = parse(v3_cut).unwrap_err().to_string();
        assert!(
            err.starts_with(
                "test.rnx:15: record cut short: broadcast orbit line 7 has no field 2 (AODC)"
            ),
            "{err}"
        );
    }

    #[test]
    fn short_last_line_and_missing_fields_read_as_zero() {
        // The first V2 record's last line has two fields only.
        let ephs = parse(&format!("{V2_HEADER}{V2_BODY}")).unwrap();
        assert_eq!(ephs[0].fit_interval_s, 4.0 * 3600.0);
    }

    #[test]
    fn gzip_is_detected_by_magic_bytes() {
        use std::io::Write;
        let dir = std::env::temp_dir().join(format!("skyforge-nav-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let text = format!("{V3_HEADER}{V3_BODY}");
        let plain = dir.join("a.rnx");
        std::fs::write(&plain, &text).unwrap();
        let gz = dir.join("a.rnx.bin");
        let mut enc = flate2::write::GzEncoder::new(Vec::new(), flate2::Compression::fast());
        enc.write_all(text.as_bytes()).unwrap();
        std::fs::write(&gz, enc.finish().unwrap()).unwrap();
        let a = read_nav_file(&plain).unwrap();
        let b = read_nav_file(&gz).unwrap();
        assert_eq!(a, b);
        assert_eq!(a.len(), 1);
        assert!(matches!(
            read_nav_file(&dir.join("missing.rnx")),
            Err(NavError::Io { .. })
        ));
        std::fs::remove_dir_all(&dir).unwrap();
    }

    fn body_line() -> impl Strategy<Value = String> {
        prop_oneof![
            ".{0,90}",
            "[ 0-9.DE+-]{0,82}",
            Just("> EPH G05 LNAV".to_string()),
            Just("> EPH C19 D1".to_string()),
            Just("G05 2023 03 12 00 00 00 1.0e-04 0.0 0.0".to_string()),
            Just("C01 2023 03 12 00 00 00".to_string()),
            Just(" 5 22  1  1  0  0  0.0 0.1D-03".to_string()),
            Just("     0.100000000000e+01 0.5153e+04".to_string()),
        ]
    }

    proptest! {
        #[test]
        fn parser_never_panics(
            header in prop_oneof![Just(V2_HEADER), Just(V3_HEADER), Just(V4_HEADER)],
            lines in proptest::collection::vec(body_line(), 0..40),
        ) {
            let _ = parse(&format!("{header}{}", lines.join("\n")));
        }

        #[test]
        fn corrupting_one_valid_line_never_panics(
            which in 0usize..33,
            col in 0usize..80,
            ch in any::<char>(),
        ) {
            let text = format!("{V4_HEADER}{V4_BODY}");
            let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
            let i = 2 + which % (lines.len() - 2);
            let mut chars: Vec<char> = lines[i].chars().collect();
            if col < chars.len() { chars[col] = ch; } else { chars.push(ch); }
            lines[i] = chars.into_iter().collect();
            let _ = parse(&lines.join("\n"));
        }
    }
}
