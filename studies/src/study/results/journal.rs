//! A shard's journal: the runs it finished, one JSON line each, flushed as they finish,
//! so that a rerun after a crash makes only the missing runs. One process at a time holds
//! a shard ([`ShardLock`]): a second (a requeued Slurm task overlapping the first) is
//! refused before it touches the journal.

use super::{ResultsError, io};
use crate::study::{RunResult, Shard, Study};
use serde::{Deserialize, Serialize};
use std::io::{BufRead, BufReader, Read, Write};
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
    /// Held as long as the journal is open.
    _lock: ShardLock,
}

/// An exclusive lock on `shard-<i>-of-<n>.lock` (`flock`), which the operating system
/// releases when the process ends however it ends (no stale lock after a kill or a lost
/// node); the holder's host and process id are written inside for the message that
/// refuses a second holder.
#[derive(Debug)]
struct ShardLock {
    _file: std::fs::File,
}

impl ShardLock {
    fn take(dir: &Path, shard: Shard) -> Result<Self, ResultsError> {
        let path = dir.join(format!("{}.lock", shard.tag()));
        let mut file = std::fs::OpenOptions::new()
            .read(true)
            .write(true)
            .create(true)
            .truncate(false)
            .open(&path)
            .map_err(|e| io("write", &path, e))?;
        match file.try_lock() {
            Ok(()) => {}
            Err(std::fs::TryLockError::WouldBlock) => {
                let mut holder = String::new();
                let _ = (&file).take(200).read_to_string(&mut holder);
                return Err(ResultsError::Busy(format!(
                    "{}: shard {}/{} is being made by another process ({}); wait for it, or \
                     stop it, before running this shard again",
                    path.display(),
                    shard.index,
                    shard.count,
                    holder.trim()
                )));
            }
            Err(std::fs::TryLockError::Error(e)) => return Err(io("lock", &path, e)),
        }
        let host = std::fs::read_to_string("/proc/sys/kernel/hostname")
            .map_or_else(|_| "an unknown host".to_string(), |h| h.trim().to_string());
        file.set_len(0)
            .and_then(|()| writeln!(file, "host {host}, process {}", std::process::id()))
            .map_err(|e| io("write", &path, e))?;
        Ok(Self { _file: file })
    }
}

/// Whether the file at `path` goes on past byte `end` (a line ending there has its
/// newline: it was written whole).
fn goes_on_past(path: &Path, end: u64) -> bool {
    std::fs::metadata(path).is_ok_and(|m| m.len() > end)
}

/// The journal's path in `dir`.
fn journal_path(dir: &Path, shard: Shard) -> PathBuf {
    dir.join(format!("{}.runs.jsonl", shard.tag()))
}

impl Journal {
    /// Open (or start) the journal of `shard` of `study` in `dir`, holding the shard's
    /// lock; the runs it holds. A journal of another study, or naming a run that is not
    /// one of this shard's, is an error; a last line cut by a crash is dropped (the head
    /// line too: the journal starts again).
    pub fn open(
        dir: &Path,
        study: &Study,
        shard: Shard,
    ) -> Result<(Self, Vec<RunResult>), ResultsError> {
        let lock = ShardLock::take(dir, shard)?;
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
            let mut lines = reader.split(b'\n').enumerate().peekable();
            while let Some((n, line)) = lines.next() {
                let line = line.map_err(|e| io("read", &path, e))?;
                if lines.peek().is_none() && !goes_on_past(&path, keep_bytes + line.len() as u64) {
                    break; // the last line, cut by a crash
                }
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
                    if !shard.holds(run.run, study.runs()) {
                        return Err(ResultsError::NotThisStudy(format!(
                            "{}:{}: run {} is not a run of shard {}/{} of this study ({} runs)",
                            path.display(),
                            n + 1,
                            run.run,
                            shard.index,
                            shard.count,
                            study.runs()
                        )));
                    }
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
        Ok((
            Self {
                path,
                file,
                _lock: lock,
            },
            done,
        ))
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
