//! RINEX observation files (version 3 here; version 2 in [`super::rinex2_read`]) into
//! per-epoch observations of every [`Signal`] ([`ObsRecord`]; the codes of
//! [`super::rinex_codes`]), through the `rinex` crate (which also reads Hatanaka-compressed and gzipped files).
//!
//! Checked on the two kinds of file this module exists for: SkyForge's truth (RINEX 3.04,
//! `C2I` for B1I, GPS time) and GNSS-SDR 0.0.17's output (RINEX 3.02, B1I as `C1I`,
//! BeiDou epochs in BDT, signal strength digit after every value). The crate keeps the
//! loss-of-lock indicator of every value and the epoch flag; it parses the epoch's seconds
//! to 100 ns, the resolution of the RINEX F11.7 field.

use super::read_error::{Kind, ObsReadError};
use super::record::{LLI_LOSS_OF_LOCK, ObsEpoch, ObsFile, ObsRecord};
use super::rinex_codes;
use super::rinex2_read::{MAX_OBS_BYTES, is_rinex2_obs, parse_rinex2_obs};
use crate::signal::Signal;
use flate2::read::GzDecoder;
use hifitime::TimeScale;
use rinex::observation::EpochFlag;
use rinex::prelude::{Constellation, Observable, Rinex};
use skyforge_orbits::ephemeris::{SatId, System};
use std::collections::BTreeMap;
use std::fs::File;
use std::io::{BufReader, Read};
use std::path::{Path, PathBuf};

/// The signal, quantity and code rank ([`rinex_codes::classify`]) of observation `code`
/// (e.g. `C1C`) of `system`, for a file of RINEX version `major.minor`.
fn classify(system: System, code: &str, major: u8, minor: u8) -> Option<(Signal, Kind, usize)> {
    let b = code.as_bytes();
    if b.len() != 3 {
        return None;
    }
    let kind = match b[0] {
        b'C' => Kind::Code,
        b'L' => Kind::Phase,
        b'D' => Kind::Doppler,
        b'S' => Kind::Strength,
        _ => return None,
    };
    let (signal, rank) = rinex_codes::classify(system, &code[1..], major, minor)?;
    Some((signal, kind, rank))
}

/// A GPS or BeiDou observation of the file: its satellite and code.
fn gnss_observation(o: &rinex::observation::SignalObservation) -> Option<(SatId, &str)> {
    let system = match o.sv.constellation {
        Constellation::GPS => System::Gps,
        Constellation::BeiDou => System::Beidou,
        _ => return None,
    };
    let code = match &o.observable {
        Observable::PseudoRange(c)
        | Observable::PhaseRange(c)
        | Observable::Doppler(c)
        | Observable::SSI(c) => c.as_str(),
        _ => return None,
    };
    Some((
        SatId {
            system,
            prn: o.sv.prn,
        },
        code,
    ))
}

/// Read a RINEX observation file: version 2 (plain or `.gz`; [`super::rinex2_read`]) or
/// 3 (plain, `.gz`, or Hatanaka `.crx[.gz]`). At most [`MAX_OBS_BYTES`] (decompressed)
/// are read.
pub fn read_obs_file(path: &Path) -> Result<ObsFile, ObsReadError> {
    let error = |message: String| ObsReadError::Read {
        path: path.to_path_buf(),
        message,
    };
    // Opened here: the crate's own `from_file` panics on a missing file.
    let file = File::open(path).map_err(|e| error(e.to_string()))?;
    let gz = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("gz"));
    let reader: Box<dyn Read> = if gz {
        Box::new(GzDecoder::new(file))
    } else {
        Box::new(file)
    };
    let mut bytes = Vec::new();
    reader
        .take(MAX_OBS_BYTES + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| error(e.to_string()))?;
    if bytes.len() as u64 > MAX_OBS_BYTES {
        return Err(error(format!(
            "more than {MAX_OBS_BYTES} bytes; larger files are not read"
        )));
    }
    let start = String::from_utf8_lossy(&bytes[..bytes.len().min(160)]);
    if is_rinex2_obs(&start) {
        return parse_rinex2_obs(&String::from_utf8_lossy(&bytes), path);
    }
    let rinex = parse_rinex(&bytes).map_err(error)?;
    from_rinex(&rinex, path)
}

/// Parse RINEX 2 or 3 observation `text`; `label` names it in errors.
pub fn parse_obs_text(text: &str, label: &str) -> Result<ObsFile, ObsReadError> {
    if is_rinex2_obs(text) {
        return parse_rinex2_obs(text, Path::new(label));
    }
    let rinex = parse_rinex(text.as_bytes()).map_err(|message| ObsReadError::Read {
        path: PathBuf::from(label),
        message,
    })?;
    from_rinex(&rinex, Path::new(label))
}

/// The `rinex` crate's reading of `bytes`. The crate panics on some malformed files (an
/// `INTERVAL` of `inf`, short or non-ASCII fields: found by fuzzing, docs/fuzzing.md);
/// such a panic is caught here and becomes an error like any other. (Its message still
/// goes to the panic hook, i.e. stderr.)
fn parse_rinex(bytes: &[u8]) -> Result<Rinex, String> {
    let parsed = std::panic::catch_unwind(|| Rinex::parse(&mut BufReader::new(bytes)));
    match parsed {
        Ok(Ok(rinex)) => Ok(rinex),
        Ok(Err(e)) => Err(e.to_string()),
        Err(panic) => {
            let why = panic
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| panic.downcast_ref::<String>().cloned())
                .unwrap_or_default();
            Err(format!("malformed RINEX (the reader failed: {why})"))
        }
    }
}

fn from_rinex(rinex: &Rinex, source: &Path) -> Result<ObsFile, ObsReadError> {
    let record = rinex
        .record
        .as_obs()
        .ok_or_else(|| ObsReadError::NotObservation(source.to_path_buf()))?;
    let (major, minor) = (rinex.header.version.major, rinex.header.version.minor);
    // One code per signal for the whole file: the preferred one it has.
    let mut chosen: BTreeMap<Signal, usize> = BTreeMap::new();
    for o in record.values().flat_map(|obs| &obs.signals) {
        if let Some((signal, _, rank)) =
            gnss_observation(o).and_then(|(sat, code)| classify(sat.system, code, major, minor))
        {
            let best = chosen.entry(signal).or_insert(rank);
            *best = (*best).min(rank);
        }
    }
    let mut epochs = Vec::with_capacity(record.len());
    for (key, observations) in record {
        let power_failure = match key.flag {
            EpochFlag::Ok => false,
            EpochFlag::PowerFailure => true,
            _ => continue,
        };
        // One record per satellite and signal (L1 and L2 of one GPS satellite are two).
        let mut sats: BTreeMap<(SatId, Signal), ObsRecord> = BTreeMap::new();
        for o in &observations.signals {
            let Some((sat, code)) = gnss_observation(o) else {
                continue;
            };
            let Some((signal, kind, rank)) = classify(sat.system, code, major, minor) else {
                continue;
            };
            if chosen.get(&signal) != Some(&rank) {
                continue;
            }
            let entry = sats
                .entry((sat, signal))
                .or_insert_with(|| ObsRecord::empty(sat, signal));
            match kind {
                Kind::Code => entry.pseudorange_m = Some(o.value),
                Kind::Phase => {
                    entry.carrier_phase_cycles = Some(o.value);
                    entry.phase_lli |= o.lli.map_or(0, |f| f.bits());
                }
                Kind::Doppler => entry.doppler_hz = Some(o.value),
                Kind::Strength => entry.cn0_dbhz = Some(o.value),
            }
        }
        if power_failure {
            for s in sats.values_mut() {
                s.phase_lli |= LLI_LOSS_OF_LOCK;
            }
        }
        epochs.push(ObsEpoch {
            time: key.epoch.to_time_scale(TimeScale::GPST),
            sats: sats.into_values().collect(),
        });
    }
    epochs.sort_by_key(|e| e.time);
    let approx_ecef_m = rinex
        .header
        .rx_position
        .map(|(x, y, z)| skyforge_orbits::Vec3::new(x, y, z))
        .filter(|r| r.iter().all(|v| v.is_finite()));
    Ok(ObsFile {
        source: source.to_path_buf(),
        approx_ecef_m,
        codes: chosen
            .into_iter()
            .map(|(signal, rank)| (signal, rinex_codes::codes(signal)[rank]))
            .collect(),
        epochs,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::observation::record::LLI_HALF_CYCLE;
    use hifitime::Epoch;

    /// A RINEX 3.04 header with GPS and BeiDou in `time_system`.
    fn header(version: &str, bds_band: char, time_system: &str) -> String {
        let lines = [
            format!("{version:>9}{:11}{:<20}{:<20}", "", "OBSERVATION DATA", "M"),
            format!("G    4 C1C L1C D1C S1C{:38}", ""),
            format!("C    4 C{b}I L{b}I D{b}I S{b}I{:38}", "", b = bds_band),
            format!(
                "  2023    03    12    00    00    0.0000000     {time_system:<3}{:9}",
                ""
            ),
            format!("{:60}", ""),
        ];
        let labels = [
            "RINEX VERSION / TYPE",
            "SYS / # / OBS TYPES",
            "SYS / # / OBS TYPES",
            "TIME OF FIRST OBS",
            "END OF HEADER",
        ];
        lines
            .iter()
            .zip(labels)
            .map(|(l, lab)| format!("{l}{lab}\n"))
            .collect()
    }

    /// A RINEX 3.04 header (GPS time) whose GPS satellites list the four observation
    /// `types` (e.g. `"C1C L1C C2W L2W"`).
    fn gps_header(types: &str) -> String {
        header("3.04", '2', "GPS").replace(
            "G    4 C1C L1C D1C S1C                                      ",
            &format!("G    4 {types:<53}"),
        )
    }

    /// RINEX 3 F14.3 value with LLI and signal-strength digits (`' '` for blank).
    fn value(v: f64, lli: char, ssi: char) -> String {
        format!("{v:14.3}{lli}{ssi}")
    }

    /// One satellite's observation line.
    fn line(sat: &str, values: &[String]) -> String {
        format!("{sat}{}\n", values.concat())
    }

    #[test]
    fn a_file_the_rinex_crate_panics_on_is_an_error() {
        // An INTERVAL of inf: the crate makes a Duration of it, which panics.
        let text = header("3.04", '2', "GPS").replace(
            "  2023    03",
            &format!("{:<60}INTERVAL\n  2023    03", "       inf"),
        );
        let e = parse_obs_text(&text, "t.rnx").unwrap_err().to_string();
        assert!(e.starts_with("t.rnx: malformed RINEX"), "{e}");
    }

    #[test]
    fn reads_values_lli_and_both_bds_band_namings() {
        for (version, band) in [("3.04", '2'), ("3.02", '1')] {
            let mut text = header(version, band, "GPS");
            text += "> 2023 03 12 00 00  1.5000000  0  2\n";
            text += &line(
                "G05",
                &[
                    value(21035576.066, ' ', '7'),
                    value(110542679.964, '1', '7'),
                    value(-1423.232, ' ', ' '),
                    value(45.25, ' ', ' '),
                ],
            );
            text += &line(
                "C07",
                &[
                    value(36000000.5, ' ', ' '),
                    value(187000000.25, '2', ' '),
                    value(1195.909, ' ', ' '),
                    value(44.5, ' ', ' '),
                ],
            );
            let f = parse_obs_text(&text, "test").unwrap();
            assert_eq!(f.epochs.len(), 1, "{version}");
            let e = &f.epochs[0];
            let t0 = Epoch::from_gregorian(2023, 3, 12, 0, 0, 1, 500_000_000, TimeScale::GPST);
            assert_eq!(e.time, t0);
            assert_eq!(e.sats.len(), 2, "{version}: {:?}", e.sats);
            let g = e.sats[0];
            assert_eq!(g.sat.to_string(), "G05");
            assert_eq!(g.signal, Signal::GpsL1Ca);
            assert_eq!(g.pseudorange_m, Some(21035576.066));
            assert_eq!(g.carrier_phase_cycles, Some(110542679.964));
            assert_eq!(g.doppler_hz, Some(-1423.232));
            assert_eq!(g.cn0_dbhz, Some(45.25));
            assert_eq!(g.phase_lli, LLI_LOSS_OF_LOCK);
            let c = e.sats[1];
            assert_eq!(c.sat.to_string(), "C07");
            assert_eq!(c.signal, Signal::BdsB1I);
            assert_eq!(c.carrier_phase_cycles, Some(187000000.25));
            assert_eq!(c.phase_lli, LLI_HALF_CYCLE);
        }
    }

    /// GPS L1 C/A and L2 P(Y) of one satellite are two records, each with its own values.
    #[test]
    fn gps_l1_and_l2_of_one_satellite_are_two_records() {
        let mut text = gps_header("C1C L1C C2W L2W");
        text += "> 2023 03 12 00 00  1.0000000  0  1\n";
        text += &line(
            "G05",
            &[
                value(21035576.066, ' ', '7'),
                value(110542679.964, ' ', '7'),
                value(21035579.5, ' ', ' '),
                value(86137163.25, '1', ' '),
            ],
        );
        let f = parse_obs_text(&text, "test").unwrap();
        let e = &f.epochs[0];
        assert_eq!(e.sats.len(), 2, "{:?}", e.sats);
        let l1 = e.sats.iter().find(|r| r.signal == Signal::GpsL1Ca).unwrap();
        let l2 = e.sats.iter().find(|r| r.signal == Signal::GpsL2).unwrap();
        assert_eq!(l1.pseudorange_m, Some(21035576.066));
        assert_eq!(l1.carrier_phase_cycles, Some(110542679.964));
        assert_eq!(l1.phase_lli, 0);
        assert_eq!(l2.pseudorange_m, Some(21035579.5));
        assert_eq!(l2.carrier_phase_cycles, Some(86137163.25));
        assert_eq!(l2.phase_lli, LLI_LOSS_OF_LOCK);
    }

    /// A file with two trackings of L2 (L2C `2L` and P(Y) `2W`): one code for the whole
    /// file, the preferred `2W`, so a satellite with only `2L` has no L2 record; a file with
    /// only `2L` gives L2 from it.
    #[test]
    fn one_code_per_signal_for_the_whole_file() {
        let text = gps_header("C2L L2L C2W L2W");
        let g07 = line(
            "G07",
            &[value(22000000.5, ' ', ' '), value(9.0e7, ' ', ' ')],
        );
        let mut both = text.clone();
        both += "> 2023 03 12 00 00  1.0000000  0  2\n";
        both += &line(
            "G05",
            &[
                value(21035579.1, ' ', ' '),
                value(86137163.5, ' ', ' '),
                value(21035579.5, ' ', ' '),
                value(86137163.25, ' ', ' '),
            ],
        );
        both += &g07;
        let f = parse_obs_text(&both, "test").unwrap();
        assert_eq!(f.codes.get(&Signal::GpsL2), Some(&"2W"));
        let l2: Vec<&ObsRecord> = f.epochs[0].sats.iter().collect();
        assert_eq!(l2.len(), 1, "{l2:?}");
        assert_eq!(l2[0].sat.prn, 5);
        assert_eq!(l2[0].pseudorange_m, Some(21035579.5));
        let only_l2c = text
            .replace(" C2W L2W", "        ")
            .replace("G    4", "G    2");
        let mut only = only_l2c;
        only += "> 2023 03 12 00 00  1.0000000  0  1\n";
        only += &g07;
        let f = parse_obs_text(&only, "test").unwrap();
        assert_eq!(f.codes.get(&Signal::GpsL2), Some(&"2L"));
        assert_eq!(f.epochs[0].sats.len(), 1);
        assert_eq!(f.epochs[0].sats[0].signal, Signal::GpsL2);
        assert_eq!(f.epochs[0].sats[0].pseudorange_m, Some(22000000.5));
    }

    /// In RINEX 3.03+ band 1 of BeiDou is B1C, which SkyForge does not compare.
    #[test]
    fn bds_band_1_is_not_b1i_after_3_02() {
        let mut text = header("3.04", '1', "GPS");
        text += "> 2023 03 12 00 00  1.0000000  0  1\n";
        text += &line("C07", &[value(36000000.5, ' ', ' ')]);
        let f = parse_obs_text(&text, "test").unwrap();
        assert!(f.epochs[0].sats.is_empty());
    }

    /// BDT = GPST - 14 s (BDS-SIS-ICD-B1I-3.0 section 5.2: BDT started 2006-01-01 00:00:00
    /// UTC, when GPST - UTC was 14 s).
    #[test]
    fn bdt_epochs_are_returned_in_gps_time() {
        let mut text = header("3.02", '1', "BDT");
        text += "> 2023 03 12 00 00 51.0000000  0  1\n";
        text += &line("C01", &[value(1433736.747, ' ', '7')]);
        let f = parse_obs_text(&text, "test").unwrap();
        let gpst = Epoch::from_gregorian(2023, 3, 12, 0, 1, 5, 0, TimeScale::GPST);
        assert_eq!(f.epochs[0].time.to_time_scale(TimeScale::GPST), gpst);
        assert_eq!(f.epochs[0].time.time_scale, TimeScale::GPST);
    }

    #[test]
    fn power_failure_epoch_flags_loss_of_lock_and_slip_records_are_skipped() {
        let mut text = header("3.04", '2', "GPS");
        text += "> 2023 03 12 00 00  1.0000000  1  1\n";
        text += &line("G05", &[value(2.0e7, ' ', ' '), value(1.0e8, ' ', ' ')]);
        text += "> 2023 03 12 00 00  1.0000000  6  1\n";
        text += &line("G05", &[value(2.0e7, ' ', ' '), value(1.0e8, '1', ' ')]);
        let f = parse_obs_text(&text, "test").unwrap();
        assert_eq!(f.epochs.len(), 1);
        assert_eq!(f.epochs[0].sats[0].phase_lli, LLI_LOSS_OF_LOCK);
    }

    #[test]
    fn a_file_that_is_not_rinex_is_an_error() {
        assert!(parse_obs_text("not a rinex file\n", "junk").is_err());
        let missing = read_obs_file(Path::new("/nonexistent/obs.rnx"));
        assert!(matches!(missing, Err(ObsReadError::Read { .. })));
    }
}
