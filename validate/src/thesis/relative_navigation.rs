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
//! Then the events of the book's figures 5-36/5-38 on their own scenario
//! ([`super::relnav_events`]).

use crate::draw::Draw;
use crate::report::{Row, Verdict};
use crate::stats::rms;
use crate::thesis::ValidateError;
use skyforge_gnss::signal::Signal;
use skyforge_navigation::pvt::PvtConfig;
use skyforge_navigation::relative::single_point_fixes;
use skyforge_navigation::relnav::{
    HillFilterConfig, RelativeEstimate, RelnavConfig, RelnavMode, RelnavRun, relative_from_files,
};
use skyforge_orbits::Vec3;
use skyforge_orbits::ephemeris::EphemerisStore;
use skyforge_orbits::frames::earth_rotation::EarthRotation;
use skyforge_orbits::frames::relative_in_target_frame;
use skyforge_orbits::time::TimeOrigin;
use skyforge_runner::{ObservationRun, observation_run};

/// Table identifier.
pub const TABLE: &str = "B-5.6";
/// The bundled scenario of this table.
pub const SCENARIO: &str = "book-relnav-leo";
/// Registered runs: seeds `FIRST_SEED ..` (assumed: four, as B-5.5).
const FIRST_SEED: u64 = 1;
const RUNS: u64 = 4;
/// Steady state from here (s): assumed, the book's "smoothing has run 50-100 s", its
/// upper end.
pub(super) const STEADY_S: f64 = 100.0;
/// Fewest steady-state epochs a run's carrier-smoothed statistics are taken over.
pub(super) const MIN_STEADY_EPOCHS: usize = 10;

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

/// The two vehicles' observation-level runs of the bundled `name` at `seed`.
pub(super) fn observe(
    name: &str,
    seed: u64,
) -> Result<(ObservationRun, ObservationRun), ValidateError> {
    let mut scenario = skyforge_scenarios::named(name)?;
    scenario.seed = seed;
    let mut runs = scenario
        .vehicle_views()
        .iter()
        .map(|v| observation_run(v).map_err(|e| ValidateError::Pipeline(e.to_string())))
        .collect::<Result<Vec<_>, _>>()?;
    if runs.len() != 2 {
        return Err(ValidateError::Pipeline(format!(
            "{name}: {} vehicles, not a target and a chaser",
            runs.len()
        )));
    }
    let chaser = runs.remove(1);
    Ok((runs.remove(0), chaser))
}

/// The settings every B-5.6 run shares: GPS L1 C/A, the target's orbit filter for the
/// frame with B-5.5's settings (SA-era fixes).
pub(super) fn relnav_config() -> RelnavConfig {
    RelnavConfig {
        signals: vec![Signal::GpsL1Ca],
        target_orbit: super::orbit_determination::filter_config(),
        ..RelnavConfig::default()
    }
}

/// `skyforge relnav` on the two vehicles' observation files with `config`.
pub(super) fn relnav_run(
    target: &ObservationRun,
    chaser: &ObservationRun,
    config: &RelnavConfig,
) -> Result<RelnavRun, ValidateError> {
    let (t_file, c_file) = match (target.measured.first(), chaser.measured.first()) {
        (Some(t), Some(c)) => (t, c),
        _ => return Err(ValidateError::Pipeline("no observations".into())),
    };
    relative_from_files(
        t_file,
        c_file,
        target.ephemerides.clone(),
        &target.iono,
        config,
    )
    .map_err(|e| ValidateError::Pipeline(e.to_string()))
}

/// The truth of the chaser relative to the target at `t_s` (the nearest geometry epoch:
/// the fixes are tagged within microseconds of it).
pub(super) fn truth_at(
    target: &ObservationRun,
    chaser: &ObservationRun,
    t_s: f64,
) -> Option<(Vec3, Vec3)> {
    let earth = EarthRotation::at_origin(target.start);
    let t = t_s.round();
    let (a, b) = (target.platform_at(t)?, chaser.platform_at(t)?);
    let (rt, vt) = earth.ecef_to_eci(t, &a.r_ecef_m, &a.v_ecef_mps);
    let (rc, vc) = earth.ecef_to_eci(t, &b.r_ecef_m, &b.v_ecef_mps);
    Some(relative_in_target_frame(&rt, &vt, &rc, &vc))
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

/// The largest absolute component of `v` over all of them.
pub(super) fn max_abs(v: impl Iterator<Item = Vec3>) -> f64 {
    v.fold(0.0, |m, e| m.max(e.amax()))
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

/// The mean of `f` over `runs` (those where it is defined; NaN when none is) and the
/// per-seed values as a note.
pub(super) fn mean_and_note<R>(runs: &[R], f: impl Fn(&R) -> f64, digits: usize) -> (f64, String) {
    let v: Vec<f64> = runs.iter().map(f).collect();
    let defined: Vec<f64> = v.iter().copied().filter(|x| x.is_finite()).collect();
    let mean = if defined.is_empty() {
        f64::NAN
    } else {
        defined.iter().sum::<f64>() / defined.len() as f64
    };
    let each: Vec<String> = v.iter().map(|x| format!("{x:.digits$}")).collect();
    (mean, each.join(" / "))
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
    rows.extend(super::relnav_events::rows(draw)?);
    Ok(rows)
}

/// REL-DGPS with the book's pseudorange relative DGPS filter (eq. 5-59).
fn single_difference_row(runs: &[RunStats], seeds_note: &str) -> Row {
    let (ratio, each_ratio) = mean_and_note(runs, |r| r.single_difference_m / r.standalone_m, 4);
    let (position, each_position) = mean_and_note(runs, |r| r.single_difference_m, 3);
    let (velocity, each_velocity) = mean_and_note(runs, |r| r.single_difference_mps, 4);
    Row::measured(
        TABLE,
        "pseudorange relative DGPS (eq. 5-59) / standalone, 3-D RMS",
        "ratio",
        "-",
        None,
        ratio,
        (
            "<= 0.5 (\"clearly better\")".into(),
            Verdict::from_ok(ratio <= 0.5),
        ),
    )
    .with_note(format!(
        "relnav mode single-difference (a filter on the single differences of pseudorange \
         and Doppler range rate, its defaults), every epoch: {position:.3} m \
         ({each_position}), velocity {velocity:.4} m/s ({each_velocity}); per seed \
         {each_ratio}; {seeds_note}"
    ))
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
        Row::measured(
            TABLE,
            format!("relative DGPS / standalone, 3-D RMS{suffix}"),
            "ratio",
            "-",
            None,
            ratio,
            (
                "<= 0.5 (\"clearly better\")".into(),
                Verdict::from_ok(ratio <= 0.5),
            ),
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
