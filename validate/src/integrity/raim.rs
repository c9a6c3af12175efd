//! RAIM Monte Carlo against Yuan 2000 table 5-1 (RTCA MOPS integrity: en route, terminal
//! and non-precision approach, on an en-route aircraft) and table 5-2 (the authors'
//! proposed LEO limits: free flight and orbit manoeuvre, on the thesis LEO).
//!
//! Each platform's observation-level scenario (`scenarios/integrity/raim-aircraft.toml`,
//! `raim-leo.toml`, parsed with [`SCENARIO_DIR`] as the base of relative paths, so that the
//! aircraft's trajectory CSV resolves whatever the working directory) runs once,
//! fault-free; its observation truth gives the noise-free pseudorange of every
//! satellite at every second (geometry, satellite clocks, troposphere: everything the
//! observation model adds noise to). Each Monte Carlo run then draws the scenario's white
//! constant code noise itself and adds the ramp fault the scenario's `iono-ramp` event
//! would add (code delayed by rate x (t - onset)): the observation model with a constant
//! model is exactly truth + sigma x N(0, 1), independent per epoch, and the event enters
//! the truth's pseudorange additively; the test `per_run_draws_are_the_observation_model`
//! checks both against a run of the observation model itself. The receiver's
//! [`solve`](skyforge_navigation::pvt::solve) (chi-square test, one-satellite exclusion,
//! protection levels) processes every epoch as it would a receiver's.
//!
//! Each [`Setting`] tests at its own false-alarm probability per epoch (its table's
//! false-alarm rate spread over independent 1 Hz epochs), so table 5-2's two phases are two
//! settings on one geometry. No platform model has thrust (the orbits crate propagates
//! gravity and drag): the orbit-manoeuvre setting runs on the coasting LEO. A snapshot
//! test sees a manoeuvre only through the geometry it leaves (which satellites the antenna
//! sees, where), never through the dynamics, so that row is the LEO's geometry tested at
//! the manoeuvre's limits; the book's GPS + star-sensor RAIM for manoeuvres (eqs. 5-14,
//! 5-15) is not modelled.
//!
//! Runs are independent; epochs within a run are not (the ramp grows, the alarm
//! persists), so every rate is counted per run and its standard error taken over runs.

use crate::report::{Row, Verdict};
use crate::thesis::ValidateError;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha20Rng;
use rayon::prelude::*;
use skyforge_gnss::signal::Signal;
use skyforge_navigation::pvt::chi2_survival;
use skyforge_navigation::pvt::{Measurement, PvtConfig, solve};
use skyforge_orbits::Vec3;
use skyforge_orbits::ephemeris::{EphemerisStore, SatId};
use skyforge_orbits::frames::c_ecef_ned;
use skyforge_orbits::frames::ecef_to_geodetic;
use skyforge_orbits::time::TimeOrigin;
use skyforge_runner::observation_run;
use skyforge_scenarios::Scenario;
use std::path::Path;

/// Table identifiers: Yuan 2000 table 5-1 and table 5-2 (`--only B-5.2` runs both).
pub const TABLE_MOPS: &str = "B-5.2-1";
pub const TABLE_LEO: &str = "B-5.2-2";

/// The folder of the RAIM scenarios, the base of their relative paths (the aircraft's
/// trajectory CSV). Absolute, from the crate's source folder: it resolves from any working
/// directory in the repository and in tests (an installed binary without the source tree
/// cannot run table 5-1).
pub const SCENARIO_DIR: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../scenarios/integrity");

/// Monte Carlo runs per platform and kind (faulted, fault-free) of `validate thesis`.
// assumed: 200, the minimum, fixed before the first run.
pub const RUNS: usize = 200;

/// Ramp rates (m/s) of table 5-1 and of table 5-2's free flight; run k takes
/// `RAMP_RATES_MPS[k % 4]`.
// assumed: slow ramps, the hard case of snapshot RAIM in the literature (Brown 1992 and
// the MOPS studies use ramps of a few m/s or slower: a step or a fast ramp is caught as
// soon as it starts); 0.5 to 5 m/s spans a positioning failure reached within about 1 to
// 60 min. Fixed before the first run.
pub const RAMP_RATES_MPS: [f64; 4] = [0.5, 1.0, 2.0, 5.0];

/// Ramp rates (m/s) of the kilometre limits (table 5-2's orbit manoeuvre, table 5-1's en
/// route), cycling as [`RAMP_RATES_MPS`].
// assumed: ramps whose range error passes 10 km within a 1200 s run (10 m/s ends a run at
// 12 km, 100 m/s passes 10 km after 100 s), so that runs can reach the 10 km limit's
// positioning failure; the free-flight ramps end a 1200 s run at 0.6 to 6 km of range
// error and would seldom reach it. Fixed before the first run of the manoeuvre setting,
// and taken for the en-route setting before its first run.
pub const FAST_RAMP_RATES_MPS: [f64; 4] = [10.0, 20.0, 50.0, 100.0];

/// The standard deviation of the code noise (m), that of the scenarios' constant model.
// assumed: 33.3 m, the SA-era range error of the MOPS RAIM analyses (scenarios'
// comment); the solver is told the same sigma.
pub const SIGMA_M: f64 = 33.3;

/// Probability of missed detection the protection levels are computed for.
// assumed: table 5-1's minimum detection probability 0.999 (for table 5-2 as well: it
// states rates, not a detection probability).
pub const P_MD: f64 = 1e-3;

/// One alarm limit of a table row.
#[derive(Debug, Clone, Copy)]
pub struct Limit {
    pub name: &'static str,
    pub hal_m: f64,
    pub tta_s: f64,
    /// Largest false-alarm rate (per hour).
    pub false_alarms_per_h: f64,
    /// Table 5-1's minimum detection probability, or table 5-2's missed-alarm rate (per
    /// hour of faulted flight).
    pub detection: Requirement,
}

/// What a table asks of detection.
#[derive(Debug, Clone, Copy)]
pub enum Requirement {
    MinDetection(f64),
    MaxMissedPerHour(f64),
}

/// One platform's Monte Carlo setting, all chosen before the first run.
#[derive(Debug, Clone)]
pub struct Setting {
    pub table: &'static str,
    pub platform: &'static str,
    /// The scenario's file name in [`SCENARIO_DIR`] and its text (embedded).
    pub scenario_file: &'static str,
    pub scenario_text: &'static str,
    /// Ramp rates of the faulted runs (m/s), cycling over the runs.
    pub ramps_mps: &'static [f64],
    /// Length of one run (s) from its start (the fault's onset in a faulted run).
    pub window_s: usize,
    /// Probability of false alarm per epoch of the test.
    pub pfa: f64,
    /// Receiver elevation mask (rad).
    pub elevation_mask_rad: f64,
    /// Seed of the run draws (starts, satellites) and of the noise.
    pub seed: u64,
    pub limits: Vec<Limit>,
    /// What every row of the setting must say besides its numbers (empty if nothing).
    pub caveat: &'static str,
}

/// Epochs per hour at the scenarios' 1 Hz.
const EPOCHS_PER_HOUR: f64 = 3600.0;

/// Table 5-1 on the en-route aircraft (en route, terminal and non-precision approach):
/// one platform for the whole table, as the MOPS writes it for one receiver in flight.
pub fn mops_setting() -> Setting {
    let mops_limit = |name, hal_m, tta_s| Limit {
        name,
        hal_m,
        tta_s,
        false_alarms_per_h: 0.002,
        detection: Requirement::MinDetection(0.999),
    };
    Setting {
        table: TABLE_MOPS,
        platform: "aircraft",
        scenario_file: "raim-aircraft.toml",
        scenario_text: include_str!("../../../scenarios/integrity/raim-aircraft.toml"),
        ramps_mps: &RAMP_RATES_MPS,
        // assumed: 30 min per run (as the static ground site that stood in for the aircraft
        // before): a 0.5 m/s ramp reaches 900 m, beyond the 556 m limit's failure for every
        // geometry whose HPL is below it. (Expected before the first run: the faster ramps
        // would also reach the en-route limit's 3706 m failure; in the event none did
        // within 1800 s, so en route has a setting of its own: `mops_en_route_setting`.)
        window_s: 1800,
        // assumed: the table's 0.002 false alarms per hour spread over independent 1 Hz
        // epochs (the noise is white): P_fa = 0.002 / 3600 per epoch.
        pfa: 0.002 / EPOCHS_PER_HOUR,
        elevation_mask_rad: 10f64.to_radians(), // as the scenario's antenna mask
        seed: 0x5241_494d_0051,                 // assumed: any fixed seed (the ground setting's)
        limits: vec![
            mops_limit("terminal", 1853.2, 10.0),
            mops_limit("non-precision approach", 555.96, 10.0),
        ],
        caveat: "",
    }
}

/// Table 5-1's en-route phase on the aircraft. Its own setting because the slow ramps of
/// [`mops_setting`] reached no 3706 m failure in 1800 s (session 11, 200 runs): the
/// detection and time-to-alarm rows had nothing to measure.
pub fn mops_en_route_setting() -> Setting {
    Setting {
        platform: "aircraft, en route",
        // assumed: the ramps of the other kilometre limit, chosen before the first run of
        // this setting; 10 m/s passes 3.7 km of range error after 370 s.
        ramps_mps: &FAST_RAMP_RATES_MPS,
        seed: 0x5241_494d_0054, // assumed: any fixed seed, another than the other settings'
        limits: vec![Limit {
            name: "en route",
            hal_m: 3706.4,
            tta_s: 30.0,
            false_alarms_per_h: 0.002,
            detection: Requirement::MinDetection(0.999),
        }],
        ..mops_setting()
    }
}

/// Table 5-2's free flight on the LEO.
pub fn leo_setting() -> Setting {
    Setting {
        table: TABLE_LEO,
        platform: "LEO",
        scenario_file: "raim-leo.toml",
        scenario_text: include_str!("../../../scenarios/integrity/raim-leo.toml"),
        ramps_mps: &RAMP_RATES_MPS,
        // assumed: 40 min per run: the 1200 s time to alarm after a failure that a 0.5 m/s
        // ramp reaches within about 20 min.
        window_s: 2400,
        // assumed: the table's 0.0005 false alarms per hour over independent 1 Hz epochs.
        pfa: 0.0005 / EPOCHS_PER_HOUR,
        // assumed: no horizon mask; the antenna's 80 deg field of view limits the view.
        elevation_mask_rad: -90f64.to_radians(),
        seed: 0x5241_494d_0052, // assumed: any fixed seed
        limits: vec![Limit {
            name: "free flight",
            hal_m: 1000.0,
            tta_s: 1200.0,
            false_alarms_per_h: 0.0005,
            detection: Requirement::MaxMissedPerHour(0.0005),
        }],
        caveat: "",
    }
}

/// Table 5-2's orbit manoeuvre on the LEO: the free-flight geometry at the manoeuvre's
/// limits and false-alarm probability (the platform cannot manoeuvre; module doc).
pub fn leo_manoeuvre_setting() -> Setting {
    Setting {
        platform: "LEO, coasting",
        ramps_mps: &FAST_RAMP_RATES_MPS,
        // assumed: 20 min per run, a long orbit-adjust burn (the book states the rates per
        // hour of manoeuvring, not a burn's length); 200 runs per kind then hold 67 h, more
        // than the 30 h without an event that show a rate of 0.1/h at 95 %.
        window_s: 1200,
        // assumed: the table's 0.1 false alarms per hour over independent 1 Hz epochs. The
        // expected false-alarm rate is then the limit itself.
        pfa: 0.1 / EPOCHS_PER_HOUR,
        seed: 0x5241_494d_0053, // assumed: any fixed seed
        limits: vec![Limit {
            name: "orbit manoeuvre",
            hal_m: 10_000.0,
            tta_s: 10.0,
            false_alarms_per_h: 0.1,
            detection: Requirement::MaxMissedPerHour(0.1),
        }],
        caveat: "no platform model has thrust: the LEO coasts, and a snapshot test sees a manoeuvre only through the geometry it leaves, so this is the LEO's geometry at the manoeuvre's limits (the book's GPS + star-sensor RAIM, eqs. 5-14/5-15, is not modelled)",
        // The rest (table, scenario, elevation mask) as the free-flight setting.
        ..leo_setting()
    }
}

/// The noise-free pseudoranges of one second and the true antenna position.
#[derive(Debug, Clone)]
pub struct GeometryEpoch {
    pub t_s: f64,
    pub r_true_ecef_m: Vec3,
    pub pseudoranges: Vec<(SatId, f64)>,
}

/// What every run of a platform shares.
#[derive(Debug)]
pub struct Geometry {
    pub origin: TimeOrigin,
    pub store: EphemerisStore,
    pub epochs: Vec<GeometryEpoch>,
}

fn pipeline_error(e: impl std::fmt::Display) -> ValidateError {
    ValidateError::Pipeline(e.to_string())
}

/// Parse a setting's scenario, its relative paths from [`SCENARIO_DIR`].
pub fn scenario(setting: &Setting) -> Result<Scenario, ValidateError> {
    Ok(skyforge_scenarios::parse(
        setting.scenario_text,
        &format!("scenarios/integrity/{}", setting.scenario_file),
        Path::new(SCENARIO_DIR),
    )?)
}

/// Run `scenario` once at the observation level and keep its observation truth.
pub fn geometry(scenario: &Scenario) -> Result<Geometry, ValidateError> {
    let run = observation_run(scenario).map_err(pipeline_error)?;
    let origin = TimeOrigin::new(run.start);
    let store = EphemerisStore::new(run.ephemerides.clone(), &origin);
    let truth = run
        .truth
        .first()
        .ok_or_else(|| pipeline_error("the scenario has no antenna"))?;
    let body = run.true_body_m.first().copied().unwrap_or_else(Vec3::zeros);
    let epochs = truth
        .epochs
        .iter()
        .filter_map(|e| {
            let t_s = (e.time - run.start).to_seconds().round();
            let p = run.platform_at(t_s)?;
            Some(GeometryEpoch {
                t_s,
                r_true_ecef_m: p.r_ecef_m + p.c_body_ecef * body,
                pseudoranges: e
                    .sats
                    .iter()
                    .filter_map(|r| Some((r.sat, r.pseudorange_m?)))
                    .collect(),
            })
        })
        .collect();
    Ok(Geometry {
        origin,
        store,
        epochs,
    })
}

/// One run's draw: first epoch index, and the fault (satellite, ramp rate) of a faulted
/// run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Draw {
    pub start: usize,
    pub fault: Option<(SatId, f64)>,
    pub noise_seed: u64,
}

/// The runs' draws, fixed by the setting's seed before any run: start uniform over the
/// epochs that leave a whole window, faulted satellite uniform among those the truth has
/// at the start, ramp rate cycling through the setting's; `runs` faulted runs then
/// `runs` fault-free ones.
pub fn draws(setting: &Setting, geometry: &Geometry, runs: usize) -> Vec<Draw> {
    let mut rng = ChaCha20Rng::seed_from_u64(setting.seed);
    let last_start = geometry
        .epochs
        .len()
        .saturating_sub(setting.window_s)
        .max(1);
    let mut out = Vec::with_capacity(2 * runs);
    for k in 0..2 * runs {
        let start = rng.random_range(0..last_start);
        let faulted = k < runs;
        let sats = &geometry.epochs[start].pseudoranges;
        let pick = rng.random_range(0..sats.len().max(1));
        let fault = (faulted && !sats.is_empty())
            .then(|| (sats[pick].0, setting.ramps_mps[k % setting.ramps_mps.len()]));
        out.push(Draw {
            start,
            fault,
            noise_seed: setting.seed.wrapping_mul(1_000_003).wrapping_add(k as u64),
        });
    }
    out
}

/// One epoch of a run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EpochResult {
    /// Seconds since the run's start.
    pub t_s: f64,
    /// Horizontal error (m) of the fix with every satellite (what fails without RAIM).
    pub hpe_all_m: f64,
    /// Horizontal error (m) of the output fix (after any exclusion).
    pub hpe_out_m: f64,
    pub hpl_m: f64,
    /// The test fired.
    pub alarm: bool,
    /// The satellite excluded, if any.
    pub excluded: Option<SatId>,
    /// Probability that a fault-free statistic exceeds this epoch's all-in statistic
    /// (chi-square survival at the all-in fix's degrees of freedom); NaN without RAIM.
    /// Uniform on (0, 1) when the noise has the weights' sigmas and there is no fault.
    pub survival: f64,
}

/// A standard normal draw (Box-Muller).
fn normal(rng: &mut ChaCha20Rng) -> f64 {
    let u1: f64 = 1.0 - rng.random::<f64>();
    let u2: f64 = rng.random::<f64>();
    (-2.0 * u1.ln()).sqrt() * (std::f64::consts::TAU * u2).cos()
}

/// The receiver configuration of a setting: the test at its P_fa, the protection levels
/// at [`P_MD`], the weights of [`SIGMA_M`], no ionosphere model (none in the scenarios).
pub fn pvt_config(setting: &Setting) -> PvtConfig {
    PvtConfig {
        elevation_mask_rad: setting.elevation_mask_rad,
        sigma_a_m: SIGMA_M,
        sigma_b_m: 0.0,
        raim_pfa: setting.pfa,
        raim_pmd: P_MD,
        ..PvtConfig::default()
    }
}

fn horizontal_error(r: &Vec3, truth: &Vec3) -> f64 {
    let g = ecef_to_geodetic(truth);
    let e = c_ecef_ned(g.lat_rad, g.lon_rad) * (r - truth);
    e.x.hypot(e.y)
}

/// One run: `setting.window_s` epochs from `draw.start`, noise drawn from its own seed,
/// the ramp on the faulted satellite from the first epoch on.
pub fn run(setting: &Setting, geometry: &Geometry, draw: &Draw) -> Vec<EpochResult> {
    let cfg = pvt_config(setting);
    let mut rng = ChaCha20Rng::seed_from_u64(draw.noise_seed);
    let mut a_priori = None;
    let end = (draw.start + setting.window_s).min(geometry.epochs.len());
    let mut out = Vec::with_capacity(end - draw.start);
    for e in &geometry.epochs[draw.start..end] {
        let t_run = e.t_s - geometry.epochs[draw.start].t_s;
        let meas: Vec<Measurement> = e
            .pseudoranges
            .iter()
            .map(|&(sat, pr)| {
                let ramp = match draw.fault {
                    Some((s, rate)) if s == sat => rate * t_run,
                    _ => 0.0,
                };
                Measurement {
                    sat,
                    pseudorange_m: pr + ramp + SIGMA_M * normal(&mut rng),
                    doppler_hz: None,
                    signal: Signal::GpsL1Ca,
                }
            })
            .collect();
        let Ok(fix) = solve(
            &meas,
            e.t_s,
            &geometry.store,
            &geometry.origin,
            &cfg,
            a_priori,
        ) else {
            continue;
        };
        a_priori = Some(fix.r_ecef_m);
        let hpe_out_m = horizontal_error(&fix.r_ecef_m, &e.r_true_ecef_m);
        let excluded = fix.excluded.first().copied();
        // The fix with every satellite: what fails without the exclusion.
        let hpe_all_m = fix.protection.as_ref().map_or(hpe_out_m, |p| {
            horizontal_error(&p.r_all_ecef_m, &e.r_true_ecef_m)
        });
        let (hpl_m, alarm) = fix
            .protection
            .as_ref()
            .map_or((f64::INFINITY, false), |p| (p.hpl_m, p.alarm));
        let dof_all = fix.dof + fix.excluded.len();
        let survival = fix
            .protection
            .as_ref()
            .map_or(f64::NAN, |p| chi2_survival(dof_all, p.chi2_all));
        out.push(EpochResult {
            t_s: t_run,
            hpe_all_m,
            hpe_out_m,
            hpl_m,
            alarm,
            excluded,
            survival,
        });
    }
    out
}

/// What one faulted run shows against one limit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FaultOutcome {
    /// First epoch (s after onset) of a positioning failure: HPE of the all-in fix > HAL.
    pub failure_s: Option<f64>,
    /// First alarm (s after onset).
    pub detection_s: Option<f64>,
    /// Time to alarm (s): from the failure to the first alarm at or after it.
    pub time_to_alarm_s: Option<f64>,
    /// A failure epoch with no alarm within the time to alarm (a missed detection).
    pub missed: bool,
    /// The missed failure happened while HPL <= HAL (RAIM claimed availability).
    pub missed_while_available: bool,
    /// The missed failure happened in an epoch without RAIM (fewer than two degrees of
    /// freedom: no test and no protection level, the receiver knew it had no integrity).
    pub missed_without_raim: bool,
    /// At the first alarm the faulted satellite was the one excluded.
    pub right_exclusion: Option<bool>,
    /// Length of the run (h).
    pub hours: f64,
}

/// Evaluate a faulted run against `limit`.
pub fn fault_outcome(epochs: &[EpochResult], fault: SatId, limit: &Limit) -> FaultOutcome {
    let failure = epochs.iter().position(|e| e.hpe_all_m > limit.hal_m);
    let first_alarm = epochs.iter().position(|e| e.alarm);
    let end_s = epochs.last().map_or(0.0, |e| e.t_s);
    let alarm_in = |from: f64, to: f64| {
        epochs
            .iter()
            .any(|e| e.alarm && e.t_s >= from && e.t_s <= to)
    };
    let mut missed = false;
    let mut missed_while_available = false;
    let mut missed_without_raim = false;
    for e in epochs.iter().filter(|e| e.hpe_all_m > limit.hal_m) {
        // A failure whose alarm window runs past the run's end cannot be judged.
        if e.t_s + limit.tta_s > end_s {
            continue;
        }
        if !alarm_in(e.t_s, e.t_s + limit.tta_s) {
            missed = true;
            missed_while_available |= e.hpl_m <= limit.hal_m;
            missed_without_raim |= !e.hpl_m.is_finite();
        }
    }
    let failure_s = failure.map(|i| epochs[i].t_s);
    FaultOutcome {
        failure_s,
        detection_s: first_alarm.map(|i| epochs[i].t_s),
        time_to_alarm_s: failure_s.and_then(|tf| {
            epochs
                .iter()
                .find(|e| e.alarm && e.t_s >= tf)
                .map(|e| e.t_s - tf)
        }),
        missed,
        missed_while_available,
        missed_without_raim,
        right_exclusion: first_alarm.map(|i| epochs[i].excluded == Some(fault)),
        hours: epochs.len() as f64 / EPOCHS_PER_HOUR,
    }
}

/// All runs of a setting: (faulted runs with their fault, fault-free runs).
pub type Runs = (Vec<(SatId, Vec<EpochResult>)>, Vec<Vec<EpochResult>>);

/// Run `runs` faulted and `runs` fault-free draws of `setting` (in parallel).
#[cfg(test)]
pub fn monte_carlo(setting: &Setting, runs: usize) -> Result<Runs, ValidateError> {
    monte_carlo_on(setting, &geometry(&scenario(setting)?)?, runs)
}

/// [`monte_carlo`] on the `geometry` of the setting's scenario, already run.
pub fn monte_carlo_on(
    setting: &Setting,
    geometry: &Geometry,
    runs: usize,
) -> Result<Runs, ValidateError> {
    if geometry.epochs.len() <= setting.window_s {
        return Err(pipeline_error(format!(
            "{}: {} epochs, fewer than one {} s window",
            setting.platform,
            geometry.epochs.len(),
            setting.window_s
        )));
    }
    let all = draws(setting, geometry, runs);
    let results: Vec<(Option<SatId>, Vec<EpochResult>)> = all
        .par_iter()
        .map(|d| (d.fault.map(|f| f.0), run(setting, geometry, d)))
        .collect();
    let mut faulted = Vec::new();
    let mut free = Vec::new();
    for (fault, epochs) in results {
        match fault {
            Some(sat) => faulted.push((sat, epochs)),
            None => free.push(epochs),
        }
    }
    Ok((faulted, free))
}

/// Mean and standard error of per-run values.
fn mean_se(values: &[f64]) -> (f64, f64) {
    let n = values.len() as f64;
    if values.is_empty() {
        return (f64::NAN, f64::NAN);
    }
    let mean = values.iter().sum::<f64>() / n;
    if values.len() < 2 {
        return (mean, f64::NAN);
    }
    let var = values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0);
    (mean, (var / n).sqrt())
}

/// A rate per hour from per-run counts and hours: (rate, standard error over runs, the
/// one-sided 95 % Poisson upper bound when no event was seen).
fn rate_per_hour(counts: &[f64], hours: &[f64]) -> (f64, f64, Option<f64>) {
    let total_h: f64 = hours.iter().sum();
    let total: f64 = counts.iter().sum();
    let rate = total / total_h;
    let n = counts.len() as f64;
    let ss: f64 = counts
        .iter()
        .zip(hours)
        .map(|(c, h)| (c - rate * h).powi(2))
        .sum();
    let se = (n / (n - 1.0).max(1.0) * ss).sqrt() / total_h;
    (rate, se, (total == 0.0).then(|| 3.0 / total_h))
}

/// Upper tail of the fault-free statistic the false-alarm rows count (a check that the
/// statistic is chi-square where alarms are too rare to show it).
const STATISTIC_TAIL: f64 = 1e-3;

/// Whether fault-free hours without an alarm could show a false-alarm rate of
/// `per_hour` (the one-sided 95 % Poisson bound 3 / hours below it), as the note says it.
fn shown_by_sample(per_hour: f64, hours: f64) -> String {
    let needed = 3.0 / per_hour;
    if hours >= needed {
        format!(
            "{hours:.1} h could show a rate of {per_hour}/h, which needs about {needed:.0} h without an alarm"
        )
    } else {
        format!(
            "the sample cannot show a rate of {per_hour}/h, which needs about {needed:.0} h without an alarm"
        )
    }
}

/// The rows of `setting` from its runs.
pub fn rows_of(setting: &Setting, runs: &Runs) -> Vec<Row> {
    let (faulted, free) = runs;
    let mut rows = Vec::new();
    let n_f = faulted.len();
    let free_hours: Vec<f64> = free
        .iter()
        .map(|r| r.len() as f64 / EPOCHS_PER_HOUR)
        .collect();
    let free_alarms: Vec<f64> = free
        .iter()
        .map(|r| r.iter().filter(|e| e.alarm).count() as f64)
        .collect();
    let free_epochs: usize = free.iter().map(Vec::len).sum();
    // The calibration of the statistic: its survival probability in the fault-free epochs
    // with RAIM, and how many fall in its upper STATISTIC_TAIL.
    let survivals: Vec<f64> = free
        .iter()
        .flat_map(|r| r.iter().map(|e| e.survival))
        .filter(|u| u.is_finite())
        .collect();
    let tail = survivals.iter().filter(|u| **u < STATISTIC_TAIL).count();
    for limit in &setting.limits {
        let outcomes: Vec<FaultOutcome> = faulted
            .iter()
            .map(|(sat, epochs)| fault_outcome(epochs, *sat, limit))
            .collect();
        let failed: Vec<&FaultOutcome> =
            outcomes.iter().filter(|o| o.failure_s.is_some()).collect();
        let n_fail = failed.len();
        let missed = failed.iter().filter(|o| o.missed).count();
        let missed_avail = failed.iter().filter(|o| o.missed_while_available).count();
        let missed_no_raim = failed.iter().filter(|o| o.missed_without_raim).count();
        let missed_where =
            format!("{missed_avail} while HPL <= HAL, {missed_no_raim} in epochs without RAIM");
        // Without a failure there is nothing to detect or time: the rows say so (their NaN
        // fails the check).
        let no_failure = if n_fail == 0 {
            format!(
                "no run reached a positioning failure (all-in HPE > HAL) within its {} s, so nothing was detected or timed and the row shows nothing; ",
                setting.window_s
            )
        } else {
            String::new()
        };
        let detected: Vec<f64> = outcomes.iter().filter_map(|o| o.detection_s).collect();
        let right: Vec<f64> = outcomes
            .iter()
            .filter_map(|o| o.right_exclusion.map(|r| f64::from(u8::from(r))))
            .collect();
        let (right_rate, right_se) = mean_se(&right);
        let (det_mean, det_se) = mean_se(&detected);
        let tta: Vec<f64> = failed.iter().filter_map(|o| o.time_to_alarm_s).collect();
        let (tta_mean, tta_se) = mean_se(&tta);
        let tta_max = tta.iter().copied().fold(f64::NAN, f64::max);
        let available: Vec<f64> = free
            .iter()
            .map(|r| {
                r.iter().filter(|e| e.hpl_m <= limit.hal_m).count() as f64 / r.len().max(1) as f64
            })
            .collect();
        let (avail, avail_se) = mean_se(&available);
        let hpls: Vec<f64> = free
            .iter()
            .flat_map(|r| r.iter().map(|e| e.hpl_m))
            .filter(|h| h.is_finite())
            .collect();
        let no_raim = free_epochs - hpls.len();
        let hpl_mean = hpls.iter().sum::<f64>() / hpls.len().max(1) as f64;
        let hpl_max = hpls.iter().copied().fold(f64::NAN, f64::max);
        // Every alarm epoch of the faulted runs: was the excluded satellite the faulted one?
        let (mut alarm_epochs, mut right_epochs) = (0usize, 0usize);
        for (sat, epochs) in faulted {
            for e in epochs.iter().filter(|e| e.alarm) {
                alarm_epochs += 1;
                right_epochs += usize::from(e.excluded == Some(*sat));
            }
        }
        let prefix = format!(
            "{} ({}, HAL {} m, TTA {} s)",
            limit.name, setting.platform, limit.hal_m, limit.tta_s
        );
        let common = format!(
            "{n_f} faulted runs (ramps {:?} m/s on one satellite, sigma {SIGMA_M} m, P_fa {:.2e}/epoch, P_md {P_MD}); {n_fail} reached HPE > HAL (all-in fix); detection in {} runs, mean {det_mean:.0} +/- {det_se:.0} s after onset; right satellite excluded at the first alarm in {:.3} +/- {:.3} of them and in {right_epochs} of {alarm_epochs} alarm epochs; RAIM available (HPL <= HAL) in {:.4} +/- {:.4} of fault-free epochs ({no_raim} epochs without RAIM: fewer than two degrees of freedom), HPL mean {hpl_mean:.0} m, largest {hpl_max:.0} m over the others{}",
            setting.ramps_mps,
            setting.pfa,
            detected.len(),
            right_rate,
            right_se,
            avail,
            avail_se,
            if setting.caveat.is_empty() {
                String::new()
            } else {
                format!("; {}", setting.caveat)
            }
        );
        match limit.detection {
            Requirement::MinDetection(p_min) => {
                let p = if n_fail > 0 {
                    1.0 - missed as f64 / n_fail as f64
                } else {
                    f64::NAN
                };
                let se = (p * (1.0 - p) / n_fail.max(1) as f64).sqrt();
                let lower = if missed == 0 && n_fail > 0 {
                    format!(
                        "; no miss: 95 % lower bound {:.4}",
                        1.0 - 3.0 / n_fail as f64
                    )
                } else {
                    String::new()
                };
                rows.push(
                    Row::measured(
                        setting.table,
                        format!("{prefix}: detection of a positioning failure within TTA"),
                        "probability",
                        "-",
                        Some(p_min),
                        p,
                        (format!(">= {p_min}"), Verdict::from_ok(p >= p_min)),
                    )
                    .with_note(format!(
                        "{no_failure}{p:.4} +/- {se:.4} over {n_fail} runs with a failure; {missed} missed ({missed_where}){lower}; {common}"
                    )),
                );
            }
            Requirement::MaxMissedPerHour(max) => {
                let counts: Vec<f64> = outcomes
                    .iter()
                    .map(|o| f64::from(u8::from(o.missed)))
                    .collect();
                let hours: Vec<f64> = outcomes.iter().map(|o| o.hours).collect();
                let (rate, se, upper) = rate_per_hour(&counts, &hours);
                let bound = upper.map_or(String::new(), |u| {
                    format!("; none seen: 95 % upper bound {u:.4}/h")
                });
                rows.push(
                    Row::measured(
                        setting.table,
                        format!("{prefix}: missed alarms per hour of faulted flight"),
                        "missed-alarm rate",
                        "1/h",
                        Some(max),
                        rate,
                        (format!("<= {max}"), Verdict::from_ok(rate <= max)),
                    )
                    .with_note(format!(
                        "{rate:.4} +/- {se:.4} /h: {missed} of {n_f} faulted runs ({:.1} h, a fault present throughout, so an upper bound of the rate a fault prior would give) missed a failure ({missed_where}), {n_fail} runs reached a failure{bound}; {common}",
                        hours.iter().sum::<f64>()
                    )),
                );
            }
        }
        rows.push(
            Row::measured(
                setting.table,
                format!("{prefix}: time to alarm after the failure, largest"),
                "time to alarm",
                "s",
                Some(limit.tta_s),
                tta_max,
                (format!("<= {}", limit.tta_s), Verdict::from_ok(tta_max <= limit.tta_s)),
            )
            .with_note(format!(
                "{no_failure}from the first epoch the all-in fix's HPE exceeds HAL (RTCA MOPS: time to alert counts from the positioning failure) to the first alarm at or after it; mean {tta_mean:.2} +/- {tta_se:.2} s over {} runs with a failure and an alarm (0: the alarm was already standing); from the fault's onset the first alarm came {det_mean:.0} +/- {det_se:.0} s later",
                tta.len()
            )),
        );
        let (rate, se, upper) = rate_per_hour(&free_alarms, &free_hours);
        let bound = upper.map_or(String::new(), |u| {
            format!("; none seen: 95 % upper bound {u:.4}/h")
        });
        rows.push(
            Row::measured(
                setting.table,
                format!("{prefix}: false alarms per hour, fault-free"),
                "false-alarm rate",
                "1/h",
                Some(limit.false_alarms_per_h),
                rate,
                (
                    format!("<= {}", limit.false_alarms_per_h),
                    Verdict::from_ok(rate <= limit.false_alarms_per_h),
                ),
            )
            .with_note(format!(
                "{rate:.4} +/- {se:.4} /h: {} alarm epochs in {} fault-free runs, {free_epochs} epochs ({:.1} h){bound}; {}; P_fa x {} epochs with RAIM expects {:.1} alarm epochs, and the statistic exceeded its {STATISTIC_TAIL} quantile in {tail} of them (expected {:.0} +/- {:.0})",
                free_alarms.iter().sum::<f64>(),
                free.len(),
                free_hours.iter().sum::<f64>(),
                shown_by_sample(limit.false_alarms_per_h, free_hours.iter().sum()),
                survivals.len(),
                setting.pfa * survivals.len() as f64,
                STATISTIC_TAIL * survivals.len() as f64,
                (STATISTIC_TAIL * survivals.len() as f64).sqrt(),
            )),
        );
    }
    rows
}

/// The settings of the selected tables, in row order (the two of table 5-2 share a
/// scenario and follow each other).
pub fn settings(mops: bool, leo: bool) -> Vec<Setting> {
    let mut out = Vec::new();
    if mops {
        out.extend([mops_en_route_setting(), mops_setting()]);
    }
    if leo {
        out.extend([leo_setting(), leo_manoeuvre_setting()]);
    }
    out
}

/// The rows of the selected tables with `runs` runs per setting and kind, each setting's
/// seed shifted by `seed_offset` (`validate thesis --seed-base`); a scenario's geometry
/// runs once for consecutive settings that share it.
pub fn rows(
    mops: bool,
    leo: bool,
    runs: usize,
    seed_offset: u64,
) -> Result<Vec<Row>, ValidateError> {
    let mut rows = Vec::new();
    let mut last: Option<(&'static str, Geometry)> = None;
    for mut setting in settings(mops, leo) {
        setting.seed = setting.seed.wrapping_add(seed_offset);
        let geometry = match last.take() {
            Some((file, g)) if file == setting.scenario_file => g,
            _ => geometry(&scenario(&setting)?)?,
        };
        let r = monte_carlo_on(&setting, &geometry, runs)?;
        rows.extend(rows_of(&setting, &r));
        last = Some((setting.scenario_file, geometry));
    }
    Ok(rows)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn draws_are_fixed_by_the_seed_and_cover_every_ramp() {
        let setting = mops_setting();
        let epochs = (0..4000)
            .map(|k| GeometryEpoch {
                t_s: k as f64,
                r_true_ecef_m: Vec3::zeros(),
                pseudoranges: vec![
                    (SatId::gps(1), 2e7),
                    (SatId::gps(2), 2e7),
                    (SatId::gps(3), 2e7),
                ],
            })
            .collect();
        let start = hifitime::Epoch::from_gregorian_str("2023-03-12T00:00:00 GPST").unwrap();
        let origin = TimeOrigin::new(start);
        let g = Geometry {
            store: EphemerisStore::new(Vec::new(), &origin),
            origin,
            epochs,
        };
        let a = draws(&setting, &g, 8);
        assert_eq!(a, draws(&setting, &g, 8));
        assert_eq!(a.len(), 16);
        assert!(a[..8].iter().all(|d| d.fault.is_some()));
        assert!(a[8..].iter().all(|d| d.fault.is_none()));
        assert!(a.iter().all(|d| d.start + setting.window_s <= 4000));
        let rates: Vec<f64> = a[..4].iter().map(|d| d.fault.unwrap().1).collect();
        assert_eq!(rates, RAMP_RATES_MPS.to_vec());
        let manoeuvre = leo_manoeuvre_setting();
        let m = draws(&manoeuvre, &g, 8);
        let rates: Vec<f64> = m[..4].iter().map(|d| d.fault.unwrap().1).collect();
        assert_eq!(rates, FAST_RAMP_RATES_MPS.to_vec());
        assert!(m.iter().all(|d| d.start + manoeuvre.window_s <= 4000));
        assert_ne!(m, a);
    }

    #[test]
    fn outcome_counts_a_late_alarm_as_a_miss_and_times_it() {
        let limit = Limit {
            name: "x",
            hal_m: 100.0,
            tta_s: 10.0,
            false_alarms_per_h: 0.0,
            detection: Requirement::MinDetection(0.999),
        };
        let sat = SatId::gps(7);
        // HPE grows 5 m/s; failure at 21 s; the alarm starts at `alarm_from`.
        let series = |alarm_from: f64| -> Vec<EpochResult> {
            (0..100)
                .map(|k| {
                    let t = k as f64;
                    EpochResult {
                        t_s: t,
                        hpe_all_m: 5.0 * t,
                        hpe_out_m: 1.0,
                        hpl_m: 50.0,
                        alarm: t >= alarm_from,
                        excluded: (t >= alarm_from).then_some(sat),
                        survival: 0.5,
                    }
                })
                .collect()
        };
        let on_time = fault_outcome(&series(25.0), sat, &limit);
        assert_eq!(on_time.failure_s, Some(21.0));
        assert_eq!(on_time.time_to_alarm_s, Some(4.0));
        assert!(!on_time.missed);
        assert_eq!(on_time.right_exclusion, Some(true));
        let late = fault_outcome(&series(35.0), sat, &limit);
        assert_eq!(late.time_to_alarm_s, Some(14.0));
        assert!(late.missed && late.missed_while_available);
        let early = fault_outcome(&series(3.0), sat, &limit);
        assert_eq!(early.time_to_alarm_s, Some(0.0));
        assert_eq!(early.detection_s, Some(3.0));
        let never = fault_outcome(&series(1e9), sat, &limit);
        assert!(never.missed && never.time_to_alarm_s.is_none());
        assert!(!never.missed_without_raim);
        // The same late alarm, with no RAIM (no protection level) in the failure's epochs.
        let mut gap = series(35.0);
        for e in gap.iter_mut().filter(|e| e.t_s >= 21.0 && e.t_s < 35.0) {
            e.hpl_m = f64::INFINITY;
        }
        let gap = fault_outcome(&gap, sat, &limit);
        assert!(gap.missed && gap.missed_without_raim && !gap.missed_while_available);
        assert!(!on_time.missed_without_raim);
    }
    /// The aircraft scenario cut to `duration_s`, with `extra` appended.
    fn short_aircraft(duration_s: f64, extra: &str) -> Scenario {
        let setting = mops_setting();
        let text = setting.scenario_text.replace(
            "duration_s = 3600.0",
            &format!("duration_s = {duration_s:.1}"),
        ) + extra;
        skyforge_scenarios::parse(&text, "test", Path::new(SCENARIO_DIR)).unwrap()
    }

    #[test]
    fn the_aircraft_scenario_parses_builds_and_flies_the_generated_leg() {
        // Parsed as the Monte Carlo parses it: the CSV resolves from SCENARIO_DIR, whatever
        // the working directory (cargo runs tests from validate/, where the relative path
        // alone would not resolve).
        let setting = mops_setting();
        assert!(!Path::new("raim-aircraft.csv").exists());
        let parsed = scenario(&setting).unwrap();
        let mut world = parsed.build().unwrap();
        assert_eq!(world.duration_s, 3600.0);
        // The platform flies the generator's leg (the CSV is that leg at 1 Hz, millimetres).
        let window = world.platform.window(0.0, 3600.0).unwrap();
        for t in [0.0, 900.5, 1800.0, 3599.25, 3600.0] {
            let r = window.state(t).r_ecef_m;
            let want = crate::integrity::aircraft::position_ecef_m(t);
            assert!((r - want).norm() < 0.01, "t {t}: {}", (r - want).norm());
        }
        // The LEO scenario builds from the same folder.
        scenario(&leo_setting()).unwrap().build().unwrap();
    }

    #[test]
    fn per_run_draws_are_the_observation_model() {
        // The observation model itself, with and without an iono-ramp event, same seed:
        // its measured code minus its truth is white noise of SIGMA_M, and the event adds
        // exactly rate x (t - start) to the faulted satellite's truth and nothing to the
        // others: what `run` draws on top of the fault-free truth.
        let free = observation_run(&short_aircraft(120.0, "")).unwrap();
        let sat = free.truth[0].epochs[30].sats[0].sat;
        let rate = 2.5;
        let event = format!(
            "\n[[errors.events]]\nkind = \"iono-ramp\"\nsatellite = \"{sat}\"\nstart_s = 30.0\nend_s = 120.0\nvalue = {rate}\n"
        );
        let faulted = observation_run(&short_aircraft(120.0, &event)).unwrap();
        let mut noise = Vec::new();
        let mut series: Vec<Vec<f64>> = Vec::new();
        for ((e_free, e_fault), e_meas) in free.truth[0]
            .epochs
            .iter()
            .zip(&faulted.truth[0].epochs)
            .zip(&faulted.measured[0].epochs)
        {
            let t = (e_fault.time - faulted.start).to_seconds();
            for ((a, b), m) in e_free.sats.iter().zip(&e_fault.sats).zip(&e_meas.sats) {
                assert_eq!((a.sat, b.sat), (m.sat, b.sat));
                let ramp = b.pseudorange_m.unwrap() - a.pseudorange_m.unwrap();
                let want = if a.sat == sat && t >= 30.0 {
                    rate * (t - 30.0)
                } else {
                    0.0
                };
                assert!(
                    (ramp - want).abs() < 1e-3,
                    "{} at {t}: {ramp} vs {want}",
                    a.sat
                );
                noise.push((m.pseudorange_m.unwrap() - b.pseudorange_m.unwrap()) / SIGMA_M);
            }
            series.push(
                e_meas
                    .sats
                    .iter()
                    .zip(&e_fault.sats)
                    .map(|(m, b)| m.pseudorange_m.unwrap() - b.pseudorange_m.unwrap())
                    .collect(),
            );
        }
        let n = noise.len() as f64;
        let mean = noise.iter().sum::<f64>() / n;
        let std = (noise.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1.0)).sqrt();
        assert!(n > 500.0, "{n}");
        assert!(mean.abs() < 4.0 / n.sqrt(), "mean {mean}");
        assert!((std - 1.0).abs() < 4.0 / (2.0 * n).sqrt(), "std {std}");
        // White: the lag-one correlation of each satellite's noise is zero within 4 sigma.
        let (mut c0, mut c1, mut pairs) = (0.0, 0.0, 0.0);
        for w in series.windows(2) {
            for (x, y) in w[0].iter().zip(&w[1]) {
                c0 += x * x;
                c1 += x * y;
                pairs += 1.0;
            }
        }
        let rho = c1 / c0;
        assert!(
            rho.abs() < 4.0 / f64::sqrt(pairs),
            "lag-1 correlation {rho}"
        );
    }

    #[test]
    fn fault_free_statistic_is_chi_square_on_the_aircraft() {
        // Six fault-free runs (10800 epochs, every one with RAIM): the all-in statistic's
        // survival probability is uniform, so each upper tail holds its share within 4
        // standard deviations. Weights with another sigma than the drawn noise, or a model
        // the receiver and the observation truth disagree on (the troposphere at 10 km,
        // the moving platform's light time), would move it.
        let (_, free) = monte_carlo(&mops_setting(), 6).unwrap();
        let u: Vec<f64> = free.iter().flatten().map(|e| e.survival).collect();
        assert!(u.len() > 10_000, "{}", u.len());
        assert!(u.iter().all(|u| (0.0..=1.0).contains(u)));
        let n = u.len() as f64;
        for p in [0.5, 0.1, 0.01] {
            let count = u.iter().filter(|x| **x < p).count() as f64;
            let sd = (n * p * (1.0 - p)).sqrt();
            assert!((count - n * p).abs() < 4.0 * sd, "P < {p}: {count} of {n}");
        }
    }

    #[test]
    fn reduced_monte_carlo_gives_every_row_with_a_finite_value() {
        // The group as `validate thesis --only B-5.2` runs it, with a few runs per kind.
        let rows = rows(true, true, 6, 0).unwrap();
        // Table 5-1: three phases on the aircraft; table 5-2: free flight and orbit
        // manoeuvre on the LEO; three rows each.
        assert_eq!(rows.len(), 5 * 3);
        for r in &rows {
            assert!(r.thesis.is_some(), "{}", r.row);
            assert!(!r.note.is_empty());
        }
        let phases: Vec<&str> = rows
            .iter()
            .step_by(3)
            .map(|r| r.row.split(" (").next().unwrap())
            .collect();
        assert_eq!(
            phases,
            [
                "en route",
                "terminal",
                "non-precision approach",
                "free flight",
                "orbit manoeuvre"
            ]
        );
        assert!(
            rows[..9]
                .iter()
                .all(|r| r.table == TABLE_MOPS && r.row.contains("aircraft"))
        );
        assert!(rows[9..].iter().all(|r| r.table == TABLE_LEO));
        // Detection happens: the ramps reach the alarm in every faulted run.
        for r in [&rows[0], &rows[12]] {
            assert!(r.note.contains("detection in 6 runs"), "{}", r.note);
        }
        // The manoeuvre rows test at their own P_fa and say what they cannot model.
        assert!(
            rows[12].note.contains("P_fa 2.78e-5/epoch"),
            "{}",
            rows[12].note
        );
        assert!(rows[12].note.contains("no platform model has thrust"));
        assert!(!rows[9].note.contains("thrust"));
        assert_eq!(rows[14].thesis, Some(0.1));
    }
}
