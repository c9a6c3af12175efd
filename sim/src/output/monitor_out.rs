//! `skyforge monitor run`'s files: `monitor.csv` (one row per epoch, satellite and
//! station), `monitor.h5` (the same as datasets) and `summary.json` (the alarms).

use hifitime::Epoch;
use serde::Serialize;
use skyforge_formats::h5::{append_rows, create_rows, text_attr};
use skyforge_navigation::integrity::{MonitorEpoch, Station, Statistic};
use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::Path;

/// The header of `monitor.csv`.
pub fn csv_header() -> String {
    let mut h = String::from("time_gpst,t_s,sat,signal,station,elevation_deg,track_age_s");
    for stat in Statistic::ALL {
        let k = stat.key();
        let _ = write!(h, ",{k},{k}_b,{k}_threshold,{k}_armed,{k}_alarm");
    }
    h.push_str(",loss_of_lock");
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
    pub monitored: usize,
    pub alarms: Vec<AlarmSummary>,
}

/// Collects the alarms of the epochs it is shown.
#[derive(Debug, Default)]
pub struct AlarmLog {
    by_key: BTreeMap<(String, String, &'static str), AlarmSummary>,
    pub epochs: usize,
    pub monitored: usize,
}

impl AlarmLog {
    /// Take one epoch.
    pub fn add(&mut self, e: &MonitorEpoch, stations: &[Station]) {
        self.epochs += 1;
        for s in &e.sats {
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
    pub fn summary(self, stations: &[Station], common: [f64; 3]) -> Summary {
        let mut alarms: Vec<AlarmSummary> = self.by_key.into_values().collect();
        alarms.sort_by(|a, b| a.first_t_s.total_cmp(&b.first_t_s));
        Summary {
            stations: stations.iter().map(|s| s.name.clone()).collect(),
            common_point_ecef_m: common,
            epochs: self.epochs,
            monitored: self.monitored,
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

/// A satellite as one number: 1000 x system (1 GPS, 2 BeiDou) + PRN.
fn sat_code(sat: skyforge_orbits::ephemeris::SatId) -> u16 {
    let system = match sat.system {
        skyforge_orbits::ephemeris::System::Gps => 1,
        skyforge_orbits::ephemeris::System::Beidou => 2,
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
