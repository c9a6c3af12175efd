//! The observation writers `skyforge synth` plugs into a synthesis session: the
//! observation truth (and at the observation level the observables) into one RINEX 3.04
//! file per antenna (`<antenna>.obs.rnx`, opened at its first epoch with the antenna's
//! position there). The truth sink is `truth.h5`'s writer
//! (`skyforge_formats::truth::TruthWriter`).

use skyforge_gnss::observation::ObsRecord;
use skyforge_gnss::observation::{ObsWriter, calendar_gpst};
use skyforge_gnss::signal::Signal;
use skyforge_orbits::Vec3;
use skyforge_signals::antenna::Antenna;
use skyforge_signals::synth::{ObservationSink, SinkError};
use std::fs::File;
use std::io::BufWriter;
use std::path::{Path, PathBuf};

/// Observation truth interval of the RINEX files (s).
const OBS_INTERVAL_S: f64 = 1.0;

/// `error` with the file it concerns.
fn writing(path: &Path, error: impl std::fmt::Display) -> SinkError {
    format!("cannot write {}: {error}", path.display()).into()
}

type Writer = ObsWriter<BufWriter<File>>;

/// One RINEX observation file per antenna: the observation truth, or the observation
/// level's observables.
#[derive(Debug)]
pub struct ObsFiles {
    paths: Vec<PathBuf>,
    names: Vec<String>,
    signals: Vec<Signal>,
    writers: Vec<Option<Writer>>,
}

impl ObsFiles {
    /// The files `dir/<antenna>.obs.rnx` of `antennas`, declaring `signals`; none is
    /// created before its first epoch.
    pub fn new(dir: &Path, antennas: &[Antenna], signals: &[Signal]) -> Self {
        Self {
            paths: antennas
                .iter()
                .map(|a| dir.join(format!("{}.obs.rnx", a.name)))
                .collect(),
            names: antennas.iter().map(|a| a.name.clone()).collect(),
            signals: signals.to_vec(),
            writers: antennas.iter().map(|_| None).collect(),
        }
    }

    /// Flush and close every file.
    pub fn finish(self) -> Result<(), SinkError> {
        for (path, w) in self.paths.iter().zip(self.writers) {
            if let Some(w) = w {
                w.finish().map_err(|e| writing(path, e))?;
            }
        }
        Ok(())
    }
}

impl ObservationSink for ObsFiles {
    fn epoch(
        &mut self,
        antenna: usize,
        at: hifitime::Epoch,
        position_ecef_m: &Vec3,
        records: &[ObsRecord],
    ) -> Result<(), SinkError> {
        let path = &self.paths[antenna];
        let writer = match &mut self.writers[antenna] {
            Some(w) => w,
            empty => {
                let file = File::create(path).map_err(|e| writing(path, e))?;
                let w = ObsWriter::new(
                    BufWriter::new(file),
                    &self.names[antenna],
                    position_ecef_m,
                    calendar_gpst(at),
                    OBS_INTERVAL_S,
                    &self.signals,
                )
                .map_err(|e| writing(path, e))?;
                empty.insert(w)
            }
        };
        writer
            .epoch(calendar_gpst(at), records)
            .map_err(|e| writing(path, e))
    }
}
