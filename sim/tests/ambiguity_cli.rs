//! `skyforge ambiguity FILE`: the built binary on good and bad problem files.

use std::path::Path;
use std::process::{Command, Output};

fn skyforge(args: &[&str], cwd: &Path) -> Output {
    Command::new(env!("CARGO_BIN_EXE_skyforge"))
        .args(args)
        .current_dir(cwd)
        .output()
        .expect("run skyforge")
}

fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// The 3-D example of de Jonge & Tiberius 1996 (LGR-Series 12, §3.8 and §4.12), whose
/// integer solution is (5, 3, 4).
const EXAMPLE_JSON: &str = r#"{
  "a_hat": [5.45, 3.10, 2.97],
  "q": [[6.290, 5.978, 0.544],
        [5.978, 6.292, 2.340],
        [0.544, 2.340, 6.288]]
}"#;

const EXAMPLE_CSV: &str = "# de Jonge & Tiberius 1996, 3-D example\n\
5.45, 3.10, 2.97\n\
6.290, 5.978, 0.544\n\
5.978, 6.292, 2.340\n\
0.544, 2.340, 6.288\n";

fn json_of(o: &Output) -> serde_json::Value {
    assert!(o.status.success(), "{}{}", stdout(o), stderr(o));
    serde_json::from_str(&stdout(o)).expect("--json prints JSON")
}

#[test]
fn json_and_csv_files_give_the_published_solution() {
    let tmp = tempfile::tempdir().unwrap();
    std::fs::write(tmp.path().join("p.json"), EXAMPLE_JSON).unwrap();
    std::fs::write(tmp.path().join("p.csv"), EXAMPLE_CSV).unwrap();

    let text = skyforge(&["ambiguity", "p.json"], tmp.path());
    assert!(text.status.success(), "{}", stderr(&text));
    let out = stdout(&text);
    for needle in [
        "[5, 3, 4]",
        "ratio",
        "bootstrapped success rate",
        "decorrelating Z",
    ] {
        assert!(out.contains(needle), "{needle:?} missing in\n{out}");
    }

    let j = json_of(&skyforge(&["ambiguity", "p.json", "--json"], tmp.path()));
    let c = json_of(&skyforge(&["ambiguity", "p.csv", "--json"], tmp.path()));
    assert_eq!(j, c, "the CSV and JSON layouts describe the same problem");
    let cands = j["candidates"].as_array().unwrap();
    assert_eq!(cands.len(), 2);
    assert_eq!(cands[0]["integers"], serde_json::json!([5, 3, 4]));
    let (n1, n2) = (
        cands[0]["squared_norm"].as_f64().unwrap(),
        cands[1]["squared_norm"].as_f64().unwrap(),
    );
    assert!(n1 <= n2);
    assert!((j["ratio"].as_f64().unwrap() - n2 / n1).abs() < 1e-12);
    let p = j["success_rate"].as_f64().unwrap();
    assert!(p > 0.0 && p < 1.0);
    let z: Vec<Vec<i64>> = serde_json::from_value(j["z"].clone()).unwrap();
    let det = z[0][0] * (z[1][1] * z[2][2] - z[1][2] * z[2][1])
        - z[0][1] * (z[1][0] * z[2][2] - z[1][2] * z[2][0])
        + z[0][2] * (z[1][0] * z[2][1] - z[1][1] * z[2][0]);
    assert_eq!(det.abs(), 1);

    let four = json_of(&skyforge(
        &["ambiguity", "p.csv", "--json", "--candidates", "4"],
        tmp.path(),
    ));
    let norms: Vec<f64> = four["candidates"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| c["squared_norm"].as_f64().unwrap())
        .collect();
    assert_eq!(norms.len(), 4);
    assert!(norms.windows(2).all(|w| w[0] <= w[1]), "{norms:?}");
}

/// Each bad file: exit code 2, one error line naming the file and what is wrong.
#[test]
fn bad_files_are_reported_with_exit_code_2() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path();
    let big_row = vec!["0"; 501].join(",");
    let cases: Vec<(&str, String, Vec<&str>)> = vec![
        (
            "syntax.json",
            "{\"a_hat\": [1, 2],\n \"q\": [[1, 0], [0, 1]".into(),
            vec!["syntax.json:2:"],
        ),
        (
            "field.json",
            r#"{"a_hat": [1, 2], "q": [[1, "x"], [0, 1]]}"#.into(),
            vec!["field.json:1:", "invalid type"],
        ),
        (
            "unknown.json",
            r#"{"a_hat": [1], "Q": [[1]]}"#.into(),
            vec!["unknown field", "`Q`"],
        ),
        (
            "rows.json",
            r#"{"a_hat": [1, 2], "q": [[1, 0]]}"#.into(),
            vec!["q has 1 rows", "2 x 2"],
        ),
        (
            "ragged.json",
            r#"{"a_hat": [1, 2], "q": [[1, 0], [0]]}"#.into(),
            vec!["q[1] has 1 entries"],
        ),
        (
            "asym.json",
            r#"{"a_hat": [1, 2], "q": [[1, 0.2], [0.3, 1]]}"#.into(),
            vec!["asym.json", "not symmetric"],
        ),
        (
            "indef.csv",
            "0.1, 0.2\n1, 2\n2, 1\n".into(),
            vec!["indef.csv", "not positive definite"],
        ),
        (
            "word.csv",
            "0.1, 0.2\n1, 0\n0, one\n".into(),
            vec!["word.csv:3:2", "finite number"],
        ),
        (
            "nan.csv",
            "0.1, NaN\n1, 0\n0, 1\n".into(),
            vec!["nan.csv:1:2", "finite number"],
        ),
        (
            "short.csv",
            "0.1, 0.2\n1, 0\n".into(),
            vec!["short.csv", "Q has 1 rows, expected 2"],
        ),
        (
            "wide.csv",
            "0.1, 0.2\n1, 0, 0\n0, 1\n".into(),
            vec!["wide.csv:2", "3 fields, expected 2"],
        ),
        (
            "huge.csv",
            big_row,
            vec!["huge.csv:1", "501 ambiguities exceed the limit of 500"],
        ),
        (
            "empty.csv",
            "# nothing\n".into(),
            vec!["empty.csv", "no data"],
        ),
        ("p.txt", "1\n1\n".into(), vec!["p.txt", ".json and .csv"]),
    ];
    for (name, content, needles) in &cases {
        std::fs::write(dir.join(name), content).unwrap();
        let o = skyforge(&["ambiguity", name], dir);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{name}: {err}");
        assert!(!err.contains("panicked"), "{name}: {err}");
        assert_eq!(
            err.trim().lines().count(),
            1,
            "{name}: one error line:\n{err}"
        );
        for n in needles {
            assert!(err.contains(n), "{name}: {n:?} missing in {err}");
        }
    }

    // Too large a file, a directory, a missing file, a bad --candidates.
    let big = vec![b' '; 5 << 20];
    std::fs::write(dir.join("big.json"), big).unwrap();
    std::fs::create_dir(dir.join("d.json")).unwrap();
    for (args, needle) in [
        (
            vec!["ambiguity", "big.json"],
            "exceed the limit of 4194304 bytes",
        ),
        (vec!["ambiguity", "d.json"], "is a directory"),
        (
            vec!["ambiguity", "missing.json"],
            "missing.json: cannot read",
        ),
        (
            vec!["ambiguity", "p.txt", "--candidates", "0"],
            "--candidates",
        ),
        (
            vec!["ambiguity", "p.txt", "--candidates", "1001"],
            "--candidates",
        ),
    ] {
        let o = skyforge(&args, dir);
        let err = stderr(&o);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert!(
            err.contains(needle),
            "{args:?}: {needle:?} missing in {err}"
        );
    }
}
