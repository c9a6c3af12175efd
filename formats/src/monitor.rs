//! What the integrity monitor writes (`skyforge monitor run`): [`MONITOR_CSV`] (one row
//! per epoch, satellite and station), [`MONITOR_H5`] (the same as datasets) and
//! [`SUMMARY_JSON`] (the alarms); and the reader of the CSV file's alarms and
//! loss-of-lock flags that `skyforge validate monitor` scores ([`read_monitor_csv`]).

use crate::csv::{Fields, FormatError, read_csv, require_columns};
use crate::h5::{append_rows, create_rows, text_attr};
use hifitime::Epoch;
use serde::Serialize;
use skyforge_navigation::integrity::{MonitorEpoch, Station, Statistic, Unmonitored};
use skyforge_orbits::time::TimeOrigin;
use std::collections::{BTreeMap, BTreeSet};
use std::fmt::Write as _;
use std::path::Path;

/// One row per epoch, satellite and station.
pub const MONITOR_CSV: &str = "monitor.csv";
/// The same rows as datasets.
pub const MONITOR_H5: &str = "monitor.h5";
/// The alarms, per station, satellite and statistic.
pub const SUMMARY_JSON: &str = "summary.json";

/// The columns before the statistics'.
const LEADING: [&str; 7] = [
    "time_gpst",
    "t_s",
    "sat",
    "signal",
    "station",
    "elevation_deg",
    "track_age_s",
];
/// The last column: the station's receiver flagged a loss of lock.
const LOSS_OF_LOCK: &str = "loss_of_lock";

/// A statistic's column with `suffix` (`""` for the statistic itself, else `b`,
/// `threshold`, `armed` or `alarm`).
fn column(stat: Statistic, suffix: &str) -> String {
    match suffix {
        "" => stat.key().to_string(),
        s => format!("{}_{s}", stat.key()),
    }
}

/// The header of `monitor.csv`.
pub fn csv_header() -> String {
    let mut h = LEADING.join(",");
    for stat in Statistic::ALL {
        for suffix in ["", "b", "threshold", "armed", "alarm"] {
            h.push(',');
            h.push_str(&column(stat, suffix));
        }
    }
    h.push(',');
    h.push_str(LOSS_OF_LOCK);
    h
}

/// The rows of one epoch.
pub fn csv_rows(e: &MonitorEpoch, stations: &[Station]) -> String {
    let mut out = String::new();
    for s in &e.sats {
        for (station, v) in stations.iter().zip(&s.stations) {
            let Some(v) = v else { continue };
            let _ = write!(
                out,
                "{},{:.3},{},{},{},{:.3},{:.0}",
                e.time,
                e.t_s,
                s.sat,
                s.signal.tag(),
                station.name,
                s.elevation_deg,
                s.track_age_s
            );
            for stat in Statistic::ALL {
                let k = stat.index();
                let _ = write!(
                    out,
                    ",{:.6},{:.6},{:.6},{},{}",
                    v.statistic[k],
                    v.b[k],
                    s.threshold[k],
                    u8::from(s.armed[k]),
                    u8::from(v.alarm[k])
                );
            }
            let _ = writeln!(out, ",{}", u8::from(v.loss_of_lock));
        }
    }
    out
}

/// One alarmed statistic of one station and satellite at one epoch.
#[derive(Debug, Clone, PartialEq)]
pub struct Alarm {
    /// Seconds since the scenario start.
    pub t_s: f64,
    pub station: String,
    pub sat: String,
    pub statistic: String,
    /// |B| over its threshold.
    pub ratio: f64,
}

/// A loss of lock a station's receiver flagged (RINEX LLI) on a satellite.
#[derive(Debug, Clone, PartialEq)]
pub struct Flag {
    /// Seconds since the scenario start.
    pub t_s: f64,
    pub station: String,
    pub sat: String,
}

/// What `monitor.csv` holds for the scoring.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct MonitorRecord {
    pub alarms: Vec<Alarm>,
    pub flags: Vec<Flag>,
    /// The first and last row's time (s since the scenario start); `None` without rows.
    pub span_s: Option<(f64, f64)>,
    /// Every station of the rows.
    pub stations: BTreeSet<String>,
}

/// The alarms and loss-of-lock flags of `monitor.csv` at `path`, timed from `start`.
pub fn read_monitor_csv(path: &Path, start: Epoch) -> Result<MonitorRecord, FormatError> {
    let required: Vec<String> = csv_header().split(',').map(String::from).collect();
    let origin = TimeOrigin::new(start);
    let mut out = MonitorRecord::default();
    let each = |header: &[&str], line: usize, text: &str| {
        let f = Fields::new(path, line, header, text)?;
        let t_s = origin.seconds_since_start(f.epoch(LEADING[0])?);
        out.span_s = Some(
            out.span_s
                .map_or((t_s, t_s), |(a, b)| (a.min(t_s), b.max(t_s))),
        );
        let station = f.text("station")?;
        if !out.stations.contains(station) {
            out.stations.insert(station.to_string());
        }
        let flagged = f.text(LOSS_OF_LOCK)? == "1";
        let mut alarmed = Vec::new();
        for stat in Statistic::ALL {
            if f.text(&column(stat, "alarm"))? == "1" {
                alarmed.push(stat);
            }
        }
        if !flagged && alarmed.is_empty() {
            return Ok(());
        }
        let (station, sat) = (f.text("station")?.to_string(), f.text("sat")?.to_string());
        if flagged {
            out.flags.push(Flag {
                t_s,
                station: station.clone(),
                sat: sat.clone(),
            });
        }
        for stat in alarmed {
            let number = |suffix: &str| {
                let c = column(stat, suffix);
                f.number(&c)?
                    .ok_or_else(|| f.error(format!("{c} is empty")))
            };
            out.alarms.push(Alarm {
                t_s,
                station: station.clone(),
                sat: sat.clone(),
                statistic: stat.key().to_string(),
                ratio: number("b")?.abs() / number("threshold")?,
            });
        }
        Ok(())
    };
    read_csv(path, |names| require_columns(path, names, &required), each)?;
    Ok(out)
}

/// One station, satellite and statistic that alarmed.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct AlarmSummary {
    pub station: String,
    pub sat: String,
    pub statistic: &'static str,
    pub first_gpst: String,
    pub first_t_s: f64,
    pub last_t_s: f64,
    pub epochs: usize,
    /// Largest |B| / threshold while alarming.
    pub peak_ratio: f64,
}

/// `summary.json`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Summary {
    pub stations: Vec<String>,
    pub common_point_ecef_m: [f64; 3],
    pub epochs: usize,
    /// Epochs at which at least one satellite was monitored.
    pub epochs_monitored: usize,
    /// Station-satellite values monitored (rows of `monitor.csv`).
    pub monitored: usize,
    /// The satellites monitored at some epoch.
    pub satellites_monitored: Vec<String>,
    /// Satellite-epochs observed but not monitored, by reason.
    pub unmonitored: Unmonitored,
    pub alarms: Vec<AlarmSummary>,
}

/// Collects the alarms of the epochs it is shown.
#[derive(Debug, Default)]
pub struct AlarmLog {
    by_key: BTreeMap<(String, String, &'static str), AlarmSummary>,
    satellites: BTreeSet<String>,
    pub epochs: usize,
    pub epochs_monitored: usize,
    pub monitored: usize,
}

impl AlarmLog {
    /// Take one epoch.
    pub fn add(&mut self, e: &MonitorEpoch, stations: &[Station]) {
        self.epochs += 1;
        if !e.sats.is_empty() {
            self.epochs_monitored += 1;
        }
        for s in &e.sats {
            self.satellites.insert(s.sat.to_string());
            for (station, v) in stations.iter().zip(&s.stations) {
                let Some(v) = v else { continue };
                self.monitored += 1;
                for stat in Statistic::ALL.into_iter().filter(|st| v.alarm[st.index()]) {
                    let k = stat.index();
                    let ratio = v.b[k].abs() / s.threshold[k];
                    let key = (station.name.clone(), s.sat.to_string(), stat.name());
                    let entry = self.by_key.entry(key).or_insert_with(|| AlarmSummary {
                        station: station.name.clone(),
                        sat: s.sat.to_string(),
                        statistic: stat.name(),
                        first_gpst: e.time.to_string(),
                        first_t_s: e.t_s,
                        last_t_s: e.t_s,
                        epochs: 0,
                        peak_ratio: 0.0,
                    });
                    entry.epochs += 1;
                    entry.last_t_s = e.t_s;
                    entry.peak_ratio = entry.peak_ratio.max(ratio);
                }
            }
        }
    }

    /// The summary, alarms by first time.
    pub fn summary(
        self,
        stations: &[Station],
        common: [f64; 3],
        unmonitored: Unmonitored,
    ) -> Summary {
        let mut alarms: Vec<AlarmSummary> = self.by_key.into_values().collect();
        alarms.sort_by(|a, b| a.first_t_s.total_cmp(&b.first_t_s));
        Summary {
            stations: stations.iter().map(|s| s.name.clone()).collect(),
            common_point_ecef_m: common,
            epochs: self.epochs,
            epochs_monitored: self.epochs_monitored,
            monitored: self.monitored,
            satellites_monitored: self.satellites.into_iter().collect(),
            unmonitored,
            alarms,
        }
    }
}

/// The datasets of `monitor.h5`, one row per epoch, satellite and station.
#[derive(Debug, Default)]
pub struct H5Rows {
    t_s: Vec<f64>,
    station: Vec<u16>,
    sat: Vec<u16>,
    elevation_deg: Vec<f64>,
    value: Vec<f64>,
    b: Vec<f64>,
    threshold: Vec<f64>,
    armed: Vec<u8>,
    alarm: Vec<u8>,
    loss_of_lock: Vec<u8>,
}

/// A satellite as one number: 1000 x system (1 GPS, 2 BeiDou, 3 Galileo) + PRN.
fn sat_code(sat: skyforge_orbits::ephemeris::SatId) -> u16 {
    let system = match sat.system {
        skyforge_orbits::ephemeris::System::Gps => 1,
        skyforge_orbits::ephemeris::System::Beidou => 2,
        skyforge_orbits::ephemeris::System::Galileo => 3,
    };
    1000 * system + u16::from(sat.prn)
}

impl H5Rows {
    /// Take one epoch.
    pub fn add(&mut self, e: &MonitorEpoch) {
        for s in &e.sats {
            for (m, v) in s.stations.iter().enumerate() {
                let Some(v) = v else { continue };
                self.t_s.push(e.t_s);
                self.station.push(u16::try_from(m).unwrap_or(u16::MAX));
                self.sat.push(sat_code(s.sat));
                self.elevation_deg.push(s.elevation_deg);
                self.value.extend_from_slice(&v.statistic);
                self.b.extend_from_slice(&v.b);
                self.threshold.extend_from_slice(&s.threshold);
                self.armed.extend(s.armed.map(u8::from));
                self.alarm.extend(v.alarm.map(u8::from));
                self.loss_of_lock.push(u8::from(v.loss_of_lock));
            }
        }
    }

    /// Write `monitor.h5` at `path`.
    pub fn write(&self, path: &Path, start: Epoch, stations: &[Station]) -> hdf5::Result<()> {
        let file = hdf5::File::create(path)?;
        text_attr(&file, "start_epoch", &start.to_string())?;
        let names: Vec<&str> = stations.iter().map(|s| s.name.as_str()).collect();
        text_attr(&file, "stations", &names.join(","))?;
        let stats: Vec<String> = Statistic::ALL
            .iter()
            .map(|s| format!("{} ({})", s.name(), s.unit()))
            .collect();
        text_attr(&file, "statistics", &stats.join(","))?;
        let root = file.as_group()?;
        let chunk = self.t_s.len().clamp(1, 65_536);
        let one = |name: &str, unit: &str, what: &str, data: &[f64]| -> hdf5::Result<()> {
            let ds = create_rows::<f64>(&root, name, 0, chunk, unit, what)?;
            append_rows(&ds, 0, data, 0)
        };
        one("t_s", "s", "time since start_epoch", &self.t_s)?;
        one(
            "elevation_deg",
            "deg",
            "elevation at the common point",
            &self.elevation_deg,
        )?;
        let ds = create_rows::<u8>(
            &root,
            "loss_of_lock",
            0,
            chunk,
            "",
            "1 when the receiver flagged a loss of lock (the track restarts)",
        )?;
        append_rows(&ds, 0, &self.loss_of_lock, 0)?;
        let ints: [(&str, &str, &[u16]); 2] = [
            (
                "station",
                "index into the stations attribute",
                &self.station,
            ),
            ("sat", "1000 x system (1 GPS, 2 BeiDou) + PRN", &self.sat),
        ];
        for (name, what, data) in ints {
            let ds = create_rows::<u16>(&root, name, 0, chunk, "", what)?;
            append_rows(&ds, 0, data, 0)?;
        }
        let four = |name: &str, what: &str, data: &[f64]| -> hdf5::Result<()> {
            let ds = create_rows::<f64>(&root, name, 4, chunk, "per statistic", what)?;
            append_rows(&ds, 0, data, 4)
        };
        four(
            "value",
            "the statistics (order of the statistics attribute)",
            &self.value,
        )?;
        four("b", "their B values", &self.b)?;
        four("threshold", "the B values' thresholds", &self.threshold)?;
        for (name, what, data) in [
            ("armed", "1 when the statistic is tested", &self.armed),
            ("alarm", "1 when |B| exceeds its threshold", &self.alarm),
        ] {
            let ds = create_rows::<u8>(&root, name, 4, chunk, "", what)?;
            append_rows(&ds, 0, data, 4)?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use skyforge_gnss::signal::Signal;
    use skyforge_navigation::integrity::{SatelliteEpoch, StationValues};
    use skyforge_orbits::Vec3;
    use skyforge_orbits::ephemeris::SatId;

    /// Two satellites seen by two stations (one satellite by one of them only); the second
    /// station alarms on the first satellite's code and carrier statistics, the first
    /// flags a loss of lock on the second satellite.
    fn epoch(start: Epoch, t_s: f64) -> MonitorEpoch {
        let values = |alarm: [bool; 4], b: f64, loss_of_lock: bool| StationValues {
            statistic: [0.5, -0.25, 1.5, 1e-3],
            b: [b, -b, 2.0 * b, 0.1],
            alarm,
            loss_of_lock,
        };
        let sat = |sat: SatId, stations: Vec<Option<StationValues>>| SatelliteEpoch {
            sat,
            signal: Signal::of_system(sat.system),
            geo: false,
            elevation_deg: 37.25,
            threshold: [0.75, 0.5, 1.25, 0.3],
            armed: [true, true, false, true],
            track_age_s: 120.0,
            stations,
        };
        MonitorEpoch {
            time: start + hifitime::Duration::from_seconds(t_s),
            t_s,
            sats: vec![
                sat(
                    SatId::gps(5),
                    vec![
                        Some(values([false; 4], 0.1, false)),
                        Some(values([true, true, false, false], 1.234567, false)),
                    ],
                ),
                sat(
                    SatId::beidou(12),
                    vec![Some(values([false; 4], 0.2, true)), None],
                ),
            ],
        }
    }

    /// Rows written by [`csv_rows`] under [`csv_header`] read back as the alarms and flags
    /// they hold: each alarm's |B| over its threshold (to the six printed decimals), each
    /// loss of lock, at the epoch's time.
    #[test]
    fn alarms_and_flags_read_back_from_the_rows_written() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join(MONITOR_CSV);
        let start = Epoch::from_gpst_seconds(1.4e9);
        let stations: Vec<Station> = ["north", "south"]
            .map(|n| Station {
                name: n.into(),
                r_ecef_m: Vec3::zeros(),
            })
            .into();
        let mut text = csv_header() + "\n";
        for t_s in [0.0, 1.0] {
            text += &csv_rows(&epoch(start, t_s), &stations);
        }
        std::fs::write(&path, text).unwrap();
        let read = read_monitor_csv(&path, start).unwrap();
        let flags: Vec<(f64, &str, &str)> = read
            .flags
            .iter()
            .map(|f| (f.t_s, f.station.as_str(), f.sat.as_str()))
            .collect();
        assert_eq!(flags, [(0.0, "north", "C12"), (1.0, "north", "C12")]);
        let alarms: Vec<(f64, &str, &str, &str)> = read
            .alarms
            .iter()
            .map(|a| {
                (
                    a.t_s,
                    a.station.as_str(),
                    a.sat.as_str(),
                    a.statistic.as_str(),
                )
            })
            .collect();
        let (code, carrier) = (Statistic::ALL[0].key(), Statistic::ALL[1].key());
        assert_eq!(
            alarms,
            [
                (0.0, "south", "G05", code),
                (0.0, "south", "G05", carrier),
                (1.0, "south", "G05", code),
                (1.0, "south", "G05", carrier),
            ]
        );
        let expected = [1.234567 / 0.75, 1.234567 / 0.5];
        for (a, want) in read.alarms.iter().zip(expected.iter().cycle()) {
            assert!((a.ratio - want).abs() < 1e-12, "{} vs {want}", a.ratio);
        }
    }

    /// A file that is not a monitor.csv is refused by the column it lacks.
    #[test]
    fn a_file_without_the_columns_is_refused() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("other.csv");
        std::fs::write(&path, "time_gpst,station\n").unwrap();
        let e = read_monitor_csv(&path, Epoch::from_gpst_seconds(0.0))
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("other.csv:1: the header has no column t_s"),
            "{e}"
        );
    }
}
