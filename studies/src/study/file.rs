//! A study file (TOML; docs/study.md): a base scenario, parameters to vary on a grid, the
//! seeds per grid point and the metrics to keep. Errors are located as a scenario's are:
//! file, line and column, field, value, what is allowed.

use super::metrics::Metric;
use serde::Deserialize;
use skyforge_orbits::check::Invalid;
use skyforge_scenarios::{Scenario, ScenarioError, bundled, locate_invalid, parse_document};
use skyforge_signals::obs_model::Level;
use std::path::{Path, PathBuf};

/// Largest number of runs a study may ask for.
pub const MAX_RUNS: u64 = 10_000_000;

/// The file as written.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
struct StudyToml {
    name: String,
    #[serde(default)]
    description: String,
    /// A bundled scenario's name or a scenario file (relative to the study file).
    scenario: String,
    /// The study seed every run's seed derives from.
    seed: u64,
    /// Runs per grid point.
    seeds: u64,
    metrics: Vec<String>,
    #[serde(default)]
    parameters: Vec<ParameterToml>,
}

#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
struct ParameterToml {
    key: String,
    values: Vec<toml::Value>,
}

/// One varied scenario setting: a dotted key of the scenario (`signal.cn0_dbhz`,
/// `antennas[1].position_body_m`) and its values.
#[derive(Debug, Clone, PartialEq)]
pub struct Parameter {
    pub key: String,
    pub values: Vec<toml::Value>,
}

/// The base scenario's text, where it came from and the directory its relative paths
/// resolve from.
#[derive(Debug, Clone)]
struct BaseScenario {
    text: String,
    source: String,
    dir: PathBuf,
}

/// A checked study.
#[derive(Debug, Clone)]
pub struct Study {
    pub name: String,
    pub description: String,
    /// The study file as given (in errors).
    pub source: String,
    /// The study file's text (kept in every output: what the results belong to).
    pub text: String,
    /// The base scenario as the study names it (a file or a bundled name).
    pub scenario: String,
    /// The base scenario (`None` when read for merging only).
    base: Option<BaseScenario>,
    pub seed: u64,
    pub seeds: u64,
    pub metrics: Vec<Metric>,
    pub parameters: Vec<Parameter>,
    /// Whether a grid point's scenario is at the signal level (known once the base
    /// scenario is read).
    signal_level: bool,
}

/// Why a study file cannot be used: located in the study file, or in its base scenario.
pub type StudyError = Box<ScenarioError>;

impl Study {
    /// Parse and check the study `text` read from `source` (relative scenario paths are
    /// resolved from `base_dir`). Every grid point's scenario is parsed and checked here,
    /// so that a bad value fails before any run.
    pub fn parse(text: &str, source: &str, base_dir: &Path) -> Result<Self, StudyError> {
        let mut study = Self::parse_plan(text, source)?;
        let bad = |field: &str, value: &dyn std::fmt::Display, allowed: &str| {
            located(text, source, field, value, allowed)
        };
        let (text_of_base, base_source, dir) = base_scenario(&study.scenario, base_dir)
            .map_err(|allowed| bad("scenario", &study.scenario, &allowed))?;
        study.base = Some(BaseScenario {
            text: text_of_base,
            source: base_source,
            dir,
        });
        for point in 0..study.points() {
            let scenario = study.point_scenario(point, 0).map_err(|e| {
                let field = study
                    .parameters
                    .iter()
                    .position(|p| e.field.starts_with(&p.key))
                    .map_or("scenario".to_string(), |i| {
                        format!("parameters[{i}].values")
                    });
                bad(
                    &field,
                    &study.describe_point(point),
                    &format!("the scenario rejects this point: {e}"),
                )
            })?;
            for m in &study.metrics {
                m.check(&scenario)
                    .map_err(|allowed| bad("metrics", &m.name(), &allowed))?;
            }
            study.signal_level |= scenario.observation.level == Level::Signal;
        }
        Ok(study)
    }

    /// Parse and check the study `text` without its base scenario: the grid, seeds and
    /// metrics, all that merging shards needs (runs cannot be made from it).
    pub fn parse_plan(text: &str, source: &str) -> Result<Self, StudyError> {
        let file: StudyToml = parse_document(text, source)?;
        let bad = |field: &str, value: &dyn std::fmt::Display, allowed: &str| {
            located(text, source, field, value, allowed)
        };
        let metrics = file
            .metrics
            .iter()
            .enumerate()
            .map(|(i, m)| {
                Metric::from_name(m).ok_or_else(|| {
                    bad(
                        &format!("metrics[{i}]"),
                        m,
                        &format!("one of {}", Metric::names().join(", ")),
                    )
                })
            })
            .collect::<Result<Vec<_>, _>>()?;
        if metrics.is_empty() {
            return Err(bad("metrics", &"[]", "at least one metric"));
        }
        if file.seeds == 0 {
            return Err(bad("seeds", &0, "at least 1 run per point"));
        }
        let mut points: u64 = 1;
        for (i, p) in file.parameters.iter().enumerate() {
            if p.values.is_empty() {
                return Err(bad(
                    &format!("parameters[{i}].values"),
                    &"[]",
                    "at least one value",
                ));
            }
            points = points.saturating_mul(p.values.len() as u64);
        }
        let runs = points.saturating_mul(file.seeds);
        if runs > MAX_RUNS {
            return Err(bad(
                "seeds",
                &file.seeds,
                &format!("points x seeds = {runs} runs; at most {MAX_RUNS}"),
            ));
        }
        Ok(Self {
            name: file.name,
            description: file.description,
            source: source.to_string(),
            text: text.to_string(),
            scenario: file.scenario,
            base: None,
            seed: file.seed,
            seeds: file.seeds,
            metrics,
            parameters: file
                .parameters
                .into_iter()
                .map(|p| Parameter {
                    key: p.key,
                    values: p.values,
                })
                .collect(),
            signal_level: false,
        })
    }

    /// Whether some runs are at the signal level: each synthesises and receives samples on
    /// two threads of its own and more (the synthesiser's), so such runs are best made one
    /// at a time.
    pub fn signal_level(&self) -> bool {
        self.signal_level
    }

    /// Grid points: the product of every parameter's number of values (1 without any).
    pub fn points(&self) -> u64 {
        self.parameters
            .iter()
            .map(|p| p.values.len() as u64)
            .product()
    }

    /// Runs: points x seeds; run `r` is seed `r % seeds` of point `r / seeds`.
    pub fn runs(&self) -> u64 {
        self.points() * self.seeds
    }

    /// The value index of each parameter at `point` (the last parameter varies fastest).
    pub fn point_indices(&self, point: u64) -> Vec<usize> {
        let mut rest = point;
        let mut out = vec![0; self.parameters.len()];
        for (slot, p) in out.iter_mut().zip(&self.parameters).rev() {
            let n = p.values.len() as u64;
            *slot = (rest % n) as usize;
            rest /= n;
        }
        out
    }

    /// `key = value, ...` of `point` (`base` without parameters).
    pub fn describe_point(&self, point: u64) -> String {
        if self.parameters.is_empty() {
            return "base".into();
        }
        self.point_indices(point)
            .iter()
            .zip(&self.parameters)
            .map(|(&i, p)| format!("{} = {}", p.key, p.values[i]))
            .collect::<Vec<_>>()
            .join(", ")
    }

    /// The scenario of `point` with the scenario seed `seed`.
    pub fn point_scenario(&self, point: u64, seed: u64) -> Result<Scenario, StudyError> {
        let Some(base) = &self.base else {
            return Err(Box::new(ScenarioError::unlocated(
                &self.source,
                "scenario",
                "",
                "read for merging only: no base scenario",
            )));
        };
        let mut doc: toml::Table = toml::from_str(&base.text).map_err(|e| {
            skyforge_scenarios::parse(&base.text, &base.source, &base.dir)
                .err()
                .unwrap_or_else(|| ScenarioError::unlocated(&base.source, "", "", e.to_string()))
        })?;
        for (&i, p) in self.point_indices(point).iter().zip(&self.parameters) {
            set_key(&mut doc, &p.key, p.values[i].clone()).map_err(|allowed| {
                ScenarioError::unlocated(&base.source, p.key.as_str(), "", allowed)
            })?;
        }
        let text = toml::to_string(&doc)
            .map_err(|e| ScenarioError::unlocated(&base.source, "", "", e.to_string()))?;
        let source = format!("{} [{}]", base.source, self.describe_point(point));
        let mut scenario = skyforge_scenarios::parse(&text, &source, &base.dir)?;
        scenario.seed = seed;
        Ok(scenario)
    }
}

/// A failed check of the study `text` (from `source`) placed at its field.
fn located(
    text: &str,
    source: &str,
    field: &str,
    value: &dyn std::fmt::Display,
    allowed: &str,
) -> StudyError {
    Box::new(locate_invalid(
        text,
        source,
        Invalid::new(field, value, allowed),
    ))
}

/// The base scenario named `arg`: a file (relative to `base_dir`) or a bundled name; its
/// text, its name in errors and the directory its relative paths resolve from.
fn base_scenario(arg: &str, base_dir: &Path) -> Result<(String, String, PathBuf), String> {
    let path = base_dir.join(arg);
    if path.is_file() {
        let text = skyforge_orbits::bounded_read::read_text(
            &path,
            skyforge_scenarios::SCENARIO_MAX_BYTES,
            "scenario file",
        )
        .map_err(|e| format!("cannot read {}: {e}", path.display()))?;
        let dir = path
            .parent()
            .map_or_else(|| PathBuf::from("."), Path::to_path_buf);
        return Ok((text, path.display().to_string(), dir));
    }
    match bundled().iter().find(|b| b.name == arg) {
        Some(b) => Ok((
            b.text.to_string(),
            format!("bundled:{}", b.name),
            base_dir.to_path_buf(),
        )),
        None => Err(format!(
            "a scenario file (relative to the study file) or a bundled scenario ({})",
            bundled()
                .iter()
                .map(|b| b.name)
                .collect::<Vec<_>>()
                .join(", ")
        )),
    }
}

/// Set the dotted `key` (segments `name` or `name[index]`) of `doc` to `value`. Every
/// table on the way must be in the base scenario (the last field may be absent: it then
/// replaces its default): a study varies the base's settings and adds no table, since a
/// table can change what a run is (`signal.cn0_dbhz` on a scenario without `[signal]`
/// made every run a signal-level one).
fn set_key(doc: &mut toml::Table, key: &str, value: toml::Value) -> Result<(), String> {
    let segments: Vec<&str> = key.split('.').collect();
    let mut table = doc;
    for (n, segment) in segments.iter().enumerate() {
        let (name, index) = split_index(segment)?;
        let last = n + 1 == segments.len();
        let slot = match index {
            None if last => {
                table.insert(name.to_string(), value);
                return Ok(());
            }
            None => table.get_mut(name).ok_or_else(|| {
                let path = segments[..=n].join(".");
                format!(
                    "the base scenario has no [{path}] table; a study varies the base's settings \
                     and adds no table (a table can change what a run is: [signal] makes it \
                     signal-level): add [{path}] to the scenario"
                )
            })?,
            Some(i) => {
                let array = table
                    .get_mut(name)
                    .and_then(toml::Value::as_array_mut)
                    .ok_or_else(|| format!("the scenario has no array `{name}`"))?;
                let len = array.len();
                let item = array
                    .get_mut(i)
                    .ok_or_else(|| format!("`{name}` has {len} entries, no [{i}]"))?;
                if last {
                    *item = value;
                    return Ok(());
                }
                item
            }
        };
        table = slot
            .as_table_mut()
            .ok_or_else(|| format!("`{segment}` of `{key}` is not a table"))?;
    }
    Err(format!("`{key}`: an empty key"))
}

/// `name[3]` -> (`name`, Some(3)); `name` -> (`name`, None).
fn split_index(segment: &str) -> Result<(&str, Option<usize>), String> {
    let bad = || format!("`{segment}`: a key segment is `name` or `name[index]`");
    match segment.split_once('[') {
        None if !segment.is_empty() => Ok((segment, None)),
        None => Err(bad()),
        Some((name, rest)) => {
            let index = rest
                .strip_suffix(']')
                .and_then(|i| i.parse().ok())
                .ok_or_else(bad)?;
            Ok((name, Some(index)))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keys_reach_nested_tables_and_arrays_of_tables_but_add_no_table() {
        let mut doc: toml::Table =
            toml::from_str("[signal]\ncn0_dbhz = 45.0\n[[antennas]]\nname = \"a\"\n").unwrap();
        set_key(&mut doc, "signal.cn0_dbhz", toml::Value::Float(40.0)).unwrap();
        set_key(
            &mut doc,
            "antennas[0].name",
            toml::Value::String("b".into()),
        )
        .unwrap();
        set_key(&mut doc, "signal.if_hz", toml::Value::Float(1.0e3)).unwrap();
        let e = set_key(
            &mut doc,
            "errors.multipath.enabled",
            toml::Value::Boolean(true),
        )
        .unwrap_err();
        assert!(e.contains("the base scenario has no [errors] table"), "{e}");
        assert_eq!(doc["signal"]["cn0_dbhz"].as_float(), Some(40.0));
        assert_eq!(doc["signal"]["if_hz"].as_float(), Some(1.0e3));
        assert_eq!(doc["antennas"][0]["name"].as_str(), Some("b"));
        assert!(!doc.contains_key("errors"));
        let e = set_key(&mut doc, "antennas[3].name", toml::Value::Integer(1)).unwrap_err();
        assert!(e.contains("1 entries"), "{e}");
        assert!(set_key(&mut doc, "signal.cn0_dbhz.x", toml::Value::Integer(1)).is_err());
        assert!(split_index("a[x]").is_err() && split_index("").is_err());
    }
}
