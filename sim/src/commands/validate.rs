//! `skyforge validate thesis`, `obs`, `attitude`, `monitor`, `od` and `relnav`.

use crate::bad_input::BadInput;
use crate::output::staged_dir::StagedDir;
use crate::output::whole_file;
use anyhow::Context;
use hifitime::Epoch;
use skyforge_formats::imu::{IMU_H5, read_h5};
use skyforge_formats::ins::{INS_CSV, read_ins_csv};
use skyforge_formats::interference::{INTERFERENCE_CSV, read_interference_csv};
use skyforge_formats::monitor::{MONITOR_CSV, read_monitor_csv};
use skyforge_formats::orbit::ORBIT_H5;
use skyforge_formats::relative::{RELATIVE_CSV, RELNAV_CSV};
use skyforge_formats::truth::{TRUTH_H5, TruthFile};
use skyforge_validate::attitude::compare_outputs;
use skyforge_validate::attitude::print_validation;
use skyforge_validate::draw::Agreement;
use skyforge_validate::draw::SeedPlan;
use skyforge_validate::ins::{compare_ins, print_ins};
use skyforge_validate::integrity::{check_same_run, print_score, run_scenario, score};
use skyforge_validate::interference::{print_jamming, score_jamming};
use skyforge_validate::observables::compare::{
    CompareOptions, SampleSpan, SignalComparison, compare_signals,
};
use skyforge_validate::observables::table::print_comparison;
use skyforge_validate::orbit::{compare_orbit, print_orbit};
use skyforge_validate::relnav::{compare_relnav, print_relnav};
use skyforge_validate::report::{Verdict, parse_results, print_table, write_json};
use skyforge_validate::thesis::curves::{CURVES_FILE, CurvesFile};
use skyforge_validate::thesis::{self, Options};
use std::path::{Path, PathBuf};
use std::str::FromStr;

/// Default real-data folder, relative to the working directory.
const DEFAULT_DATA_DIR: &str = "../shared/data";

/// Run the thesis tables, print them and optionally write `results.json` and, when the
/// tables compute thesis figures, their data in `curves.json` (on the registered seeds).
pub fn thesis(
    only: Vec<String>,
    out: Option<&Path>,
    force: bool,
    data: Option<PathBuf>,
    plan: Option<SeedPlan>,
) -> anyhow::Result<()> {
    let data_dir = data
        .or_else(|| std::env::var_os("SKYFORGE_DATA").map(PathBuf::from))
        .unwrap_or_else(|| PathBuf::from(DEFAULT_DATA_DIR));
    if let Some(id) = only.iter().find(|id| !thesis::known(id)) {
        return Err(BadInput(format!(
            "unknown table {id:?}; known tables: {}",
            thesis::TABLES.join(", ")
        ))
        .into());
    }
    let staged = out.map(|dir| StagedDir::create(dir, force)).transpose()?;
    let opts = Options {
        only,
        data_dir: Some(data_dir),
        plan,
    };
    let outcome = thesis::run(&opts, |table| eprintln!("validate: running {table}"))?;
    print_table(&outcome.results.rows, &mut std::io::stdout().lock())?;
    if let Some(staged) = staged {
        let path = staged.file("results.json");
        write_json(&outcome.results, &path)
            .with_context(|| format!("cannot write {}", path.display()))?;
        let mut written = vec!["results.json"];
        if !outcome.curves.is_empty() {
            let curves = CurvesFile {
                curves: outcome.curves,
            };
            let path = staged.file(CURVES_FILE);
            std::fs::write(&path, curves.to_json()?)
                .with_context(|| format!("cannot write {}", path.display()))?;
            written.push(CURVES_FILE);
        }
        let dir = staged.commit()?;
        for name in written {
            println!("wrote {}", dir.join(name).display());
        }
    }
    Ok(())
}

/// The rows of a `results.json` (or of `DIR/results.json`).
fn results_rows(path: &Path) -> anyhow::Result<Vec<skyforge_validate::report::Row>> {
    let file = if path.is_dir() {
        path.join("results.json")
    } else {
        path.to_path_buf()
    };
    let text = std::fs::read_to_string(&file)
        .map_err(|e| BadInput(format!("{}: cannot read: {e}", file.display())))?;
    let (_, rows) = parse_results(&text).map_err(|e| {
        BadInput(format!(
            "{}: line {}, column {}: {e}",
            file.display(),
            e.line(),
            e.column()
        ))
    })?;
    Ok(rows)
}

/// Print two `validate thesis --seeds` runs side by side ([`Agreement`]).
pub fn agree(first: &Path, second: &Path) -> anyhow::Result<()> {
    let agreement = Agreement::of(&results_rows(first)?, &results_rows(second)?);
    if agreement.rows.is_empty() {
        return Err(BadInput(
            "no row over seeds in both runs (run validate thesis with --seeds)".into(),
        )
        .into());
    }
    let mut out = std::io::stdout().lock();
    let word = |v: Verdict| match v {
        Verdict::Reproduced => "reproduced",
        Verdict::Explained => "explained",
        Verdict::Deviates => "deviates",
    };
    use std::io::Write;
    writeln!(
        out,
        "{:<8} {:<52} {:>22} {:>22}  far from the bar",
        "table", "row", "first", "second"
    )?;
    for r in &agreement.rows {
        let cell = |k: usize| format!("{} {:.2}", word(r.verdicts[k]), r.in_tolerance[k]);
        writeln!(
            out,
            "{:<8} {:<52} {:>22} {:>22}  {}",
            r.table,
            r.row,
            cell(0),
            cell(1),
            if r.settled { "yes" } else { "no" }
        )?;
    }
    let settled = agreement.rows.iter().filter(|r| r.settled).count();
    let off = agreement.settled_disagreements();
    writeln!(
        out,
        "{} rows over seeds in both; {settled} far from the bar in both; {} of them with other verdicts{}",
        agreement.rows.len(),
        off.len(),
        off.iter()
            .map(|r| format!("\n  {} {}", r.table, r.row))
            .collect::<String>()
    )?;
    Ok(())
}

/// Compare a receiver's RINEX observations with the truth (one signal per system at a
/// time), print the
/// table and optionally write the comparison as JSON (via a temporary file, renamed when complete).
pub fn obs(
    truth: &Path,
    estimate: &Path,
    json: JsonOut<'_>,
    tag_offset_s: f64,
    window: Option<&(String, String)>,
) -> anyhow::Result<()> {
    let epoch = |option: &str, text: &str| {
        Epoch::from_str(text.trim()).map_err(|e| {
            BadInput(format!(
                "--{option} {text:?}: not an epoch ({e}); write e.g. \"2023-03-12T00:00:40 GPST\""
            ))
        })
    };
    let window = match window {
        Some((from, to)) => {
            let (first, last) = (epoch("from", from)?, epoch("to", to)?);
            if last < first {
                return Err(BadInput(format!("--to {to:?} is before --from {from:?}")).into());
            }
            Some(SampleSpan { first, last })
        }
        None => None,
    };
    let bad = |e: &dyn std::fmt::Display| BadInput(e.to_string());
    let truth = super::read_observations(truth)?;
    let estimate = super::read_observations(estimate)?;
    let opts = CompareOptions {
        tag_offset_s,
        window,
    };
    use std::io::Write;
    let comparisons = compare_signals(&estimate, &truth, &opts).map_err(|e| bad(&e))?;
    let mut out = std::io::stdout().lock();
    match comparisons.as_slice() {
        [one] => {
            print_comparison(&one.comparison, &mut out)?;
            json.write(&one.comparison)
        }
        several => {
            for c in several {
                let tags: Vec<&str> = c.signals.iter().map(|s| s.tag()).collect();
                writeln!(out, "== {} ==", tags.join(" + "))?;
                print_comparison(&c.comparison, &mut out)?;
            }
            drop(out);
            json.write(&BySignal { signals: several })
        }
    }
}

/// The JSON of `validate obs` on observations of several signals of a system: one
/// comparison per layer of one signal per system.
#[derive(serde::Serialize)]
struct BySignal<'a> {
    signals: &'a [SignalComparison],
}

/// What the JSON files `validate` writes are called in messages.
const JSON_WHAT: &str = "a validation JSON";
/// How every JSON file `validate` writes begins (an object, pretty-printed).
const JSON_START: &str = "{\n  \"";

/// Where `--json` goes, checked before any comparison is made ([`whole_file::check_target`]:
/// a missing directory, a directory, a file skyforge did not write, or one it did without
/// `--force` is refused).
#[derive(Debug, Clone, Copy)]
pub struct JsonOut<'a> {
    path: Option<&'a Path>,
    force: bool,
}

impl<'a> JsonOut<'a> {
    pub fn new(path: Option<&'a Path>, force: bool) -> Result<Self, BadInput> {
        if let Some(p) = path {
            whole_file::check_target(p, force, JSON_WHAT, |f| {
                whole_file::starts_with(f, JSON_START.as_bytes())
            })?;
        }
        Ok(Self { path, force })
    }

    /// Write `value` pretty-printed, whole or not at all ([`whole_file`]); an existing
    /// file is replaced only when it begins with the same first key (the same kind of
    /// comparison).
    fn write(self, value: &impl serde::Serialize) -> anyhow::Result<()> {
        let Some(path) = self.path else {
            return Ok(());
        };
        let text = serde_json::to_string_pretty(value)? + "\n";
        let first_key = text
            .find("\":")
            .map_or(text.as_str(), |end| &text[..end + 2]);
        whole_file::check_target(path, self.force, JSON_WHAT, |f| {
            whole_file::starts_with(f, first_key.as_bytes())
        })?;
        whole_file::write(path, text.as_bytes())
            .with_context(|| format!("cannot write {}", path.display()))?;
        println!("wrote {}", path.display());
        Ok(())
    }
}

/// Compare `skyforge attitude`'s output in `attitude` with the truth of the run in
/// `truth` (and the observations the chain read), print the table and optionally write
/// the JSON.
pub fn attitude(
    truth: &Path,
    observations: &Path,
    attitude: &Path,
    json: JsonOut<'_>,
) -> anyhow::Result<()> {
    let comparison =
        compare_outputs(truth, observations, attitude).map_err(|e| BadInput(e.to_string()))?;
    let summary = comparison.summary();
    print_validation(&summary, &mut std::io::stdout().lock())?;
    json.write(&summary)
}

/// Compare `skyforge monitor run`'s alarms in `monitor` with the fault events of the run
/// in `truth`, print the table and optionally write the JSON.
pub fn monitor(truth: &Path, monitor: &Path, json: JsonOut<'_>) -> anyhow::Result<()> {
    let scenario = run_scenario(truth).map_err(BadInput)?;
    let csv = monitor.join(MONITOR_CSV);
    let record =
        read_monitor_csv(&csv, scenario.time.start).map_err(|e| BadInput(e.to_string()))?;
    check_same_run(&scenario, &record, &csv, truth).map_err(BadInput)?;
    let score = score(&scenario.errors.events, &record);
    print_score(&score, &mut std::io::stdout().lock())?;
    json.write(&score)
}

/// A `--settle-s` value: finite and not negative.
fn check_settle(settle_s: f64) -> Result<(), BadInput> {
    if settle_s.is_finite() && settle_s >= 0.0 {
        Ok(())
    } else {
        Err(BadInput(format!(
            "--settle-s {settle_s}: must be a finite number of seconds >= 0"
        )))
    }
}

/// Compare `skyforge relnav`'s estimates in `relnav` with the relative truth of the run
/// in `truth`, print the table and optionally write the JSON.
pub fn relnav(truth: &Path, relnav: &Path, settle_s: f64, json: JsonOut<'_>) -> anyhow::Result<()> {
    check_settle(settle_s)?;
    let comparison = compare_relnav(
        &truth.join(RELATIVE_CSV),
        &relnav.join(RELNAV_CSV),
        settle_s,
    )
    .map_err(|e| BadInput(e.to_string()))?;
    print_relnav(&comparison, &mut std::io::stdout().lock())?;
    json.write(&comparison)
}

/// Compare `skyforge od`'s orbit in `orbit` with the truth of the run in `truth`, print
/// the table and optionally write the JSON.
/// `validate interference`: `DIR/interference.csv` against `SIMDIR/truth.h5`'s jammers.
pub fn interference(truth: &Path, detections: &Path, json: JsonOut<'_>) -> anyhow::Result<()> {
    let bad = |e: skyforge_formats::FormatError| BadInput(e.to_string());
    let epochs = read_interference_csv(&detections.join(INTERFERENCE_CSV)).map_err(bad)?;
    let file = TruthFile::open(&truth.join(TRUTH_H5)).map_err(bad)?;
    let start = file.start_epoch().map_err(bad)?;
    let jammers = (file.jammers(MAX_JAMMER_EPOCHS).map_err(bad)?).ok_or_else(|| {
        BadInput(format!(
            "{}: the run had no jammer (no group jammers)",
            truth.join(TRUTH_H5).display()
        ))
    })?;
    let score = score_jamming(&epochs, &jammers, |e| (e.t - start).to_seconds());
    print_jamming(&score, &mut std::io::stdout().lock())?;
    json.write(&score)
}

/// The most geometry epochs of jammer truth read (a day at 10 Hz).
const MAX_JAMMER_EPOCHS: usize = 864_000;

/// `validate ins`: `INSDIR/ins.csv` against `SIMDIR/imu.h5`.
pub fn ins(truth: &Path, ins: &Path, json: JsonOut<'_>) -> anyhow::Result<()> {
    let bad = |e: String| BadInput(e);
    let rows = read_ins_csv(&ins.join(INS_CSV)).map_err(|e| bad(e.to_string()))?;
    let imu = read_h5(&truth.join(IMU_H5)).map_err(|e| bad(e.to_string()))?;
    let comparison = compare_ins(&rows, &imu).map_err(bad)?;
    print_ins(&comparison, &mut std::io::stdout().lock())?;
    json.write(&comparison)
}

pub fn od(truth: &Path, orbit: &Path, settle_s: f64, json: JsonOut<'_>) -> anyhow::Result<()> {
    check_settle(settle_s)?;
    let comparison = compare_orbit(&truth.join(TRUTH_H5), &orbit.join(ORBIT_H5), settle_s)
        .map_err(|e| BadInput(e.to_string()))?;
    print_orbit(&comparison, &mut std::io::stdout().lock())?;
    json.write(&comparison)
}
