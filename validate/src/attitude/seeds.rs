//! Independent runs of one scenario at its level (the observation level's model, or
//! samples synthesised and received): the scenario's seed and the next ones, each run
//! through the attitude chain and compared with its own truth. Runs are
//! independent where epochs within a run are not (loop noise correlated over seconds,
//! double differences sharing a reference), so statistics are taken per run and their
//! spread over runs gives the standard error.

use super::{ChainComparison, compare, nominal_geometry};
use crate::draw::Draw;
use rayon::prelude::*;
use skyforge_navigation::relative::RelativeConfig;
use skyforge_runner::run_at_level;
use skyforge_scenarios::Scenario;
use skyforge_signals::obs_model::Level;

/// Independent runs per setting: the scenario's seed and the next seven.
// assumed: eight runs, chosen before the first run: enough for a standard error of the
// mean over runs, cheap at the observation level (minutes each at the signal level).
pub const SEEDS: u64 = 8;

/// The chain with each of `configs` over `scenario` on the seeds of `draw` (registered:
/// `seed .. seed + SEEDS`), each compared with its truth: one vector of runs (seed order)
/// per configuration. Every configuration reads the same observations of a seed, made
/// once.
pub fn seed_runs(
    scenario: &Scenario,
    configs: &[RelativeConfig],
    draw: Draw,
) -> Result<Vec<Vec<ChainComparison>>, String> {
    let run_seed = |seed: u64| -> Result<Vec<ChainComparison>, String> {
        let mut s = scenario.clone();
        s.seed = seed;
        let fail = |e: &dyn std::fmt::Display| format!("{} seed {}: {e}", scenario.name, s.seed);
        let run = run_at_level(&s).map_err(|e| fail(&e))?;
        let geometry = nominal_geometry(&run);
        configs
            .iter()
            .map(|c| compare(&run, &geometry, c.clone()).map_err(|e| fail(&e)))
            .collect()
    };
    let seeds = draw.seeds(scenario.seed, SEEDS);
    // A signal-level run keeps every core busy itself (synthesis and reception side by
    // side, each parallel inside, waiting on each other): such runs go one at a time,
    // outside the pool. Observation-level runs go side by side on every core.
    let per_seed: Vec<Vec<ChainComparison>> = if scenario.observation.level == Level::Signal {
        seeds.map(run_seed).collect::<Result<_, String>>()?
    } else {
        seeds
            .into_par_iter()
            .map(run_seed)
            .collect::<Result<_, String>>()?
    };
    let mut out: Vec<Vec<ChainComparison>> = configs.iter().map(|_| Vec::new()).collect();
    for runs in per_seed {
        for (all, run) in out.iter_mut().zip(runs) {
            all.push(run);
        }
    }
    Ok(out)
}
