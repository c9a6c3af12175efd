//! The monitor over several receivers' observation files, aligned by epoch.

use super::config::MonitorConfig;
use super::monitor::{Monitor, MonitorEpoch, MonitorError, Station};
use crate::relative::files::records_at;
use skyforge_gnss::observation::ObsFile;
use skyforge_orbits::Vec3;
use skyforge_orbits::ephemeris::BroadcastEphemeris;
use skyforge_orbits::time::TimeOrigin;

/// Why the files could not be monitored.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum FilesError {
    #[error("{0}: no observation epochs")]
    NoEpochs(String),
    #[error(
        "{0}: no APPROX POSITION XYZ in its header; give the station positions in the configuration ([[stations]])"
    )]
    NoPosition(String),
    #[error("{files} observation files but {stations} [[stations]] in the configuration")]
    StationCount { files: usize, stations: usize },
    #[error(transparent)]
    Monitor(#[from] MonitorError),
}

/// The stations of `files` named `names`: positions from the configuration's
/// `[[stations]]` (in file order; their names win) or else each file's header.
pub fn stations(
    files: &[ObsFile],
    names: &[String],
    config: &MonitorConfig,
) -> Result<Vec<Station>, FilesError> {
    if !config.stations.is_empty() {
        if config.stations.len() != files.len() {
            return Err(FilesError::StationCount {
                files: files.len(),
                stations: config.stations.len(),
            });
        }
        return Ok(config
            .stations
            .iter()
            .map(|s| Station {
                name: s.name.clone(),
                r_ecef_m: Vec3::from(s.position_ecef_m),
            })
            .collect());
    }
    files
        .iter()
        .zip(names)
        .map(|(f, name)| {
            let r = f
                .approx_ecef_m
                .ok_or_else(|| FilesError::NoPosition(f.source.display().to_string()))?;
            Ok(Station {
                name: name.clone(),
                r_ecef_m: r,
            })
        })
        .collect()
}

/// Monitor `files` (one per station of `stations`, from [`stations`]) over the epochs of
/// the first, handing each epoch's outcome to `each`; returns the common point used.
pub fn run_files(
    files: &[ObsFile],
    stations: Vec<Station>,
    ephemerides: Vec<BroadcastEphemeris>,
    config: MonitorConfig,
    mut each: impl FnMut(&MonitorEpoch),
) -> Result<Vec3, FilesError> {
    let first = files
        .first()
        .ok_or(MonitorError::TooFewStations(0))
        .map_err(FilesError::from)?;
    let start = first
        .epochs
        .first()
        .ok_or_else(|| FilesError::NoEpochs(first.source.display().to_string()))?
        .time;
    if let Some(empty) = files.iter().find(|f| f.epochs.is_empty()) {
        return Err(FilesError::NoEpochs(empty.source.display().to_string()));
    }
    let common = config.common_point_ecef_m.map(Vec3::from);
    let mut monitor = Monitor::new(
        config,
        stations,
        common,
        ephemerides,
        TimeOrigin::new(start),
    )?;
    let mut cursors = vec![0usize; files.len()];
    for epoch in &first.epochs {
        let records: Vec<_> = files
            .iter()
            .zip(cursors.iter_mut())
            .map(|(f, c)| records_at(f, c, epoch.time).map(|(_, r)| r))
            .collect();
        each(&monitor.epoch(epoch.time, &records));
    }
    Ok(monitor.common_point())
}
