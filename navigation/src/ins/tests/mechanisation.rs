//! The ECEF mechanisation against closed-form trajectories: at rest, in a steady turn, in
//! coning motion, and with an accelerometer bias of known effect.

use super::truth::{Bias, Circle, Coning, Static, Trajectory, increments, site, true_state};
use crate::ins::{InsState, attitude_difference};
use skyforge_orbits::Vec3;
use skyforge_orbits::constants::OMEGA_E_GPS;
use skyforge_orbits::frames::YawPitchRoll;
use skyforge_orbits::frames::c_ecef_ned;

/// IMU interval of every test (s): 100 Hz.
const DT: f64 = 0.01;

/// Largest position, velocity and attitude errors over a run (m, m/s, rad), checked once
/// per second, and the same at the end.
#[derive(Debug, Default)]
struct Errors {
    max: [f64; 3],
    end: [f64; 3],
}

fn errors_at(state: &InsState, traj: &dyn Trajectory, t: f64) -> [f64; 3] {
    let truth = true_state(traj, t);
    assert_eq!(state.t, truth.t);
    [
        (state.r_ecef_m - truth.r_ecef_m).norm(),
        (state.v_ecef_mps - truth.v_ecef_mps).norm(),
        attitude_difference(&state.c_body_ecef, &truth.c_body_ecef).norm(),
    ]
}

/// Navigates `traj` for `seconds` from the true initial state; `corrections` false feeds
/// no previous increment, so neither coning nor sculling is corrected.
fn run(traj: &dyn Trajectory, seconds: f64, bias: &Bias, corrections: bool) -> (InsState, Errors) {
    let n = (seconds / DT).round() as usize;
    let incs = increments(traj, DT, n, bias);
    let mut state = true_state(traj, 0.0);
    let mut errors = Errors::default();
    for (k, inc) in incs.iter().enumerate() {
        let prev = if corrections && k > 0 {
            Some(&incs[k - 1])
        } else {
            None
        };
        state.propagate(prev, inc).unwrap();
        if (k + 1) % 100 == 0 || k + 1 == n {
            let e = errors_at(&state, traj, (k + 1) as f64 * DT);
            for (max, now) in errors.max.iter_mut().zip(e) {
                *max = max.max(now);
            }
            errors.end = e;
        }
    }
    (state, errors)
}

/// (a) At rest at latitude 30 deg for 10 min: the increments are exactly the Earth's rate
/// and minus normal gravity, and the mechanisation must return them to the same state.
#[test]
fn stationary_ten_minutes() {
    let yaw = YawPitchRoll::new(40f64.to_radians(), 2f64.to_radians(), -1f64.to_radians());
    let traj = Static::new(&site(), yaw);
    let (_, e) = run(&traj, 600.0, &Bias::default(), true);
    println!(
        "stationary 600 s: max errors {:?} (m, m/s, rad), end {:?}",
        e.max, e.end
    );
    assert!(e.max[0] < 1e-6, "position {:e} m", e.max[0]);
    assert!(e.max[1] < 1e-7, "velocity {:e} m/s", e.max[1]);
    assert!(e.max[2] < 1e-10, "attitude {:e} rad", e.max[2]);
}

/// (b) A level circle of 200 m radius at 20 m/s (2 m/s^2 centripetal, 0.1 rad/s turn),
/// heading along the track, for 10 min (9.5 turns). What remains is the trapezoid rule
/// of the position update: its error per step, `(tau^3 / 12) w^2 v` along the track,
/// sums to `(tau w)^2 / 12 |r(t) - r(0)|`, at most 3.3e-5 m on this circle, and halving
/// the step quarters it (the quadrature of the truth is exact to ~1e-13 of an
/// increment and is not the limit).
#[test]
fn circle_ten_minutes() {
    let traj = Circle::new(&site(), 200.0, 20.0);
    let (_, e) = run(&traj, 600.0, &Bias::default(), true);
    println!(
        "circle 600 s: max errors {:?} (m, m/s, rad), end {:?}",
        e.max, e.end
    );
    let bound = (DT * 0.1_f64).powi(2) / 12.0 * 400.0;
    assert!(e.end[0] < 1e-3, "position {:e} m", e.end[0]);
    assert!(e.max[0] < 1.5 * bound, "position {:e} m", e.max[0]);
    assert!(e.max[1] < 1e-7, "velocity {:e} m/s", e.max[1]);
    assert!(e.max[2] < 1e-10, "attitude {:e} rad", e.max[2]);
}

/// (c) Classical coning (half-angle 1 deg at 1 Hz) at rest for 60 s: the body's z axis
/// precesses, the rate vector turns, and the sum of the increments misses the rotation
/// that results. Per interval the missed rotation is `s^2 (x - sin x) / 2` about the cone
/// axis (`s = sin(beta)`, `x = W tau`); the two-sample correction estimates it as
/// `(1/12) |alpha_{k-1} x alpha_k| = s^2 sin^2(x/2) sin(x) / 3`, leaving `s^2 x^5 / 60`.
/// The first interval has no predecessor and misses its whole coning term. Both errors
/// must follow that theory within 1 %, and the correction must cut the attitude error
/// about 1000-fold (`5 / x^2`).
#[test]
fn coning_correction_matters() {
    let (beta, rate, seconds) = (1f64.to_radians(), std::f64::consts::TAU, 60.0);
    let traj = Coning::new(&site(), beta, rate);
    let (_, with) = run(&traj, seconds, &Bias::default(), true);
    let (_, without) = run(&traj, seconds, &Bias::default(), false);
    let (s2, x) = (beta.sin().powi(2), rate * DT);
    let steps = seconds / DT;
    let per_step = s2 * (x - x.sin()) / 2.0;
    let missed = steps * per_step;
    let corrected = (steps - 1.0) * (per_step - s2 * (x / 2.0).sin().powi(2) * x.sin() / 3.0);
    let residual = corrected + per_step;
    println!(
        "coning 60 s, corrected: max {:?}, end {:?}; theory {residual:e} rad",
        with.max, with.end
    );
    println!(
        "coning 60 s, uncorrected: max {:?}, end {:?}; theory {missed:e} rad",
        without.max, without.end
    );
    assert!(
        (with.end[2] - residual).abs() < 0.01 * residual,
        "corrected attitude {:e} rad",
        with.end[2]
    );
    assert!(
        (without.end[2] - missed).abs() < 0.01 * missed,
        "uncorrected attitude {:e} rad",
        without.end[2]
    );
    assert!(
        without.end[2] > 500.0 * with.end[2],
        "attitude {without:?} vs {with:?}"
    );
    assert!(
        without.end[0] > 50.0 * with.end[0],
        "position {without:?} vs {with:?}"
    );
    assert!(with.end[0] < 1e-4, "corrected position {:e} m", with.end[0]);
}

/// An accelerometer bias of 1e-4 m/s^2 along north moves a stationary INS north by
/// `b t^2 / 2` (0.18 m in 60 s; the Schuler loop takes 0.05 % of that), and the Coriolis
/// acceleration `-2 w_ie x v` of the growing north velocity moves it east by
/// `w_ie sin(L) b t^3 / 3` (0.26 mm): checks the sign and scale of the specific-force and
/// Coriolis paths.
#[test]
fn north_accelerometer_bias_moves_north_and_east() {
    let site = site();
    let traj = Static::new(&site, YawPitchRoll::new(0.0, 0.0, 0.0));
    let (b, t) = (1e-4, 60.0);
    let bias = Bias {
        accel_mps2: Vec3::new(b, 0.0, 0.0),
        ..Bias::default()
    };
    let (state, _) = run(&traj, t, &bias, true);
    let d_ned = c_ecef_ned(site.lat_rad, site.lon_rad) * (state.r_ecef_m - traj.r);
    let north = 0.5 * b * t * t;
    let east = OMEGA_E_GPS * site.lat_rad.sin() * b * t.powi(3) / 3.0;
    println!("north bias 60 s: NED displacement {d_ned:?}, expected north {north}, east {east}");
    assert!((d_ned.x - north).abs() < 0.01 * north, "{d_ned:?}");
    assert!((d_ned.y - east).abs() < 0.02 * east, "{d_ned:?}");
    assert!(d_ned.z.abs() < 1e-3 * north, "{d_ned:?}");
}
