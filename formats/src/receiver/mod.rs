//! What `skyforge receive` writes at every observation epoch of the bundled receiver, into
//! one directory (the caller's staged output directory), and the files' names:
//! - `<antenna>.obs.rnx`: RINEX 3.04 observations with loss-of-lock and signal strength
//!   indicators, tagged with the receiver time
//!   ([`RinexObsFiles`], the receiver crate's writer); the header is written at
//!   the antenna's first fix (its approximate position) or, when a position was given,
//!   at its first observations;
//! - `pvt.csv`: one row per antenna and epoch with a fix ([`pvt_csv`]);
//! - `<antenna>.nmea`: GGA, GSA and RMC sentences per fix ([`nmea_log`]);
//! - `receiver.h5`: observations per antenna and satellite and the fixes per antenna, in
//!   resizable datasets appended in chunks ([`receiver_h5`]).
//!
//! Times are the receiver's own clock (GPST scale): `t_rx`, the epoch's tag; the GPST of a
//! fix is `t_rx - clock_bias_m / c`.

mod nmea_log;
mod pvt_csv;
mod receiver_h5;

use anyhow::{Context, bail};
use nmea_log::NmeaLog;
use pvt_csv::PvtCsv;
use receiver_h5::ReceiverH5;
use skyforge_gnss::antenna_name::check_antenna_name;
use skyforge_gnss::signal::Signal;
use skyforge_orbits::Vec3;
use skyforge_receiver::pipeline::EpochReport;
use skyforge_receiver::session::{EpochSink, RinexObsFiles, SinkError};
use std::path::{Path, PathBuf};

/// The fixes of every antenna, one row per antenna and epoch.
pub const PVT_CSV: &str = "pvt.csv";
/// The observations and fixes in HDF5.
pub const RECEIVER_H5: &str = "receiver.h5";

/// An antenna's NMEA log.
pub fn nmea_file(antenna: &str) -> String {
    format!("{antenna}.nmea")
}

/// What was written.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Summary {
    /// Epochs written.
    pub epochs: usize,
    /// Per antenna (input order): observations (satellite x epoch) written.
    pub observations: Vec<usize>,
    /// Per antenna: position fixes written.
    pub fixes: Vec<usize>,
}

/// The receiver's output files, fed one epoch at a time.
#[derive(Debug)]
pub struct ReceiverOutputs {
    antenna_names: Vec<String>,
    rinex: RinexObsFiles,
    csv: PvtCsv,
    nmea: Vec<NmeaLog>,
    h5: ReceiverH5,
    /// Where `h5` is written (HDF5's own errors bury the path in their text).
    h5_path: PathBuf,
    summary: Summary,
}

/// An antenna name must name files and HDF5 groups, once.
fn check_name(name: &str, seen: &[String]) -> anyhow::Result<()> {
    if let Err(rule) = check_antenna_name(name) {
        bail!("antenna name {name:?} {rule}");
    }
    if seen.iter().any(|s| s == name) {
        bail!("antenna name {name:?} appears twice");
    }
    Ok(())
}

impl ReceiverOutputs {
    /// Create the files in `dir` (an existing directory) for antennas `antenna_names`
    /// (index = `AntennaFix::antenna`), receiving `signals`. `approx_ecef_m` is the
    /// RINEX header position (m, ECEF); when `None`, each antenna's first fix gives it.
    /// `interval_s` is the observation interval (RINEX `INTERVAL`).
    pub fn create(
        dir: &Path,
        antenna_names: &[String],
        signals: &[Signal],
        approx_ecef_m: Option<Vec3>,
        interval_s: f64,
    ) -> anyhow::Result<Self> {
        if signals.is_empty() {
            bail!("no signal to write observations of");
        }
        let mut names: Vec<String> = Vec::with_capacity(antenna_names.len());
        for name in antenna_names {
            check_name(name, &names)?;
            names.push(name.clone());
        }
        let nmea = names
            .iter()
            .map(|n| NmeaLog::create(&dir.join(nmea_file(n))))
            .collect::<anyhow::Result<Vec<_>>>()?;
        let h5_path = dir.join(RECEIVER_H5);
        let h5 = ReceiverH5::create(&h5_path, &names)
            .with_context(|| format!("cannot create {}", h5_path.display()))?;
        Ok(Self {
            rinex: RinexObsFiles::new(dir, &names, signals, approx_ecef_m, interval_s),
            csv: PvtCsv::create(&dir.join(PVT_CSV))?,
            nmea,
            h5,
            h5_path,
            summary: Summary {
                epochs: 0,
                observations: vec![0; names.len()],
                fixes: vec![0; names.len()],
            },
            antenna_names: names,
        })
    }

    /// Write one epoch: every antenna's observations and fixes.
    pub fn write_epoch(&mut self, report: &EpochReport) -> anyhow::Result<()> {
        let n = self.antenna_names.len();
        let bad = report
            .observations
            .iter()
            .map(|o| o.antenna)
            .chain(report.fixes.iter().map(|f| f.antenna))
            .find(|&a| a >= n);
        if let Some(a) = bad {
            bail!(
                "the receiver reported antenna index {a} at {}, but there are {n} antennas",
                report.t_rx
            );
        }
        self.rinex.write_epoch(report)?;
        let h5_path = &self.h5_path;
        self.h5
            .write_epoch(report)
            .with_context(|| format!("cannot write {}", h5_path.display()))?;
        for af in &report.fixes {
            let Ok(fix) = &af.fix else {
                continue;
            };
            let name = &self.antenna_names[af.antenna];
            self.csv.row(name, report.t_rx, fix, af.velocity.as_ref())?;
            self.nmea[af.antenna].write(report.t_rx, fix, af.velocity.as_ref())?;
            self.summary.fixes[af.antenna] += 1;
        }
        for o in &report.observations {
            self.summary.observations[o.antenna] += 1;
        }
        self.summary.epochs += 1;
        Ok(())
    }

    /// Write what is buffered, close every file and say what was written.
    pub fn finish(self) -> anyhow::Result<Summary> {
        self.rinex.finish()?;
        self.csv.finish()?;
        for log in self.nmea {
            log.finish()?;
        }
        let h5_path = self.h5_path;
        self.h5
            .finish()
            .with_context(|| format!("cannot write {}", h5_path.display()))?;
        Ok(self.summary)
    }
}

impl EpochSink for ReceiverOutputs {
    fn epoch(&mut self, report: &EpochReport) -> Result<(), SinkError> {
        self.write_epoch(report)
            .map_err(|e| format!("{e:#}").into())
    }
}

/// Error context naming an output file.
fn writing(path: &Path) -> String {
    format!("cannot write {}", path.display())
}

#[cfg(test)]
mod tests {
    use super::*;
    use skyforge_receiver::pipeline::fixtures::report;

    #[test]
    fn a_run_writes_every_file_and_counts_what_it_wrote() {
        let dir = tempfile::tempdir().unwrap();
        let names = vec!["ant1".to_string(), "ant2".to_string()];
        let mut out = ReceiverOutputs::create(
            dir.path(),
            &names,
            &[Signal::GpsL1Ca, Signal::BdsB1I],
            None,
            0.1,
        )
        .unwrap();
        for k in 0..5 {
            out.write_epoch(&report(k)).unwrap();
        }
        let summary = out.finish().unwrap();
        assert_eq!(
            summary,
            Summary {
                epochs: 5,
                observations: vec![20, 5],
                fixes: vec![4, 0],
            }
        );
        for f in [
            "ant1.obs.rnx",
            "ant2.obs.rnx",
            "pvt.csv",
            "ant1.nmea",
            "ant2.nmea",
            "receiver.h5",
        ] {
            assert!(dir.path().join(f).is_file(), "{f}");
        }
        // The antenna without a fix has its observations all the same, with no position.
        let ant2 = std::fs::read_to_string(dir.path().join("ant2.obs.rnx")).unwrap();
        assert_eq!(ant2.lines().filter(|l| l.starts_with('>')).count(), 5);
        assert!(!ant2.contains("APPROX POSITION XYZ"));
        assert!(
            std::fs::read_to_string(dir.path().join("ant2.nmea"))
                .unwrap()
                .is_empty()
        );
    }

    #[test]
    fn bad_antenna_names_and_indices_are_refused() {
        let dir = tempfile::tempdir().unwrap();
        let create = |names: &[&str]| {
            let names: Vec<String> = names.iter().map(|s| s.to_string()).collect();
            ReceiverOutputs::create(dir.path(), &names, &[Signal::GpsL1Ca], None, 1.0)
        };
        assert!(create(&["a/b"]).is_err());
        assert!(create(&["x", "x"]).is_err());
        assert!(create(&[".."]).is_err());
        let mut one = create(&["solo"]).unwrap();
        let err = one.write_epoch(&report(1)).unwrap_err().to_string();
        assert!(err.contains("antenna index 1"), "{err}");
    }
}
