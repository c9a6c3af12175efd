//! Reading a scenario: TOML syntax, schema (serde), then the checks, every failure mapped
//! to one located [`ScenarioError`].

use crate::bundled::bundled;
use crate::checks;
use crate::error::{ScenarioError, shorten};
use crate::locate::{Document, line_column};
use crate::schema::{
    GnssConfig, Scenario, ScenarioFile, TimeSpan, absent_galileo, default_constellation,
};
use serde::Deserialize;
use skyforge_orbits::bounded_read::read_text;
use skyforge_orbits::check::Invalid;
use skyforge_signals::obs_model::Level;
use std::path::{Path, PathBuf};

/// Largest scenario file read.
pub const SCENARIO_MAX_BYTES: u64 = 1 << 20;

/// Parse and check a scenario given as text. `source` names it in errors (a file path or
/// `bundled:NAME`); relative paths inside it are resolved from `base_dir`. Runs every
/// check that needs no file access; [`Scenario::build`] does the rest.
pub fn parse(text: &str, source: &str, base_dir: &Path) -> Result<Scenario, ScenarioError> {
    let doc = Document::parse(text).map_err(|e| syntax_error(text, source, &e))?;
    let explicit_truth_rate = doc.number_at("signal.truth_rate_hz").is_some();
    let file = ScenarioFile::deserialize(toml::de::Deserializer::from(doc.into_root()))
        .map_err(|e| schema_error(text, source, &e))?;
    let gnss = GnssConfig {
        gps: file.gnss.gps.unwrap_or_else(default_constellation),
        beidou: file.gnss.beidou.unwrap_or_else(default_constellation),
        galileo: file.gnss.galileo.unwrap_or_else(absent_galileo),
    };
    let start =
        checks::parse_start(&file.time.start).map_err(|e| locate_invalid(text, source, e))?;
    let (platform, antennas) =
        checks::platform_or_vehicles(file.platform, file.antennas, &file.vehicles)
            .map_err(|e| locate_invalid(text, source, e))?;
    let mut scenario = Scenario {
        name: file.name,
        description: file.description,
        seed: file.seed,
        time: TimeSpan {
            start,
            duration_s: file.time.duration_s,
        },
        truth: file.truth,
        gnss,
        platform,
        antennas,
        signal: file.signal,
        errors: file.errors,
        observation: file.observation,
        imu: file.imu,
        vehicles: file.vehicles,
        jammers: file.jammers,
        vehicle: None,
        source: source.to_string(),
        base_dir: base_dir.to_path_buf(),
        text: text.to_string(),
    };
    observation_level_truth_rate(&mut scenario, explicit_truth_rate);
    checks::check(&scenario).map_err(|e| locate_invalid(text, source, e))?;
    Ok(scenario)
}

/// At the observation level no sample is made, and the signal truth serves only its
/// observation epochs' records (the observation truth RINEX): unless the file sets
/// `[signal] truth_rate_hz`, it is written at 1 Hz there (or `[observation] rate_hz`), not
/// at the signal level's 1 kHz
/// (which over hours fills disks: about 3 GB per antenna-hour with 10 satellites).
fn observation_level_truth_rate(scenario: &mut Scenario, explicit: bool) {
    if let (Some(signal), false, Level::Observation) = (
        scenario.signal.as_mut(),
        explicit,
        scenario.observation.level,
    ) {
        signal.truth_rate_hz = OBSERVATION_LEVEL_TRUTH_RATE_HZ.max(scenario.observation.rate_hz());
    }
}

/// The signal truth's default rate at the observation level (Hz).
pub const OBSERVATION_LEVEL_TRUTH_RATE_HZ: u32 = 1;

/// Read, parse and check the scenario file at `path` (relative paths inside it are
/// resolved from its directory).
pub fn load(path: &Path) -> Result<Scenario, ScenarioError> {
    let source = path.display().to_string();
    let text = read_text(path, SCENARIO_MAX_BYTES, "scenario file")
        .map_err(|e| ScenarioError::unlocated(&source, "", "", format!("cannot read: {e}")))?;
    let base_dir = match path.parent() {
        Some(dir) if !dir.as_os_str().is_empty() => dir.to_path_buf(),
        _ => PathBuf::from("."),
    };
    parse(&text, &source, &base_dir)
}

/// The scenario named by a command-line argument: an existing file, else a bundled
/// scenario of that name (relative paths resolved from the current directory), else an
/// error listing the bundled names.
pub fn resolve(arg: &str) -> Result<Scenario, ScenarioError> {
    let path = Path::new(arg);
    if path.exists() {
        return load(path);
    }
    if !bundled().iter().any(|b| b.name == arg) {
        return Err(ScenarioError::unlocated(
            arg,
            "",
            "",
            format!(
                "no such scenario file, and no bundled scenario of that name (bundled: {})",
                bundled_names()
            ),
        ));
    }
    // A bundled scenario that fails its checks here (Galileo E1 without the user's code
    // tables) says why.
    named(arg)
}

/// The bundled scenario `name`, never a file (a file of the same name in the working
/// directory does not replace it; relative paths inside it are resolved from the current
/// directory).
pub fn named(name: &str) -> Result<Scenario, ScenarioError> {
    let Some(found) = bundled().iter().find(|b| b.name == name) else {
        return Err(ScenarioError::unlocated(
            name,
            "",
            "",
            format!(
                "no bundled scenario of that name (bundled: {})",
                bundled_names()
            ),
        ));
    };
    let base_dir = std::env::current_dir().unwrap_or_else(|_| PathBuf::from("."));
    parse(found.text, &format!("bundled:{}", found.name), &base_dir)
}

fn bundled_names() -> String {
    bundled()
        .iter()
        .map(|b| b.name)
        .collect::<Vec<_>>()
        .join(", ")
}

/// A TOML syntax error, at its position, with the field it interrupts when known; the
/// offending text is quoted in the message (the value stays empty: there is none yet).
fn syntax_error(text: &str, source: &str, err: &toml::de::Error) -> ScenarioError {
    let Some(span) = err.span() else {
        let allowed = format!("TOML syntax error: {}", err.message());
        return ScenarioError::unlocated(source, "", "", allowed);
    };
    let field = Document::parse_recoverable(text).path_at(span.start).0;
    let allowed = match text.get(span.clone()).map(shorten) {
        Some(snippet) if !snippet.is_empty() => {
            format!("TOML syntax error at `{snippet}`: {}", err.message())
        }
        _ => format!("TOML syntax error: {}", err.message()),
    };
    ScenarioError::unlocated(source, field, "", allowed).at(Some(line_column(text, span.start)))
}

/// A schema error (unknown key, wrong type, missing key, bad enum value) at its position,
/// with its field path and the value written there.
fn schema_error(text: &str, source: &str, err: &toml::de::Error) -> ScenarioError {
    let message = err.message();
    let (Some(span), Ok(doc)) = (err.span(), Document::parse(text)) else {
        return ScenarioError::unlocated(source, "", "", message);
    };
    let (path, value_span) = if doc.is_root(&span) {
        (String::new(), span.clone())
    } else {
        doc.path_at(span.start)
    };
    let (field, value) = match missing_field(message) {
        Some(name) if path.is_empty() => (name.to_string(), "(missing)".to_string()),
        Some(name) => (format!("{path}.{name}"), "(missing)".to_string()),
        None => (
            path,
            doc.snippet(&value_span).map(shorten).unwrap_or_default(),
        ),
    };
    ScenarioError::unlocated(source, field, value, message).at(Some(doc.position(span.start)))
}

/// `name` from serde's "missing field `name`".
fn missing_field(message: &str) -> Option<&str> {
    message.strip_prefix("missing field `")?.split('`').next()
}

/// Parse the TOML document `text` (named `source` in errors) into `T`, every syntax and
/// schema error located as a scenario's are: for SkyForge's other TOML files (studies).
pub fn parse_document<T: serde::de::DeserializeOwned>(
    text: &str,
    source: &str,
) -> Result<T, ScenarioError> {
    let doc = Document::parse(text).map_err(|e| syntax_error(text, source, &e))?;
    T::deserialize(toml::de::Deserializer::from(doc.into_root()))
        .map_err(|e| schema_error(text, source, &e))
}

/// A failed check, placed at its field in the text (or the nearest enclosing header). A
/// number the check reports is shown as written when the text holds that number there.
pub fn locate_invalid(text: &str, source: &str, invalid: Invalid) -> ScenarioError {
    let Ok(doc) = Document::parse(text) else {
        return ScenarioError::unlocated(source, invalid.field, invalid.value, invalid.allowed);
    };
    let position = doc.position(doc.span_of(&invalid.field).start);
    let value = match doc.number_at(&invalid.field) {
        Some(written) if same_number(written, &invalid.value) => written.to_string(),
        _ => invalid.value,
    };
    ScenarioError::unlocated(source, invalid.field, value, invalid.allowed).at(Some(position))
}

/// Whether TOML number text `written` and the check's `reported` value are the same
/// number (NaN matches NaN).
fn same_number(written: &str, reported: &str) -> bool {
    let parse = |t: &str| match t.trim_start_matches('+') {
        "nan" | "-nan" | "NaN" => Some(f64::NAN),
        "inf" => Some(f64::INFINITY),
        "-inf" => Some(f64::NEG_INFINITY),
        t => t.parse::<f64>().ok(),
    };
    match (parse(written), parse(reported)) {
        (Some(a), Some(b)) => a == b || (a.is_nan() && b.is_nan()),
        _ => false,
    }
}

#[cfg(test)]
mod tests {
    use super::same_number;

    #[test]
    fn numbers_match_across_spellings() {
        assert!(same_number("1.0", "1"));
        assert!(same_number("1e3", "1000"));
        assert!(same_number("-0.0", "-0"));
        assert!(same_number("nan", "NaN"));
        assert!(same_number("+inf", "inf"));
        assert!(same_number("-inf", "-inf"));
        assert!(!same_number("600.0", "-1"));
        assert!(!same_number("0x10", "16")); // not worth decoding: the reported value is shown
        assert!(!same_number("1.0", "(missing)"));
    }
}
