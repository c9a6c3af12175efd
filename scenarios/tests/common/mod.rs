//! Shared helpers of the scenario tests: a small valid scenario, text edits, and the
//! position of a piece of text computed from the text itself (the oracle for locations).

#![allow(dead_code)] // each test file uses a different subset
#![allow(clippy::result_large_err)] // see the crate root: errors are cold

use skyforge_scenarios::{Scenario, ScenarioError, parse};
use std::path::Path;

/// Source name used in every test.
pub const SOURCE: &str = "test.toml";

/// A small valid scenario: the thesis LEO, embedded GPS + BeiDou, two antennas.
pub const BASE: &str = r#"name = "base"
seed = 7

[time]
start = "2023-03-12T00:00:00 GPST"
duration_s = 600.0

[truth]
geometry_rate_hz = 1.0

[gnss.gps]
source = "embedded"

[gnss.beidou]
enabled = true

[platform.leo.elements]
semi_major_axis_km = 6971.593
eccentricity = 0.000846
inclination_deg = 34.911
raan_deg = -78.005
arg_perigee_deg = 47.757
mean_anomaly_deg = 351.636

[platform.leo.forces]
mass_kg = 100.0
area_m2 = 1.0

[[antennas]]
name = "ant1"
position_body_m = [0.0, 0.0, 0.0]

[[antennas]]
name = "ant2"
position_body_m = [1.0, 0.0, 0.0]
fov_half_angle_deg = 80.0
"#;

/// A static ground site version of [`BASE`].
pub fn ground(site: &str) -> String {
    let start = BASE.find("[platform.leo.elements]").expect("leo section");
    let end = BASE.find("[[antennas]]").expect("antennas");
    format!(
        "{}[platform.ground]\n{site}\n\n{}",
        &BASE[..start],
        &BASE[end..]
    )
}

/// `text` with the single occurrence of `from` replaced by `to`.
pub fn replace(text: &str, from: &str, to: &str) -> String {
    assert_eq!(text.matches(from).count(), 1, "{from:?} must occur once");
    text.replacen(from, to, 1)
}

/// 1-based line and column (characters) where `part` starts inside the single occurrence
/// of `context` in `text`.
pub fn position_of(text: &str, context: &str, part: &str) -> (usize, usize) {
    assert_eq!(
        text.matches(context).count(),
        1,
        "{context:?} must occur once"
    );
    let offset = text.find(context).expect("context") + context.find(part).expect("part");
    let before = &text[..offset];
    let line = before.matches('\n').count() + 1;
    let line_start = before.rfind('\n').map_or(0, |i| i + 1);
    (line, before[line_start..].chars().count() + 1)
}

/// Parse `text` as [`SOURCE`] relative to `base_dir`.
pub fn parse_in(text: &str, base_dir: &Path) -> Result<Scenario, ScenarioError> {
    parse(text, SOURCE, base_dir)
}

/// The error `parse` must return for `text`.
pub fn parse_error(text: &str) -> ScenarioError {
    match parse_in(text, Path::new(".")) {
        Ok(s) => panic!("expected an error, parsed {:?}", s.name),
        Err(e) => e,
    }
}

/// The error `build` must return for `text` (which must parse).
pub fn build_error(text: &str, base_dir: &Path) -> ScenarioError {
    let scenario = match parse_in(text, base_dir) {
        Ok(s) => s,
        Err(e) => panic!("expected the scenario to parse: {e}"),
    };
    match scenario.build() {
        Ok(_) => panic!("expected build to fail"),
        Err(e) => e,
    }
}

/// The error `parse` must return for `text`, checked by [`assert_error`] to name `field`
/// and `value` and to point at `value` inside the single occurrence of `context`.
pub fn parse_error_at(text: &str, field: &str, context: &str, value: &str) -> ScenarioError {
    let err = parse_error(text);
    assert_error(&err, field, value, position_of(text, context, value));
    err
}

/// The error of `BASE` with `from` replaced by `to`, checked by [`parse_error_at`] to
/// point at `value` inside `to`.
pub fn replaced_error(from: &str, to: &str, field: &str, value: &str) -> ScenarioError {
    parse_error_at(&replace(BASE, from, to), field, to, value)
}

/// The error `build` must return for `text`, checked by [`assert_error`] to name `field`
/// and `value` and to point at `part` inside the single occurrence of `context`.
pub fn build_error_at(
    text: &str,
    base_dir: &Path,
    field: &str,
    value: &str,
    (context, part): (&str, &str),
) -> ScenarioError {
    let err = build_error(text, base_dir);
    assert_error(&err, field, value, position_of(text, context, part));
    err
}

/// Line and column of `err` are `at`.
pub fn assert_at(err: &ScenarioError, at: (usize, usize)) {
    assert_eq!((err.line, err.column), (Some(at.0), Some(at.1)), "{err}");
}

/// Field, value and position of `err`, and that its message names the file.
pub fn assert_error(err: &ScenarioError, field: &str, value: &str, at: (usize, usize)) {
    assert_eq!(err.field, field, "field of: {err}");
    assert_eq!(err.value, value, "value of: {err}");
    assert_eq!(
        (err.line, err.column),
        (Some(at.0), Some(at.1)),
        "position of: {err}"
    );
    assert_eq!(err.file, SOURCE);
    assert!(!err.allowed.trim().is_empty(), "no message: {err}");
    assert!(
        err.to_string()
            .starts_with(&format!("{SOURCE}:{}:{}: {field}", at.0, at.1)),
        "display: {err}"
    );
}
