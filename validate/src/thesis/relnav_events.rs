//! B-5.6's events (book section 5.6.5, figures 5-36/5-38): carrier-smoothed relative
//! navigation with each vehicle on its own satellites (the book's procedure, relnav's
//! `satellite_sets = "own"`) on the bundled [`SCENARIO`]: the two sets differ at 39 s
//! and 164 s (a setting satellite the chaser loses 2 s before the target) and the chaser
//! has no pseudoranges at 237 s and 485 s (its smoothers restart).
//!
//! Rows (`BOOK_PAPER001_TARGETS.md` 1.4, REL-ev and REL-tr; registered 2026-12-01 before
//! the first run of the events; each value the mean over seeds 1-4 of a per-run
//! statistic; the book prints no number for any of them):
//! - mismatch: the largest axis position error over the epochs a mismatch lasts, over the
//!   run's steady-state largest (B-5.6's carrier-smoothed steady state: both vehicles on
//!   one set, unchanged for [`STEADY_S`]): the book's "the errors grow rapidly", > 3;
//! - re-initialisation: the largest axis position error over the [`AFTER_EPOCHS`] epochs
//!   after each missed one, over the mismatches': the book's "small jump", < 1;
//! - transient: from the first epoch after a missed one until the largest axis position
//!   error stays within [`SETTLED_M`] up to the next change of either vehicle's
//!   satellites (or the run's end): the book's 50-100 s, [25, 200] s, and every draw
//!   settled. The last condition was added after the first run, which registered the
//!   mean alone with an unsettled draw counted at its window's length: 6 of 8 draws were
//!   unsettled, so the mean (82 s) was mostly the windows' lengths and "reproduced" said
//!   nothing (docs/orbit-determination.md: the ionosphere's code-carrier divergence under
//!   unequal smoothing ages keeps the error near 1 m after a re-initialisation);
//! - velocity: the largest axis velocity error over the [`AFTER_EPOCHS`] epochs after each
//!   missed one, over the run's steady-state largest: "almost unaffected", < 2.

use super::relnav_common::{
    MIN_STEADY_EPOCHS, STEADY_S, TABLE, max_abs, mean_and_note, observe, relnav_config, relnav_run,
    truth_at,
};
use crate::draw::Draw;
use crate::report::{Row, Verdict};
use crate::thesis::ValidateError;
use skyforge_navigation::relnav::{RelnavConfig, RelnavMode, SatelliteSets};
use skyforge_orbits::Vec3;

/// The bundled scenario of these rows.
pub const SCENARIO: &str = "book-relnav-events";
/// Registered runs: seeds `FIRST_SEED ..` (assumed: as B-5.6's other rows).
const FIRST_SEED: u64 = 1;
const RUNS: u64 = 4;
/// The scenario's mismatches: the first epoch (s) and how many epochs the sets differ
/// (the chaser loses the satellite 2 s before the target).
const MISMATCHES: [(f64, usize); 2] = [(39.0, 2), (164.0, 2)];
/// The scenario's epochs without chaser pseudoranges (s).
const MISSED: [f64; 2] = [237.0, 485.0];
/// Epochs after a missed one the jumps are taken over (assumed: 10 s, the start of the
/// book's 50-100 s transient, where a restarted smoother is at its noisiest).
const AFTER_EPOCHS: usize = 10;
/// The position error (largest axis, m) a transient has ended within: REL-CS's
/// reproduction bound, the book's +/-0.5 m steady state at factor 1.6.
const SETTLED_M: f64 = 0.8;

/// One estimate's errors against the truth.
struct Sample {
    t_s: f64,
    /// Both vehicles on one unchanged set for this long (s; 0 while the sets differ).
    same_s: f64,
    position_m: Vec3,
    velocity_mps: Vec3,
}

/// One re-initialisation's transient.
#[derive(Clone, Copy)]
enum Transient {
    /// Settled after this long (s).
    Settled(f64),
    /// Still beyond [`SETTLED_M`] at the end of its window of this length (s).
    Unsettled(f64),
}

impl Transient {
    /// Its length, a window's length where it has not settled (a lower bound).
    fn s(self) -> f64 {
        match self {
            Transient::Settled(s) | Transient::Unsettled(s) => s,
        }
    }
}

/// One run's statistics.
struct RunStats {
    steady_position_m: f64,
    steady_velocity_mps: f64,
    steady_epochs: usize,
    /// Per mismatch, the largest axis position error while the sets differ (m).
    mismatch_m: Vec<f64>,
    /// Per missed epoch, the largest axis position (m) and velocity (m/s) error after it.
    reinit_m: Vec<f64>,
    reinit_mps: Vec<f64>,
    transients: Vec<Transient>,
}

/// The relnav settings of these rows: B-5.6's, carrier-smoothed, own sets.
fn config() -> RelnavConfig {
    RelnavConfig {
        mode: RelnavMode::CarrierSmoothed,
        satellite_sets: SatelliteSets::Own,
        ..relnav_config()
    }
}

/// The samples with `t_s` in `[from, from + epochs)` (whole-second epochs, tagged
/// within milliseconds).
fn window(samples: &[Sample], from: f64, epochs: usize) -> impl Iterator<Item = &Sample> {
    let (lo, hi) = (from - 0.5, from + epochs as f64 - 0.5);
    samples.iter().filter(move |s| (lo..hi).contains(&s.t_s))
}

/// The transient after the missed epoch `missed_s`: over the samples from the next
/// epoch while both vehicles keep one unchanged set and no epoch is missed.
fn transient(samples: &[Sample], missed_s: f64) -> Option<Transient> {
    let first = samples.iter().position(|s| s.t_s > missed_s + 0.5)?;
    let mut end = first + 1;
    while end < samples.len()
        && samples[end].same_s > samples[end - 1].same_s
        && samples[end].t_s - samples[end - 1].t_s < 1.5
    {
        end += 1;
    }
    let run = &samples[first..end];
    let start = run[0].t_s;
    let last_out = run.iter().rposition(|s| s.position_m.amax() > SETTLED_M);
    Some(match last_out {
        None => Transient::Settled(0.0),
        Some(i) if i + 1 == run.len() => Transient::Unsettled(run[i].t_s + 1.0 - start),
        Some(i) => Transient::Settled(run[i + 1].t_s - start),
    })
}

/// One seed's statistics.
fn run_stats(seed: u64) -> Result<RunStats, ValidateError> {
    let (target, chaser) = observe(SCENARIO, seed)?;
    let run = relnav_run(&target, &chaser, &config())?;
    let samples: Vec<Sample> = (run.estimates.iter())
        .filter_map(|e| {
            let (p, v) = truth_at(&target, &chaser, e.t_s)?;
            Some(Sample {
                t_s: e.t_s,
                same_s: e.same_satellites_s,
                position_m: e.position_m - p,
                velocity_mps: e.velocity_mps - v,
            })
        })
        .collect();
    // A run without a steady state has no steady-state largest: the ratios to it are
    // undefined (NaN), left out of the mean and out of tolerance in a draw of its own,
    // as B-5.6's carrier-smoothed rows.
    let steady: Vec<&Sample> = samples.iter().filter(|s| s.same_s >= STEADY_S).collect();
    let steady_max = |f: fn(&&Sample) -> Vec3| {
        if steady.len() < MIN_STEADY_EPOCHS {
            f64::NAN
        } else {
            max_abs(steady.iter().map(f))
        }
    };
    let largest =
        |from: f64, epochs: usize, f: fn(&Sample) -> Vec3| -> Result<f64, ValidateError> {
            let w: Vec<&Sample> = window(&samples, from, epochs).collect();
            if w.is_empty() {
                return Err(ValidateError::Pipeline(format!(
                    "{SCENARIO} seed {seed}: no estimate in the {epochs} epochs from {from} s"
                )));
            }
            Ok(max_abs(w.into_iter().map(f)))
        };
    let position = |s: &Sample| s.position_m;
    let velocity = |s: &Sample| s.velocity_mps;
    let after = |&m: &f64| m + 1.0;
    Ok(RunStats {
        steady_position_m: steady_max(|s| s.position_m),
        steady_velocity_mps: steady_max(|s| s.velocity_mps),
        steady_epochs: steady.len(),
        mismatch_m: (MISMATCHES.iter())
            .map(|&(t, n)| largest(t, n, position))
            .collect::<Result<_, _>>()?,
        reinit_m: (MISSED.iter().map(after))
            .map(|t| largest(t, AFTER_EPOCHS, position))
            .collect::<Result<_, _>>()?,
        reinit_mps: (MISSED.iter().map(after))
            .map(|t| largest(t, AFTER_EPOCHS, velocity))
            .collect::<Result<_, _>>()?,
        transients: (MISSED.iter())
            .map(|&t| {
                transient(&samples, t).ok_or_else(|| {
                    ValidateError::Pipeline(format!(
                        "{SCENARIO} seed {seed}: no estimate after {t} s"
                    ))
                })
            })
            .collect::<Result<_, _>>()?,
    })
}

fn mean(v: impl Iterator<Item = f64>) -> f64 {
    let v: Vec<f64> = v.collect();
    v.iter().sum::<f64>() / v.len() as f64
}

/// The four event rows over `draw`'s runs.
pub fn rows(draw: Draw) -> Result<Vec<Row>, ValidateError> {
    let seeds = draw.seeds(FIRST_SEED, RUNS);
    let runs = (seeds.clone())
        .map(run_stats)
        .collect::<Result<Vec<_>, _>>()?;
    let seeds_note = format!(
        "{SCENARIO}, carrier-smoothed on each vehicle's own satellites, seeds {}..{}",
        seeds.start,
        seeds.end - 1
    );
    let (mismatch, each_mismatch) = mean_and_note(
        &runs,
        |r| mean(r.mismatch_m.iter().map(|m| m / r.steady_position_m)),
        1,
    );
    let (_, each_mismatch_m) = mean_and_note(&runs, |r| mean(r.mismatch_m.iter().copied()), 2);
    let (_, each_steady) = mean_and_note(&runs, |r| r.steady_position_m, 3);
    let (_, each_epochs) = mean_and_note(&runs, |r| r.steady_epochs as f64, 0);
    let (reinit, each_reinit) = mean_and_note(
        &runs,
        |r| mean(r.reinit_m.iter().copied()) / mean(r.mismatch_m.iter().copied()),
        3,
    );
    let (_, each_reinit_m) = mean_and_note(&runs, |r| mean(r.reinit_m.iter().copied()), 2);
    let (transient, each_transient) =
        mean_and_note(&runs, |r| mean(r.transients.iter().map(|t| t.s())), 0);
    let unsettled = (runs.iter())
        .flat_map(|r| &r.transients)
        .filter(|t| matches!(t, Transient::Unsettled(_)))
        .count();
    let (velocity, each_velocity) = mean_and_note(
        &runs,
        |r| mean(r.reinit_mps.iter().map(|v| v / r.steady_velocity_mps)),
        2,
    );
    Ok(vec![
        Row::measured(
            TABLE,
            "events: satellite-set mismatch / steady-state max, position",
            "ratio",
            "-",
            None,
            mismatch,
            (
                "> 3 (\"the errors grow rapidly\")".into(),
                Verdict::from_ok(mismatch > 3.0),
            ),
        )
        .with_note(format!(
            "the largest axis position error while the sets differ (39-40 s and 164-165 s: \
             {each_mismatch_m} m per seed) over the steady-state largest ({each_steady} m \
             over {each_epochs} epochs); per seed {each_mismatch}; {seeds_note}"
        )),
        Row::measured(
            TABLE,
            "events: re-initialisation jump / mismatch jump, position",
            "ratio",
            "-",
            None,
            reinit,
            (
                "< 1 (\"a small jump\")".into(),
                Verdict::from_ok(reinit < 1.0),
            ),
        )
        .with_note(format!(
            "the largest axis position error over the {AFTER_EPOCHS} epochs after the \
             chaser's missing pseudoranges (237 s, 485 s: {each_reinit_m} m per seed) over \
             the mismatches'; per seed {each_reinit}; {seeds_note}"
        )),
        Row::measured(
            TABLE,
            "events: transient after re-initialisation",
            "mean",
            "s",
            None,
            transient,
            (
                "[25, 200] s (the book's 50-100 s), every draw settled".into(),
                Verdict::from_ok(unsettled == 0 && (25.0..=200.0).contains(&transient)),
            ),
        )
        .with_note(format!(
            "from the first epoch after the missing one until the largest axis position \
             error stays within {SETTLED_M} m, up to the next change of either vehicle's \
             satellites; per seed (mean of the two) {each_transient}; unsettled at the \
             window's end: {unsettled} of {} (counted at the window's length, a lower \
             bound); {seeds_note}",
            2 * runs.len()
        )),
        Row::measured(
            TABLE,
            "events: velocity after re-initialisation / steady-state max",
            "ratio",
            "-",
            None,
            velocity,
            (
                "< 2 (\"almost unaffected\")".into(),
                Verdict::from_ok(velocity < 2.0),
            ),
        )
        .with_note(format!(
            "the largest axis velocity error over the {AFTER_EPOCHS} epochs after the \
             missing pseudoranges over the steady-state largest (the Doppler velocities \
             are not smoothed); per seed {each_velocity}; {seeds_note}"
        )),
    ])
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sample(t_s: f64, same_s: f64, error_m: f64) -> Sample {
        Sample {
            t_s,
            same_s,
            position_m: Vec3::new(0.0, -error_m, 0.0),
            velocity_mps: Vec3::zeros(),
        }
    }

    #[test]
    fn transients_end_where_the_error_stays_within_the_bound_or_the_set_changes() {
        // Missed epoch at 10 s; from 11 s the error falls below 0.8 m at 14 s, one more
        // excursion at 16 s, within from 17 s; a set change at 20 s ends the window.
        let errors = [5.0, 2.0, 1.0, 0.5, 0.5, 0.9, 0.3, 0.2, 0.1, 3.0, 3.0];
        let samples: Vec<Sample> = (errors.iter().enumerate())
            .map(|(k, &e)| {
                let same = if k < 9 { k as f64 } else { (k - 9) as f64 };
                sample(11.0 + k as f64, same, e)
            })
            .collect();
        assert!(matches!(transient(&samples, 10.0), Some(Transient::Settled(s)) if s == 6.0));
        // Still beyond at the window's end: unsettled, the window's length.
        let tail: Vec<Sample> = (0..5)
            .map(|k| sample(11.0 + k as f64, k as f64, 2.0))
            .collect();
        assert!(matches!(transient(&tail, 10.0), Some(Transient::Unsettled(s)) if s == 5.0));
        // Never beyond: no transient.
        let calm: Vec<Sample> = (0..5)
            .map(|k| sample(11.0 + k as f64, k as f64, 0.1))
            .collect();
        assert!(matches!(transient(&calm, 10.0), Some(Transient::Settled(s)) if s == 0.0));
        assert!(transient(&calm, 20.0).is_none());
        assert_eq!(window(&samples, 12.0, 2).count(), 2);
    }
}
