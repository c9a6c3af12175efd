//! RINEX 3.04 observation files: pseudorange, carrier phase, Doppler and C/N0 per satellite,
//! one file per antenna. One writer serves both the signal truth of `skyforge synth` (whole
//! seconds) and the bundled receiver's observations (receiver time tags with a fractional
//! second, loss-of-lock indicators). RINEX 3.04 section 5, tables A2 (header) and A3 (data
//! records); observation codes of [`super::rinex_codes`] (GPS L1 C/A 1C, BeiDou B1I 2I,
//! tables 4 and 9), every signal of a system on one line per satellite.

use super::record::{LLI_LOSS_OF_LOCK, ObsRecord};
use super::rinex_codes::written_code;
use crate::signal::Signal;
use hifitime::{Duration, Epoch, TimeScale};
use skyforge_orbits::Vec3;
use skyforge_orbits::ephemeris::System;
use std::io::{self, Write};

/// Calendar fields (GPS time) of an epoch.
pub type Calendar = (i32, u8, u8, u8, u8, f64);

/// `REC # / TYPE / VERS` receiver type of the synthesiser's truth files.
pub const TRUTH_RECEIVER_TYPE: &str = "SKYFORGE TRUTH";
/// `REC # / TYPE / VERS` receiver type of the bundled receiver's files.
pub const RECEIVER_TYPE: &str = "SKYFORGE RECEIVER";

/// What the header of an observation file says.
#[derive(Debug, Clone, PartialEq)]
pub struct ObsHeader<'a> {
    /// `MARKER NAME` (the antenna's name).
    pub marker: &'a str,
    /// `REC # / TYPE / VERS` receiver type, e.g. [`RECEIVER_TYPE`].
    pub receiver_type: &'a str,
    /// `ANT # / TYPE` antenna type.
    pub antenna_type: &'a str,
    /// `APPROX POSITION XYZ` (m, ECEF); the record is left out when unknown (RINEX 3.04
    /// table A2: optional for moving platforms).
    pub approx_ecef_m: Option<Vec3>,
    /// `TIME OF FIRST OBS` (GPS time).
    pub first: Calendar,
    /// `INTERVAL` (s); left out unless positive.
    pub interval_s: f64,
    /// The signals whose observation types the header declares (C, L, D, S each), in
    /// the order of their columns within each system.
    pub signals: &'a [Signal],
}

/// Streams epochs of observations into a RINEX 3.04 observation file.
#[derive(Debug)]
pub struct ObsWriter<W: Write> {
    out: W,
    /// Each declared system (GPS first) and the signals of its columns.
    columns: Vec<(System, Vec<Signal>)>,
}

/// The header's systems (GPS, Galileo, BeiDou, RINEX's order of system letters G, E, C)
/// with their signals, in the order given.
fn columns(signals: &[Signal]) -> Vec<(System, Vec<Signal>)> {
    [System::Gps, System::Galileo, System::Beidou]
        .into_iter()
        .map(|system| {
            let mut of_system: Vec<Signal> = Vec::new();
            for s in signals.iter().filter(|s| s.system() == system) {
                if !of_system.contains(s) {
                    of_system.push(*s);
                }
            }
            (system, of_system)
        })
        .filter(|(_, s)| !s.is_empty())
        .collect()
}

/// The four observation types (C, L, D, S) of each of `signals`.
fn observation_types(signals: &[Signal]) -> Vec<String> {
    signals
        .iter()
        .flat_map(|s| ["C", "L", "D", "S"].map(|t| format!("{t}{}", written_code(*s))))
        .collect()
}

/// The calendar epoch of `at` in GPS time.
pub fn calendar_gpst(at: Epoch) -> Calendar {
    let (y, mo, d, h, mi, s, ns) = at.to_gregorian(TimeScale::GPST);
    (y, mo, d, h, mi, f64::from(s) + f64::from(ns) * 1e-9)
}

/// The RINEX signal strength indicator of a C/N0 (dB-Hz): `min(max(int(cn0 / 6), 1), 9)`,
/// RINEX 3.04 section 5.7 and table 12 (< 12 dB-Hz -> 1, 12-17 -> 2, ..., >= 54 -> 9).
/// `None` (blank: not known) for a value that is not finite.
pub fn signal_strength_indicator(cn0_dbhz: f64) -> Option<u8> {
    cn0_dbhz
        .is_finite()
        .then(|| (cn0_dbhz / 6.0).trunc().clamp(1.0, 9.0) as u8)
}

/// An epoch rounded to the 100 ns resolution of the RINEX epoch fields (F11.7 seconds),
/// the rounding carried through minutes, hours, days, months and years.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct Stamp {
    year: i32,
    month: u8,
    day: u8,
    hour: u8,
    minute: u8,
    second: u8,
    /// Fraction of the second in units of 100 ns (0..10^7).
    ticks: u32,
}

impl Stamp {
    pub(crate) fn new(at: Calendar) -> io::Result<Self> {
        let (y, mo, d, h, mi, s) = at;
        let invalid = |what: String| {
            io::Error::new(io::ErrorKind::InvalidInput, format!("epoch {at:?}: {what}"))
        };
        if !(0.0..61.0).contains(&s) {
            return Err(invalid("seconds outside [0, 61)".into()));
        }
        let start_of_minute = Epoch::maybe_from_gregorian(y, mo, d, h, mi, 0, 0, TimeScale::GPST)
            .map_err(|e| invalid(e.to_string()))?;
        let ticks = (s * 1e7).round() as i64;
        let rounded = start_of_minute + Duration::from_total_nanoseconds(i128::from(ticks) * 100);
        let (year, month, day, hour, minute, second, ns) = rounded.to_gregorian(TimeScale::GPST);
        Ok(Self {
            year,
            month,
            day,
            hour,
            minute,
            second,
            ticks: ns / 100,
        })
    }

    /// The epoch the fields name (GPS time).
    pub(crate) fn epoch(&self) -> Epoch {
        Epoch::from_gregorian(
            self.year,
            self.month,
            self.day,
            self.hour,
            self.minute,
            self.second,
            self.ticks * 100,
            TimeScale::GPST,
        )
    }

    /// `yyyymmdd hhmmss` of the header's `PGM / RUN BY / DATE`.
    fn compact(&self) -> String {
        format!(
            "{:04}{:02}{:02} {:02}{:02}{:02}",
            self.year, self.month, self.day, self.hour, self.minute, self.second
        )
    }
}

/// The F14.3 text of `value` (RINEX 3.04 table A3), or `None` when it is not finite or
/// does not fit (the field is then blank).
pub(crate) fn f14_3(value: f64) -> Option<String> {
    let text = format!("{value:14.3}");
    (value.is_finite() && text.len() <= 14).then_some(text)
}

/// One observation field: F14.3, loss-of-lock indicator I1, signal strength indicator I1
/// (RINEX 3.04 table A3); a value that does not fit F14.3 or is not finite is blank.
fn field(value: Option<f64>, lli: Option<u8>, ssi: Option<u8>) -> String {
    let digit = |d: Option<u8>| d.map_or(' ', |d| char::from(b'0' + d.min(9)));
    match value.and_then(f14_3) {
        Some(text) => format!("{text}{}{}", digit(lli), digit(ssi)),
        None => " ".repeat(16),
    }
}

/// The phase as written: a phase that overflows F14.3 is brought back into range by whole
/// multiples of 10^9 cycles and flagged with loss-of-lock bit 0 (RINEX 3.04 table A3).
pub(crate) fn wrapped_phase(cycles: Option<f64>, lli: u8) -> (Option<f64>, u8) {
    match cycles {
        Some(c) if c.is_finite() && f14_3(c).is_none() => (Some(c % 1e9), lli | LLI_LOSS_OF_LOCK),
        c => (c, lli),
    }
}

/// The phase field ([`wrapped_phase`]); the loss-of-lock indicator is written when not 0.
fn phase_field(cycles: Option<f64>, lli: u8, ssi: Option<u8>) -> String {
    let (cycles, lli) = wrapped_phase(cycles, lli);
    field(cycles, (lli != 0).then_some(lli), ssi)
}

impl<W: Write> ObsWriter<W> {
    /// Write the header of the synthesiser's truth: marker `name` at `approx_ecef_m`, first
    /// epoch `first` (GPS time), `interval_s`, and which signals are present.
    pub fn new(
        out: W,
        name: &str,
        approx_ecef_m: &Vec3,
        first: Calendar,
        interval_s: f64,
        signals: &[Signal],
    ) -> io::Result<Self> {
        Self::with_header(
            out,
            &ObsHeader {
                marker: name,
                receiver_type: TRUTH_RECEIVER_TYPE,
                antenna_type: "SKYFORGE",
                approx_ecef_m: Some(*approx_ecef_m),
                first,
                interval_s,
                signals,
            },
        )
    }

    /// Write the header `h` (RINEX 3.04 table A2).
    pub fn with_header(mut out: W, h: &ObsHeader<'_>) -> io::Result<Self> {
        let first = Stamp::new(h.first)?;
        let columns = columns(h.signals);
        let letter = match columns.as_slice() {
            [(System::Gps, _)] => 'G',
            [(System::Beidou, _)] => 'C',
            _ => 'M',
        };
        writeln!(
            out,
            "{:>9}{:11}{:<20}{:<20}RINEX VERSION / TYPE",
            "3.04", "", "OBSERVATION DATA", letter
        )?;
        writeln!(
            out,
            "{:<20}{:<20}{:<20}PGM / RUN BY / DATE",
            "skyforge",
            "",
            format!("{} GPS", first.compact())
        )?;
        writeln!(out, "{:<60}MARKER NAME", h.marker)?;
        writeln!(out, "{:<60}MARKER TYPE", "NON_GEODETIC")?;
        writeln!(
            out,
            "{:<20}{:<40}OBSERVER / AGENCY",
            "skyforge", "simulation"
        )?;
        writeln!(
            out,
            "{:<20}{:<20}{:<20}REC # / TYPE / VERS",
            "0",
            h.receiver_type,
            env!("CARGO_PKG_VERSION")
        )?;
        writeln!(
            out,
            "{:<20}{:<20}{:<20}ANT # / TYPE",
            "0", h.antenna_type, ""
        )?;
        if let Some(r) = h.approx_ecef_m {
            writeln!(
                out,
                "{:14.4}{:14.4}{:14.4}{:18}APPROX POSITION XYZ",
                r.x, r.y, r.z, ""
            )?;
        }
        writeln!(
            out,
            "{:14.4}{:14.4}{:14.4}{:18}ANTENNA: DELTA H/E/N",
            0.0, 0.0, 0.0, ""
        )?;
        for (system, signals) in &columns {
            let types = observation_types(signals);
            // 13 types per line, continuation lines indented (RINEX 3.04 table A2).
            for (i, chunk) in types.chunks(13).enumerate() {
                let listed: String = chunk.iter().map(|t| format!(" {t}")).collect();
                let head = if i == 0 {
                    format!("{}  {:>3}", system.letter(), types.len())
                } else {
                    " ".repeat(6)
                };
                writeln!(out, "{head}{listed:<54}SYS / # / OBS TYPES")?;
            }
        }
        writeln!(out, "{:<60}SIGNAL STRENGTH UNIT", "DBHZ")?;
        if h.interval_s > 0.0 {
            writeln!(out, "{:10.3}{:50}INTERVAL", h.interval_s, "")?;
        }
        writeln!(
            out,
            "{:6}{:6}{:6}{:6}{:6}{:5}.{:07}     GPS{:9}TIME OF FIRST OBS",
            first.year,
            first.month,
            first.day,
            first.hour,
            first.minute,
            first.second,
            first.ticks,
            ""
        )?;
        // The phases are those of each signal's reference tracking (the codes written), so
        // no phase shift is applied (RINEX 3.04 section 9.1, table A23).
        for (system, signals) in &columns {
            for s in signals {
                writeln!(
                    out,
                    "{:<60}SYS / PHASE SHIFT",
                    format!("{} L{}", system.letter(), written_code(*s))
                )?;
            }
        }
        writeln!(out, "{:60}END OF HEADER", "")?;
        Ok(Self { out, columns })
    }

    /// Append one epoch (GPS time `at`, written rounded to 100 ns) of observations: epoch
    /// flag 0, then one record per satellite with C, L, D, S; the phase carries the
    /// loss-of-lock indicator and the signal strength indicator of the C/N0 (RINEX 3.04
    /// table A3, notes 1 and 2). A record of a signal the header does not declare is an
    /// error.
    pub fn epoch(&mut self, at: Calendar, records: &[ObsRecord]) -> io::Result<()> {
        let declared = |r: &ObsRecord| {
            self.columns
                .iter()
                .any(|(system, signals)| *system == r.sat.system && signals.contains(&r.signal))
        };
        if let Some(r) = records.iter().find(|r| !declared(r)) {
            return Err(io::Error::new(
                io::ErrorKind::InvalidInput,
                format!(
                    "{} {}: the signal has no observation types in the header",
                    r.sat, r.signal
                ),
            ));
        }
        // The satellites in the order they first appear.
        let mut sats = Vec::new();
        for r in records {
            if !sats.contains(&r.sat) {
                sats.push(r.sat);
            }
        }
        let t = Stamp::new(at)?;
        writeln!(
            self.out,
            "> {:04} {:02} {:02} {:02} {:02}{:3}.{:07}  0{:3}",
            t.year,
            t.month,
            t.day,
            t.hour,
            t.minute,
            t.second,
            t.ticks,
            sats.len()
        )?;
        for sat in sats {
            let signals = self
                .columns
                .iter()
                .find(|(system, _)| *system == sat.system)
                .map_or(&[][..], |(_, s)| s.as_slice());
            let mut line = sat.to_string();
            for signal in signals {
                match records.iter().find(|r| r.sat == sat && r.signal == *signal) {
                    Some(r) => {
                        let ssi = r.cn0_dbhz.and_then(signal_strength_indicator);
                        line += &field(r.pseudorange_m, None, None);
                        line += &phase_field(r.carrier_phase_cycles, r.phase_lli, ssi);
                        line += &field(r.doppler_hz, None, None);
                        line += &field(r.cn0_dbhz, None, None);
                    }
                    None => line += &field(None, None, None).repeat(4),
                }
            }
            writeln!(self.out, "{line}")?;
        }
        Ok(())
    }

    /// Flush and hand back the writer.
    pub fn finish(mut self) -> io::Result<W> {
        self.out.flush()?;
        Ok(self.out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::signal::Signal;
    use skyforge_orbits::ephemeris::SatId;

    fn gps(prn: u8) -> SatId {
        SatId {
            system: System::Gps,
            prn,
        }
    }

    fn record(sat: SatId, cn0_dbhz: f64, loss_of_lock: bool) -> ObsRecord {
        ObsRecord {
            phase_lli: u8::from(loss_of_lock),
            ..ObsRecord::complete(
                sat,
                Signal::of_system(sat.system),
                21_234_567.891,
                111_587_654.321,
                -1234.567,
                cn0_dbhz,
            )
        }
    }

    fn header(signals: &[Signal], first: Calendar) -> ObsHeader<'_> {
        ObsHeader {
            marker: "ant1",
            receiver_type: RECEIVER_TYPE,
            antenna_type: "PATCH",
            approx_ecef_m: None,
            first,
            interval_s: 0.1,
            signals,
        }
    }

    fn write(first: Calendar, epochs: &[(Calendar, Vec<ObsRecord>)]) -> String {
        let mut w = ObsWriter::with_header(Vec::new(), &header(&[Signal::GpsL1Ca], first)).unwrap();
        for (at, records) in epochs {
            w.epoch(*at, records).unwrap();
        }
        String::from_utf8(w.finish().unwrap()).unwrap()
    }

    #[test]
    fn signal_strength_follows_table_12() {
        // RINEX 3.04 table 12: < 12 -> 1, 12-17 -> 2, 18-23 -> 3, 24-29 -> 4, 30-35 -> 5,
        // 36-41 -> 6, 42-47 -> 7, 48-53 -> 8, >= 54 -> 9.
        let rows = [
            (-3.0, 1),
            (0.0, 1),
            (11.9, 1),
            (12.0, 2),
            (17.9, 2),
            (18.0, 3),
            (29.99, 4),
            (30.0, 5),
            (35.9, 5),
            (36.0, 6),
            (45.0, 7),
            (48.0, 8),
            (53.99, 8),
            (54.0, 9),
            (80.0, 9),
        ];
        for (cn0, ssi) in rows {
            assert_eq!(signal_strength_indicator(cn0), Some(ssi), "{cn0} dB-Hz");
        }
        assert_eq!(signal_strength_indicator(f64::NAN), None);
    }

    #[test]
    fn epoch_seconds_round_to_100_ns_and_carry_through_the_calendar() {
        let line = |at: Calendar| {
            write(at, &[(at, vec![])])
                .lines()
                .find(|l| l.starts_with('>'))
                .unwrap()
                .to_string()
        };
        let cases: [(Calendar, &str); 4] = [
            (
                (2022, 1, 1, 0, 0, 12.000_000_1),
                "> 2022 01 01 00 00 12.0000001  0  0",
            ),
            (
                (2022, 1, 1, 0, 0, 12.000_000_04),
                "> 2022 01 01 00 00 12.0000000  0  0",
            ),
            (
                (2022, 1, 1, 0, 0, 7.5),
                "> 2022 01 01 00 00  7.5000000  0  0",
            ),
            // 59.99999996 s rounds to the next minute, which here is the next year.
            (
                (2022, 12, 31, 23, 59, 59.999_999_96),
                "> 2023 01 01 00 00  0.0000000  0  0",
            ),
        ];
        for (at, expected) in cases {
            assert_eq!(line(at), expected, "{at:?}");
        }
        // Fixed columns of table A3: '>' A1, 1X I4, 4(1X I2.2), F11.7, 2X I1, I3.
        let l = line((2024, 2, 29, 13, 5, 1.234_567_8));
        assert_eq!(&l[2..6], "2024");
        assert_eq!(&l[18..29], "  1.2345678");
        assert_eq!(&l[31..32], "0");
    }

    #[test]
    fn epochs_next_to_calendar_boundaries_match_hifitime_rounding() {
        // Around the ends of a minute, an hour, a leap day, a month and a year, every 7 ns
        // from -70 ns to +70 ns: the epoch line must show hifitime's own rounding of the
        // epoch to 100 ns.
        let edges = [
            (2022, 3, 5, 10, 16),
            (2022, 3, 5, 11, 0),
            (2024, 2, 29, 0, 0),
            (2024, 3, 1, 0, 0),
            (2023, 1, 1, 0, 0),
        ];
        for (y, mo, d, h, mi) in edges {
            let edge = Epoch::from_gregorian(y, mo, d, h, mi, 0, 0, TimeScale::GPST);
            for ns in (-70..=70).step_by(7) {
                let at = edge + Duration::from_total_nanoseconds(ns);
                let rounded = at.round(Duration::from_total_nanoseconds(100));
                let (ry, rmo, rd, rh, rmi, rs, rns) = rounded.to_gregorian(TimeScale::GPST);
                let expected = format!(
                    "> {ry:04} {rmo:02} {rd:02} {rh:02} {rmi:02}{rs:3}.{:07}  0  0",
                    rns / 100
                );
                let mut w = ObsWriter::with_header(
                    Vec::new(),
                    &header(&[Signal::GpsL1Ca], calendar_gpst(at)),
                )
                .unwrap();
                w.epoch(calendar_gpst(at), &[]).unwrap();
                let text = String::from_utf8(w.finish().unwrap()).unwrap();
                let line = text.lines().find(|l| l.starts_with('>')).unwrap();
                assert_eq!(line, expected, "{at} ({ns} ns from {edge})");
            }
        }
    }

    #[test]
    fn the_header_carries_the_first_epoch_and_fixed_columns() {
        let text = write((2022, 1, 1, 0, 0, 59.999_999_99), &[]);
        let header: Vec<&str> = text.lines().collect();
        for l in &header {
            assert!(l.len() > 60 && l.len() <= 80, "{l:?}");
        }
        let label = |name: &str| {
            header
                .iter()
                .find(|l| l[60..].trim_end() == name)
                .unwrap_or_else(|| panic!("no {name}"))
                .to_string()
        };
        // TIME OF FIRST OBS: 5I6, F13.7, 5X, A3.
        let first = label("TIME OF FIRST OBS");
        assert_eq!(&first[..30], "  2022     1     1     0     1");
        assert_eq!(&first[30..43], "    0.0000000");
        assert_eq!(&first[48..51], "GPS");
        assert_eq!(&label("REC # / TYPE / VERS")[20..37], "SKYFORGE RECEIVER");
        assert_eq!(&label("ANT # / TYPE")[20..25], "PATCH");
        assert_eq!(
            &label("SYS / # / OBS TYPES")[..22],
            "G    4 C1C L1C D1C S1C"
        );
        assert_eq!(label("SYS / PHASE SHIFT")[..5].to_string(), "G L1C");
        assert_eq!(label("SIGNAL STRENGTH UNIT")[..4].to_string(), "DBHZ");
        assert!(!text.contains("APPROX POSITION XYZ"));
        assert_eq!(header.last().unwrap()[60..].trim_end(), "END OF HEADER");
    }

    #[test]
    fn loss_of_lock_and_strength_sit_after_the_phase() {
        let at = (2022, 1, 1, 0, 0, 1.0);
        let text = write(
            at,
            &[(
                at,
                vec![record(gps(7), 45.3, true), record(gps(12), 54.0, false)],
            )],
        );
        let body = text.split("END OF HEADER").nth(1).unwrap();
        let lines: Vec<&str> = body.lines().filter(|l| l.starts_with('G')).collect();
        // Table A3: A1,I2.2 then per observation F14.3, LLI I1, SSI I1.
        let obs = |l: &str, i: usize| l[3 + 16 * i..3 + 16 * (i + 1)].to_string();
        let g07 = lines[0];
        assert_eq!(&g07[..3], "G07");
        assert_eq!(obs(g07, 0), "  21234567.891  ");
        assert_eq!(
            obs(g07, 1),
            " 111587654.32117",
            "LLI 1, SSI 7 (42-47 dB-Hz)"
        );
        assert_eq!(obs(g07, 2), "     -1234.567  ");
        assert_eq!(obs(g07, 3), "        45.300  ");
        let g12 = lines[1];
        assert_eq!(
            obs(g12, 1),
            " 111587654.321 9",
            "no LLI, SSI 9 (>= 54 dB-Hz)"
        );
    }

    #[test]
    fn overflowing_phase_is_wrapped_and_flagged_and_missing_values_are_blank() {
        let mut r = record(gps(3), f64::NAN, false);
        r.carrier_phase_cycles = Some(12_345_678_901.25);
        r.doppler_hz = None;
        let at = (2022, 1, 1, 0, 0, 1.0);
        let text = write(at, &[(at, vec![r])]);
        let l = text.lines().find(|l| l.starts_with("G03")).unwrap();
        assert_eq!(&l[19..35], " 345678901.2501 ");
        assert_eq!(&l[35..], " ".repeat(32));
    }

    /// Several signals per system: one line per satellite with every signal's four values
    /// in the header's order, blanks where a satellite lacks one; the reader returns each
    /// record as written.
    #[test]
    fn several_signals_per_system_round_trip_through_the_reader() {
        let signals = [
            Signal::GpsL1Ca,
            Signal::GpsL2,
            Signal::GpsL5,
            Signal::BdsB1I,
            Signal::BdsB2I,
            Signal::BdsB3I,
        ];
        let c19 = SatId {
            system: System::Beidou,
            prn: 19,
        };
        let at = (2022, 1, 1, 0, 0, 12.0);
        let mut records = Vec::new();
        for (k, signal) in signals.into_iter().enumerate() {
            let sat = if signal.system() == System::Gps {
                gps(7)
            } else {
                c19
            };
            // G07 has no L2.
            if signal == Signal::GpsL2 {
                continue;
            }
            records.push(ObsRecord::complete(
                sat,
                signal,
                21_000_000.0 + k as f64,
                110_000_000.25 + k as f64,
                -1000.5 - k as f64,
                40.0 + k as f64,
            ));
        }
        let mut w = ObsWriter::with_header(Vec::new(), &header(&signals, at)).unwrap();
        w.epoch(at, &records).unwrap();
        let text = String::from_utf8(w.finish().unwrap()).unwrap();
        assert!(
            text.contains("G   12 C1C L1C D1C S1C C2W L2W D2W S2W C5I L5I D5I S5I"),
            "{text}"
        );
        assert!(text.contains("C   12 C2I L2I D2I S2I C7I L7I D7I S7I C6I L6I D6I S6I"));
        let g07 = text.lines().find(|l| l.starts_with("G07")).unwrap();
        assert_eq!(&g07[3 + 64..3 + 128], " ".repeat(64), "{g07}");
        let read = crate::observation::parse_obs_text(&text, "t.rnx").unwrap();
        let mut back = read.epochs[0].sats.clone();
        back.sort_by_key(|r| (r.sat, r.signal));
        records.sort_by_key(|r| (r.sat, r.signal));
        assert_eq!(back.len(), records.len());
        for (b, r) in back.iter().zip(&records) {
            assert_eq!((b.sat, b.signal), (r.sat, r.signal));
            assert_eq!(b.pseudorange_m, r.pseudorange_m);
            assert_eq!(b.carrier_phase_cycles, r.carrier_phase_cycles);
            assert_eq!(b.doppler_hz, r.doppler_hz);
            assert_eq!(b.cn0_dbhz, r.cn0_dbhz);
        }
    }

    #[test]
    fn undeclared_systems_are_refused() {
        let at = (2022, 1, 1, 0, 0, 1.0);
        let mut w = ObsWriter::with_header(Vec::new(), &header(&[Signal::GpsL1Ca], at)).unwrap();
        let c19 = SatId {
            system: System::Beidou,
            prn: 19,
        };
        assert!(w.epoch(at, &[record(c19, 40.0, false)]).is_err());
        assert!(
            ObsWriter::with_header(
                Vec::new(),
                &header(&[Signal::GpsL1Ca], (2022, 2, 30, 0, 0, 0.0))
            )
            .is_err()
        );
    }

    #[test]
    fn the_rinex_crate_reads_epochs_flags_and_strengths() {
        use rinex::prelude::{Constellation, Observable};
        let signals = [Signal::GpsL1Ca, Signal::BdsB1I];
        let c19 = SatId {
            system: System::Beidou,
            prn: 19,
        };
        let t0 = (2022, 1, 1, 0, 0, 12.000_000_1);
        let t1 = (2022, 1, 1, 0, 0, 12.100_000_1);
        let mut w = ObsWriter::with_header(Vec::new(), &header(&signals, t0)).unwrap();
        w.epoch(t0, &[record(gps(7), 45.0, true), record(c19, 30.0, false)])
            .unwrap();
        w.epoch(t1, &[record(gps(7), 45.0, false), record(c19, 11.0, true)])
            .unwrap();
        let bytes = w.finish().unwrap();
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("ant1.obs.rnx");
        std::fs::write(&path, bytes).unwrap();
        let rnx = rinex::Rinex::from_file(&path).unwrap();
        let start = Epoch::from_gregorian(2022, 1, 1, 0, 0, 12, 100, TimeScale::GPST);
        let mut seen = Vec::new();
        for (key, o) in rnx.signal_observations_iter() {
            let Observable::PhaseRange(code) = &o.observable else {
                continue;
            };
            let dt_s = (key.epoch.to_time_scale(TimeScale::GPST) - start).to_seconds();
            let letter = match o.sv.constellation {
                Constellation::GPS => 'G',
                Constellation::BeiDou => 'C',
                c => panic!("{c:?}"),
            };
            let lli = o.lli.map(|f| f.bits());
            let ssi = o.snr.map(|s| format!("{s:x}"));
            seen.push((
                format!("{dt_s:.7}"),
                format!("{letter}{:02} {code}", o.sv.prn),
                lli,
                ssi,
                o.value,
            ));
        }
        seen.sort_by(|a, b| a.partial_cmp(b).unwrap());
        let phase = 111_587_654.321;
        assert_eq!(
            seen,
            vec![
                (
                    "0.0000000".into(),
                    "C19 L2I".into(),
                    None,
                    Some("5".into()),
                    phase
                ),
                (
                    "0.0000000".into(),
                    "G07 L1C".into(),
                    Some(1),
                    Some("7".into()),
                    phase
                ),
                (
                    "0.1000000".into(),
                    "C19 L2I".into(),
                    Some(1),
                    Some("1".into()),
                    phase
                ),
                (
                    "0.1000000".into(),
                    "G07 L1C".into(),
                    None,
                    Some("7".into()),
                    phase
                ),
            ]
        );
    }
}
