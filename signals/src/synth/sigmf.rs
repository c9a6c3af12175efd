//! SigMF recordings of a synthesis: the metadata of one antenna's recording of a band
//! ([`RunInfo::meta`]), and [`SigmfRecordings`], the sample sink of a synthesis session
//! that writes one `<antenna>.<tag>.sigmf-data` + `.sigmf-meta` pair per antenna and band.
//! The format itself (key names, the metadata document) is [`skyforge_gnss::sigmf`].

use super::session::{Band, RunInfo, SampleSink, SinkError};
use crate::antenna::Antenna;
use skyforge_gnss::sigmf::RecordingMeta;
use skyforge_gnss::sigmf::format_utc;
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

/// Bytes gathered per write to a recording: a 1 ms block is about 10 kB, more than a
/// default buffer holds, so without this every block would be a system call of its own.
const WRITE_BUFFER_BYTES: usize = 1 << 20;

/// The file-name stem of antenna `antenna`'s recording of `band`: `<antenna>.<tag>`.
pub fn recording_name(antenna: &str, band: &Band) -> String {
    format!("{antenna}.{}", band.tag())
}

impl RunInfo {
    /// The metadata of antenna `antenna`'s recording of `band` (nominal body position
    /// `position_body_m`).
    pub fn meta(&self, band: &Band, antenna: &str, position_body_m: [f64; 3]) -> RecordingMeta {
        RecordingMeta {
            format: self.format,
            sample_rate_hz: self.sample_rate_hz,
            centre_frequency_hz: band.signal().carrier_hz() - self.if_hz,
            if_hz: self.if_hz,
            datetime_utc: format_utc(self.start),
            antenna_name: antenna.to_owned(),
            antenna_position_body_m: position_body_m,
            scenario: self.scenario.clone(),
            seed: self.seed,
            vehicle: self.vehicle.clone(),
            description: format!(
                "SkyForge synthesis of {} for antenna {antenna}: {}",
                self.scenario,
                band.name()
            ),
            signals: band.signals().to_vec(),
        }
    }
}

/// The sample files of a synthesis: one per band and antenna, in a directory.
#[derive(Debug)]
pub struct SigmfRecordings {
    dir: PathBuf,
    bands: Vec<Band>,
    antennas: Vec<(String, [f64; 3])>,
    /// `files[band][antenna]`.
    files: Vec<Vec<(PathBuf, BufWriter<File>)>>,
}

impl SigmfRecordings {
    /// Create the (empty) data files of every band and antenna in `dir`.
    pub fn create(dir: &Path, bands: &[Band], antennas: &[Antenna]) -> std::io::Result<Self> {
        let files = bands
            .iter()
            .map(|b| {
                antennas
                    .iter()
                    .map(|a| {
                        let path = dir.join(format!("{}.sigmf-data", recording_name(&a.name, b)));
                        let file = File::create(&path).map_err(|e| named(&path, e))?;
                        Ok((path, BufWriter::with_capacity(WRITE_BUFFER_BYTES, file)))
                    })
                    .collect::<std::io::Result<Vec<_>>>()
            })
            .collect::<std::io::Result<Vec<_>>>()?;
        Ok(Self {
            dir: dir.to_path_buf(),
            bands: bands.to_vec(),
            antennas: antennas
                .iter()
                .map(|a| (a.name.clone(), a.nominal_body_m.into()))
                .collect(),
            files,
        })
    }

    /// Flush the data files and write each one's `.sigmf-meta`.
    pub fn finish(self, run: &RunInfo) -> std::io::Result<()> {
        for (path, mut f) in self.files.into_iter().flatten() {
            f.flush().map_err(|e| named(&path, e))?;
        }
        for band in &self.bands {
            for (antenna, position) in &self.antennas {
                let name = recording_name(antenna, band);
                let meta = run.meta(band, antenna, *position);
                let path = self.dir.join(format!("{name}.sigmf-meta"));
                std::fs::write(&path, meta.to_text()).map_err(|e| named(&path, e))?;
            }
        }
        Ok(())
    }
}

impl SampleSink for SigmfRecordings {
    fn samples(&mut self, band: usize, antenna: usize, bytes: &[u8]) -> Result<(), SinkError> {
        let (path, file) = &mut self.files[band][antenna];
        file.write_all(bytes).map_err(|e| named(path, e))?;
        Ok(())
    }
}

/// `e` with the file it happened on.
fn named(path: &Path, e: std::io::Error) -> std::io::Error {
    std::io::Error::new(e.kind(), format!("cannot write {}: {e}", path.display()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use hifitime::Epoch;
    use skyforge_gnss::sample_format::SampleFormat;
    use skyforge_gnss::signal::Signal;

    /// The file `skyforge synth` wrote for this run before the format moved to
    /// `skyforge_gnss::sigmf`.
    const RI8_BDS_TEXT: &str = r#"{
  "annotations": [],
  "captures": [
    {
      "core:datetime": "2024-02-29T23:59:59.123456789Z",
      "core:frequency": 1557006000.0,
      "core:sample_start": 0
    }
  ],
  "global": {
    "core:datatype": "ri8",
    "core:description": "SkyForge synthesis of static-bds for antenna ant2: BDS B1I",
    "core:extensions": [
      {
        "name": "skyforge",
        "optional": true,
        "version": "1.0.0"
      }
    ],
    "core:num_channels": 1,
    "core:recorder": "skyforge 0.1.0",
    "core:sample_rate": 16368000.0,
    "core:version": "1.0.0",
    "skyforge:antenna": "ant2",
    "skyforge:antenna_position_body_m": [
      0.5,
      -0.25,
      0.1
    ],
    "skyforge:if_hz": 4092000.0,
    "skyforge:scenario": "static-bds",
    "skyforge:seed": 42
  }
}
"#;

    #[test]
    fn a_run_writes_the_metadata_it_always_wrote() {
        let run = RunInfo {
            format: SampleFormat::Ri8,
            sample_rate_hz: 16.368e6,
            if_hz: 4.092e6,
            start: Epoch::from_gregorian_utc(2024, 2, 29, 23, 59, 59, 123_456_789),
            scenario: "static-bds".into(),
            seed: 42,
            vehicle: None,
        };
        let band = Band::new(Signal::BdsB1I, 0, 3);
        assert_eq!(recording_name("ant2", &band), "ant2.bds-b1i");
        let meta = run.meta(&band, "ant2", [0.5, -0.25, 0.1]);
        // Captured at version 0.1.0; the recorder is this build's.
        let expected = RI8_BDS_TEXT.replace(
            "\"skyforge 0.1.0\"",
            &format!("\"{}\"", skyforge_gnss::sigmf::RECORDER),
        );
        assert_eq!(meta.to_text(), expected);
    }
}
