//! Single-epoch ambiguity success rates of the integer searches the chain offers, on an
//! observation-level scenario: every epoch resolved from its own float solution (no
//! integers held from earlier epochs), the best candidate taken whatever its ratio, and
//! compared with the truth's integers. The empirical success rate of integer least
//! squares, P(z_check = z) (Teunissen 1999), for plain LAMBDA and for the searches that
//! also use the known body geometry (Teunissen 2010).
//!
//! Beside it, what the chain does with its acceptance test: the fraction of epochs whose
//! best candidate passes the ratio test at the chain's default threshold, and how many of
//! those were wrong.

use super::{ChainComparison, seed_runs};
use crate::stats::AcrossRuns;
use skyforge_gnss::signal::Signal;
use skyforge_navigation::relative::Constraint;
use skyforge_navigation::relative::RelativeConfig;
use skyforge_scenarios::Scenario;

/// One search on one signal set over the runs.
#[derive(Debug, Clone)]
pub struct SuccessRate {
    pub constraint: Constraint,
    pub signals: Vec<Signal>,
    /// Per run: epochs whose best candidate has every integer right, over all epochs.
    pub success: AcrossRuns,
    /// Per run: epochs whose best candidate passes the default ratio test, over all epochs.
    pub accepted: AcrossRuns,
    /// Accepted epochs with a wrong integer, summed over runs.
    pub accepted_wrong: usize,
    /// Epochs summed over runs.
    pub epochs: usize,
}

impl SuccessRate {
    /// `ILS success ... ; accepted ... with N wrong ; M epochs`, for tables printed by the
    /// tests.
    pub fn summary(&self) -> String {
        format!(
            "ILS success {} ; accepted {} with {} wrong ; {} epochs",
            self.success.describe(1.0, 4),
            self.accepted.describe(1.0, 4),
            self.accepted_wrong,
            self.epochs
        )
    }
}

/// The chain resolving every epoch on its own with `constraint`; `accept_any` takes the
/// best candidate whatever its ratio (the ILS success rate), otherwise the default test.
fn config(signals: &[Signal], constraint: Constraint, accept_any: bool) -> RelativeConfig {
    let mut c = RelativeConfig {
        signals: signals.to_vec(),
        hold: false,
        constraint,
        ..RelativeConfig::default()
    };
    if accept_any {
        c.ratio_threshold = 1.0;
        c.min_success_rate = f64::MIN_POSITIVE;
    }
    c
}

fn rate(runs: &[ChainComparison], good: impl Fn(&ChainComparison) -> usize) -> Option<AcrossRuns> {
    let per_run: Vec<f64> = runs
        .iter()
        .map(|r| good(r) as f64 / r.epochs.max(1) as f64)
        .collect();
    AcrossRuns::of(&per_run)
}

/// The single-epoch success rate of `constraint` with `signals` on the seeds of
/// [`seed_runs`].
pub fn single_epoch(
    scenario: &Scenario,
    signals: &[Signal],
    constraint: Constraint,
) -> Result<SuccessRate, String> {
    let mut rates = single_epoch_each(
        scenario,
        &[signals],
        constraint,
        crate::draw::Draw::REGISTERED,
    )?;
    rates
        .pop()
        .ok_or_else(|| format!("{}: no runs", scenario.name))
}

/// [`single_epoch`] for each of `sets` of signals on the seeds of `draw`, all on the same
/// runs (made once per seed: what a signal-level scenario needs).
pub fn single_epoch_each(
    scenario: &Scenario,
    sets: &[&[Signal]],
    constraint: Constraint,
    draw: crate::draw::Draw,
) -> Result<Vec<SuccessRate>, String> {
    let configs: Vec<RelativeConfig> = sets
        .iter()
        .flat_map(|signals| {
            [
                config(signals, constraint, true),
                config(signals, constraint, false),
            ]
        })
        .collect();
    let runs = seed_runs(scenario, &configs, draw)?;
    let none = || format!("{}: no runs", scenario.name);
    sets.iter()
        .zip(runs.chunks(2))
        .map(|(signals, pair)| {
            let [best, tested] = pair else {
                return Err(format!(
                    "{}: one set of runs per configuration",
                    scenario.name
                ));
            };
            Ok(SuccessRate {
                constraint,
                signals: signals.to_vec(),
                success: rate(best, |r| r.fixed_epochs - r.fixed_epochs_wrong).ok_or_else(none)?,
                accepted: rate(tested, |r| r.fixed_epochs).ok_or_else(none)?,
                accepted_wrong: tested.iter().map(|r| r.fixed_epochs_wrong).sum(),
                epochs: best.iter().map(|r| r.epochs).sum(),
            })
        })
        .collect()
}
