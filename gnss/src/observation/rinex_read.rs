//! RINEX observation files (version 3 here; version 2 in [`super::rinex2_read`]) into
//! per-epoch observations of every [`Signal`] ([`ObsRecord`]; the codes of
//! [`super::rinex_codes`]), through the `rinex` crate (which also reads Hatanaka-compressed and gzipped files).
//!
//! Checked on the two kinds of file this module exists for: SkyForge's truth (RINEX 3.04,
//! `C2I` for B1I, GPS time) and GNSS-SDR 0.0.17's output (RINEX 3.02, B1I as `C1I`,
//! BeiDou epochs in BDT, signal strength digit after every value). The crate keeps the
//! loss-of-lock indicator of every value and the epoch flag; it parses the epoch's seconds
//! to 100 ns, the resolution of the RINEX F11.7 field.

use super::read_error::{Kind, ObsReadError, check_physical};
use super::record::{LLI_LOSS_OF_LOCK, ObsEpoch, ObsFile, ObsRecord};
use super::rinex_codes;
use super::rinex2_read::{MAX_OBS_BYTES, is_rinex2_obs, parse_rinex2_obs};
use super::rinex3_scan::{Scan, scan};
use crate::signal::Signal;
use flate2::read::GzDecoder;
use hifitime::TimeScale;
use rinex::observation::EpochFlag;
use rinex::prelude::{Constellation, Observable, Rinex};
use skyforge_orbits::ephemeris::{SatId, System};
use std::collections::{BTreeMap, BTreeSet};
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

/// A GPS, BeiDou or Galileo observation of the file: its satellite and code.
fn gnss_observation(o: &rinex::observation::SignalObservation) -> Option<(SatId, &str)> {
    let system = match o.sv.constellation {
        Constellation::GPS => System::Gps,
        Constellation::BeiDou => System::Beidou,
        Constellation::Galileo => System::Galileo,
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
    let text = String::from_utf8_lossy(&bytes);
    let scan = scan(&text, path)?;
    let rinex = parse_rinex(&bytes).map_err(error)?;
    from_rinex(&rinex, path, scan)
}

/// Parse RINEX 2 or 3 observation `text`; `label` names it in errors.
pub fn parse_obs_text(text: &str, label: &str) -> Result<ObsFile, ObsReadError> {
    if is_rinex2_obs(text) {
        return parse_rinex2_obs(text, Path::new(label));
    }
    let scan = scan(text, Path::new(label))?;
    let rinex = parse_rinex(text.as_bytes()).map_err(|message| ObsReadError::Read {
        path: PathBuf::from(label),
        message,
    })?;
    from_rinex(&rinex, Path::new(label), scan)
}

/// The `rinex` crate's reading of `bytes`, whose header [`scan`] has checked (an
/// `INTERVAL` of `inf` made the crate panic). The crate has panicked on other malformed
/// files (short or non-ASCII fields: found by fuzzing, docs/fuzzing.md); such a panic is
/// caught here and becomes an error like any other. (Its message still goes to the panic
/// hook, i.e. stderr.)
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

/// The observations of the crate's `rinex`, less the epochs [`scan`] refused; every value
/// within its physical range ([`check_physical`]).
fn from_rinex(rinex: &Rinex, source: &Path, mut scan: Scan) -> Result<ObsFile, ObsReadError> {
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
    let mut delivered = BTreeSet::new();
    for (key, observations) in record {
        let power_failure = match key.flag {
            EpochFlag::Ok => false,
            EpochFlag::PowerFailure => true,
            _ => continue,
        };
        let calendar = key.epoch.to_gregorian(key.epoch.time_scale);
        // Only the epoch lines the scan found good (all, in a Hatanaka file).
        let scanned = match &scan.epochs {
            Some(good) => match good.get(&calendar) {
                Some(e) => Some(e),
                None => continue,
            },
            None => None,
        };
        delivered.insert(calendar);
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
        for rec in sats.values() {
            check_physical(rec).map_err(|message| {
                let line = scanned.map_or(0, |e| {
                    e.sat_lines
                        .get(&rec.sat.to_string())
                        .copied()
                        .unwrap_or(e.line)
                });
                ObsReadError::Syntax {
                    path: source.to_path_buf(),
                    line,
                    message,
                }
            })?;
        }
        epochs.push(ObsEpoch {
            time: key.epoch.to_time_scale(TimeScale::GPST),
            sats: sats.into_values().collect(),
        });
    }
    epochs.sort_by_key(|e| e.time);
    scan.settle(&delivered, source)?;
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
        marker: scan.marker,
        dropped: scan.dropped,
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

    /// Issue #33 (5): the header is checked before the crate reads it; `INTERVAL inf`
    /// made the crate panic (and print a backtrace) before.
    #[test]
    fn a_non_finite_interval_is_refused_before_the_crate_reads_it() {
        for bad in ["inf", "NaN", "-5", "1e300"] {
            let text = header("3.04", '2', "GPS").replace(
                "  2023    03",
                &format!("{bad:>10}{:50}INTERVAL\n  2023    03", ""),
            );
            let hook = std::panic::take_hook();
            std::panic::set_hook(Box::new(|_| panic!("the crate panicked")));
            let result = std::panic::catch_unwind(|| parse_obs_text(&text, "t.rnx"));
            std::panic::set_hook(hook);
            let e = result.expect("no panic").unwrap_err().to_string();
            assert!(e.starts_with("t.rnx:4: INTERVAL"), "{bad}: {e}");
        }
    }

    /// Issue #33 (12): versions other than 2.xx, 3.xx and 4.xx are refused (9.99 was read
    /// as 3.x); 4.xx is read like 3.04.
    #[test]
    fn unsupported_versions_are_refused_and_version_4_is_read() {
        let epoch = "> 2023 03 12 00 00  1.0000000  0  1\n".to_string()
            + &line("G05", &[value(2.1e7, ' ', ' '), value(1.1e8, ' ', ' ')]);
        for v in ["9.99", "1.00", "5.00"] {
            let text = header(v, '2', "GPS") + &epoch;
            let e = parse_obs_text(&text, "t.rnx").unwrap_err().to_string();
            assert!(
                e.contains("t.rnx:1: RINEX version") && e.contains("is not read"),
                "{e}"
            );
        }
        let f = parse_obs_text(&(header("4.01", '2', "GPS") + &epoch), "t").unwrap();
        assert_eq!(f.epochs.len(), 1);
        assert_eq!(f.epochs[0].sats[0].pseudorange_m, Some(2.1e7));
    }

    /// Ten good epochs of G05 (1 s apart), starting at line 6.
    fn ten_epochs() -> Vec<String> {
        (0..10)
            .flat_map(|k| {
                [
                    format!("> 2023 03 12 00 00 {:>10.7}  0  1\n", f64::from(k)),
                    line("G05", &[value(2.1e7, ' ', ' '), value(1.1e8, ' ', ' ')]),
                ]
            })
            .collect()
    }

    /// Issue #33 (12): malformed epochs were dropped without a word (minute 99, NaN or
    /// 1e308 seconds, -5 satellites, flag 9) and a year 0 was read as 2000; junk between
    /// epochs was skipped. One of ten is left out with its line named; more than 10 % or
    /// every epoch is an error naming the lines.
    #[test]
    fn malformed_epochs_are_left_out_and_counted() {
        let text = |body: &[String]| header("3.04", '2', "GPS") + &body.concat();
        for (bad, why) in [
            ("> 2023 03 12 00 99  5.0000000  0  1\n", "epoch minute 99"),
            ("> 2023 03 12 00 00        NaN  0  1\n", "epoch seconds NaN"),
            (
                "> 2023 03 12 00 00      1e308  0  1\n",
                "epoch seconds 1e308",
            ),
            ("> 2023 03 12 00 00  5.0000000  0 -5\n", "\"-5\""),
            ("> 2023 03 12 00 00  5.0000000  9  1\n", "epoch flag 9"),
            ("> 0000 03 12 00 00  5.0000000  0  1\n", "epoch year 0"),
        ] {
            let mut body = ten_epochs();
            body[10] = bad.to_string();
            let f = parse_obs_text(&text(&body), "t.rnx").unwrap();
            assert_eq!(f.epochs.len(), 9, "{bad}");
            assert_eq!(f.dropped.len(), 1, "{bad}");
            assert_eq!(f.dropped[0].line, 16, "{bad}");
            let w = f.dropped_warning().unwrap();
            assert!(w.starts_with("t.rnx: 1 malformed"), "{w}");
            assert!(w.contains("line 16: ") && w.contains(why), "{why}: {w}");
            // Two of ten: refused.
            body[2] = bad.to_string();
            let e = parse_obs_text(&text(&body), "t.rnx")
                .unwrap_err()
                .to_string();
            assert!(e.contains("2 of 10 epochs and lines cannot be read"), "{e}");
            assert!(e.contains("line 8: ") && e.contains("line 16: "), "{e}");
        }
        // Junk after the header, and nothing else: no epoch left.
        let e = parse_obs_text(&text(&["junk\n".into(), "more junk\n".into()]), "t.rnx")
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("no epoch left") && e.contains("line 6: neither"),
            "{e}"
        );
    }

    /// Issue #33 (12): observations of 1e308 (and NaN) were used; outside the physical
    /// ranges they are an error naming the satellite's line.
    #[test]
    fn non_physical_observations_are_refused() {
        // As another writer might put them: the shortest text, right-aligned.
        let raw = |v: f64| {
            let t = v.to_string();
            let t = if t.len() > 14 { format!("{v:e}") } else { t };
            format!("{t:>14}  ")
        };
        let g = |values: [f64; 4]| {
            let mut body = ten_epochs();
            body[3] = line("G05", &values.map(raw));
            header("3.04", '2', "GPS") + &body.concat()
        };
        for (values, what) in [
            (
                [9.99e300, 1.1e8, 1.0, 40.0],
                "pseudorange (m) 9.99e300: allowed -1e9 to 1e9 m",
            ),
            ([f64::NAN, 1.1e8, 1.0, 40.0], "pseudorange (m) NaN"),
            ([-1.5e9, 1.1e8, 1.0, 40.0], "pseudorange (m) -1.5e9"),
            ([2.1e7, 1e308, 1.0, 40.0], "carrier phase (cycles) 1e308"),
            ([2.1e7, 1.1e8, -2e5, 40.0], "Doppler (Hz) -2e5"),
            ([2.1e7, 1.1e8, 1.0, f64::NAN], "signal strength NaN"),
        ] {
            let e = parse_obs_text(&g(values), "t.rnx").unwrap_err().to_string();
            assert!(e.starts_with("t.rnx:9: G05 GPS L1 C/A "), "{e}");
            assert!(e.contains(what), "{what}: {e}");
        }
    }

    #[test]
    fn a_file_that_is_not_rinex_is_an_error() {
        assert!(parse_obs_text("not a rinex file\n", "junk").is_err());
        let missing = read_obs_file(Path::new("/nonexistent/obs.rnx"));
        assert!(matches!(missing, Err(ObsReadError::Read { .. })));
    }
}
