//! The chain over files: several antennas' RINEX observation files (master first), a
//! navigation file and the body geometry. The master's position comes from its own
//! single-point solution, the lines of sight from the broadcast ephemerides.

use super::{RelativeConfig, RelativeEpoch, RelativeError, RelativeSolver};
use crate::baseline::LineOfSight;
use crate::pvt::{Measurement, PvtConfig, predicted_view, solve};
use hifitime::Epoch;
use serde::{Deserialize, Serialize};
use skyforge_orbits::Vec3;
use skyforge_orbits::ephemeris::{BroadcastEphemeris, EphemerisStore};
use skyforge_orbits::time::TimeOrigin;
use skyforge_signals::observation::{ObsFile, ObsRecord};
use std::path::Path;

/// Largest geometry file read (bytes).
const MAX_GEOMETRY_BYTES: u64 = 1 << 20;
/// Epochs of different files closer than this (s) are the same epoch.
const SAME_EPOCH_S: f64 = 1e-6;

/// One antenna of the body geometry.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct GeometryAntenna {
    pub name: String,
    /// Nominal phase-centre position in the body frame (m).
    pub position_body_m: [f64; 3],
}

/// The body geometry file (TOML, `[[antennas]]` with `name` and `position_body_m`, master
/// first), as `skyforge synth` writes it for its scenario.
#[derive(Debug, Clone, PartialEq, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct BodyGeometryFile {
    pub antennas: Vec<GeometryAntenna>,
}

/// Why the files could not be processed.
#[derive(Debug, thiserror::Error)]
pub enum FilesError {
    #[error("{path}: {message}")]
    Geometry { path: String, message: String },
    #[error(
        "{files} observation files for the {geometry} antennas of the geometry file (one file per antenna, in its order)"
    )]
    AntennaCount { files: usize, geometry: usize },
    #[error("{0}: no observation epochs")]
    NoEpochs(String),
    #[error(transparent)]
    Relative(#[from] RelativeError),
}

impl BodyGeometryFile {
    /// Read and check the geometry file at `path`.
    pub fn read(path: &Path) -> Result<Self, FilesError> {
        let error = |message: String| FilesError::Geometry {
            path: path.display().to_string(),
            message,
        };
        let size = std::fs::metadata(path)
            .map_err(|e| error(e.to_string()))?
            .len();
        if size > MAX_GEOMETRY_BYTES {
            return Err(error(format!(
                "{size} bytes; at most {MAX_GEOMETRY_BYTES} are read"
            )));
        }
        let text = std::fs::read_to_string(path).map_err(|e| error(e.to_string()))?;
        let file: Self = toml::from_str(&text).map_err(|e| error(e.to_string()))?;
        if file.antennas.len() < 2 {
            return Err(error(format!(
                "{} antennas; at least two are needed for a baseline",
                file.antennas.len()
            )));
        }
        if let Some(a) = file
            .antennas
            .iter()
            .find(|a| a.position_body_m.iter().any(|v| !v.is_finite()))
        {
            return Err(error(format!(
                "antenna {}: position_body_m is not finite",
                a.name
            )));
        }
        Ok(file)
    }

    /// Body positions, master first.
    pub fn positions(&self) -> Vec<Vec3> {
        self.antennas
            .iter()
            .map(|a| Vec3::from(a.position_body_m))
            .collect()
    }
}

/// One epoch of the master's file and what became of it.
#[derive(Debug)]
pub struct EpochOutcome {
    pub time: Epoch,
    /// The master's single-point position, when it had one.
    pub master_ecef_m: Option<Vec3>,
    /// The chain's result, or why the epoch gave none (a missing antenna, too few
    /// satellites, no position).
    pub result: Result<RelativeEpoch, String>,
}

/// The records of `file` at `time`, if it has that epoch (`cursor` advances through the
/// file's time-ordered epochs).
fn records_at<'f>(file: &'f ObsFile, cursor: &mut usize, time: Epoch) -> Option<&'f [ObsRecord]> {
    while *cursor < file.epochs.len()
        && (file.epochs[*cursor].time - time).to_seconds() < -SAME_EPOCH_S
    {
        *cursor += 1;
    }
    let e = file.epochs.get(*cursor)?;
    ((e.time - time).to_seconds().abs() <= SAME_EPOCH_S).then_some(e.sats.as_slice())
}

/// Run the chain over `files` (one per antenna of `geometry`, same order), handing each
/// master epoch's outcome to `each`.
pub fn run_files(
    files: &[ObsFile],
    ephemerides: Vec<BroadcastEphemeris>,
    geometry: &BodyGeometryFile,
    config: RelativeConfig,
    mut each: impl FnMut(EpochOutcome),
) -> Result<(), FilesError> {
    if files.len() != geometry.antennas.len() {
        return Err(FilesError::AntennaCount {
            files: files.len(),
            geometry: geometry.antennas.len(),
        });
    }
    let master = &files[0];
    let Some(first) = master.epochs.first() else {
        return Err(FilesError::NoEpochs(master.source.display().to_string()));
    };
    let origin = TimeOrigin::new(first.time);
    let store = EphemerisStore::new(ephemerides, &origin);
    let pvt = PvtConfig::default();
    let mut solver = RelativeSolver::new(config, &geometry.positions())?;
    let mut cursors = vec![0usize; files.len()];
    let mut prior: Option<Vec3> = None;
    for epoch in &master.epochs {
        let t_s = origin.seconds_since_start(epoch.time);
        let mut antennas: Vec<&[ObsRecord]> = vec![epoch.sats.as_slice()];
        let mut missing = None;
        for (k, file) in files.iter().enumerate().skip(1) {
            match records_at(file, &mut cursors[k], epoch.time) {
                Some(r) => antennas.push(r),
                None => missing = missing.or(Some(k)),
            }
        }
        let meas: Vec<Measurement> = epoch
            .sats
            .iter()
            .filter(|r| store.select(r.sat, t_s).is_some())
            .filter_map(|r| {
                Some(Measurement {
                    sat: r.sat,
                    pseudorange_m: r.pseudorange_m?,
                    doppler_hz: None,
                    carrier_hz: r.signal.carrier_hz(),
                })
            })
            .collect();
        let fix = solve(&meas, t_s, &store, &origin, &pvt, prior);
        let master_ecef_m = fix.as_ref().ok().map(|f| f.r_ecef_m);
        prior = master_ecef_m.or(prior);
        let result = match (missing, master_ecef_m) {
            (Some(k), _) => Err(format!(
                "antenna {} has no epoch at {}",
                geometry.antennas[k].name, epoch.time
            )),
            (None, None) => Err(format!(
                "no single-point position of the master: {}",
                fix.err().map_or_else(String::new, |e| e.to_string())
            )),
            (None, Some(r)) => {
                let views: Vec<LineOfSight> = epoch
                    .sats
                    .iter()
                    .filter_map(|rec| {
                        let eph = store.select(rec.sat, t_s)?;
                        Some(LineOfSight::from_view(
                            rec.sat,
                            &predicted_view(eph, t_s, &r),
                        ))
                    })
                    .collect();
                solver
                    .epoch(t_s, &antennas, &views, &r)
                    .map_err(|e| e.to_string())
            }
        };
        each(EpochOutcome {
            time: epoch.time,
            master_ecef_m,
            result,
        });
    }
    Ok(())
}
