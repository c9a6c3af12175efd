//! B-5.6: relative navigation of two spacecraft (book sections 5.6.4-5.6.5): a chaser 32
//! km behind a target at 500 km, e = 0.01 (bundled [`SCENARIO`], SA-era satellite errors,
//! GPS L1 C/A at the observation level with Doppler noise), each vehicle's observations
//! into `navigation::relnav`, against the relative truth in the target's orbit frame.
//!
//! Rows (`BOOK_PAPER001_TARGETS.md` 1.4; every value the mean over the registered runs,
//! seeds 1-4, of a per-run statistic):
//! - REL-DGPS: relative DGPS (fixes on the common satellites, differenced) "clearly
//!   better" than standalone: its 3-D RMS at most half the chaser's standalone fixes'
//!   3-D RMS (no number printed);
//! - REL-CS: carrier-smoothed relative positioning in steady state (the book's: the
//!   smoothing has run 50-100 s, here [`STEADY_S`], and neither vehicle has changed
//!   satellites since): the largest absolute error over the three axes and those epochs,
//!   position (book 0.5 m; reproduced in [0.1, 0.8] m) and velocity (book 0.002 m/s,
//!   printed "m"; reproduced up to 0.0032 m/s).
//!
//!
//! - REL-DGPS again with the book's pseudorange relative DGPS (eq. 5-59, relnav's mode
//!   `single-difference` with its defaults; registered 2026-12-01 before its first run):
//!   its 3-D RMS at most half the standalone fixes'.
//!
//! The events of the book's figures 5-36/5-38 have their own scenario and rows
//! ([`super::relnav_events`]); what both share is [`super::relnav_common`].

use super::relnav_common::{
    MIN_STEADY_EPOCHS, STEADY_S, TABLE, max_abs, mean_and_note, observe, relnav_config, relnav_run,
    truth_at,
};
use crate::draw::Draw;
use crate::report::{Row, Verdict};
use crate::stats::rms;
use crate::thesis::ValidateError;
use skyforge_gnss::signal::Signal;
use skyforge_navigation::pvt::PvtConfig;
use skyforge_navigation::relative::single_point_fixes;
use skyforge_navigation::relnav::{HillFilterConfig, RelativeEstimate, RelnavConfig, RelnavMode};
use skyforge_orbits::Vec3;
use skyforge_orbits::ephemeris::EphemerisStore;
use skyforge_orbits::time::TimeOrigin;
use skyforge_runner::ObservationRun;

/// The bundled scenario of this table.
pub const SCENARIO: &str = "book-relnav-leo";
/// Registered runs: seeds `FIRST_SEED ..` (assumed: four, as B-5.5).
const FIRST_SEED: u64 = 1;
const RUNS: u64 = 4;
/// One set-up's statistics of one run: the differences as they are, or through the
/// book's relative filter.
struct SetupStats {
    /// 3-D RMS of relative DGPS (m).
    dgps_m: f64,
    /// Carrier-smoothed, steady state: the largest absolute axis error of position (m)
    /// and velocity (m/s).
    cs_position_m: f64,
    cs_velocity_mps: f64,
    /// Carrier-smoothed estimates in steady state.
    steady_epochs: usize,
}

/// One run's statistics.
struct RunStats {
    /// 3-D RMS of the chaser's standalone fixes (m).
    standalone_m: f64,
    /// The differences as they are (the registered set-up of 2026-11-30).
    plain: SetupStats,
    /// Through the book's relative filter (`relnav::HillFilter`, its defaults; the
    /// second set-up, registered 2026-12-01 before its first run).
    filtered: SetupStats,
    /// 3-D RMS (m) and velocity 3-D RMS (m/s) of the single-difference pseudorange
    /// filter (eq. 5-59).
    single_difference_m: f64,
    single_difference_mps: f64,
}

/// Each estimate's position and velocity errors where its fix has used the same
/// satellites for `steady_s` or more.
fn errors(
    target: &ObservationRun,
    chaser: &ObservationRun,
    estimates: &[RelativeEstimate],
    steady_s: f64,
) -> Vec<(Vec3, Vec3)> {
    (estimates.iter())
        .filter(|e| e.same_satellites_s >= steady_s)
        .filter_map(|e| {
            let (p, v) = truth_at(target, chaser, e.t_s)?;
            Some((e.position_m - p, e.velocity_mps - v))
        })
        .collect()
}

/// One seed's statistics.
fn run_stats(seed: u64) -> Result<RunStats, ValidateError> {
    let (target, chaser) = observe(SCENARIO, seed)?;
    let relnav = |mode: RelnavMode, filter: Option<HillFilterConfig>| {
        let config = RelnavConfig {
            mode,
            filter,
            ..relnav_config()
        };
        relnav_run(&target, &chaser, &config)
    };
    let c_file = (chaser.measured.first())
        .ok_or_else(|| ValidateError::Pipeline("no observations".into()))?;
    // The chaser's standalone fixes against its truth.
    let origin = TimeOrigin::new(chaser.start);
    let store = EphemerisStore::new(chaser.ephemerides.clone(), &origin);
    let pvt = PvtConfig {
        iono_gps: chaser.iono.gps,
        iono_bds: chaser.iono.bds,
        ..PvtConfig::default()
    };
    let fixes = single_point_fixes(c_file, &store, &origin, &[Signal::GpsL1Ca], &pvt);
    let standalone: Vec<f64> = (fixes.iter().flatten())
        .filter_map(|f| Some((f.r_ecef_m - chaser.true_position(0, f.t_s)?).norm()))
        .collect();
    let setup = |filter: Option<HillFilterConfig>| -> Result<SetupStats, ValidateError> {
        let dgps = relnav(RelnavMode::PositionDifference, filter.clone())?;
        let dgps_errors = errors(&target, &chaser, &dgps.estimates, 0.0);
        let cs = relnav(RelnavMode::CarrierSmoothed, filter)?;
        let cs_errors = errors(&target, &chaser, &cs.estimates, STEADY_S);
        if dgps_errors.len() < 10 {
            return Err(ValidateError::Pipeline(format!(
                "seed {seed}: {} relative DGPS estimates",
                dgps_errors.len(),
            )));
        }
        // A run whose satellites never stayed the same for STEADY_S has no steady state:
        // its carrier-smoothed statistics are undefined (NaN), left out of the mean and
        // counted in the note.
        let steady_max = |f: fn(&(Vec3, Vec3)) -> Vec3| {
            if cs_errors.len() < MIN_STEADY_EPOCHS {
                f64::NAN
            } else {
                max_abs(cs_errors.iter().map(f))
            }
        };
        Ok(SetupStats {
            dgps_m: rms(&dgps_errors.iter().map(|e| e.0.norm()).collect::<Vec<_>>()),
            cs_position_m: steady_max(|e| e.0),
            cs_velocity_mps: steady_max(|e| e.1),
            steady_epochs: cs_errors.len(),
        })
    };
    if standalone.len() < 10 {
        return Err(ValidateError::Pipeline(format!(
            "seed {seed}: {} standalone fixes",
            standalone.len()
        )));
    }
    let sd = relnav(RelnavMode::SingleDifference, None)?;
    let sd_errors = errors(&target, &chaser, &sd.estimates, 0.0);
    if sd_errors.len() < 10 {
        return Err(ValidateError::Pipeline(format!(
            "seed {seed}: {} single-difference estimates",
            sd_errors.len(),
        )));
    }
    let norms = |f: fn(&(Vec3, Vec3)) -> Vec3| {
        rms(&sd_errors.iter().map(|e| f(e).norm()).collect::<Vec<_>>())
    };
    Ok(RunStats {
        single_difference_m: norms(|e| e.0),
        single_difference_mps: norms(|e| e.1),
        standalone_m: rms(&standalone),
        plain: setup(None)?,
        // # assumed: the filter's defaults (docs/orbit-determination.md), the book's J2
        // and drag for U; chosen before the first run of this set-up.
        filtered: setup(Some(HillFilterConfig::default()))?,
    })
}

/// The rows of B-5.6 over `draw`'s runs: the registered set-up (the differences as they
/// are), then the same rows through the book's relative filter.
pub fn rows(draw: Draw) -> Result<Vec<Row>, ValidateError> {
    let seeds = draw.seeds(FIRST_SEED, RUNS);
    let runs = seeds
        .clone()
        .map(run_stats)
        .collect::<Result<Vec<_>, _>>()?;
    let seeds_note = format!("seeds {}..{}", seeds.start, seeds.end - 1);
    let mut rows = setup_rows(&runs, |r| &r.plain, "", &seeds_note);
    rows.extend(setup_rows(
        &runs,
        |r| &r.filtered,
        " (relative filter)",
        &seeds_note,
    ));
    rows.push(single_difference_row(&runs, &seeds_note));
    Ok(rows)
}

/// REL-DGPS with the book's pseudorange relative DGPS filter (eq. 5-59).
fn single_difference_row(runs: &[RunStats], seeds_note: &str) -> Row {
    let (ratio, each_ratio) = mean_and_note(runs, |r| r.single_difference_m / r.standalone_m, 4);
    let (position, each_position) = mean_and_note(runs, |r| r.single_difference_m, 3);
    let (velocity, each_velocity) = mean_and_note(runs, |r| r.single_difference_mps, 4);
    dgps_ratio_row(
        "pseudorange relative DGPS (eq. 5-59) / standalone, 3-D RMS".into(),
        ratio,
    )
    .with_note(format!(
        "relnav mode single-difference (a filter on the single differences of pseudorange \
         and Doppler range rate, its defaults), every epoch: {position:.3} m \
         ({each_position}), velocity {velocity:.4} m/s ({each_velocity}); per seed \
         {each_ratio}; {seeds_note}"
    ))
}

/// REL-DGPS's row `name`: a relative DGPS 3-D RMS over the chaser's standalone one,
/// "clearly better" at most half.
fn dgps_ratio_row(name: String, ratio: f64) -> Row {
    Row::measured(
        TABLE,
        name,
        "ratio",
        "-",
        None,
        ratio,
        (
            "<= 0.5 (\"clearly better\")".into(),
            Verdict::from_ok(ratio <= 0.5),
        ),
    )
}

/// The three rows of one set-up (`pick` of each run), their names ending in `suffix`.
fn setup_rows(
    runs: &[RunStats],
    pick: fn(&RunStats) -> &SetupStats,
    suffix: &str,
    seeds_note: &str,
) -> Vec<Row> {
    let (ratio, each_ratio) = mean_and_note(runs, |r| pick(r).dgps_m / r.standalone_m, 4);
    let (dgps, each_dgps) = mean_and_note(runs, |r| pick(r).dgps_m, 3);
    let (standalone, each_standalone) = mean_and_note(runs, |r| r.standalone_m, 2);
    let (pos, each_pos) = mean_and_note(runs, |r| pick(r).cs_position_m, 3);
    let (vel, each_vel) = mean_and_note(runs, |r| pick(r).cs_velocity_mps, 4);
    let (_, each_steady) = mean_and_note(runs, |r| pick(r).steady_epochs as f64, 0);
    let filter_note = if suffix.is_empty() {
        "the differences as they are"
    } else {
        "through the book's relative filter (eqs. 5-57/5-58, Hill dynamics about the \
         target's orbit, its defaults)"
    };
    vec![
        dgps_ratio_row(
            format!("relative DGPS / standalone, 3-D RMS{suffix}"),
            ratio,
        )
        .with_note(format!(
            "relative DGPS (fixes on the common satellites, differenced; {filter_note}) \
             {dgps:.3} m ({each_dgps}) against the chaser's standalone fixes {standalone:.2} \
             m ({each_standalone}); per seed {each_ratio}; {seeds_note}"
        )),
        Row::measured(
            TABLE,
            format!("carrier-smoothed, max |position error|{suffix}"),
            "max over axes",
            "m",
            Some(0.5),
            pos,
            (
                "[0.1, 0.8] m".into(),
                Verdict::from_ok((0.1..=0.8).contains(&pos)),
            ),
        )
        .with_note(format!(
            "steady state: the same satellites for {STEADY_S} s or more; the largest axis \
             error of the target-frame position ({filter_note}); per seed {each_pos} over \
             {each_steady} epochs; {seeds_note}"
        )),
        Row::measured(
            TABLE,
            format!("carrier-smoothed, max |velocity error|{suffix}"),
            "max over axes",
            "m/s",
            Some(0.002),
            vel,
            ("<= 0.0032 m/s".into(), Verdict::from_ok(vel <= 0.0032)),
        )
        .with_note(format!(
            "the difference of the two Doppler velocities (calibrated Doppler noise; \
             {filter_note}), in steady state; per seed {each_vel}; {seeds_note}"
        )),
    ]
}
