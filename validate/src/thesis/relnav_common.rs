//! What B-5.6's rows share (book sections 5.6.4-5.6.5, [`super::relative_navigation`] and
//! [`super::relnav_events`]): the table's name, its steady state, the two vehicles'
//! observation-level runs, relnav on them, the relative truth, and the per-seed means.

use crate::thesis::ValidateError;
use skyforge_gnss::signal::Signal;
use skyforge_navigation::relnav::{RelnavConfig, RelnavRun, relative_from_files};
use skyforge_orbits::Vec3;
use skyforge_orbits::frames::earth_rotation::EarthRotation;
use skyforge_orbits::frames::relative_in_target_frame;
use skyforge_runner::{ObservationRun, observation_run};

/// Table identifier.
pub const TABLE: &str = "B-5.6";
/// Steady state from here (s): assumed, the book's "smoothing has run 50-100 s", its
/// upper end.
pub(crate) const STEADY_S: f64 = 100.0;
/// Fewest steady-state epochs a run's carrier-smoothed statistics are taken over.
pub(crate) const MIN_STEADY_EPOCHS: usize = 10;

/// The two vehicles' observation-level runs of the bundled `name` at `seed`.
pub(crate) fn observe(
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
pub(crate) fn relnav_config() -> RelnavConfig {
    RelnavConfig {
        signals: vec![Signal::GpsL1Ca],
        target_orbit: super::orbit_determination::filter_config(),
        ..RelnavConfig::default()
    }
}

/// `skyforge relnav` on the two vehicles' observation files with `config`.
pub(crate) fn relnav_run(
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
pub(crate) fn truth_at(
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

/// The largest absolute component of `v` over all of them.
pub(crate) fn max_abs(v: impl Iterator<Item = Vec3>) -> f64 {
    v.fold(0.0, |m, e| m.max(e.amax()))
}

/// The mean of `f` over `runs` (those where it is defined; NaN when none is) and the
/// per-seed values as a note.
pub(crate) fn mean_and_note<R>(runs: &[R], f: impl Fn(&R) -> f64, digits: usize) -> (f64, String) {
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
