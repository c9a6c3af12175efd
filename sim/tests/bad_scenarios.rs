//! Issue #11: a generated table of bad scenarios. Every value of two scenarios that between
//! them use most tables (a three-antenna LEO with GPS + BeiDou and every error source; an
//! observation-level thesis scenario) is replaced in turn by values no field accepts: NaN,
//! infinity, a value of the wrong type, and +-1e300 (finite, but outside every physical
//! range: issue #33 item 10). Each mutant must give exit code 2, one message
//! that points at the mutated line and names the field, and nothing written.

mod support;

use std::path::Path;
use support::{listing, skyforge};

/// Values a field accepts by design, though other fields refuse them: (key, value, why).
const ACCEPTED: &[(&str, &str, &str)] = &[
    (
        "end_s",
        "inf",
        "a fault event without end (docs/scenario.md, events)",
    ),
    (
        "end_s",
        "1e300",
        "an end beyond the scenario's (the fault lasts to it)",
    ),
];

/// One value of a scenario text: its line (1-based), key, and byte span in the line.
struct Value {
    line: usize,
    key: String,
    span: (usize, usize),
    is_string: bool,
}

/// The `key = value` scalars of `text` (numbers and strings, also inside inline tables),
/// and the first element of number arrays.
fn values(text: &str) -> Vec<Value> {
    let mut out = Vec::new();
    for (i, raw) in text.lines().enumerate() {
        let line = raw.split('#').next().unwrap_or("");
        let mut rest = 0;
        while let Some(eq) = line[rest..].find(" = ") {
            let eq = rest + eq;
            if line[..eq].matches('"').count() % 2 == 1 {
                break; // inside a string
            }
            let key_start = line[..eq]
                .rfind(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
                .map_or(0, |p| p + 1);
            let key = line[key_start..eq].to_string();
            let mut start = eq + 3;
            if line[start..].starts_with('[') {
                start += 1;
            }
            let value = &line[start..];
            let (len, is_string) = if let Some(s) = value.strip_prefix('"') {
                (s.find('"').map_or(0, |e| e + 2), true)
            } else {
                let n = value
                    .find(|c: char| !(c.is_ascii_alphanumeric() || "+-._".contains(c)))
                    .unwrap_or(value.len());
                (n, false)
            };
            if len > 0 && !key.is_empty() && !value.starts_with('{') && !value.starts_with('[') {
                out.push(Value {
                    line: i + 1,
                    key,
                    span: (start, start + len),
                    is_string,
                });
            }
            rest = eq + 3;
        }
    }
    out
}

/// `text` with value `v` replaced by `by`.
fn mutated(text: &str, v: &Value, by: &str) -> String {
    text.lines()
        .enumerate()
        .map(|(i, l)| {
            if i + 1 == v.line {
                format!("{}{by}{}", &l[..v.span.0], &l[v.span.1..])
            } else {
                l.to_string()
            }
        })
        .collect::<Vec<_>>()
        .join("\n")
}

/// Run every mutant of `text` in `dir`; returns the count.
fn check_all(dir: &Path, text: &str) -> usize {
    let before = listing(dir);
    let mut count = 0;
    let mut failures = Vec::new();
    for v in values(text) {
        let bad: &[&str] = if v.is_string {
            &["42"]
        } else {
            &["nan", "inf", "\"text\"", "1e300", "-1e300"]
        };
        for by in bad {
            if ACCEPTED.iter().any(|(k, b, _)| *k == v.key && b == by) {
                continue;
            }
            std::fs::write(dir.join("bad.toml"), mutated(text, &v, by)).unwrap();
            let o = skyforge(&["run", "bad.toml", "--out", "out"], dir);
            let err = String::from_utf8_lossy(&o.stderr).into_owned();
            let at = format!("bad.toml:{}:", v.line);
            let ok = o.status.code() == Some(2)
                && err.matches("error:").count() == 1
                && err.contains(&at)
                && err.contains(&v.key);
            if !ok {
                failures.push(format!(
                    "line {} {} = {by}: exit {:?}: {}",
                    v.line,
                    v.key,
                    o.status.code(),
                    err.trim()
                ));
            }
            std::fs::remove_file(dir.join("bad.toml")).unwrap();
            if listing(dir) != before {
                failures.push(format!("line {} {} = {by}: wrote something", v.line, v.key));
                let _ = std::fs::remove_dir_all(dir.join("out"));
            }
            count += 1;
        }
    }
    assert!(
        failures.is_empty(),
        "{} of {count} mutants not refused as they should be:\n{}",
        failures.len(),
        failures.join("\n")
    );
    count
}

#[test]
fn every_value_replaced_by_nan_infinity_or_a_wrong_type_is_refused_at_its_line() {
    let tmp = tempfile::tempdir().unwrap();
    let leo =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenarios/check/leo-three-antennas.toml");
    let leo = std::fs::read_to_string(leo).unwrap();
    let o = skyforge(&["scenarios", "show", "thesis/t-1.2-3"], tmp.path());
    let thesis = String::from_utf8(o.stdout).unwrap();
    let mut total = 0;
    for text in [&leo, &thesis] {
        assert!(
            values(text).len() > 20,
            "the value finder found too few values"
        );
        total += check_all(tmp.path(), text);
    }
    println!("{total} mutants refused");
}

/// Issue #33 item 10: a trajectory at the Earth's centre or at 1e30 m (finite, so it
/// passed before and gave NaN or blank truth) is refused with the CSV's file and line.
#[test]
fn a_trajectory_off_the_earth_is_refused_at_its_line() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path();
    let scenarios = Path::new(env!("CARGO_MANIFEST_DIR")).join("../scenarios/integrity");
    let scenario = std::fs::read_to_string(scenarios.join("raim-aircraft.toml"))
        .unwrap()
        .replace("duration_s = 3600.0", "duration_s = 5.0");
    std::fs::write(dir.join("s.toml"), scenario).unwrap();
    let csv = std::fs::read_to_string(scenarios.join("raim-aircraft.csv")).unwrap();
    let before = listing(dir);
    for (row, shown) in [
        ("3,0.0,0.0,0.0", "[0, 0, 0] (radius 0 m)"),
        ("3,1e30,0.0,0.0", "[1e30, 0, 0] (radius 1e30 m)"),
    ] {
        // The data row of t = 3 s replaced.
        let (mut lines, mut at) = (Vec::new(), 0);
        for (i, l) in csv.lines().enumerate() {
            if l.starts_with("3,") || l.starts_with("3.0,") {
                lines.push(row.to_string());
                at = i + 1;
            } else {
                lines.push(l.to_string());
            }
        }
        assert!(at > 0, "no row at t = 3 s");
        std::fs::write(dir.join("raim-aircraft.csv"), lines.join("\n") + "\n").unwrap();
        let o = skyforge(&["run", "s.toml", "--out", "out"], dir);
        let err = String::from_utf8_lossy(&o.stderr).into_owned();
        assert_eq!(o.status.code(), Some(2), "{row}: {err}");
        assert_eq!(err.matches("error:").count(), 1, "{err}");
        let says = format!("raim-aircraft.csv:{at}: x_m, y_m, z_m = {shown}");
        assert!(err.contains(&says), "{row}: missing {says:?} in {err}");
        assert!(
            err.contains("must lie at a radius in [6355000, 1e8] m"),
            "{err}"
        );
        std::fs::remove_file(dir.join("raim-aircraft.csv")).unwrap();
        assert_eq!(listing(dir), before, "{row}: wrote something");
    }
}
