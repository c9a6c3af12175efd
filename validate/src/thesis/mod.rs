//! The thesis acceptance tables (`../shared/reference/THESIS_TARGETS.md`): each module runs
//! the bundled scenarios of its table and returns one [`Row`](crate::report::Row) per
//! printed number; T-3.3-R, T-3.3-S, T-4.3 and T-5.5 also give the data of the thesis
//! figures they compute ([`curves`]).

pub(crate) mod attitude_noise;
pub(crate) mod attitude_realtime;
mod attitude_runs;
pub(crate) mod boat_lake;
pub(crate) mod book_cascade;
pub(crate) mod book_gps_ins;
pub mod curves;
pub(crate) mod fast_sync;
pub(crate) mod geometry_offsets;
mod geometry_run;
pub(crate) mod loop_budget;
pub(crate) mod orbit_determination;
pub(crate) mod pmf_fft;
pub(crate) mod relative_navigation;
pub(crate) mod relnav_common;
pub(crate) mod relnav_events;
pub(crate) mod reverse_filter;
pub(crate) mod static_sins;
pub(crate) mod tdcp_clock;
pub(crate) mod tdcp_ins;
pub(crate) mod visibility;
pub(crate) mod zero_baseline;

pub use loop_budget::{LoopFigure, figure_settings};

use crate::draw::{self, Draw, Kind, SeedPlan};
use crate::integrity::raim;
use crate::report::Row;
use curves::Curve;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// Table identifiers `validate thesis --only` accepts, in run order.
pub const TABLES: &[&str] = &[
    "V-1.2.1", "T-1.2-2", "T-1.2-3", "T-3.2", "T-3.3-R", "T-3.3-S", "T-4.3", "T-5.4-2", "T-5.4-3",
    "T-5.4-4", "T-5.4-5", "T-5.5", "P2-4.2", "P2-PD", "B-5.2-1", "B-5.2-2", "B-5.5", "B-5.6",
    "P1-S", "P1-F2", "P1-D", "B-3.2",
];

/// Why a validation could not run.
#[derive(Debug, thiserror::Error)]
pub enum ValidateError {
    #[error("bundled scenario: {0}")]
    Scenario(Box<skyforge_scenarios::ScenarioError>),
    #[error("geometry: {0}")]
    Geometry(String),
    #[error("acquisition: {0}")]
    Acquisition(#[from] skyforge_receiver::acquisition::AcquisitionError),
    #[error("tracking: {0}")]
    Tracking(#[from] skyforge_receiver::tracking::TrackingError),
    #[error("observations: {0}")]
    Observations(#[from] crate::observables::ObsError),
    #[error("{0}")]
    Pipeline(String),
    #[error("unknown table {id:?}; known tables: {known}")]
    UnknownTable { id: String, known: String },
}

impl From<skyforge_scenarios::ScenarioError> for ValidateError {
    fn from(e: skyforge_scenarios::ScenarioError) -> Self {
        ValidateError::Scenario(Box::new(e))
    }
}

/// What to run.
#[derive(Debug, Clone, Default)]
pub struct Options {
    /// Table IDs to run (empty: all).
    pub only: Vec<String>,
    /// The real-data folder (`SKYFORGE_DATA`); tables add real-data rows when it exists.
    pub data_dir: Option<PathBuf>,
    /// `--seeds N --seed-base B`: each table as a study over seeds ([`crate::draw`]); `None`:
    /// each table once on its registered seeds.
    pub plan: Option<SeedPlan>,
}

/// Whether `--only id` selects `table`: the same identifier, or a group of it (`T-1.2`
/// selects `T-1.2-2` and `T-1.2-3`), ignoring case.
fn selects(id: &str, table: &str) -> bool {
    let (id, table) = (id.to_ascii_uppercase(), table.to_ascii_uppercase());
    table == id
        || table
            .strip_prefix(&id)
            .is_some_and(|rest| rest.starts_with('-'))
}

/// Whether `--only id` selects any table.
pub fn known(id: &str) -> bool {
    TABLES.iter().any(|t| selects(id, t))
}

/// Where a table's scenario comes from.
#[derive(Debug, Clone, Copy)]
enum Source {
    /// A bundled scenario, by name (never a file of that name).
    Bundled(&'static str),
    /// The embedded scenario of a RAIM setting (a file of [`raim::SCENARIO_DIR`]).
    Raim(fn() -> raim::Setting),
}

/// An evaluation: the rows of the `wanted` tables of its group.
type Evaluate = fn(&[&str], Option<&Path>, Draw) -> Result<Vec<Row>, ValidateError>;

/// The tables of one evaluation (a group whose tables share runs), how it takes part in a
/// plan over seeds, its scenarios, the evaluation itself (`wanted`: the group's selected
/// tables) and the thesis figures it computes.
struct Unit {
    tables: &'static [&'static str],
    kind: Kind,
    scenarios: &'static [Source],
    evaluate: Evaluate,
    figures: Option<Figures>,
}

/// Rows and figures' data of one evaluation.
type RowsAndCurves = Result<(Vec<Row>, Vec<Curve>), ValidateError>;

/// The thesis figures of a one-table unit, always on its registered seeds: with the rows
/// of that evaluation (one computation, for a run on the registered seeds), or alone (for
/// a run over seeds, whose draws give the rows).
struct Figures {
    with_rows: fn() -> RowsAndCurves,
    alone: fn() -> Result<Vec<Curve>, ValidateError>,
}

fn has(wanted: &[&str], table: &str) -> bool {
    wanted.contains(&table)
}

/// Every table, in run order.
const UNITS: &[Unit] = &[
    Unit {
        tables: &["V-1.2.1"],
        kind: Kind::PerRun,
        scenarios: &[Source::Bundled(visibility::SCENARIO)],
        evaluate: |_, data, draw| visibility::rows(data, draw),
        figures: None,
    },
    Unit {
        tables: &[attitude_noise::TABLE_NOISE, attitude_noise::TABLE_OFFSETS],
        kind: Kind::PerRun,
        scenarios: &[
            Source::Bundled(attitude_noise::SCENARIO_NOISE),
            Source::Bundled(attitude_noise::SCENARIO_OFFSETS),
        ],
        evaluate: |wanted, _, draw| {
            attitude_noise::rows(
                has(wanted, attitude_noise::TABLE_NOISE),
                has(wanted, attitude_noise::TABLE_OFFSETS),
                draw,
            )
        },
        figures: None,
    },
    Unit {
        tables: &["T-3.2"],
        kind: Kind::Deterministic,
        scenarios: &[Source::Bundled(loop_budget::SCENARIO)],
        evaluate: |_, _, _| loop_budget::rows(),
        figures: None,
    },
    Unit {
        tables: &["T-3.3-R"],
        kind: Kind::PerRun,
        scenarios: &[],
        evaluate: |_, _, draw| pmf_fft::rows(draw),
        figures: Some(Figures {
            with_rows: pmf_fft::rows_and_curves,
            alone: pmf_fft::curves,
        }),
    },
    Unit {
        tables: &["T-3.3-S"],
        kind: Kind::PerRun,
        scenarios: &[],
        evaluate: |_, _, draw| fast_sync::rows(draw),
        figures: Some(Figures {
            with_rows: fast_sync::rows_and_curves,
            alone: fast_sync::curves,
        }),
    },
    Unit {
        tables: &[geometry_offsets::TABLE],
        kind: Kind::PerRun,
        scenarios: &[Source::Bundled(geometry_offsets::SCENARIO)],
        evaluate: |_, _, draw| geometry_offsets::rows(draw),
        figures: Some(Figures {
            with_rows: geometry_offsets::rows_and_curves,
            alone: geometry_offsets::curves,
        }),
    },
    Unit {
        tables: &[zero_baseline::TABLE],
        kind: Kind::PerRun,
        scenarios: &[Source::Bundled(zero_baseline::SCENARIO)],
        evaluate: |_, _, draw| zero_baseline::rows_from_chain(draw),
        figures: None,
    },
    Unit {
        tables: &attitude_realtime::TABLES,
        kind: Kind::PerRun,
        scenarios: &[Source::Bundled(attitude_realtime::SCENARIO)],
        evaluate: |_, _, draw| attitude_realtime::rows(draw),
        figures: None,
    },
    Unit {
        tables: &[reverse_filter::TABLE],
        kind: Kind::PerRun,
        scenarios: &[Source::Bundled(reverse_filter::SCENARIO)],
        evaluate: |_, _, draw| reverse_filter::rows(draw),
        figures: Some(Figures {
            with_rows: reverse_filter::rows_and_curves,
            alone: reverse_filter::curves,
        }),
    },
    Unit {
        tables: &[
            crate::integrity::patterns::TABLE,
            crate::integrity::detection::TABLE,
        ],
        kind: Kind::MonteCarlo,
        scenarios: &[Source::Bundled(crate::integrity::lab::SCENARIO)],
        evaluate: |wanted, _, draw| {
            crate::integrity::rows(
                draw,
                has(wanted, crate::integrity::patterns::TABLE),
                has(wanted, crate::integrity::detection::TABLE),
            )
            .map_err(ValidateError::Pipeline)
        },
        figures: None,
    },
    Unit {
        tables: &[raim::TABLE_MOPS, raim::TABLE_LEO],
        kind: Kind::MonteCarlo,
        scenarios: &[
            Source::Raim(raim::mops_setting),
            Source::Raim(raim::leo_setting),
        ],
        evaluate: |wanted, _, draw| {
            raim::rows(
                has(wanted, raim::TABLE_MOPS),
                has(wanted, raim::TABLE_LEO),
                raim::RUNS,
                draw.offset,
            )
        },
        figures: None,
    },
    Unit {
        tables: &[orbit_determination::TABLE],
        kind: Kind::PerRun,
        scenarios: &[Source::Bundled(orbit_determination::SCENARIO)],
        evaluate: |_, _, draw| orbit_determination::rows(draw),
        figures: None,
    },
    Unit {
        tables: &[relnav_common::TABLE],
        kind: Kind::PerRun,
        scenarios: &[
            Source::Bundled(relative_navigation::SCENARIO),
            Source::Bundled(relnav_events::SCENARIO),
        ],
        evaluate: |_, _, draw| {
            let mut rows = relative_navigation::rows(draw)?;
            rows.extend(relnav_events::rows(draw)?);
            Ok(rows)
        },
        figures: None,
    },
    Unit {
        tables: &[static_sins::TABLE],
        kind: Kind::MonteCarlo,
        scenarios: &[Source::Bundled(tdcp_ins::SCENARIO)],
        evaluate: |_, _, draw| {
            let mut rows = static_sins::rows(draw)?;
            rows.extend(tdcp_ins::rows(draw)?);
            Ok(rows)
        },
        figures: None,
    },
    Unit {
        tables: &[tdcp_clock::TABLE],
        kind: Kind::PerRun,
        scenarios: &[Source::Bundled(tdcp_clock::SCENARIO)],
        evaluate: |_, _, draw| tdcp_clock::rows(draw),
        figures: None,
    },
    Unit {
        tables: &[boat_lake::TABLE],
        kind: Kind::MonteCarlo,
        scenarios: &[Source::Bundled(boat_lake::SCENARIO)],
        evaluate: |_, _, draw| boat_lake::rows(draw),
        figures: None,
    },
    Unit {
        tables: &[book_gps_ins::TABLE],
        kind: Kind::MonteCarlo,
        scenarios: &[Source::Bundled(book_gps_ins::SCENARIO)],
        evaluate: |_, _, draw| {
            let mut rows = book_gps_ins::rows(draw)?;
            rows.extend(book_cascade::rows(draw)?);
            Ok(rows)
        },
        figures: None,
    },
];

/// A scenario a run used, as `results.json` records it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ScenarioSource {
    /// The bundled name, or the path of the file an embedded scenario was compiled from.
    pub name: String,
    /// `bundled` (a bundled scenario) or `embedded` (a RAIM setting's scenario).
    pub origin: String,
    /// The scenario's text as the run read it.
    pub text: String,
}

/// What a `validate thesis` run was: `results.json` beside its rows.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Provenance {
    /// SkyForge's version and the commit it was built from (`unknown` outside a git
    /// checkout).
    pub version: String,
    pub commit: String,
    /// The tables run.
    pub tables: Vec<String>,
    /// The plan over seeds (`None`: registered seeds).
    pub plan: Option<SeedPlan>,
    pub scenarios: Vec<ScenarioSource>,
}

/// A run's rows and what it was.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Results {
    pub provenance: Provenance,
    pub rows: Vec<Row>,
}

/// What a run gives: its rows (`results.json`) and the data of the thesis figures its
/// tables compute (`curves.json`), the latter always on the registered seeds.
#[derive(Debug, Clone, PartialEq)]
pub struct Outcome {
    pub results: Results,
    pub curves: Vec<Curve>,
}

fn source_of(source: Source) -> ScenarioSource {
    match source {
        Source::Bundled(name) => ScenarioSource {
            name: name.to_string(),
            origin: "bundled".into(),
            text: skyforge_scenarios::bundled()
                .iter()
                .find(|b| b.name == name)
                .map_or_else(String::new, |b| b.text.to_string()),
        },
        Source::Raim(setting) => {
            let setting = setting();
            ScenarioSource {
                text: setting.scenario_text.to_string(),
                name: Path::new(raim::SCENARIO_DIR)
                    .join(setting.scenario_file)
                    .display()
                    .to_string(),
                origin: "embedded".into(),
            }
        }
    }
}

/// Tables whose runs stream the synthesis into the receiver (`runner::signal_run_with`: two
/// threads waiting on each other, each parallel inside): under a plan their draws go one at
/// a time, outside the pool, since draws side by side on the pool's workers would leave no
/// worker for the synthesis they wait on.
const ONE_DRAW_AT_A_TIME: &[&str] = &[tdcp_clock::TABLE];

/// One unit's rows under `plan` (`None`: registered seeds) and its figures' data (on its
/// registered seeds either way).
fn evaluate_unit(
    unit: &Unit,
    wanted: &[&str],
    data: Option<&Path>,
    plan: Option<SeedPlan>,
) -> RowsAndCurves {
    if let (None, Some(figures)) = (plan, &unit.figures) {
        return (figures.with_rows)();
    }
    let eval = |draw| (unit.evaluate)(wanted, data, draw);
    let rows = match (plan, unit.kind) {
        (None, _) => eval(Draw::REGISTERED)?,
        (Some(plan), Kind::PerRun) => {
            let draws: Vec<Draw> = plan.each().collect();
            let rows: Vec<Vec<Row>> = if unit.tables.iter().any(|t| ONE_DRAW_AT_A_TIME.contains(t))
            {
                draws.into_iter().map(eval).collect::<Result<_, _>>()?
            } else {
                draws.into_par_iter().map(eval).collect::<Result<_, _>>()?
            };
            draw::combine(plan, &rows)
        }
        (Some(plan), kind) => {
            let draw = match kind {
                Kind::MonteCarlo => Draw::shifted(plan.base),
                _ => Draw::REGISTERED,
            };
            eval(draw)?
                .into_iter()
                .map(|r| draw::once(kind, plan, r))
                .collect()
        }
    };
    let curves = match &unit.figures {
        Some(figures) => (figures.alone)()?,
        None => Vec::new(),
    };
    Ok((rows, curves))
}

/// Run the selected tables and return their rows with the run's provenance, and their
/// figures' data; `starting` is told each table's ID before it runs (for progress
/// output).
pub fn run(opts: &Options, mut starting: impl FnMut(&str)) -> Result<Outcome, ValidateError> {
    for id in &opts.only {
        if !known(id) {
            return Err(ValidateError::UnknownTable {
                id: id.clone(),
                known: TABLES.join(", "),
            });
        }
    }
    let selected = |t: &str| opts.only.is_empty() || opts.only.iter().any(|id| selects(id, t));
    let (mut rows, mut curves) = (Vec::new(), Vec::new());
    let mut provenance = Provenance {
        version: env!("CARGO_PKG_VERSION").to_string(),
        commit: option_env!("SKYFORGE_COMMIT")
            .unwrap_or("unknown")
            .to_string(),
        tables: Vec::new(),
        plan: opts.plan,
        scenarios: Vec::new(),
    };
    for unit in UNITS {
        let wanted: Vec<&str> = unit
            .tables
            .iter()
            .copied()
            .filter(|t| selected(t))
            .collect();
        let Some(first) = wanted.first() else {
            continue;
        };
        match opts.plan {
            Some(plan) if unit.kind == Kind::PerRun => {
                starting(&format!("{first} over {} seeds", plan.draws))
            }
            _ => starting(first),
        }
        let (unit_rows, unit_curves) =
            evaluate_unit(unit, &wanted, opts.data_dir.as_deref(), opts.plan)?;
        curves.extend(unit_curves);
        rows.extend(
            unit_rows
                .into_iter()
                .filter(|r| wanted.contains(&r.table.as_str())),
        );
        provenance
            .tables
            .extend(wanted.iter().map(|t| t.to_string()));
        provenance
            .scenarios
            .extend(unit.scenarios.iter().map(|&s| source_of(s)));
    }
    Ok(Outcome {
        results: Results { provenance, rows },
        curves,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// results.json records every table's scenario text: each source resolves to one.
    #[test]
    fn every_scenario_source_has_its_text() {
        for source in UNITS.iter().flat_map(|u| u.scenarios) {
            let recorded = source_of(*source);
            assert!(
                recorded.text.contains("[time]") || recorded.text.contains("[platform"),
                "{}: no scenario text",
                recorded.name
            );
        }
    }

    #[test]
    fn figures_are_on_the_registered_seed_also_over_seeds() {
        let unit = UNITS
            .iter()
            .find(|u| u.tables == [fast_sync::TABLE])
            .unwrap();
        let (rows, curves) = evaluate_unit(unit, unit.tables, None, None).unwrap();
        assert_eq!(rows, fast_sync::rows(Draw::REGISTERED).unwrap());
        assert_eq!(curves, fast_sync::curves().unwrap());
        let plan = SeedPlan { draws: 1, base: 7 };
        let (rows_7, curves_7) = evaluate_unit(unit, unit.tables, None, Some(plan)).unwrap();
        assert_eq!(curves_7, curves);
        assert!(rows_7.iter().all(|r| r.over_seeds.is_some()));
        assert_ne!(
            rows_7.iter().map(|r| r.ours).collect::<Vec<_>>(),
            rows.iter().map(|r| r.ours).collect::<Vec<_>>()
        );
    }

    #[test]
    fn t_5_5_gives_its_figures_with_its_rows_and_over_seeds() {
        // Thesis figures 5.5-2..5.5-5: from the rows' own runs on the registered seeds,
        // the same figures under a plan (T-4.3 is wired alike; its runs take minutes).
        let unit = UNITS
            .iter()
            .find(|u| u.tables == [reverse_filter::TABLE])
            .unwrap();
        let (rows, curves) = evaluate_unit(unit, unit.tables, None, None).unwrap();
        assert_eq!(rows, reverse_filter::rows(Draw::REGISTERED).unwrap());
        assert_eq!(curves.len(), 8);
        assert!(curves.iter().all(|c| c.figure.starts_with("5.5-")));
        let plan = SeedPlan { draws: 1, base: 7 };
        let (rows_7, curves_7) = evaluate_unit(unit, unit.tables, None, Some(plan)).unwrap();
        assert_eq!(curves_7, curves);
        assert!(rows_7.iter().all(|r| r.over_seeds.is_some()));
    }

    #[test]
    fn only_selects_a_table_or_its_group() {
        assert!(selects("t-1.2-2", "T-1.2-2"));
        assert!(selects("T-1.2", "T-1.2-3"));
        assert!(selects("T-5.4", "T-5.4-2"));
        assert!(!selects("T-5.4-2", "T-5.4-3"));
        assert!(!selects("T-1", "T-1.2-2"));
        assert!(!selects("T-3.3", "T-3.2"));
        assert!(!selects("T-3.3-", "T-3.3-R"));
        assert!(selects("T-5.5", "T-5.5"));
        assert!(!selects("T-5.5", "T-5.4-5"));
    }
}
