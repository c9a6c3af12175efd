//! The loosely coupled filter against closed-form truth (the INS tests' trajectories and
//! error-free increments, plus biases and noise drawn here): its errors stay inside its
//! covariance over seeds, through GNSS updates and through an outage; bad input is refused.

use super::*;
use crate::ins::InsState;
use crate::ins::tests::truth::{Bias, Circle, Trajectory, increments, site, t0, true_state};
use hifitime::Duration;
use rand::SeedableRng;
use rand_chacha::ChaCha20Rng;
use rand_distr::{Distribution, StandardNormal};
use skyforge_gnss::imu::ImuIncrement;
use skyforge_orbits::{Mat3, Vec3};

const DT: f64 = 0.01;
/// The antenna from the IMU (body, m).
const LEVER: [f64; 3] = [1.0, 0.5, -1.5];

/// A tactical-grade IMU (assumed: biases large enough to be estimated in minutes).
fn config() -> LooselyCoupledConfig {
    LooselyCoupledConfig {
        imu: ImuNoise {
            gyro_arw: 0.1 * std::f64::consts::PI / 180.0 / 60.0,
            accel_vrw: 0.05 / 60.0,
            gyro_bias: 1.0 * std::f64::consts::PI / 180.0 / 3600.0,
            gyro_bias_tau_s: None,
            accel_bias: 1e-3 * 9.80665,
            accel_bias_tau_s: None,
        },
        lever_arm_body_m: Vec3::from(LEVER),
        initial_position_m: 2.0,
        initial_velocity_mps: 0.1,
        initial_tilt_rad: 1e-3,
        initial_heading_rad: 5e-3,
    }
}

fn normal3(rng: &mut ChaCha20Rng) -> Vec3 {
    Vec3::from_fn(|_, _| StandardNormal.sample(rng))
}

/// The truth's increments with drawn constant biases and white noise.
fn imu(
    traj: &dyn Trajectory,
    n: usize,
    cfg: &LooselyCoupledConfig,
    rng: &mut ChaCha20Rng,
) -> (Vec<ImuIncrement>, Bias) {
    let bias = Bias {
        gyro_rps: normal3(rng) * cfg.imu.gyro_bias,
        accel_mps2: normal3(rng) * cfg.imu.accel_bias,
    };
    let mut incs = increments(traj, DT, n, &bias);
    for inc in &mut incs {
        inc.dtheta_rad += normal3(rng) * cfg.imu.gyro_arw * DT.sqrt();
        inc.dv_mps += normal3(rng) * cfg.imu.accel_vrw * DT.sqrt();
    }
    (incs, bias)
}

/// The true state at `t` with errors drawn from the filter's initial covariance.
fn perturbed_start(
    traj: &dyn Trajectory,
    cfg: &LooselyCoupledConfig,
    rng: &mut ChaCha20Rng,
) -> InsState {
    let mut s = true_state(traj, 0.0);
    s.r_ecef_m += normal3(rng) * cfg.initial_position_m;
    s.v_ecef_mps += normal3(rng) * cfg.initial_velocity_mps;
    let up = s.r_ecef_m.normalize();
    let tilt = normal3(rng) * cfg.initial_tilt_rad;
    let psi = (tilt - up * up.dot(&tilt))
        + up * (cfg.initial_heading_rad * {
            let n: f64 = StandardNormal.sample(rng);
            n
        });
    s.c_body_ecef = nalgebra::Rotation3::new(psi).matrix() * s.c_body_ecef;
    s
}

/// A fix of the antenna at `t` seconds with white noise of `sigma_r` and `sigma_v`.
fn fix(traj: &dyn Trajectory, t: f64, sigma: (f64, f64), rng: &mut ChaCha20Rng) -> GnssFix {
    let c = traj.c_body_ecef(t);
    let lever = Vec3::from(LEVER);
    let w = traj.w_eb_body(t);
    let v_antenna = traj.v(t) + c * w.cross(&lever);
    GnssFix {
        t: t0() + Duration::from_seconds(t),
        r_ecef_m: traj.r(t) + c * lever + normal3(rng) * sigma.0,
        r_cov_m2: Mat3::identity() * sigma.0.powi(2),
        v_ecef_mps: Some((
            v_antenna + normal3(rng) * sigma.1,
            Mat3::identity() * sigma.1.powi(2),
        )),
    }
}

/// Position, velocity and attitude errors of `filter` against the truth at `t`.
fn errors(filter: &LooselyCoupled, traj: &dyn Trajectory, t: f64) -> [Vec3; 3] {
    let s = filter.state();
    let truth = true_state(traj, t);
    let d = s.c_body_ecef * truth.c_body_ecef.transpose();
    let psi = nalgebra::Rotation3::from_matrix(&d).scaled_axis();
    [
        s.r_ecef_m - truth.r_ecef_m,
        s.v_ecef_mps - truth.v_ecef_mps,
        psi,
    ]
}

/// The normalised squared error of the blocks `blocks` (indices of 3-vectors: 0 position,
/// 1 velocity, 2 attitude).
fn nees(filter: &LooselyCoupled, e: &[Vec3; 3], blocks: &[usize]) -> f64 {
    let p = filter.covariance();
    let n = 3 * blocks.len();
    let x = nalgebra::DVector::from_iterator(n, blocks.iter().flat_map(|&b| e[b].iter().copied()));
    let sub = nalgebra::DMatrix::from_fn(n, n, |i, j| {
        p[(3 * blocks[i / 3] + i % 3, 3 * blocks[j / 3] + j % 3)]
    });
    (x.transpose() * sub.cholesky().unwrap().inverse() * &x)[(0, 0)]
}

/// The chi-square(k) mean of `n` draws lies outside its two-sided 99 % band (normal
/// approximation: sd sqrt(2k/n)) when this returns false.
fn in_band(mean: f64, k: f64, n: f64) -> bool {
    let z = 2.576;
    (mean - k).abs() <= z * (2.0 * k / n).sqrt()
}

/// One run: `with_fixes_s` of 1-Hz fixes, then `outage_s` without; the NEES of
/// position, velocity and attitude at the last fix and of position at the outage's end.
fn run(seed: u64, with_fixes_s: usize, outage_s: usize) -> (f64, f64, LooselyCoupled, Bias) {
    let traj = Circle::new(&site(), 200.0, 10.0);
    let cfg = config();
    let mut rng = ChaCha20Rng::seed_from_u64(seed);
    let per_s = (1.0 / DT).round() as usize;
    let (incs, bias) = imu(&traj, (with_fixes_s + outage_s) * per_s, &cfg, &mut rng);
    let mut filter = LooselyCoupled::new(perturbed_start(&traj, &cfg, &mut rng), cfg).unwrap();
    let mut before = 0.0;
    for (k, inc) in incs.iter().enumerate() {
        filter.propagate(inc).unwrap();
        let t = (k + 1) as f64 * DT;
        if (k + 1) % per_s == 0 && (k + 1) / per_s <= with_fixes_s {
            filter
                .update(&fix(&traj, t, (0.5, 0.05), &mut rng))
                .unwrap();
            before = nees(&filter, &errors(&filter, &traj, t), &[0, 1, 2]);
        }
    }
    let t_end = (with_fixes_s + outage_s) as f64;
    let after = nees(&filter, &errors(&filter, &traj, t_end), &[0]);
    (before, after, filter, bias)
}

/// Over 20 seeds (assumed: enough for a 99 % band of +-2.6 sqrt(2k/20)), the errors at
/// the last fix (9 dof) and at the end of a 60-s outage (3 dof) are as large as the
/// filter's covariance says: the means of their NEES inside the chi-square band.
#[test]
fn errors_match_the_covariance_through_fixes_and_an_outage() {
    let seeds = 20;
    let (mut before, mut after) = (0.0, 0.0);
    for seed in 0..seeds {
        let (b, a, ..) = run(seed, 120, 60);
        before += b / seeds as f64;
        after += a / seeds as f64;
    }
    assert!(
        in_band(before, 9.0, seeds as f64),
        "NEES at the last fix {before}"
    );
    assert!(
        in_band(after, 3.0, seeds as f64),
        "NEES after the outage {after}"
    );
}

/// On a circle the turning makes every accelerometer bias observable: after four minutes
/// each estimate is within three of its sigmas of the drawn bias and its sigma is below
/// a third of the prior.
#[test]
fn biases_are_estimated_on_a_circle() {
    let (_, _, filter, bias) = run(7, 240, 0);
    let (_, accel) = filter.biases();
    let p = filter.covariance();
    let prior = config().imu.accel_bias;
    for k in 0..3 {
        let sigma = p[(9 + k, 9 + k)].sqrt();
        assert!(
            (accel[k] - bias.accel_mps2[k]).abs() < 3.0 * sigma,
            "axis {k}: {} vs {}",
            accel[k],
            bias.accel_mps2[k]
        );
        assert!(sigma < prior / 3.0, "axis {k}: sigma {sigma}");
    }
}

#[test]
fn bad_settings_and_fixes_are_refused() {
    let traj = Circle::new(&site(), 200.0, 10.0);
    let mut cfg = config();
    cfg.initial_position_m = 0.0;
    let err = LooselyCoupled::new(true_state(&traj, 0.0), cfg).unwrap_err();
    assert!(err.to_string().contains("initial_position_m"), "{err}");
    let mut cfg = config();
    cfg.imu.gyro_bias_tau_s = Some(-1.0);
    let err = LooselyCoupled::new(true_state(&traj, 0.0), cfg).unwrap_err();
    assert!(err.to_string().contains("gyro_bias_tau_s"), "{err}");
    let mut filter = LooselyCoupled::new(true_state(&traj, 0.0), config()).unwrap();
    let mut rng = ChaCha20Rng::seed_from_u64(1);
    let mut f = fix(&traj, 0.0, (0.5, 0.05), &mut rng);
    f.r_ecef_m.x = f64::NAN;
    assert!(matches!(
        filter.update(&f),
        Err(IntegrationError::BadFix { .. })
    ));
    let far = fix(&traj, 5.0, (0.5, 0.05), &mut rng);
    assert!(matches!(
        filter.update(&far),
        Err(IntegrationError::FixOutOfStep { .. })
    ));
    let state = *filter.state();
    let mut f = fix(&traj, 0.0, (0.5, 0.05), &mut rng);
    f.r_cov_m2[(0, 0)] = -1.0;
    assert!(filter.update(&f).is_err());
    assert_eq!(*filter.state(), state, "nothing changed");
}
