//! A study's files (docs/study.md): the journal a shard appends each finished run to (so a
//! rerun after a crash makes only the missing runs), the shard's HDF5 file written from it
//! once every run is in, and the merged HDF5 file with the per-point summaries. Files are
//! written in run order without modification times: the same runs give the same bytes.

use anyhow::Context;
use hdf5::types::VarLenUnicode;
use hdf5::{File, Group, H5Type};
use serde::{Deserialize, Serialize};
use skyforge_formats::h5::{create_group, text_attr};
use skyforge_studies::study::{MetricSummary, RunResult, Shard, Study, run_seed};
use std::io::{BufRead, BufReader, Write};
use std::path::{Path, PathBuf};

/// The `format` attribute of a study file.
const FORMAT: &str = "skyforge-study 1";
pub use skyforge_studies::study::MERGED_FILE;

/// The journal's first line: the study it belongs to.
#[derive(Debug, Serialize, Deserialize)]
struct JournalHead {
    study: String,
    shard: String,
}

/// One finished run; the values as their IEEE 754 bits, so that they come back exactly.
#[derive(Debug, Serialize, Deserialize)]
struct JournalRun {
    run: u64,
    bits: Vec<u64>,
}

/// The journal of a shard: finished runs, one JSON line each, flushed as they finish.
#[derive(Debug)]
pub struct Journal {
    path: PathBuf,
    file: std::fs::File,
}

/// The journal's path in `dir`.
fn journal_path(dir: &Path, shard: Shard) -> PathBuf {
    dir.join(format!("{}.runs.jsonl", shard.tag()))
}

/// The shard file's path in `dir`.
pub fn shard_path(dir: &Path, shard: Shard) -> PathBuf {
    dir.join(format!("{}.h5", shard.tag()))
}

impl Journal {
    /// Open (or start) the journal of `shard` of `study` in `dir`; the runs it holds. A
    /// journal of another study is an error; a last line cut by a crash is dropped.
    pub fn open(dir: &Path, study: &Study, shard: Shard) -> anyhow::Result<(Self, Vec<RunResult>)> {
        let path = journal_path(dir, shard);
        let head = JournalHead {
            study: study.text.clone(),
            shard: format!("{}/{}", shard.index, shard.count),
        };
        let mut done = Vec::new();
        let mut keep_bytes = 0u64;
        if path.exists() {
            let reader = BufReader::new(
                std::fs::File::open(&path)
                    .with_context(|| format!("cannot read {}", path.display()))?,
            );
            for (n, line) in reader.split(b'\n').enumerate() {
                let line = line.with_context(|| format!("cannot read {}", path.display()))?;
                if n == 0 {
                    let found: JournalHead = serde_json::from_slice(&line).map_err(|_| {
                        crate::bad_input::BadInput(format!(
                            "{}: not a study journal",
                            path.display()
                        ))
                    })?;
                    if found.study != head.study || found.shard != head.shard {
                        return Err(crate::bad_input::BadInput(format!(
                            "{}: the journal of another study or shard ({}); use another --out",
                            path.display(),
                            found.shard
                        ))
                        .into());
                    }
                } else {
                    let Ok(run) = serde_json::from_slice::<JournalRun>(&line) else {
                        break; // cut by a crash: the run is made again
                    };
                    done.push(RunResult {
                        run: run.run,
                        values: run.bits.iter().map(|&b| f64::from_bits(b)).collect(),
                    });
                }
                keep_bytes += line.len() as u64 + 1;
            }
        }
        let mut file = std::fs::OpenOptions::new()
            .create(true)
            .append(true)
            .open(&path)
            .with_context(|| format!("cannot write {}", path.display()))?;
        if keep_bytes == 0 {
            file.set_len(0)?;
            writeln!(file, "{}", serde_json::to_string(&head)?)?;
        } else {
            file.set_len(keep_bytes)
                .with_context(|| format!("cannot write {}", path.display()))?;
        }
        Ok((Self { path, file }, done))
    }

    /// Append a finished run and flush it to disk.
    pub fn append(&mut self, r: &RunResult) -> anyhow::Result<()> {
        let line = JournalRun {
            run: r.run,
            bits: r.values.iter().map(|v| v.to_bits()).collect(),
        };
        writeln!(self.file, "{}", serde_json::to_string(&line)?)
            .and_then(|()| self.file.sync_data())
            .with_context(|| format!("cannot write {}", self.path.display()))
    }
}

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
    text_attr(file, "format", FORMAT)?;
    text_attr(file, "study_toml", &study.text)?;
    text_attr(file, "name", &study.name)?;
    text_attr(file, "shard", shard)?;
    let points = create_group(file, "points")?;
    let described: Vec<VarLenUnicode> = (0..study.points())
        .map(|p| study.describe_point(p).parse().unwrap_or_default())
        .collect();
    column(&points, "description", &described, "")?;
    let group = create_group(file, "runs")?;
    let index: Vec<u64> = runs.iter().map(|r| r.run).collect();
    column(&group, "run", &index, "1")?;
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

/// Write `path` (through a temporary file beside it, renamed when complete).
fn write_atomically(
    path: &Path,
    write: impl FnOnce(&File) -> hdf5::Result<()>,
) -> anyhow::Result<()> {
    let tmp = path.with_extension("h5.partial");
    let written = File::create(&tmp).and_then(|f| {
        write(&f)?;
        f.close()
    });
    if let Err(e) = written {
        let _ = std::fs::remove_file(&tmp);
        return Err(anyhow::anyhow!("cannot write {}: {e}", path.display()));
    }
    std::fs::rename(&tmp, path).with_context(|| format!("cannot write {}", path.display()))
}

/// Write the shard file of `shard` (its runs, sorted).
pub fn write_shard(
    path: &Path,
    study: &Study,
    shard: Shard,
    runs: &[RunResult],
) -> anyhow::Result<()> {
    write_atomically(path, |f| {
        write_common(f, study, &format!("{}/{}", shard.index, shard.count), runs)
    })
}

/// Write the merged file: every run, and per point and metric the summaries.
pub fn write_merged(path: &Path, study: &Study, runs: &[RunResult]) -> anyhow::Result<()> {
    let summaries = study.summarise(runs);
    write_atomically(path, |f| {
        write_common(f, study, "merged", runs)?;
        let group = create_group(f, "summary")?;
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
            column(&g, "mean", &of(|s| s.mean), unit)?;
            column(&g, "mean_ci_low", &of(|s| s.mean_ci.0), unit)?;
            column(&g, "mean_ci_high", &of(|s| s.mean_ci.1), unit)?;
            column(&g, "std", &of(|s| s.std), unit)?;
            column(&g, "p50", &of(|s| s.p50), unit)?;
            column(&g, "p50_ci_low", &of(|s| s.p50_ci.0), unit)?;
            column(&g, "p50_ci_high", &of(|s| s.p50_ci.1), unit)?;
            column(&g, "p95", &of(|s| s.p95), unit)?;
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
pub fn read_shard(path: &Path, metrics: &[&str]) -> anyhow::Result<ShardFile> {
    let read = || -> hdf5::Result<ShardFile> {
        let f = File::open(path)?;
        let text = |name: &str| -> hdf5::Result<String> {
            Ok(f.attr(name)?
                .read_scalar::<VarLenUnicode>()?
                .as_str()
                .to_string())
        };
        let index: Vec<u64> = f.dataset("runs/run")?.read_raw()?;
        let columns = metrics
            .iter()
            .map(|m| f.dataset(&format!("runs/{m}"))?.read_raw::<f64>())
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
            study_toml: text("study_toml")?,
            runs,
        })
    };
    read().map_err(|e| {
        crate::bad_input::BadInput(format!(
            "{}: not a study shard file of this study ({e})",
            path.display()
        ))
        .into()
    })
}

/// The study text a shard file belongs to.
pub fn shard_study_text(path: &Path) -> anyhow::Result<String> {
    let read = || -> hdf5::Result<String> {
        let f = File::open(path)?;
        let format = f.attr("format")?.read_scalar::<VarLenUnicode>()?;
        if format.as_str() != FORMAT {
            return Err(format!("format {format}").into());
        }
        Ok(f.attr("study_toml")?
            .read_scalar::<VarLenUnicode>()?
            .as_str()
            .to_string())
    };
    read().map_err(|e| {
        crate::bad_input::BadInput(format!("{}: not a study shard file ({e})", path.display()))
            .into()
    })
}
