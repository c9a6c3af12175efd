//! `<antenna>.obs.rnx` of the receiver: one RINEX 3.04 observation file per antenna,
//! opened when its header can be written. The header needs the first epoch and, when no
//! position was given, the antenna's first fix: the epochs before that fix wait in memory,
//! at most [`PENDING_EPOCHS_MAX`] of them (then, or at the end, the header goes without
//! `APPROX POSITION XYZ`, which RINEX 3.04 table A2 makes optional for moving platforms).

use super::{EpochSink, SinkError};
use crate::pipeline::EpochReport;
use skyforge_gnss::observation::ObsRecord;
use skyforge_gnss::observation::{Calendar, ObsHeader, ObsWriter, RECEIVER_TYPE, calendar_gpst};
use skyforge_gnss::signal::Signal;
use skyforge_orbits::Vec3;
use std::fs::File;
use std::io::{self, BufWriter};
use std::path::{Path, PathBuf};

/// Epochs that may wait for a first fix before the header is written without a position.
const PENDING_EPOCHS_MAX: usize = 600;

type Writer = ObsWriter<BufWriter<File>>;

/// One epoch of one antenna.
type PendingEpoch = (Calendar, Vec<ObsRecord>);

/// Where an antenna's file stands.
#[derive(Debug)]
enum State {
    /// Epochs waiting for the header (empty before the first observations).
    Waiting(Vec<PendingEpoch>),
    Open(Writer),
}

/// `e` with the file it happened on.
fn writing(path: &Path, e: io::Error) -> io::Error {
    io::Error::new(e.kind(), format!("cannot write {}: {e}", path.display()))
}

/// The observation files of every antenna, as an epoch sink.
#[derive(Debug)]
pub struct RinexObsFiles {
    paths: Vec<PathBuf>,
    names: Vec<String>,
    /// The signals the receiver tracks.
    signals: Vec<Signal>,
    approx_ecef_m: Option<Vec3>,
    interval_s: f64,
    states: Vec<State>,
}

impl RinexObsFiles {
    /// The files `dir/<antenna>.obs.rnx` of antennas `names` (the receiver's antenna
    /// indices index them), declaring `systems`; `approx_ecef_m` is the header position
    /// (each antenna's first fix when `None`); `interval_s` the RINEX `INTERVAL`.
    pub fn new(
        dir: &Path,
        names: &[String],
        signals: &[Signal],
        approx_ecef_m: Option<Vec3>,
        interval_s: f64,
    ) -> Self {
        Self {
            paths: names
                .iter()
                .map(|n| dir.join(format!("{n}.obs.rnx")))
                .collect(),
            names: names.to_vec(),
            signals: signals.to_vec(),
            approx_ecef_m,
            interval_s,
            states: names.iter().map(|_| State::Waiting(Vec::new())).collect(),
        }
    }

    /// Open antenna `a`'s file (header at `position`) and write its waiting epochs.
    fn open(&mut self, a: usize, position: Option<Vec3>) -> io::Result<()> {
        let State::Waiting(pending) = &mut self.states[a] else {
            return Ok(());
        };
        let Some(first) = pending.first().map(|p| p.0) else {
            return Ok(());
        };
        let pending = std::mem::take(pending);
        let path = &self.paths[a];
        let file = File::create(path).map_err(|e| writing(path, e))?;
        let header = ObsHeader {
            marker: &self.names[a],
            receiver_type: RECEIVER_TYPE,
            antenna_type: "SKYFORGE",
            approx_ecef_m: position,
            first,
            interval_s: self.interval_s,
            signals: &self.signals,
        };
        let mut w =
            ObsWriter::with_header(BufWriter::new(file), &header).map_err(|e| writing(path, e))?;
        for (at, records) in &pending {
            w.epoch(*at, records).map_err(|e| writing(path, e))?;
        }
        self.states[a] = State::Open(w);
        Ok(())
    }

    /// Write (or hold) every antenna's observations of `report`.
    pub fn write_epoch(&mut self, report: &EpochReport) -> io::Result<()> {
        let at = calendar_gpst(report.t_rx);
        for a in 0..self.states.len() {
            let records = report.records(a);
            match &mut self.states[a] {
                State::Open(w) => {
                    if !records.is_empty() {
                        w.epoch(at, &records)
                            .map_err(|e| writing(&self.paths[a], e))?;
                    }
                }
                State::Waiting(pending) => {
                    if !records.is_empty() {
                        pending.push((at, records));
                    }
                    let fix_position = report
                        .fixes
                        .iter()
                        .find(|f| f.antenna == a)
                        .and_then(|f| f.fix.as_ref().ok())
                        .map(|f| f.r_ecef_m);
                    match (self.approx_ecef_m.or(fix_position), pending.len()) {
                        (_, 0) => {}
                        (Some(r), _) => self.open(a, Some(r))?,
                        (None, n) if n >= PENDING_EPOCHS_MAX => self.open(a, None)?,
                        (None, _) => {}
                    }
                }
            }
        }
        Ok(())
    }

    /// Write the epochs still waiting (header without a position) and close every file.
    pub fn finish(mut self) -> io::Result<()> {
        for a in 0..self.states.len() {
            self.open(a, None)?;
        }
        for (state, path) in self.states.into_iter().zip(&self.paths) {
            if let State::Open(w) = state {
                w.finish().map_err(|e| writing(path, e))?;
            }
        }
        Ok(())
    }
}

impl EpochSink for RinexObsFiles {
    fn epoch(&mut self, report: &EpochReport) -> Result<(), SinkError> {
        Ok(self.write_epoch(report)?)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pipeline::fixtures::report;

    fn run(approx: Option<Vec3>, epochs: usize) -> (String, String) {
        let dir = tempfile::tempdir().unwrap();
        let names = vec!["ant1".to_string(), "ant2".to_string()];
        let mut files = RinexObsFiles::new(
            dir.path(),
            &names,
            &[Signal::GpsL1Ca, Signal::BdsB1I],
            approx,
            0.1,
        );
        for k in 0..epochs {
            files.write_epoch(&report(k)).unwrap();
        }
        files.finish().unwrap();
        let read = |n: &str| std::fs::read_to_string(dir.path().join(n)).unwrap();
        (read("ant1.obs.rnx"), read("ant2.obs.rnx"))
    }

    fn header_line<'a>(text: &'a str, label: &str) -> Option<&'a str> {
        text.lines()
            .find(|l| l.get(60..).map(str::trim_end) == Some(label))
    }

    #[test]
    fn the_first_fix_gives_the_position_and_earlier_epochs_are_kept() {
        let (ant1, _) = run(None, 4);
        // Epoch 0 has no fix; the header written at epoch 1 carries its fix position and
        // starts at epoch 0 (2022-01-01 00:00:30.0000001 GPST).
        let pos = header_line(&ant1, "APPROX POSITION XYZ").unwrap();
        assert_eq!(&pos[..42], " -2267749.0000  5009154.0000  3221290.0000");
        let first = header_line(&ant1, "TIME OF FIRST OBS").unwrap();
        assert_eq!(&first[..43], "  2022     1     1     0     0   30.0000001");
        let epochs: Vec<&str> = ant1.lines().filter(|l| l.starts_with('>')).collect();
        assert_eq!(
            epochs,
            [
                "> 2022 01 01 00 00 30.0000001  0  4",
                "> 2022 01 01 00 00 30.1000001  0  4",
                "> 2022 01 01 00 00 30.2000001  0  4",
                "> 2022 01 01 00 00 30.3000001  0  4",
            ]
        );
        // Satellites sorted, GPS before BeiDou; loss of lock: all at epoch 0, G12 at 2.
        let flagged: Vec<(usize, &str)> = ant1
            .split('>')
            .skip(1)
            .enumerate()
            .flat_map(|(k, block)| {
                block
                    .lines()
                    .skip(1)
                    .filter(|l| l.as_bytes().get(33) == Some(&b'1'))
                    .map(move |l| (k, &l[..3]))
            })
            .collect();
        assert_eq!(
            flagged,
            [(0, "G07"), (0, "G12"), (0, "G19"), (0, "C19"), (2, "G12")]
        );
    }

    #[test]
    fn a_given_position_opens_the_file_at_once() {
        let r = Vec3::new(1.0e6, 2.0e6, 3.0e6);
        let (ant1, ant2) = run(Some(r), 1);
        for text in [ant1, ant2] {
            let pos = header_line(&text, "APPROX POSITION XYZ").unwrap();
            assert_eq!(&pos[..42], "  1000000.0000  2000000.0000  3000000.0000");
            assert_eq!(text.lines().filter(|l| l.starts_with('>')).count(), 1);
        }
    }

    #[test]
    fn without_any_fix_the_header_has_no_position_and_nothing_is_lost() {
        let (_, ant2) = run(None, PENDING_EPOCHS_MAX + 3);
        assert!(header_line(&ant2, "APPROX POSITION XYZ").is_none());
        assert_eq!(
            ant2.lines().filter(|l| l.starts_with('>')).count(),
            PENDING_EPOCHS_MAX + 3
        );
    }
}
