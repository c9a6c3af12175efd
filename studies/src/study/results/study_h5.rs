//! A study's HDF5 files (docs/study.md): a shard's file, written from its journal once
//! every run is in, and the merged file with the per-point summaries, written in run order
//! without modification times (the same runs give the same bytes); the readers of both.

use super::{
    FORMAT, FORMAT_ATTR, MEAN, MEAN_CI_HIGH, MEAN_CI_LOW, P95, RUN, RUNS_GROUP, ResultsError,
    STUDY_TOML_ATTR, SUMMARY_GROUP, io,
};
use crate::study::{MetricSummary, RunResult, Shard, Study, run_seed};
use hdf5::types::VarLenUnicode;
use hdf5::{File, Group, H5Type};
use skyforge_formats::FormatError;
use skyforge_formats::h5::{create_group, read_column, text_attr};
use skyforge_orbits::bounded_read::starts_with;
use std::path::{Path, PathBuf};

/// A 1-D dataset `name` of `data` in `group`, with its unit.
fn column<T: H5Type>(group: &Group, name: &str, data: &[T], unit: &str) -> hdf5::Result<()> {
    let ds = group
        .new_dataset_builder()
        .obj_track_times(false)
        .with_data(data)
        .create(name)?;
    text_attr(&ds, "units", unit)
}

/// The parts every study file holds: attributes, the points, the runs.
fn write_common(file: &File, study: &Study, shard: &str, runs: &[RunResult]) -> hdf5::Result<()> {
    text_attr(file, FORMAT_ATTR, FORMAT)?;
    text_attr(file, STUDY_TOML_ATTR, &study.text)?;
    text_attr(file, "name", &study.name)?;
    text_attr(file, "shard", shard)?;
    let points = create_group(file, "points")?;
    let described: Vec<VarLenUnicode> = (0..study.points())
        .map(|p| study.describe_point(p).parse().unwrap_or_default())
        .collect();
    column(&points, "description", &described, "")?;
    let group = create_group(file, RUNS_GROUP)?;
    let index: Vec<u64> = runs.iter().map(|r| r.run).collect();
    column(&group, RUN, &index, "1")?;
    let point: Vec<u64> = index.iter().map(|&r| study.point_of(r)).collect();
    column(&group, "point", &point, "1")?;
    let seed: Vec<u64> = index.iter().map(|&r| run_seed(study.seed, r)).collect();
    column(&group, "seed", &seed, "1")?;
    for (m, metric) in study.metrics.iter().enumerate() {
        let values: Vec<f64> = runs.iter().map(|r| r.values[m]).collect();
        column(&group, metric.name(), &values, metric.unit())?;
    }
    Ok(())
}

/// Write `path` through a new file beside it (`.NAME.partial-PID`, never an existing
/// one), renamed over `path` when complete; on any failure only that file is removed.
fn write_atomically(
    path: &Path,
    write: impl FnOnce(&File) -> hdf5::Result<()>,
) -> Result<(), ResultsError> {
    let name = path.file_name().map(|n| n.to_string_lossy().into_owned());
    let tmp = path.with_file_name(format!(
        ".{}.partial-{}",
        name.unwrap_or_default(),
        std::process::id()
    ));
    if std::fs::symlink_metadata(&tmp).is_ok() {
        return Err(ResultsError::Io(format!(
            "cannot write {}: {} exists (another run?)",
            path.display(),
            tmp.display()
        )));
    }
    let written = File::create_excl(&tmp).and_then(|f| {
        write(&f)?;
        f.close()
    });
    if let Err(e) = written {
        let _ = std::fs::remove_file(&tmp);
        return Err(ResultsError::Io(format!(
            "cannot write {}: {e}",
            path.display()
        )));
    }
    std::fs::rename(&tmp, path).map_err(|e| {
        let _ = std::fs::remove_file(&tmp);
        io("write", path, e)
    })
}

/// Write the shard file of `shard` (its runs, sorted).
pub fn write_shard(
    path: &Path,
    study: &Study,
    shard: Shard,
    runs: &[RunResult],
) -> Result<(), ResultsError> {
    write_atomically(path, |f| {
        write_common(f, study, &format!("{}/{}", shard.index, shard.count), runs)
    })
}

/// Write the merged file: every run, and per point and metric the summaries.
pub fn write_merged(path: &Path, study: &Study, runs: &[RunResult]) -> Result<(), ResultsError> {
    let summaries = study.summarise(runs);
    write_atomically(path, |f| {
        write_common(f, study, "merged", runs)?;
        let group = create_group(f, SUMMARY_GROUP)?;
        for (m, metric) in study.metrics.iter().enumerate() {
            let g = create_group(&group, metric.name())?;
            let of = |get: fn(&MetricSummary) -> f64| -> Vec<f64> {
                summaries.iter().map(|p| get(&p[m])).collect()
            };
            let unit = metric.unit();
            let count = |get: fn(&MetricSummary) -> usize| -> Vec<u64> {
                summaries.iter().map(|p| get(&p[m]) as u64).collect()
            };
            column(&g, "n", &count(|s| s.n), "1")?;
            column(&g, "missing", &count(|s| s.missing), "1")?;
            column(&g, MEAN, &of(|s| s.mean), unit)?;
            column(&g, MEAN_CI_LOW, &of(|s| s.mean_ci.0), unit)?;
            column(&g, MEAN_CI_HIGH, &of(|s| s.mean_ci.1), unit)?;
            column(&g, "std", &of(|s| s.std), unit)?;
            column(&g, "p50", &of(|s| s.p50), unit)?;
            column(&g, "p50_ci_low", &of(|s| s.p50_ci.0), unit)?;
            column(&g, "p50_ci_high", &of(|s| s.p50_ci.1), unit)?;
            column(&g, P95, &of(|s| s.p95), unit)?;
            column(&g, "p95_ci_low", &of(|s| s.p95_ci.0), unit)?;
            column(&g, "p95_ci_high", &of(|s| s.p95_ci.1), unit)?;
        }
        Ok(())
    })
}

/// A shard file read back: its study text and runs.
#[derive(Debug)]
pub struct ShardFile {
    pub study_toml: String,
    pub runs: Vec<RunResult>,
}

/// Read the shard file at `path` for the metrics named `metrics`.
pub fn read_shard(path: &Path, metrics: &[&str]) -> Result<ShardFile, ResultsError> {
    let read = || -> hdf5::Result<ShardFile> {
        let f = File::open(path)?;
        let text = |name: &str| -> hdf5::Result<String> {
            Ok(f.attr(name)?
                .read_scalar::<VarLenUnicode>()?
                .as_str()
                .to_string())
        };
        let index: Vec<u64> = f.dataset(&format!("{RUNS_GROUP}/{RUN}"))?.read_raw()?;
        let columns = metrics
            .iter()
            .map(|m| f.dataset(&format!("{RUNS_GROUP}/{m}"))?.read_raw::<f64>())
            .collect::<hdf5::Result<Vec<_>>>()?;
        let runs = index
            .iter()
            .enumerate()
            .map(|(i, &run)| RunResult {
                run,
                values: columns
                    .iter()
                    .map(|c| c.get(i).copied().unwrap_or(f64::NAN))
                    .collect(),
            })
            .collect();
        Ok(ShardFile {
            study_toml: text(STUDY_TOML_ATTR)?,
            runs,
        })
    };
    read().map_err(|e| {
        ResultsError::NotThisStudy(format!(
            "{}: not a study shard file of this study ({e})",
            path.display()
        ))
    })
}

/// The first bytes of every HDF5 file SkyForge writes (no user block).
const HDF5_SIGNATURE: &[u8; 8] = b"\x89HDF\r\n\x1a\n";

/// The study text a study file (a shard's or the merged one) belongs to.
pub fn shard_study_text(path: &Path) -> Result<String, ResultsError> {
    let read = || -> hdf5::Result<String> {
        if !starts_with(path, HDF5_SIGNATURE) {
            return Err("not an HDF5 file".into());
        }
        let f = File::open(path)?;
        let format = f.attr(FORMAT_ATTR)?.read_scalar::<VarLenUnicode>()?;
        if format.as_str() != FORMAT {
            return Err(format!("format {format}").into());
        }
        Ok(f.attr(STUDY_TOML_ATTR)?
            .read_scalar::<VarLenUnicode>()?
            .as_str()
            .to_string())
    };
    read().map_err(|e| {
        ResultsError::NotThisStudy(format!("{}: not a study shard file ({e})", path.display()))
    })
}

/// A merged study file open for reading (the report's figures).
#[derive(Debug)]
pub struct MergedFile {
    file: File,
    path: PathBuf,
}

impl MergedFile {
    /// Open `path` (HDF5).
    pub fn open(path: &Path) -> Result<Self, FormatError> {
        let file = File::open(path)
            .map_err(|e| FormatError::file(path, format!("not readable as HDF5: {e}")))?;
        Ok(Self {
            file,
            path: path.to_path_buf(),
        })
    }

    /// The study file's text the runs were made from.
    pub fn study_toml(&self) -> Result<String, FormatError> {
        self.file
            .attr(STUDY_TOML_ATTR)
            .and_then(|a| a.read_scalar::<VarLenUnicode>())
            .map(|s| s.as_str().to_string())
            .map_err(|e| FormatError::file(&self.path, format!("attribute {STUDY_TOML_ATTR}: {e}")))
    }

    /// Statistic `stat` ([`super::MEAN`] and the like) of `metric` at each of `points`
    /// grid points.
    pub fn summary(
        &self,
        metric: &str,
        stat: &str,
        points: usize,
    ) -> Result<Vec<f64>, FormatError> {
        let name = format!("{SUMMARY_GROUP}/{metric}/{stat}");
        let v: Vec<f64> = read_column(&self.file, &self.path, &name, points)?;
        if v.len() != points {
            return Err(FormatError::file(
                &self.path,
                format!("{name} has {} values for {points} points", v.len()),
            ));
        }
        Ok(v)
    }
}
