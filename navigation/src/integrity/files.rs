//! The monitor over several receivers' observation files, aligned by epoch.

use super::config::MonitorConfig;
use super::monitor::{Monitor, MonitorEpoch, MonitorError, Station, Unmonitored};
use crate::relative::files::records_at;
use skyforge_gnss::observation::ObsFile;
use skyforge_orbits::Vec3;
use skyforge_orbits::check::{GROUND_RADIUS_M, Invalid, check_position};
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
    /// A station's APPROX POSITION XYZ is not on the ground.
    #[error("{file}: {invalid}")]
    Position { file: String, invalid: Invalid },
    #[error(
        "{second}: station name {name:?} is also {first}'s; each station needs its own name \
         (the file name up to its first dot, or [[stations]] name)"
    )]
    SameName {
        name: String,
        first: String,
        second: String,
    },
    #[error(
        "{file}: no epoch in common with {first} ({file}: {file_span}; {first}: {first_span}); \
         the stations must observe at the same times"
    )]
    NoCommonEpoch {
        file: String,
        file_span: String,
        first: String,
        first_span: String,
    },
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
    let list: Vec<Station> = if config.stations.is_empty() {
        files
            .iter()
            .zip(names)
            .map(|(f, name)| {
                let file = f.source.display().to_string();
                let r = f
                    .approx_ecef_m
                    .ok_or_else(|| FilesError::NoPosition(file.clone()))?;
                check_position("APPROX POSITION XYZ", &r.into(), GROUND_RADIUS_M)
                    .map_err(|invalid| FilesError::Position { file, invalid })?;
                Ok(Station {
                    name: name.clone(),
                    r_ecef_m: r,
                })
            })
            .collect::<Result<_, FilesError>>()?
    } else {
        if config.stations.len() != files.len() {
            return Err(FilesError::StationCount {
                files: files.len(),
                stations: config.stations.len(),
            });
        }
        config
            .stations
            .iter()
            .map(|s| Station {
                name: s.name.clone(),
                r_ecef_m: Vec3::from(s.position_ecef_m),
            })
            .collect()
    };
    for (i, station) in list.iter().enumerate() {
        if let Some(j) = list[..i].iter().position(|s| s.name == station.name) {
            let source = |k: usize| files[k].source.display().to_string();
            return Err(FilesError::SameName {
                name: station.name.clone(),
                first: source(j),
                second: source(i),
            });
        }
    }
    Ok(list)
}

/// What [`run_files`] monitored besides the epochs it handed over.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Monitored {
    /// The common point the stations were mapped to (ECEF, m).
    pub common_point_ecef_m: Vec3,
    /// The satellite-epochs it could not monitor, by reason.
    pub unmonitored: Unmonitored,
}

/// The first and last epoch of `f`, for messages.
fn span(f: &ObsFile) -> String {
    match (f.epochs.first(), f.epochs.last()) {
        (Some(a), Some(b)) => format!("{} to {}", a.time, b.time),
        _ => "no epochs".into(),
    }
}

/// Monitor `files` (one per station of `stations`, from [`stations`]) over the epochs of
/// the first, handing each epoch's outcome to `each`; returns the common point used and
/// what could not be monitored. A file whose epochs do not overlap the first's is
/// refused.
pub fn run_files(
    files: &[ObsFile],
    stations: Vec<Station>,
    ephemerides: Vec<BroadcastEphemeris>,
    config: MonitorConfig,
    mut each: impl FnMut(&MonitorEpoch),
) -> Result<Monitored, FilesError> {
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
    let end = first.epochs.last().map_or(start, |e| e.time);
    let apart = |f: &&ObsFile| {
        f.epochs.last().is_some_and(|e| e.time < start)
            || f.epochs.first().is_some_and(|e| e.time > end)
    };
    if let Some(f) = files.iter().find(apart) {
        return Err(FilesError::NoCommonEpoch {
            file: f.source.display().to_string(),
            file_span: span(f),
            first: first.source.display().to_string(),
            first_span: span(first),
        });
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
    Ok(Monitored {
        common_point_ecef_m: monitor.common_point(),
        unmonitored: monitor.unmonitored(),
    })
}
