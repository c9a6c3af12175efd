//! A shard's journal: the runs it finished, one JSON line each, flushed as they finish,
//! so that a rerun after a crash makes only the missing runs.

use super::{ResultsError, io};
use crate::study::{RunResult, Shard, Study};
use serde::{Deserialize, Serialize};
use std::io::{BufRead, BufReader, Write};
use std::path::{Path, PathBuf};

/// One JSON line (a journal's own records always serialise).
fn json_line(value: &impl Serialize) -> String {
    serde_json::to_string(value).unwrap_or_default()
}

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

impl Journal {
    /// Open (or start) the journal of `shard` of `study` in `dir`; the runs it holds. A
    /// journal of another study is an error; a last line cut by a crash is dropped.
    pub fn open(
        dir: &Path,
        study: &Study,
        shard: Shard,
    ) -> Result<(Self, Vec<RunResult>), ResultsError> {
        let path = journal_path(dir, shard);
        let head = JournalHead {
            study: study.text.clone(),
            shard: format!("{}/{}", shard.index, shard.count),
        };
        let mut done = Vec::new();
        let mut keep_bytes = 0u64;
        if path.exists() {
            let reader =
                BufReader::new(std::fs::File::open(&path).map_err(|e| io("read", &path, e))?);
            for (n, line) in reader.split(b'\n').enumerate() {
                let line = line.map_err(|e| io("read", &path, e))?;
                if n == 0 {
                    let found: JournalHead = serde_json::from_slice(&line).map_err(|_| {
                        ResultsError::NotThisStudy(format!(
                            "{}: not a study journal",
                            path.display()
                        ))
                    })?;
                    if found.study != head.study || found.shard != head.shard {
                        return Err(ResultsError::NotThisStudy(format!(
                            "{}: the journal of another study or shard ({}); use another --out",
                            path.display(),
                            found.shard
                        )));
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
            .map_err(|e| io("write", &path, e))?;
        let written = if keep_bytes == 0 {
            file.set_len(0)
                .and_then(|()| writeln!(file, "{}", json_line(&head)))
        } else {
            file.set_len(keep_bytes)
        };
        written.map_err(|e| io("write", &path, e))?;
        Ok((Self { path, file }, done))
    }

    /// Append a finished run and flush it to disk.
    pub fn append(&mut self, r: &RunResult) -> Result<(), ResultsError> {
        let line = JournalRun {
            run: r.run,
            bits: r.values.iter().map(|v| v.to_bits()).collect(),
        };
        writeln!(self.file, "{}", json_line(&line))
            .and_then(|()| self.file.sync_data())
            .map_err(|e| io("write", &self.path, e))
    }
}
