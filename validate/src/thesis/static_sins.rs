//! P1-S: paper 001's static test (`BOOK_PAPER001_TARGETS.md` spec 2, TD-S): the
//! ring-laser SINS standing on a square in Changsha, aligned, then navigating alone (at
//! about 2050 s the paper prints north position about 70 m, east 310 m, north velocity
//! 0.05 m/s, east 0.33 m/s) and integrated with the three BeiDou GEOs' time-differenced
//! carrier phase under an altitude constraint (its integrated standard deviations, maxima,
//! north/east asymmetry, and the integrated position against the pure INS's).
//!
//! **Run** (each seed): the navigation-grade IMU of `signals::imu` (paper 001's gyro
//! drift 0.005 deg/h as a random constant; the rest of the grade assumed, docs/imu.md)
//! at [`RATE_HZ`] on a static site; coarse alignment over [`COARSE_S`], fine alignment
//! (zero-velocity updates) over [`FINE_S`], then the INS alone for [`PURE_S`]. The
//! estimator reads only the increments and the surveyed site (truth firewall); the
//! comparison is with the site, which is the truth of a static IMU.
//!
//! **Verdicts** (registered before the first run, TD-S): the median over the seeds of
//! each absolute error within a factor 3 of the paper's (the errors depend on the drawn
//! biases and the unstated alignment, so one seed says little).

use crate::draw::Draw;
use crate::report::{Row, Verdict};
use crate::thesis::ValidateError;
use hifitime::{Duration, Epoch};
use rayon::prelude::*;
use skyforge_gnss::imu::ImuIncrement;
use skyforge_navigation::ins::{
    FineAlignment, FineAlignmentConfig, InsState, coarse_alignment, fine_alignment, static_means,
};
use skyforge_orbits::Vec3;
use skyforge_orbits::frames::{Geodetic, YawPitchRoll, c_ecef_ned, geodetic_to_ecef};
use skyforge_orbits::gravity::normal_gravity_ecef;
use skyforge_orbits::platform::Kinematics;
use skyforge_signals::imu::{ImuConfig, ImuGrade, ImuSimulator};

/// Table identifier.
pub const TABLE: &str = "P1-S";
/// Registered runs: seeds `FIRST_SEED ..` (TD-S: at least 20; assumed: 20).
const FIRST_SEED: u64 = 1;
const RUNS: u64 = 20;
/// assumed: 100 Hz, the targets' suggestion (the paper gives no rate).
const RATE_HZ: f64 = 100.0;
/// assumed: 60 s of coarse alignment, then 540 s of fine alignment (ten minutes of
/// static alignment, usual for a navigation-grade SINS; the paper's is unstated).
const COARSE_S: f64 = 60.0;
const FINE_S: f64 = 540.0;
/// Paper 001: the pure-INS errors read at about 2050 s.
const PURE_S: f64 = 2050.0;
/// assumed: the square in front of NUDT's main building, Changsha, about 50 m high.
const SITE_DEG: (f64, f64, f64) = (28.2, 112.99, 50.0);
/// assumed: the vehicle heading north, level.
const HEADING_DEG: f64 = 0.0;
/// Paper 001's printed pure-INS errors at 2050 s: north and east position (m), north
/// and east velocity (m/s).
const PAPER: [(&str, &str, f64); 4] = [
    ("pure INS north position at 2050 s", "m", 70.0),
    ("pure INS east position at 2050 s", "m", 310.0),
    ("pure INS north velocity at 2050 s", "m/s", 0.05),
    ("pure INS east velocity at 2050 s", "m/s", 0.33),
];
/// TD-S: within a factor 3.
const FACTOR: f64 = 3.0;

/// The site's position and the IMU's body-to-ECEF attitude.
pub(crate) fn site() -> (Geodetic, Vec3, skyforge_orbits::Mat3) {
    let g = Geodetic::from_degrees(SITE_DEG.0, SITE_DEG.1, SITE_DEG.2);
    let c_ned_ecef = c_ecef_ned(g.lat_rad, g.lon_rad).transpose();
    let attitude = YawPitchRoll::new(HEADING_DEG.to_radians(), 0.0, 0.0).c_body_ref();
    (g, geodetic_to_ecef(&g), c_ned_ecef * attitude)
}

/// One seed's IMU from `start`: its static alignment (coarse over [`COARSE_S`], fine over
/// [`FINE_S`]) and the [`PURE_S`] of increments after it.
pub(crate) fn aligned_imu(
    seed: u64,
    start: Epoch,
) -> Result<(FineAlignment, Vec<ImuIncrement>), ValidateError> {
    let (g, r, c) = site();
    let still = Kinematics {
        r_ecef_m: r,
        v_ecef_mps: Vec3::zeros(),
        a_ecef_mps2: Vec3::zeros(),
        c_body_ecef: c,
        omega_eb_body_rps: Vec3::zeros(),
        gravity_ecef_mps2: normal_gravity_ecef(&g),
    };
    let config = ImuConfig::of_grade(ImuGrade::Navigation, RATE_HZ);
    let mut imu = ImuSimulator::new(&config, seed, 0);
    let fail = |e: String| ValidateError::Pipeline(format!("{TABLE} seed {seed}: {e}"));
    let mut take = |seconds: f64| -> Result<Vec<ImuIncrement>, ValidateError> {
        let n = (seconds * RATE_HZ).round() as usize;
        (0..n)
            .map(|_| {
                let s = imu
                    .next_sample(&|_| Some(still))
                    .map_err(|e| fail(e.to_string()))?;
                Ok(ImuIncrement {
                    t_end: start + Duration::from_seconds(s.t_s),
                    dt_s: s.dt_s,
                    dtheta_rad: s.dtheta_rad,
                    dv_mps: s.dv_mps,
                })
            })
            .collect()
    };
    let coarse = take(COARSE_S)?;
    let means = static_means(&coarse).map_err(|e| fail(e.to_string()))?;
    let c0 = coarse_alignment(&means.f_body_mps2, &means.w_body_rps, &g)
        .map_err(|e| fail(e.to_string()))?;
    let end = coarse.last().map_or(start, |i| i.t_end);
    let fine = take(FINE_S)?;
    let aligned = fine_alignment(
        &InsState::at_rest(end, r, c0),
        &fine,
        &FineAlignmentConfig::default(),
    )
    .map_err(|e| fail(e.to_string()))?;
    Ok((aligned, take(PURE_S)?))
}

/// North and east position (m) and velocity (m/s) errors of `state` at the static site.
pub(crate) fn ned_errors(state: &InsState) -> [f64; 4] {
    let (g, r, _) = site();
    let to_ned = c_ecef_ned(g.lat_rad, g.lon_rad);
    let (dr, dv) = (to_ned * (state.r_ecef_m - r), to_ned * state.v_ecef_mps);
    [dr.x, dr.y, dv.x, dv.y]
}

/// One seed: the absolute north and east position (m) and velocity (m/s) errors of the
/// pure INS at the end.
fn run(seed: u64, start: Epoch) -> Result<[f64; 4], ValidateError> {
    let (aligned, free) = aligned_imu(seed, start)?;
    let mut ins = aligned.state;
    ins.propagate_all(&free)
        .map_err(|e| ValidateError::Pipeline(format!("{TABLE} seed {seed}: {e}")))?;
    Ok(ned_errors(&ins).map(f64::abs))
}

/// The median of `values`.
pub(crate) fn median(mut values: Vec<f64>) -> f64 {
    values.sort_by(f64::total_cmp);
    let n = values.len();
    if n % 2 == 1 {
        values[n / 2]
    } else {
        0.5 * (values[n / 2 - 1] + values[n / 2])
    }
}

/// The four rows over the draw's seeds.
pub fn rows(draw: Draw) -> Result<Vec<Row>, ValidateError> {
    let seeds = draw.seeds(FIRST_SEED, RUNS);
    let start = Epoch::from_gpst_seconds(1.36e9); // assumed: any day; a static IMU's errors do not depend on it
    let errors: Vec<[f64; 4]> = seeds
        .clone()
        .into_par_iter()
        .map(|s| run(s, start))
        .collect::<Result<_, _>>()?;
    let note = format!(
        "median over seeds {}..{} of the absolute error; navigation-grade IMU at {RATE_HZ} Hz, \
         {COARSE_S} s coarse + {FINE_S} s fine alignment (assumed), Changsha, heading north",
        seeds.start,
        seeds.end - 1
    );
    Ok(PAPER
        .iter()
        .enumerate()
        .map(|(k, (row, unit, paper))| {
            let ours = median(errors.iter().map(|e| e[k]).collect());
            let inside = ours <= paper * FACTOR && ours >= paper / FACTOR;
            Row::measured(
                TABLE,
                *row,
                "median absolute error",
                unit,
                Some(*paper),
                ours,
                ("within a factor 3".into(), Verdict::from_ok(inside)),
            )
            .with_note(note.clone())
        })
        .collect())
}
