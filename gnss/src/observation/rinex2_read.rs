//! RINEX 2.10/2.11 observation files into per-epoch GPS L1 C/A, L2 and L5 observations
//! ([`ObsRecord`]); [`super::read_obs_file`] hands a file here when its first line says
//! version 2.
//!
//! The format (RINEX 2.10, Gurtner 2002): a header of 80-column lines labelled in columns
//! 61-80, `# / TYPES OF OBSERV` listing the observation codes (nine a line, continued on
//! further lines); then epochs, each an epoch line (`yy mm dd hh mm ss.sssssss  f nnn` and
//! up to 12 satellites, continued on lines starting in column 33) followed by every
//! satellite's values, five `F14.3` values a line each with a loss-of-lock digit and a
//! signal-strength digit.
//!
//! GPS codes used: `L1`/`C1`/`D1`/`S1` for L1 C/A; `L2`/`P2`/`D2`/`S2` for L2 (`C2`, the
//! L2C code, when the file has no `P2`); `L5`/`C5`/`D5`/`S5` for L5. `P1` is the L1 P(Y) code, another signal, and is
//! left out. Loss-of-lock bit 0 is kept as [`LLI_LOSS_OF_LOCK`]; bit 1 (the wavelength
//! factor opposite to the header's for this epoch) as [`LLI_HALF_CYCLE`]; bit 2
//! (anti-spoofing on) is dropped. A band whose `WAVELENGTH FACT L1/2` is 2 (squaring
//! receivers: half-wavelength phase) has its phases left out. Satellites of other
//! systems (GLONASS, Galileo, SBAS) are skipped. Epochs flagged 2-5 (events, with their
//! header lines) and 6 (cycle-slip records) are skipped; a power failure (flag 1) marks
//! every phase of its epoch as lock lost.

use super::read_error::{EpochFields, Kind, ObsReadError, check_physical, marker_name};
use super::record::{LLI_HALF_CYCLE, LLI_LOSS_OF_LOCK, ObsEpoch, ObsFile, ObsRecord};
use crate::signal::Signal;
use hifitime::{Epoch, TimeScale};
use skyforge_orbits::Vec3;
use skyforge_orbits::ephemeris::{SatId, System};
use skyforge_orbits::rinex_header::{label, supported_major, version_and_type};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// Largest observation text read (bytes): a day of 1-Hz data from 30 satellites with
/// eight observation types is about 0.5 GB.
pub const MAX_OBS_BYTES: u64 = 1 << 30;

/// Most observation types a file may list (RINEX 2.11 has fewer than 30 codes).
const MAX_TYPES: usize = 64;

/// Where each listed observation type goes (`None`: not used).
fn classify_types(types: &[String], wavelength_factor: [u8; 2]) -> Vec<Option<(Signal, Kind)>> {
    let has_p2 = types.iter().any(|t| t == "P2");
    types
        .iter()
        .map(|t| {
            let (signal, kind) = match t.as_str() {
                "L1" => (Signal::GpsL1Ca, Kind::Phase),
                "C1" => (Signal::GpsL1Ca, Kind::Code),
                "D1" => (Signal::GpsL1Ca, Kind::Doppler),
                "S1" => (Signal::GpsL1Ca, Kind::Strength),
                "L2" => (Signal::GpsL2, Kind::Phase),
                "P2" => (Signal::GpsL2, Kind::Code),
                "C2" if !has_p2 => (Signal::GpsL2, Kind::Code),
                "D2" => (Signal::GpsL2, Kind::Doppler),
                "S2" => (Signal::GpsL2, Kind::Strength),
                "L5" => (Signal::GpsL5, Kind::Phase),
                "C5" => (Signal::GpsL5, Kind::Code),
                "D5" => (Signal::GpsL5, Kind::Doppler),
                "S5" => (Signal::GpsL5, Kind::Strength),
                _ => return None,
            };
            // The wavelength factors are L1's and L2's (RINEX 2.11 table A1); L5 is whole.
            let factor = match signal {
                Signal::GpsL1Ca => wavelength_factor[0],
                Signal::GpsL2 => wavelength_factor[1],
                _ => 1,
            };
            if kind == Kind::Phase && factor != 1 {
                return None;
            }
            Some((signal, kind))
        })
        .collect()
}

/// A parse error at line `line` (1-based) of `source`.
fn at(source: &Path, line: usize, message: impl Into<String>) -> ObsReadError {
    ObsReadError::Syntax {
        path: source.to_path_buf(),
        line,
        message: message.into(),
    }
}

/// Columns `from..to` (0-based, end exclusive) of `line`, blank where the line is shorter.
fn field(line: &str, from: usize, to: usize) -> &str {
    let end = to.min(line.len());
    if from >= end {
        return "";
    }
    line.get(from..end).unwrap_or("")
}

/// Whether `text` (the start of an observation file) is RINEX 2 observation data.
pub fn is_rinex2_obs(text: &str) -> bool {
    let first = text.lines().next().unwrap_or("");
    version_and_type(first).is_ok_and(|(v, kind)| supported_major(v) == Ok(2) && kind == "O")
        && label(first) == "RINEX VERSION / TYPE"
}

/// What the header says.
struct Header {
    types: Vec<String>,
    wavelength_factor: [u8; 2],
    approx_ecef_m: Option<Vec3>,
    marker: Option<String>,
}

/// Parse the header from `lines`, leaving them after `END OF HEADER`.
fn parse_header<'a>(
    lines: &mut impl Iterator<Item = (usize, &'a str)>,
    source: &Path,
) -> Result<Header, ObsReadError> {
    let mut types: Vec<String> = Vec::new();
    let mut expected_types: Option<usize> = None;
    let mut wavelength_factor = [1u8; 2];
    let mut approx_ecef_m = None;
    let mut marker = None;
    let mut first = true;
    for (n, line) in lines.by_ref() {
        let lab = label(line);
        if first {
            first = false;
            if lab != "RINEX VERSION / TYPE" || field(line, 20, 21) != "O" {
                return Err(at(source, n, "not a RINEX observation header"));
            }
            let system = field(line, 40, 41);
            if !matches!(system, "G" | "M" | " " | "") {
                return Err(at(
                    source,
                    n,
                    format!("satellite system {system:?}: no GPS observations"),
                ));
            }
            continue;
        }
        match lab {
            "# / TYPES OF OBSERV" => {
                if expected_types.is_none() {
                    let count: usize = field(line, 0, 6)
                        .trim()
                        .parse()
                        .map_err(|_| at(source, n, "number of observation types (I6)"))?;
                    if count == 0 || count > MAX_TYPES {
                        return Err(at(
                            source,
                            n,
                            format!("{count} observation types: 1 to {MAX_TYPES} are read"),
                        ));
                    }
                    expected_types = Some(count);
                }
                for k in 0..9 {
                    let code = field(line, 6 + 6 * k + 4, 6 + 6 * k + 6).trim();
                    if !code.is_empty() {
                        types.push(code.to_string());
                    }
                }
            }
            "WAVELENGTH FACT L1/2" => {
                for (band, (from, to)) in [(0, 6), (6, 12)].into_iter().enumerate() {
                    match field(line, from, to).trim() {
                        "" | "0" | "1" => {}
                        "2" => wavelength_factor[band] = 2,
                        other => {
                            return Err(at(
                                source,
                                n,
                                format!("wavelength factor {other:?}: 1 or 2"),
                            ));
                        }
                    }
                }
            }
            "APPROX POSITION XYZ" => {
                // Three F14.4; a header that cannot be read leaves the position unknown.
                let v: Vec<f64> = (0..3)
                    .filter_map(|k| field(line, 14 * k, 14 * k + 14).trim().parse().ok())
                    .collect();
                approx_ecef_m = (v.len() == 3 && v.iter().all(|x| x.is_finite()))
                    .then(|| Vec3::new(v[0], v[1], v[2]));
            }
            "MARKER NAME" => marker = marker_name(line),
            "TIME OF FIRST OBS" => {
                let system = field(line, 48, 51).trim();
                if !matches!(system, "" | "GPS") {
                    return Err(at(
                        source,
                        n,
                        format!("time system {system:?}: only GPS time is read"),
                    ));
                }
            }
            "END OF HEADER" => {
                let Some(count) = expected_types else {
                    return Err(at(source, n, "no # / TYPES OF OBSERV in the header"));
                };
                if types.len() != count {
                    return Err(at(
                        source,
                        n,
                        format!(
                            "{count} observation types announced, {} listed",
                            types.len()
                        ),
                    ));
                }
                return Ok(Header {
                    types,
                    wavelength_factor,
                    approx_ecef_m,
                    marker,
                });
            }
            _ => {}
        }
    }
    Err(at(source, 0, "no END OF HEADER"))
}

/// The epoch line's time (`yy mm dd hh mm ss.sssssss`, columns 2-26), in GPS time.
fn epoch_time(line: &str, n: usize, source: &Path) -> Result<Epoch, ObsReadError> {
    let int = |from: usize, to: usize, what: &str| -> Result<u8, ObsReadError> {
        field(line, from, to).trim().parse().map_err(|_| {
            at(
                source,
                n,
                format!("epoch {what} (columns {}-{to})", from + 1),
            )
        })
    };
    let yy = int(0, 3, "year")?;
    let year = if yy >= 80 {
        1900 + i32::from(yy)
    } else {
        2000 + i32::from(yy)
    };
    let fields = EpochFields {
        year,
        month: int(3, 6, "month")?,
        day: int(6, 9, "day")?,
        hour: int(9, 12, "hour")?,
        minute: int(12, 15, "minute")?,
        seconds: field(line, 15, 26)
            .trim()
            .parse()
            .map_err(|_| at(source, n, "epoch seconds (columns 16-26)"))?,
    };
    fields
        .check()
        .and_then(|()| fields.epoch(TimeScale::GPST))
        .map_err(|m| at(source, n, m))
}

/// Parse RINEX 2 observation `text`; `source` names it in errors.
pub fn parse_rinex2_obs(text: &str, source: &Path) -> Result<ObsFile, ObsReadError> {
    let mut lines = text.lines().enumerate().map(|(i, l)| (i + 1, l));
    let header = parse_header(&mut lines, source)?;
    let targets = classify_types(&header.types, header.wavelength_factor);
    let lines_per_sat = header.types.len().div_ceil(5);
    let mut epochs: Vec<ObsEpoch> = Vec::new();
    while let Some((n, line)) = lines.next() {
        if line.trim().is_empty() {
            continue;
        }
        let flag = field(line, 28, 29).trim();
        let count: usize = field(line, 29, 32)
            .trim()
            .parse()
            .map_err(|_| at(source, n, "number of satellites or records (columns 30-32)"))?;
        match flag {
            "" | "0" | "1" | "6" => {}
            "2" | "3" | "4" | "5" => {
                // Event: `count` header lines follow.
                for _ in 0..count {
                    lines
                        .next()
                        .ok_or_else(|| at(source, n, "event records missing at end of file"))?;
                }
                continue;
            }
            other => return Err(at(source, n, format!("epoch flag {other:?}: 0 to 6"))),
        }
        let time = epoch_time(line, n, source)?;
        // Satellite list: 12 per line, continued from column 33 of the next lines.
        let mut sat_names: Vec<String> = Vec::with_capacity(count);
        let mut list_line = line;
        let mut list_n = n;
        while sat_names.len() < count {
            let k = sat_names.len() % 12;
            if k == 0 && !sat_names.is_empty() {
                let (m, next) = lines
                    .next()
                    .ok_or_else(|| at(source, list_n, "satellite list continues past the end"))?;
                list_line = next;
                list_n = m;
            }
            let name = field(list_line, 32 + 3 * k, 35 + 3 * k);
            if name.trim().is_empty() {
                return Err(at(
                    source,
                    list_n,
                    format!("{count} satellites announced, fewer listed"),
                ));
            }
            sat_names.push(name.to_string());
        }
        let mut sats: BTreeMap<(SatId, Signal), ObsRecord> = BTreeMap::new();
        for name in &sat_names {
            let sat = parse_sat(name).map_err(|m| at(source, list_n, m))?;
            let mut values: Vec<(Option<f64>, u8)> = Vec::with_capacity(header.types.len());
            let mut m_first = None;
            for _ in 0..lines_per_sat {
                let (m, data) = lines.next().ok_or_else(|| {
                    at(
                        source,
                        n,
                        format!("{name}: observation lines missing at end of file"),
                    )
                })?;
                m_first.get_or_insert(m);
                for k in 0..5 {
                    if values.len() == header.types.len() {
                        break;
                    }
                    let text = field(data, 16 * k, 16 * k + 14).trim();
                    let value = if text.is_empty() {
                        None
                    } else {
                        let v: f64 = text.parse().map_err(|_| {
                            at(source, m, format!("{name}: value {text:?} is not a number"))
                        })?;
                        Some(v)
                    };
                    let lli = field(data, 16 * k + 14, 16 * k + 15).trim();
                    let lli: u8 = if lli.is_empty() {
                        0
                    } else {
                        lli.parse().map_err(|_| {
                            at(source, m, format!("{name}: loss-of-lock digit {lli:?}"))
                        })?
                    };
                    values.push((value, lli));
                }
            }
            let Some(sat) = sat else {
                continue;
            };
            if flag == "6" {
                continue;
            }
            let first_line = m_first.unwrap_or(n);
            for ((value, lli), target) in values.iter().zip(&targets) {
                let (Some((signal, kind)), Some(v)) = (target, value) else {
                    continue;
                };
                let entry = sats
                    .entry((sat, *signal))
                    .or_insert_with(|| ObsRecord::empty(sat, *signal));
                match kind {
                    Kind::Code => entry.pseudorange_m = Some(*v),
                    Kind::Phase => {
                        entry.carrier_phase_cycles = Some(*v);
                        if lli & 0x01 != 0 {
                            entry.phase_lli |= LLI_LOSS_OF_LOCK;
                        }
                        if lli & 0x02 != 0 {
                            entry.phase_lli |= LLI_HALF_CYCLE;
                        }
                    }
                    Kind::Doppler => entry.doppler_hz = Some(*v),
                    Kind::Strength => entry.cn0_dbhz = Some(*v),
                }
            }
            for (_, rec) in sats.iter().filter(|(k, _)| k.0 == sat) {
                check_physical(rec).map_err(|m| at(source, first_line, m))?;
            }
        }
        if flag == "6" {
            continue;
        }
        if flag == "1" {
            for s in sats.values_mut() {
                s.phase_lli |= LLI_LOSS_OF_LOCK;
            }
        }
        epochs.push(ObsEpoch {
            time,
            sats: sats.into_values().collect(),
        });
    }
    epochs.sort_by_key(|e| e.time);
    Ok(ObsFile {
        source: PathBuf::from(source),
        approx_ecef_m: header.approx_ecef_m,
        codes: Default::default(),
        epochs,
        marker: header.marker,
        dropped: Vec::new(),
    })
}

/// A satellite of the epoch line (`G05`, ` 5`: blank system is GPS); `None` for systems
/// SkyForge does not read from RINEX 2 (GLONASS, Galileo, SBAS).
fn parse_sat(name: &str) -> Result<Option<SatId>, String> {
    // `name` is three columns of the line, which need not be ASCII.
    let Some((system, prn)) = name.split_at_checked(1) else {
        return Err(format!("satellite {name:?}: unknown system"));
    };
    let prn: u8 = prn
        .trim()
        .parse()
        .map_err(|_| format!("satellite {name:?}: PRN is not a number"))?;
    match system {
        "G" | " " => Ok(Some(SatId {
            system: System::Gps,
            prn,
        })),
        "R" | "E" | "S" | "C" | "J" | "T" => Ok(None),
        other => Err(format!("satellite {name:?}: unknown system {other:?}")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn header_line(content: &str, lab: &str) -> String {
        format!("{content:<60}{lab}\n")
    }

    fn header(types: &[&str]) -> String {
        let mut t = header_line(
            "     2.10           OBSERVATION DATA    G (GPS)",
            "RINEX VERSION / TYPE",
        );
        t += &header_line(
            " -3976219.5082  3382372.5671  3652512.9849",
            "APPROX POSITION XYZ",
        );
        t += &header_line("     1     1", "WAVELENGTH FACT L1/2");
        for (k, chunk) in types.chunks(9).enumerate() {
            let mut line = if k == 0 {
                format!("{:6}", types.len())
            } else {
                format!("{:6}", "")
            };
            for c in chunk {
                line += &format!("{c:>6}");
            }
            t += &header_line(&line, "# / TYPES OF OBSERV");
        }
        t += &header_line(
            "  2005     4     2     0     0    0.0000000     GPS",
            "TIME OF FIRST OBS",
        );
        t += &header_line("", "END OF HEADER");
        t
    }

    /// GEONET 0759's first epoch, first two satellites (2005-04-02).
    const EPOCH: &str = " 05  4  2  0  0  0.0000000  0  2G 3G 7
  55923622.160    24767686.375    43647388.2424   24767684.8224
   -691177.8981   24361933.475     -537007.1404   24361930.5994
";

    #[test]
    fn reads_the_geonet_layout() {
        let text = header(&["L1", "C1", "L2", "P2"]) + EPOCH;
        let f = parse_rinex2_obs(&text, Path::new("t.05o")).unwrap();
        assert_eq!(f.epochs.len(), 1);
        let e = &f.epochs[0];
        assert_eq!(
            e.time,
            Epoch::from_gregorian(2005, 4, 2, 0, 0, 0, 0, TimeScale::GPST)
        );
        assert_eq!(e.sats.len(), 4, "{:?}", e.sats);
        let g3l1 = e.sats[0];
        assert_eq!(g3l1.sat.to_string(), "G03");
        assert_eq!(g3l1.signal, Signal::GpsL1Ca);
        assert_eq!(g3l1.carrier_phase_cycles, Some(55923622.160));
        assert_eq!(g3l1.pseudorange_m, Some(24767686.375));
        assert_eq!(g3l1.phase_lli, 0);
        let g3l2 = e.sats[1];
        assert_eq!(g3l2.signal, Signal::GpsL2);
        assert_eq!(g3l2.carrier_phase_cycles, Some(43647388.242));
        assert_eq!(g3l2.pseudorange_m, Some(24767684.822));
        // LLI 4 (anti-spoofing) is not a loss of lock.
        assert_eq!(g3l2.phase_lli, 0);
        assert_eq!(e.sats[2].sat.to_string(), "G07");
        assert_eq!(e.sats[2].phase_lli, LLI_LOSS_OF_LOCK);
    }

    /// RINEX 2.11's `L5`/`C5` are GPS L5 (whole cycles, whatever L1/L2's wavelength
    /// factors).
    #[test]
    fn l5_codes_are_gps_l5() {
        let epoch = " 05  4  2  0  0  0.0000000  0  1G 3
  55923622.160    24767686.375    43647388.2424   24767684.8224
";
        let text = header(&["L1", "C1", "L5", "C5"]) + epoch;
        let f = parse_rinex2_obs(&text, Path::new("t.05o")).unwrap();
        let l5 = f.epochs[0]
            .sats
            .iter()
            .find(|r| r.signal == Signal::GpsL5)
            .unwrap();
        assert_eq!(l5.carrier_phase_cycles, Some(43647388.242));
        assert_eq!(l5.pseudorange_m, Some(24767684.822));
    }

    #[test]
    fn a_non_ascii_satellite_is_an_error() {
        // Found by fuzzing: the system letter was split off at byte 1.
        let text = header(&["L1", "C1"]) + " 05  4  2  0  0  0.0000000  0  1\u{e9}3\n";
        let e = parse_rinex2_obs(&text, Path::new("t.05o")).unwrap_err();
        assert!(e.to_string().contains("unknown system"), "{e}");
    }

    #[test]
    fn continuation_lines_of_satellites_and_types() {
        let types = ["L1", "L2", "C1", "P1", "P2", "D1", "D2", "S1", "S2", "C2"];
        let mut text = header(&types);
        let sats: Vec<String> = (1..=14).map(|p| format!("G{p:02}")).collect();
        text += &format!(" 05  4  2  0  0 30.0000000  0 14{}\n", sats[..12].concat());
        text += &format!("{:32}{}\n", "", sats[12..].concat());
        for p in 1..=14 {
            text += &format!(
                "{:14.3}  {:14.3}  {:14.3}  {:14.3}  {:14.3}  \n",
                1e8 + f64::from(p),
                8e7,
                2e7,
                2e7 + 1.0,
                2e7 + 2.0
            );
            text += &format!(
                "{:14.3}  {:14.3}  {:14.3}  {:14.3}  {:14.3}\n",
                1.0,
                2.0,
                45.0,
                40.0,
                2e7 + 3.0
            );
        }
        let f = parse_rinex2_obs(&text, Path::new("t")).unwrap();
        let e = &f.epochs[0];
        assert_eq!(e.sats.len(), 28);
        let l2 = e
            .sats
            .iter()
            .find(|r| r.sat.prn == 14 && r.signal == Signal::GpsL2)
            .unwrap();
        // P2 is preferred to C2 when both are listed.
        assert_eq!(l2.pseudorange_m, Some(2e7 + 2.0));
        assert_eq!(l2.doppler_hz, Some(2.0));
        assert_eq!(l2.cn0_dbhz, Some(40.0));
        let l1 = e
            .sats
            .iter()
            .find(|r| r.sat.prn == 14 && r.signal == Signal::GpsL1Ca)
            .unwrap();
        // C1, not P1.
        assert_eq!(l1.pseudorange_m, Some(2e7));
        assert_eq!(l1.carrier_phase_cycles, Some(1e8 + 14.0));
    }

    #[test]
    fn events_slips_power_failures_and_other_systems() {
        let mut text = header(&["L1", "C1"]);
        text += " 05  4  2  0  0  0.0000000  1  2G 3R 7\n";
        text += "  55923622.160    24767686.375\n";
        text += "  55923622.160    24767686.375\n";
        text += &format!("{:28}4  1\n", "");
        text += &header_line("a comment", "COMMENT");
        text += " 05  4  2  0  0 30.0000000  6  1G 3\n";
        text += "  55923622.160 1  24767686.375\n";
        let f = parse_rinex2_obs(&text, Path::new("t")).unwrap();
        assert_eq!(f.epochs.len(), 1);
        assert_eq!(f.epochs[0].sats.len(), 1);
        assert_eq!(f.epochs[0].sats[0].phase_lli, LLI_LOSS_OF_LOCK);
    }

    #[test]
    fn half_wavelength_bands_lose_their_phase() {
        let text = header(&["L1", "C1", "L2", "P2"])
            .replace("     1     1      ", "     1     2      ")
            + EPOCH;
        let f = parse_rinex2_obs(&text, Path::new("t")).unwrap();
        let l2 = f.epochs[0].sats[1];
        assert_eq!(l2.signal, Signal::GpsL2);
        assert_eq!(l2.carrier_phase_cycles, None);
        assert_eq!(l2.pseudorange_m, Some(24767684.822));
    }

    #[test]
    fn errors_name_the_line() {
        let good = header(&["L1", "C1", "L2", "P2"]) + EPOCH;
        let cases = [
            (
                good.replace("24767686.375", "2476x686.375"),
                8,
                "not a number",
            ),
            (
                good.replace("  0  2G 3G 7", "  0  3G 3G 7"),
                7,
                "fewer listed",
            ),
            (
                good.replace("  0  2G 3G 7", "  9  2G 3G 7"),
                7,
                "epoch flag",
            ),
            (
                good.replace(" 05  4  2", " 05 13  2"),
                7,
                "epoch month 13: allowed 1 to 12",
            ),
            (good.replace("     4    L1", "     5    L1"), 6, "announced"),
            (good.replace("     GPS  ", "     GLO  "), 5, "time system"),
            (
                good.lines().take(8).collect::<Vec<_>>().join("\n"),
                7,
                "missing",
            ),
        ];
        for (text, line, what) in cases {
            let e = parse_rinex2_obs(&text, Path::new("x.05o")).unwrap_err();
            let m = e.to_string();
            assert!(m.starts_with(&format!("x.05o:{line}:")), "{m}");
            assert!(m.contains(what), "{what}: {m}");
        }
    }

    proptest! {
        /// Any corruption of a valid file is read or refused, never a panic.
        #[test]
        fn corrupted_files_never_panic(pos in 0usize..2000, byte in 0u8..128, cut in 0usize..2000) {
            let good = header(&["L1", "C1", "L2", "P2"]) + EPOCH;
            let mut bytes = good.into_bytes();
            let pos = pos % bytes.len();
            bytes[pos] = byte;
            bytes.truncate(cut.max(1).min(bytes.len()));
            let text = String::from_utf8_lossy(&bytes);
            let _ = parse_rinex2_obs(&text, Path::new("fuzz"));
        }
    }
}
