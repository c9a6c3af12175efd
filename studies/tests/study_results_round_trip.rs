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
