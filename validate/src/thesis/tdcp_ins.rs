//! P1-S, integrated: paper 001's static test with its SINS corrected by the three BeiDou
//! GEOs (`BOOK_PAPER001_TARGETS.md` spec 2, TD-S): integrated standard deviations of the
//! velocity north 0.006 and east 0.001 m/s and of the position north 1 and east 0.2 m,
//! maxima 0.025 / under 0.005 m/s and 3.5 / under 0.5 m, and the integrated position at
//! 2050 s at least 20 times smaller than the pure INS's.
//!
//! **Run** (each seed; the IMU and alignment of [`super::static_sins`] on the same seed):
//! the bundled `paper001-tdcp-static` (the site, the three GEOs, the oscillator) at the
//! observation level over the alignment and the 2050 s at the paper's 10 Hz
//! (`[observation] rate_hz = 10`; until 2026-12-02 the observation level had whole seconds
//! only and the rows ran at 1 Hz), into `navigation::gnss_ins::tdcp_aided`:
//! the time-differenced carrier phase's double differences, the code differenced between
//! the GEOs, and the site's height. The estimator reads the observations, the navigation
//! data and the surveyed site (its start and height); the comparison is with the site.
//!
//! **Statistics**: per seed, over the 2050 s, the standard deviation and the largest
//! absolute value of each error; the rows are medians over [`RUNS`] seeds. **Verdicts**
//! (registered before the first run): each standard deviation within a factor 2 of the
//! paper's; the maxima within a factor 2 (0.025 m/s, 3.5 m) or under twice the paper's
//! bound (0.005 m/s, 0.5 m); the north/east ratios of the standard deviations above 2;
//! the pure INS's horizontal error at 2050 s at least 20 times the integrated one's.

use super::static_sins::{TABLE, aligned_imu, median, ned_errors, site};
use crate::draw::Draw;
use crate::report::{Row, Verdict};
use crate::thesis::ValidateError;
use rayon::prelude::*;
use skyforge_gnss::signal::Signal;
use skyforge_navigation::gnss_ins::{ImuNoise, LooselyCoupledConfig, TdcpAidedConfig, tdcp_aided};
use skyforge_navigation::ins::FineAlignment;
use skyforge_navigation::pvt::PvtConfig;
use skyforge_navigation::tdcp::TdcpConfig;
use skyforge_orbits::Vec3;
use skyforge_orbits::constants::OMEGA_E_GPS;
use skyforge_orbits::ephemeris::EphemerisStore;
use skyforge_orbits::frames::Geodetic;
use skyforge_orbits::time::TimeOrigin;
use skyforge_runner::observation_run;
use skyforge_scenarios::Scenario;
use skyforge_signals::imu::NAVIGATION;
use skyforge_signals::obs_model::Level;

/// The bundled scenario whose site, satellites and oscillator the run uses.
pub(crate) const SCENARIO: &str = "paper001-tdcp-static";
/// Registered runs: seeds `FIRST_SEED ..` (assumed: eight, fewer than the pure INS's 20
/// because each needs a 2650 s GNSS run).
const FIRST_SEED: u64 = 1;
const RUNS: u64 = 8;
/// Paper 001: the filter at 10 Hz.
const RATE_HZ: u32 = 10;
/// The alignment and the integrated span (s): [`super::static_sins`]'s.
const ALIGNMENT_S: f64 = 600.0;
const INTEGRATED_S: f64 = 2050.0;
/// assumed: a pseudorange's error for the code differences (the GEOs' code at 45 dB-Hz
/// plus the broadcast orbit and ionosphere residuals, metres).
const CODE_SIGMA_M: f64 = 2.0;
/// assumed: the altitude constraint, the surveyed height known to 0.5 m.
const HEIGHT_SIGMA_M: f64 = 0.5;
/// assumed: the carrier phase's error (m), the TDCP default.
const PHASE_SIGMA_M: f64 = 0.003;

/// One seed's statistics: standard deviations and maxima of the north and east position
/// (m) and velocity (m/s) errors, and the horizontal error at the end, integrated and pure.
struct SeedStats {
    sigma: [f64; 4],
    max: [f64; 4],
    end_m: f64,
    pure_end_m: f64,
}

fn scenario(seed: u64) -> Result<Scenario, ValidateError> {
    let mut s = skyforge_scenarios::named(SCENARIO)?;
    s.seed = seed;
    s.time.duration_s = ALIGNMENT_S + INTEGRATED_S + 1.0;
    s.observation.rate_hz = Some(RATE_HZ);
    s.observation.level = Level::Observation;
    Ok(s)
}

/// The filter's initial tilt and heading sigmas (rad) after a static alignment at `g`:
/// the alignment's own, or what the grade's accelerometer bias (tilt `b / g`) and gyro
/// bias (heading `b / (w_ie cos L)`) leave, at three sigma, when larger.
pub(crate) fn initial_attitude_sigmas(
    aligned: &FineAlignment,
    g: &Geodetic,
    noise: &ImuNoise,
) -> (f64, f64) {
    let gyrocompass = OMEGA_E_GPS * g.lat_rad.cos();
    (
        aligned
            .level_sigma_rad
            .max(3.0 * noise.accel_bias / 9.80665),
        aligned
            .heading_sigma_rad
            .hypot(3.0 * noise.gyro_bias / gyrocompass),
    )
}

fn run(seed: u64) -> Result<SeedStats, ValidateError> {
    let fail = |e: String| ValidateError::Pipeline(format!("{TABLE} integrated seed {seed}: {e}"));
    let scenario = scenario(seed)?;
    let gnss = observation_run(&scenario).map_err(|e| fail(e.to_string()))?;
    let (aligned, free) = aligned_imu(seed, gnss.start)?;
    let (g, r_site, _) = site();
    let origin = TimeOrigin::new(gnss.start);
    let store = EphemerisStore::new(gnss.ephemerides.clone(), &origin);
    let pvt = PvtConfig {
        elevation_mask_rad: 10f64.to_radians(),
        iono_gps: gnss.iono.gps,
        iono_bds: gnss.iono.bds,
        ..PvtConfig::default()
    };
    let noise = crate::ins::filter_noise(NAVIGATION);
    let (initial_tilt_rad, initial_heading_rad) = initial_attitude_sigmas(&aligned, &g, &noise);
    let config = TdcpAidedConfig {
        filter: LooselyCoupledConfig {
            imu: noise,
            lever_arm_body_m: Vec3::zeros(),
            initial_position_m: 0.1, // the surveyed site
            initial_velocity_mps: 0.01,
            initial_tilt_rad,
            initial_heading_rad,
        },
        tdcp: TdcpConfig {
            signal: Some(Signal::BdsB1I),
            sigma_phase_m: PHASE_SIGMA_M,
            ..TdcpConfig::default()
        },
        code_sigma_m: Some(CODE_SIGMA_M),
        height_m: Some((g.h_m, HEIGHT_SIGMA_M)),
    };
    let mut start = aligned.state;
    start.r_ecef_m = r_site;
    let epochs = &gnss.measured[0].epochs;
    let solutions = tdcp_aided(start, &free, epochs, (&store, &origin, &pvt), &config)
        .map_err(|e| fail(e.to_string()))?;
    let errors: Vec<[f64; 4]> = solutions.iter().map(|s| ned_errors(&s.state)).collect();
    let last = errors
        .last()
        .ok_or_else(|| fail("no integrated solution".into()))?;
    let mut pure = aligned.state;
    pure.propagate_all(&free).map_err(|e| fail(e.to_string()))?;
    let p = ned_errors(&pure);
    let n = errors.len() as f64;
    let stat = |k: usize| {
        let mean = errors.iter().map(|e| e[k]).sum::<f64>() / n;
        let var = errors.iter().map(|e| (e[k] - mean).powi(2)).sum::<f64>() / n;
        (
            var.sqrt(),
            errors.iter().map(|e| e[k].abs()).fold(0.0, f64::max),
        )
    };
    let both: Vec<(f64, f64)> = (0..4).map(stat).collect();
    Ok(SeedStats {
        sigma: [0, 1, 2, 3].map(|k| both[k].0),
        max: [0, 1, 2, 3].map(|k| both[k].1),
        end_m: last[0].hypot(last[1]),
        pure_end_m: p[0].hypot(p[1]),
    })
}

/// A row against a printed number `paper` with the verdict `ok`.
fn row(
    name: &str,
    unit: &str,
    paper: Option<f64>,
    ours: f64,
    check: (&str, bool),
    note: &str,
) -> Row {
    Row::measured(
        TABLE,
        name,
        "median over seeds",
        unit,
        paper,
        ours,
        (check.0.into(), Verdict::from_ok(check.1)),
    )
    .with_note(note.into())
}

/// The integrated rows over the draw's seeds.
pub fn rows(draw: Draw) -> Result<Vec<Row>, ValidateError> {
    let seeds = draw.seeds(FIRST_SEED, RUNS);
    let stats: Vec<SeedStats> = seeds
        .clone()
        .into_par_iter()
        .map(run)
        .collect::<Result<_, _>>()?;
    let med = |f: &dyn Fn(&SeedStats) -> f64| median(stats.iter().map(f).collect());
    let note = format!(
        "seeds {}..{}; {RATE_HZ} Hz observation level (the paper's rate), TDCP double \
         differences + code differences (sigma {CODE_SIGMA_M} m) + height ({HEIGHT_SIGMA_M} m), \
         the sigmas assumed",
        seeds.start,
        seeds.end - 1
    );
    let factor2 = |ours: f64, paper: f64| ours <= 2.0 * paper && ours >= paper / 2.0;
    let mut rows = Vec::new();
    let names = [
        "north position",
        "east position",
        "north velocity",
        "east velocity",
    ];
    let units = ["m", "m", "m/s", "m/s"];
    let paper_sigma = [1.0, 0.2, 0.006, 0.001];
    for k in 0..4 {
        let ours = med(&|s| s.sigma[k]);
        rows.push(row(
            &format!("integrated {} sigma", names[k]),
            units[k],
            Some(paper_sigma[k]),
            ours,
            ("within a factor 2", factor2(ours, paper_sigma[k])),
            &note,
        ));
    }
    // The maxima: north within a factor 2, east under twice the paper's bound.
    let paper_max = [(3.5, false), (0.5, true), (0.025, false), (0.005, true)];
    for (k, (paper, bound)) in paper_max.into_iter().enumerate() {
        let ours = med(&|s| s.max[k]);
        let (check, ok) = if bound {
            ("under twice the paper's bound", ours < 2.0 * paper)
        } else {
            ("within a factor 2", factor2(ours, paper))
        };
        rows.push(row(
            &format!("integrated {} maximum", names[k]),
            units[k],
            Some(paper),
            ours,
            (check, ok),
            &note,
        ));
    }
    for (name, k, paper) in [("position", 0, 5.0), ("velocity", 2, 6.0)] {
        let ours = med(&|s| s.sigma[k] / s.sigma[k + 1]);
        rows.push(row(
            &format!("integrated north/east {name} sigma ratio"),
            "1",
            Some(paper),
            ours,
            ("above 2", ours > 2.0),
            &note,
        ));
    }
    let ratio = med(&|s| s.pure_end_m / s.end_m);
    rows.push(row(
        "pure INS / integrated horizontal error at 2050 s",
        "1",
        None,
        ratio,
        ("at least 20", ratio >= 20.0),
        &note,
    ));
    Ok(rows)
}
