//! `skyforge study`: run a study or one shard of it (resumable: runs already in the
//! shard's journal are not made again), and merge shards into one file.

use crate::bad_input::BadInput;
use crate::output::slurm_scripts::{
    SlurmJob, refuse_backslash, refuse_control_characters, written_by_skyforge,
};
use crate::output::{staged_dir, whole_file};
use anyhow::Context;
use indicatif::{ProgressBar, ProgressStyle};
use rayon::prelude::*;
use skyforge_orbits::bounded_read::read_text;
use skyforge_studies::study::MERGED_FILE;
use skyforge_studies::study::results::{
    Journal, read_shard, shard_path, shard_study_text, write_merged, write_shard,
};
use skyforge_studies::study::{RunResult, Shard, Study};
use std::collections::HashSet;
use std::path::{Path, PathBuf};
use std::sync::Mutex;

/// Largest study file read.
const STUDY_MAX_BYTES: u64 = 1 << 20;

/// Read and check the study file at `path` (its scenario resolved from its directory).
pub fn load(path: &Path) -> anyhow::Result<Study> {
    let text = read_text(path, STUDY_MAX_BYTES, "study file")
        .map_err(|e| BadInput(format!("{}: cannot read: {e}", path.display())))?;
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => PathBuf::from("."),
    };
    Study::parse(&text, &path.display().to_string(), &dir)
        .map_err(|e| BadInput(e.to_string()).into())
}

/// Whether a study file may be written at `target`: absent, this study's own (a rerun
/// writes the same runs again), or another study's with `force`; never a file that is no
/// study file ([`whole_file::check_target`]).
fn check_study_target(target: &Path, study_text: &str, force: bool) -> Result<(), BadInput> {
    let existing = shard_study_text(target);
    match &existing {
        Ok(text) if text == study_text => Ok(()),
        Ok(_) if !force => Err(BadInput(format!(
            "{}: the file of another study; give --force to replace it, or choose another --out",
            target.display()
        ))),
        _ => whole_file::check_target(target, force, "a study file", |_| existing.is_ok()),
    }
}

/// `skyforge study run STUDY --out DIR [--shard i/n] [--force]`.
pub fn run(path: &Path, out: &Path, shard: Option<&str>, force: bool) -> anyhow::Result<()> {
    let study = load(path)?;
    let shard = shard
        .map(str::parse::<Shard>)
        .transpose()
        .map_err(|e| BadInput(format!("--shard {e}")))?
        .unwrap_or(Shard::WHOLE);
    if out.exists() && !out.is_dir() {
        return Err(BadInput(format!("--out {}: not a directory", out.display())).into());
    }
    staged_dir::create_shared(out)?;
    let shard_file = shard_path(out, shard);
    let merged = out.join(MERGED_FILE);
    for target in std::iter::once(&shard_file).chain((shard == Shard::WHOLE).then_some(&merged)) {
        check_study_target(target, &study.text, force)?;
    }
    let (journal, done) = Journal::open(out, &study, shard)?;
    let mine: Vec<u64> = shard.runs(study.runs()).collect();
    let done_runs: HashSet<u64> = done.iter().map(|r| r.run).collect();
    let pending: Vec<u64> = mine
        .iter()
        .copied()
        .filter(|r| !done_runs.contains(r))
        .collect();
    println!(
        "study      {} ({}): {} points x {} seeds = {} runs",
        study.name,
        study.source,
        study.points(),
        study.seeds,
        study.runs()
    );
    println!(
        "shard      {}/{}: {} runs, {} already done, {} to make",
        shard.index,
        shard.count,
        mine.len(),
        mine.len() - pending.len(),
        pending.len()
    );
    let bar = ProgressBar::new(pending.len() as u64).with_style(
        ProgressStyle::with_template("{spinner} study [{bar:40}] {pos}/{len} runs ({eta} left)")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    let journal = Mutex::new(journal);
    let make = |&r: &u64| -> anyhow::Result<RunResult> {
        let result = study.run(r).map_err(|e| anyhow::anyhow!("{e}"))?;
        journal
            .lock()
            .map_err(|_| anyhow::anyhow!("journal lock poisoned"))?
            .append(&result)?;
        bar.inc(1);
        Ok(result)
    };
    // A signal-level run keeps every core busy itself (synthesis and reception side by
    // side, each parallel inside): such runs go one at a time. Observation-level runs go
    // side by side on every core.
    let made = if study.signal_level() {
        pending
            .iter()
            .map(make)
            .collect::<anyhow::Result<Vec<_>>>()?
    } else {
        pending
            .par_iter()
            .map(make)
            .collect::<anyhow::Result<Vec<_>>>()?
    };
    bar.finish_and_clear();
    let mut runs: Vec<RunResult> = done.into_iter().chain(made).collect();
    runs.sort_by_key(|r| r.run);
    runs.dedup_by_key(|r| r.run);
    write_shard(&shard_file, &study, shard, &runs)?;
    println!("wrote      {}", shard_file.display());
    if shard == Shard::WHOLE {
        let runs = study.merge(vec![runs]).map_err(|e| anyhow::anyhow!(e))?;
        write_merged(&merged, &study, &runs)?;
        print_summary(&study, &runs);
        println!("wrote      {}", merged.display());
    }
    Ok(())
}

/// The shard files in `dirs` (every `shard-*-of-*.h5` of a directory, or a file itself).
fn shard_files(dirs: &[PathBuf]) -> anyhow::Result<Vec<PathBuf>> {
    let mut files = Vec::new();
    for d in dirs {
        if d.is_file() {
            files.push(d.clone());
            continue;
        }
        let entries =
            std::fs::read_dir(d).map_err(|e| BadInput(format!("{}: {e}", d.display())))?;
        let mut found: Vec<PathBuf> = entries
            .filter_map(Result::ok)
            .map(|e| e.path())
            .filter(|p| {
                p.file_name()
                    .and_then(|n| n.to_str())
                    .is_some_and(|n| n.starts_with("shard-") && n.ends_with(".h5"))
            })
            .collect();
        found.sort();
        if found.is_empty() {
            return Err(
                BadInput(format!("{}: no shard files (shard-*-of-*.h5)", d.display())).into(),
            );
        }
        files.extend(found);
    }
    Ok(files)
}

/// `skyforge study merge DIR... [--out FILE] [--force]`.
pub fn merge(dirs: &[PathBuf], out: Option<&Path>, force: bool) -> anyhow::Result<()> {
    let files = shard_files(dirs)?;
    let first = files
        .first()
        .ok_or_else(|| BadInput("no shard files given".into()))?;
    let text = shard_study_text(first)?;
    let study = Study::parse_plan(&text, &first.display().to_string())
        .map_err(|e| BadInput(e.to_string()))?;
    let path = out.map_or_else(|| dirs[0].join(MERGED_FILE), Path::to_path_buf);
    check_study_target(&path, &text, force)?;
    let names: Vec<&str> = study.metrics.iter().map(|m| m.name()).collect();
    let mut parts = Vec::new();
    for f in &files {
        let shard = read_shard(f, &names)?;
        if shard.study_toml != text {
            return Err(BadInput(format!(
                "{}: the shard of another study than {}",
                f.display(),
                first.display()
            ))
            .into());
        }
        parts.push(shard.runs);
    }
    let runs = study
        .merge(parts)
        .map_err(|e| BadInput(format!("merging {} shard files: {e}", files.len())))?;
    write_merged(&path, &study, &runs)?;
    print_summary(&study, &runs);
    println!(
        "merged     {} shard files, {} runs",
        files.len(),
        runs.len()
    );
    println!("wrote      {}", path.display());
    Ok(())
}

/// Per metric, a row per point: runs, mean with its 95 % interval, median, 95th percentile.
fn print_summary(study: &Study, runs: &[RunResult]) {
    let summaries = study.summarise(runs);
    for (m, metric) in study.metrics.iter().enumerate() {
        println!("{} [{}]", metric.name(), metric.unit());
        for (p, s) in summaries.iter().enumerate() {
            let s = &s[m];
            println!(
                "  {:<40} n {:>4}{}  mean {:.4} [{:.4}, {:.4}]  p50 {:.4}  p95 {:.4}",
                study.describe_point(p as u64),
                s.n,
                if s.missing > 0 {
                    format!(" ({} without)", s.missing)
                } else {
                    String::new()
                },
                s.mean,
                s.mean_ci.0,
                s.mean_ci.1,
                s.p50,
                s.p95
            );
        }
    }
}

/// `skyforge study slurm STUDY --out DIR --shards N`: the scripts in DIR/slurm/.
pub fn slurm(
    path: &Path,
    out: &Path,
    shards: u64,
    skyforge: Option<&Path>,
    options: &[String],
    force: bool,
) -> anyhow::Result<()> {
    let study = load(path)?;
    if let Some(bad) = options.iter().find(|o| !o.starts_with('-')) {
        return Err(BadInput(format!(
            "--sbatch {bad:?}: an sbatch option on one line, starting with - (e.g. --partition=short)"
        ))
        .into());
    }

    let absolute = |p: &Path| std::path::absolute(p).with_context(|| format!("{}", p.display()));
    let exe = match skyforge {
        Some(p) => p.to_path_buf(),
        None => std::env::current_exe().context("the path of this skyforge binary")?,
    };
    let (study_path, out) = (absolute(path)?, absolute(out)?);
    // Every path and option the scripts hold: no control character (a newline in --out
    // ran the rest of the path as a command when the job ran).
    let paths = [
        ("--out", &out),
        ("the study file", &study_path),
        ("the skyforge binary", &exe),
    ];
    let paths = paths.map(|(what, p)| (what, p.display().to_string()));
    let sbatch = options.iter().map(|o| ("--sbatch", o.clone()));
    for (what, text) in paths.into_iter().chain(sbatch) {
        refuse_control_characters(what, &text).map_err(BadInput)?;
    }
    refuse_backslash("--out", &out.display().to_string()).map_err(BadInput)?;
    let dir = out.join("slurm");
    const SCRIPTS: [&str; 3] = ["array.sbatch", "merge.sbatch", "submit.sh"];
    if dir.is_dir() {
        for name in SCRIPTS {
            whole_file::check_target(
                &dir.join(name),
                force,
                "a Slurm script",
                written_by_skyforge,
            )?;
        }
    }
    staged_dir::create_shared(&dir)?;
    let job = SlurmJob {
        skyforge: &exe,
        study: &study_path,
        out: &out,
        shards,
        name: &study.name,
        options,
    };
    for (name, text) in SCRIPTS
        .into_iter()
        .zip([job.array(), job.merge(), job.submit()])
    {
        let p = dir.join(name);
        whole_file::write(&p, text.as_bytes())
            .with_context(|| format!("cannot write {}", p.display()))?;
    }
    println!(
        "study      {}: {} runs in {shards} array tasks",
        study.name,
        study.runs()
    );
    println!(
        "wrote      {}/{{array.sbatch, merge.sbatch, submit.sh}}",
        dir.display()
    );
    println!("submit     bash {}", dir.join("submit.sh").display());
    Ok(())
}
