//! A study's files written by the one writer and read back by the one reader: the
//! journal keeps every finished run bit for bit, a shard file gives back its runs and its
//! study, the merged file gives back the summaries the study computes; another study's
//! files are refused as the user's input.

use skyforge_studies::study::results::{
    Journal, MEAN, MEAN_CI_HIGH, MEAN_CI_LOW, MergedFile, P95, ResultsError, read_shard,
    shard_path, shard_study_text, write_merged, write_shard,
};
use skyforge_studies::study::{RunResult, Shard, Study};

const STUDY: &str = r#"
name = "round-trip"
scenario = "none.toml"
seed = 11
seeds = 3
metrics = ["fix_rate", "yaw_rms_deg"]

[[parameters]]
key = "signal.cn0_dbhz"
values = [35.0, 45.0]
"#;

fn study() -> Study {
    Study::parse_plan(STUDY, "round-trip.toml").unwrap()
}

/// Every run of the study, with values that are awkward in text (NaN, a subnormal, -0).
fn runs(study: &Study) -> Vec<RunResult> {
    (0..study.runs())
        .map(|r| RunResult {
            run: r,
            values: vec![
                if r == 4 { f64::NAN } else { 0.1 * r as f64 },
                [1.0e-310, -0.0, 1.0 / 3.0][r as usize % 3] + r as f64,
            ],
        })
        .collect()
}

fn same(a: &[RunResult], b: &[RunResult]) -> bool {
    a.len() == b.len()
        && a.iter().zip(b).all(|(x, y)| {
            x.run == y.run
                && x.values
                    .iter()
                    .map(|v| v.to_bits())
                    .eq(y.values.iter().map(|v| v.to_bits()))
        })
}

#[test]
fn the_journal_shard_and_merged_files_read_back_as_written() {
    let dir = tempfile::tempdir().unwrap();
    let study = study();
    let all = runs(&study);
    let (mut journal, done) = Journal::open(dir.path(), &study, Shard::WHOLE).unwrap();
    assert!(done.is_empty());
    for r in &all[..4] {
        journal.append(r).unwrap();
    }
    drop(journal);
    let (_, done) = Journal::open(dir.path(), &study, Shard::WHOLE).unwrap();
    assert!(same(&done, &all[..4]));

    let shard = shard_path(dir.path(), Shard::WHOLE);
    write_shard(&shard, &study, Shard::WHOLE, &all).unwrap();
    assert_eq!(shard_study_text(&shard).unwrap(), STUDY);
    let names: Vec<&str> = study.metrics.iter().map(|m| m.name()).collect();
    let back = read_shard(&shard, &names).unwrap();
    assert_eq!(back.study_toml, STUDY);
    assert!(same(&back.runs, &all));

    let merged = dir.path().join("study.h5");
    write_merged(&merged, &study, &all).unwrap();
    let file = MergedFile::open(&merged).unwrap();
    assert_eq!(file.study_toml().unwrap(), STUDY);
    let points = study.points() as usize;
    let summaries = study.summarise(&all);
    for (m, name) in names.iter().enumerate() {
        let expected = |get: fn(&skyforge_studies::study::MetricSummary) -> f64| -> Vec<u64> {
            summaries.iter().map(|p| get(&p[m]).to_bits()).collect()
        };
        let read = |stat: &str| -> Vec<u64> {
            let v = file.summary(name, stat, points).unwrap();
            v.iter().map(|x| x.to_bits()).collect()
        };
        assert_eq!(read(MEAN), expected(|s| s.mean), "{name}");
        assert_eq!(read(MEAN_CI_LOW), expected(|s| s.mean_ci.0), "{name}");
        assert_eq!(read(MEAN_CI_HIGH), expected(|s| s.mean_ci.1), "{name}");
        assert_eq!(read(P95), expected(|s| s.p95), "{name}");
    }
    let e = file
        .summary(names[0], MEAN, points + 1)
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("summary/fix_rate/mean has 2 values for 3 points"),
        "{e}"
    );
}

#[test]
fn another_studys_files_are_the_users_input() {
    let dir = tempfile::tempdir().unwrap();
    let study = study();
    Journal::open(dir.path(), &study, Shard::WHOLE).unwrap();
    let other = Study::parse_plan(&STUDY.replace("seed = 11", "seed = 12"), "other.toml").unwrap();
    let e = Journal::open(dir.path(), &other, Shard::WHOLE).unwrap_err();
    assert!(matches!(e, ResultsError::NotThisStudy(_)), "{e}");
    assert!(
        e.to_string().contains("the journal of another study"),
        "{e}"
    );
    let text = dir.path().join("text.h5");
    std::fs::write(&text, "not hdf5").unwrap();
    let e = shard_study_text(&text).unwrap_err();
    assert!(matches!(e, ResultsError::NotThisStudy(_)), "{e}");
    let e = MergedFile::open(&text).unwrap_err().to_string();
    assert!(e.contains("not readable as HDF5"), "{e}");
}

/// One process at a time holds a shard: a second open (a requeued Slurm task overlapping
/// the first made every run again and corrupted the journal) is refused, naming the
/// holder, and leaves the journal as it was; the lock goes with the first journal.
#[test]
fn a_second_holder_of_a_shard_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let study = study();
    let (mut first, _) = Journal::open(dir.path(), &study, Shard::WHOLE).unwrap();
    first.append(&runs(&study)[0]).unwrap();
    let journal = dir.path().join("shard-1-of-1.runs.jsonl");
    let before = std::fs::read(&journal).unwrap();
    let e = Journal::open(dir.path(), &study, Shard::WHOLE).unwrap_err();
    assert!(matches!(e, ResultsError::Busy(_)), "{e}");
    let said = e.to_string();
    assert!(
        said.contains("shard-1-of-1.lock: shard 1/1 is being made by another process (host ")
            && said.contains(&format!("process {})", std::process::id())),
        "{said}"
    );
    assert_eq!(std::fs::read(&journal).unwrap(), before);
    // Another shard is not held.
    Journal::open(dir.path(), &study, Shard { index: 2, count: 2 }).unwrap();
    drop(first);
    let (_, done) = Journal::open(dir.path(), &study, Shard::WHOLE).unwrap();
    assert_eq!(done.len(), 1);
}

/// A last line cut by a crash is dropped, the head line too (the journal starts again);
/// a run that is not one of the shard's is the user's input, named by line.
#[test]
fn a_torn_last_line_is_dropped_and_a_foreign_run_refused() {
    let dir = tempfile::tempdir().unwrap();
    let study = study();
    let (mut j, _) = Journal::open(dir.path(), &study, Shard::WHOLE).unwrap();
    j.append(&runs(&study)[0]).unwrap();
    drop(j);
    let path = dir.path().join("shard-1-of-1.runs.jsonl");
    let whole = std::fs::read_to_string(&path).unwrap();
    let lines: Vec<&str> = whole.lines().collect();

    // The run's line without its newline: cut.
    std::fs::write(&path, format!("{}\n{}", lines[0], lines[1])).unwrap();
    let (_, done) = Journal::open(dir.path(), &study, Shard::WHOLE).unwrap();
    assert!(done.is_empty());
    assert_eq!(
        std::fs::read_to_string(&path).unwrap(),
        format!("{}\n", lines[0])
    );

    // Half a head line: the journal starts again.
    std::fs::write(&path, &lines[0][..10]).unwrap();
    let (_, done) = Journal::open(dir.path(), &study, Shard::WHOLE).unwrap();
    assert!(done.is_empty());
    assert_eq!(
        std::fs::read_to_string(&path).unwrap(),
        format!("{}\n", lines[0])
    );

    // Run 99999999 of a 6-run study, and a run of another shard.
    for (line, shard) in [
        (
            lines[1].replace("\"run\":0", "\"run\":99999999"),
            Shard::WHOLE,
        ),
        (lines[1].to_string(), Shard { index: 2, count: 2 }),
    ] {
        let head = lines[0].replace("\"1/1\"", &format!("\"{}/{}\"", shard.index, shard.count));
        let path = dir.path().join(format!("{}.runs.jsonl", shard.tag()));
        std::fs::write(&path, format!("{head}\n{line}\n")).unwrap();
        let e = Journal::open(dir.path(), &study, shard).unwrap_err();
        assert!(matches!(e, ResultsError::NotThisStudy(_)), "{e}");
        assert!(
            e.to_string().contains(&format!(
                "runs.jsonl:2: run {} is not a run of shard {}/{} of this study (6 runs)",
                if shard == Shard::WHOLE { 99999999 } else { 0 },
                shard.index,
                shard.count
            )),
            "{e}"
        );
    }
}
