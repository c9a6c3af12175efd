//! SigMF 1.x recordings: the metadata (`.sigmf-meta`) of one antenna's recording, and
//! [`SigmfRecordings`], the sample sink of a synthesis session that writes one
//! `<antenna>.<tag>.sigmf-data` + `.sigmf-meta` pair per antenna and band.

use super::session::{Band, RunInfo, SampleSink, SinkError};
use crate::antenna::Antenna;
use hifitime::Epoch;
use serde_json::{Value, json};
use skyforge_gnss::sample_format::SampleFormat;
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

/// Bytes gathered per write to a recording: a 1 ms block is about 10 kB, more than a
/// default buffer holds, so without this every block would be a system call of its own.
const WRITE_BUFFER_BYTES: usize = 1 << 20;

/// What a recording's metadata says.
#[derive(Debug, Clone, PartialEq)]
pub struct RecordingMeta {
    pub format: SampleFormat,
    pub sample_rate_hz: f64,
    /// Centre frequency of the recorded band (Hz): the carrier minus the IF.
    pub centre_frequency_hz: f64,
    /// Intermediate frequency of the signal within the recording (Hz, 0 for baseband).
    pub if_hz: f64,
    /// ISO-8601 UTC time of the first sample.
    pub datetime_utc: String,
    pub antenna_name: String,
    /// Nominal antenna position in the body frame (m).
    pub antenna_position_body_m: [f64; 3],
    pub scenario: String,
    pub seed: u64,
    pub description: String,
}

impl RecordingMeta {
    /// The `.sigmf-meta` JSON document (`core` namespace plus a `skyforge` extension).
    pub fn to_json(&self) -> Value {
        json!({
            "global": {
                "core:datatype": self.format.sigmf_datatype(),
                "core:sample_rate": self.sample_rate_hz,
                "core:version": "1.0.0",
                "core:num_channels": 1,
                "core:description": self.description,
                "core:recorder": concat!("skyforge ", env!("CARGO_PKG_VERSION")),
                "core:extensions": [{"name": "skyforge", "version": "1.0.0", "optional": true}],
                "skyforge:scenario": self.scenario,
                "skyforge:seed": self.seed,
                "skyforge:antenna": self.antenna_name,
                "skyforge:antenna_position_body_m": self.antenna_position_body_m,
                "skyforge:if_hz": self.if_hz,
            },
            "captures": [{
                "core:sample_start": 0,
                "core:frequency": self.centre_frequency_hz,
                "core:datetime": self.datetime_utc,
            }],
            "annotations": [],
        })
    }
}

/// SigMF `core:datetime` of `at`: ISO-8601 UTC with nanoseconds and a trailing Z.
pub fn sigmf_datetime(at: Epoch) -> String {
    let (y, mo, d, h, mi, sec, ns) = at.to_gregorian_utc();
    format!("{y:04}-{mo:02}-{d:02}T{h:02}:{mi:02}:{sec:02}.{ns:09}Z")
}

/// The file-name stem of antenna `antenna`'s recording of `band`: `<antenna>.<tag>`.
pub fn recording_name(antenna: &str, band: &Band) -> String {
    format!("{antenna}.{}", band.signal.tag())
}

impl RunInfo {
    /// The metadata of antenna `antenna`'s recording of `band` (nominal body position
    /// `position_body_m`).
    pub fn meta(&self, band: &Band, antenna: &str, position_body_m: [f64; 3]) -> RecordingMeta {
        RecordingMeta {
            format: self.format,
            sample_rate_hz: self.sample_rate_hz,
            centre_frequency_hz: band.signal.carrier_hz() - self.if_hz,
            if_hz: self.if_hz,
            datetime_utc: sigmf_datetime(self.start),
            antenna_name: antenna.to_owned(),
            antenna_position_body_m: position_body_m,
            scenario: self.scenario.clone(),
            seed: self.seed,
            description: format!(
                "SkyForge synthesis of {} for antenna {antenna}: {}",
                self.scenario,
                band.signal.name()
            ),
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
                let text =
                    serde_json::to_string_pretty(&meta.to_json()).map_err(std::io::Error::other)?;
                std::fs::write(&path, text + "\n").map_err(|e| named(&path, e))?;
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

    #[test]
    fn has_the_core_fields_sigmf_readers_need() {
        let meta = RecordingMeta {
            format: SampleFormat::Ci8,
            sample_rate_hz: 4.092e6,
            centre_frequency_hz: 1575.42e6,
            if_hz: 0.0,
            datetime_utc: "2023-03-12T00:00:00.000Z".into(),
            antenna_name: "ant1".into(),
            antenna_position_body_m: [0.0, 1.0, 0.0],
            scenario: "thesis-leo".into(),
            seed: 3,
            description: "test".into(),
        };
        let v = meta.to_json();
        assert_eq!(v["global"]["core:datatype"], "ci8");
        assert_eq!(v["global"]["core:sample_rate"], 4.092e6);
        assert_eq!(v["captures"][0]["core:frequency"], 1575.42e6);
        assert_eq!(v["captures"][0]["core:sample_start"], 0);
        assert!(v["annotations"].as_array().unwrap().is_empty());
        // Every non-core global key belongs to a declared extension.
        let declared: Vec<&str> = v["global"]["core:extensions"]
            .as_array()
            .unwrap()
            .iter()
            .map(|e| e["name"].as_str().unwrap())
            .collect();
        for key in v["global"].as_object().unwrap().keys() {
            let ns = key.split(':').next().unwrap();
            assert!(ns == "core" || declared.contains(&ns), "{key}");
        }
    }
}
