//! Thesis section 4.2.1: the iterative attitude of Ardalan, against data made with known
//! angles.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, StandardNormal};
use skyforge_orbits::{Mat3, Vec3};
use skyforge_receiver::attitude::least_squares::LsConfig;
use skyforge_receiver::attitude::{AttitudeError, wrap_diff};
use skyforge_receiver::geometry_offset::iterative::{self, AntennaLevers, LeverAttitude};

const DEG: f64 = std::f64::consts::PI / 180.0;

fn gauss(rng: &mut ChaCha8Rng) -> f64 {
    StandardNormal.sample(rng)
}

fn gauss3(rng: &mut ChaCha8Rng, sigma: f64) -> Vec3 {
    sigma * Vec3::new(gauss(rng), gauss(rng), gauss(rng))
}

// ---------------------------------------------------------------- 4.2.1 iterative

/// Frame rotations about x, y, z (the thesis' `R_x`, `R_y`, `R_z`), written here
/// independently of the library.
fn frame_rotation(axis: usize, a: f64) -> Mat3 {
    let (s, c) = a.sin_cos();
    let (i, j) = ((axis + 1) % 3, (axis + 2) % 3);
    let mut m = Mat3::identity();
    m[(i, i)] = c;
    m[(j, j)] = c;
    m[(i, j)] = s;
    m[(j, i)] = -s;
    m
}

#[test]
fn c_l_b_is_r_y_roll_r_x_pitch_r_z_yaw() {
    let att = LeverAttitude {
        yaw_rad: 2.3,
        pitch_rad: -0.7,
        roll_rad: 0.4,
    };
    let product = frame_rotation(1, att.roll_rad)
        * frame_rotation(0, att.pitch_rad)
        * frame_rotation(2, att.yaw_rad);
    assert!((att.c_l_b() - product).amax() < 1e-15);
    // The bow (y_b) in ENU at pitch 0, roll 0: yaw turns it from north towards west.
    let bow = LeverAttitude {
        yaw_rad: 0.5,
        ..Default::default()
    }
    .c_l_b()
    .transpose()
        * Vec3::y();
    assert!((bow - Vec3::new(-0.5f64.sin(), 0.5f64.cos(), 0.0)).amax() < 1e-15);
}

/// A vector of length `len` along `axis` turned off it by up to `max_rad` about each of
/// the two other axes.
fn misaligned(rng: &mut ChaCha8Rng, axis: usize, len: f64, max_rad: f64) -> Vec3 {
    let mut turn = |a| frame_rotation(a, rng.random_range(-max_rad..max_rad));
    let (a1, a2) = ((axis + 1) % 3, (axis + 2) % 3);
    let t = turn(a1) * turn(a2);
    t * (len * Vec3::ith(axis, 1.0))
}

/// Random misaligned antenna positions (antenna 1 off the centre of gravity, baseline 12
/// near the bow, 13 near starboard, each up to `max_rad` off per axis).
fn random_levers(rng: &mut ChaCha8Rng, max_rad: f64) -> [Vec3; 3] {
    let r1 = Vec3::new(
        rng.random_range(-2.0..2.0),
        rng.random_range(-5.0..5.0),
        rng.random_range(-0.5..1.5),
    );
    let (l12, l13) = (rng.random_range(0.8..3.0), rng.random_range(0.5..2.0));
    let r12 = misaligned(rng, 1, l12, max_rad);
    let r13 = misaligned(rng, 0, l13, max_rad);
    [r1, r1 + r12, r1 + r13]
}

/// The l-frame baselines of antennas at `r_b` for the attitude `att` (eq. 4.2-2).
fn enu_baselines(r_b: &[Vec3; 3], att: &LeverAttitude) -> (Vec3, Vec3) {
    let c_b_l = att.c_l_b().transpose();
    (c_b_l * (r_b[1] - r_b[0]), c_b_l * (r_b[2] - r_b[0]))
}

fn random_attitude(rng: &mut ChaCha8Rng, max_tilt_rad: f64) -> LeverAttitude {
    LeverAttitude {
        yaw_rad: rng.random_range(-180.0 * DEG..180.0 * DEG),
        pitch_rad: rng.random_range(-max_tilt_rad..max_tilt_rad),
        roll_rad: rng.random_range(-max_tilt_rad..max_tilt_rad),
    }
}

fn lever_error(est: &LeverAttitude, truth: &LeverAttitude) -> Vec3 {
    Vec3::new(
        wrap_diff(est.yaw_rad, truth.yaw_rad),
        est.pitch_rad - truth.pitch_rad,
        est.roll_rad - truth.roll_rad,
    )
}

/// Enough passes for the slowest case of the validity range (about 100 at 60 deg tilt
/// and 10 deg misalignment).
const PASSES: LsConfig = LsConfig {
    tolerance_rad: 1e-12,
    max_iterations: 200,
};

/// Validity range: |pitch|, |roll| < 60 deg with both baselines turned up to 10 deg about
/// each of the other two body axes, or < 45 deg with 15 deg; any yaw. Exact baselines give
/// the angles to 1e-9 rad, where the textbook pitch of an aligned baseline is off by
/// degrees.
#[test]
fn recovers_random_attitudes_with_misaligned_levers() {
    let mut rng = ChaCha8Rng::seed_from_u64(421);
    for (tilt_deg, misalignment_deg) in [(60.0, 10.0), (45.0, 15.0)] {
        let (mut worst, mut naive_worst, mut most_passes) = (0.0f64, 0.0f64, 0);
        for _ in 0..2000 {
            let r_b = random_levers(&mut rng, misalignment_deg * DEG);
            let truth = random_attitude(&mut rng, tilt_deg * DEG);
            let (r12_l, r13_l) = enu_baselines(&r_b, &truth);
            let levers = AntennaLevers::new(r_b[0], r_b[1], r_b[2]).unwrap();
            let sol = iterative::solve(&levers, &r12_l, &r13_l, &PASSES).unwrap();
            worst = worst.max(lever_error(&sol.attitude, &truth).amax());
            most_passes = most_passes.max(sol.iterations);
            assert!(sol.misfit_m < 1e-9, "{}", sol.misfit_m);
            let naive_pitch = (r12_l.z / r12_l.norm()).asin();
            naive_worst = naive_worst.max((naive_pitch - truth.pitch_rad).abs());
        }
        assert!(worst < 1e-9, "largest angle error {worst:e} rad");
        assert!(naive_worst > 5.0 * DEG, "{naive_worst}");
        assert!(most_passes > 5, "the misalignment never needed iterating");
    }
}

/// Sample means and standard deviations of the yaw, pitch, roll errors over `n` draws of
/// `sigma_m` white noise on every baseline component.
fn noise_statistics(
    r_b: &[Vec3; 3],
    truth: &LeverAttitude,
    sigma_m: f64,
    n: usize,
) -> (Vec3, Vec3) {
    let mut rng = ChaCha8Rng::seed_from_u64(77);
    let levers = AntennaLevers::new(r_b[0], r_b[1], r_b[2]).unwrap();
    let (r12_l, r13_l) = enu_baselines(r_b, truth);
    let errors: Vec<Vec3> = (0..n)
        .map(|_| {
            let a = r12_l + gauss3(&mut rng, sigma_m);
            let b = r13_l + gauss3(&mut rng, sigma_m);
            let sol = iterative::solve(&levers, &a, &b, &PASSES).unwrap();
            lever_error(&sol.attitude, truth)
        })
        .collect();
    let mean = errors.iter().sum::<Vec3>() / n as f64;
    let var = errors
        .iter()
        .map(|e| (e - mean).component_mul(&(e - mean)))
        .sum::<Vec3>()
        / (n - 1) as f64;
    (mean, var.map(f64::sqrt))
}

/// Level, aligned antennas: to first order yaw and pitch err by `sigma / l_12`, roll by
/// `sigma / l_13` (the horizontal noise of baseline 12 turns it, the vertical ones tilt
/// the baselines).
#[test]
fn millimetre_noise_gives_sigma_over_baseline_length() {
    let (l12, l13, sigma) = (2.0, 1.0, 1e-3);
    let r_b = [
        Vec3::new(0.3, -1.0, 0.8),
        Vec3::new(0.3, -1.0 + l12, 0.8),
        Vec3::new(0.3 + l13, -1.0, 0.8),
    ];
    let n = 4000;
    let (mean, std) = noise_statistics(&r_b, &LeverAttitude::default(), sigma, n);
    let expected = Vec3::new(sigma / l12, sigma / l12, sigma / l13);
    for k in 0..3 {
        let ratio = std[k] / expected[k];
        assert!(
            (ratio - 1.0).abs() < 0.06,
            "axis {k}: std {} vs {}",
            std[k],
            expected[k]
        );
        assert!(
            mean[k].abs() < 4.0 * expected[k] / (n as f64).sqrt(),
            "axis {k} bias {}",
            mean[k]
        );
    }
}

/// Tilted, misaligned antennas: the error spread is the first-order propagation of the
/// noise through the estimator (central differences of `solve` in each of the six
/// baseline components).
#[test]
fn millimetre_noise_matches_its_linear_propagation_when_tilted() {
    let r_b = [
        Vec3::new(0.2, 0.5, 1.0),
        Vec3::new(0.35, 2.4, 1.12),
        Vec3::new(1.45, 0.62, 0.93),
    ];
    let truth = LeverAttitude {
        yaw_rad: -2.0,
        pitch_rad: 35.0 * DEG,
        roll_rad: -40.0 * DEG,
    };
    let sigma = 1e-3;
    let levers = AntennaLevers::new(r_b[0], r_b[1], r_b[2]).unwrap();
    let (r12_l, r13_l) = enu_baselines(&r_b, &truth);
    let mut variance = Vec3::zeros();
    let d = 1e-6;
    for k in 0..6 {
        let nudge = |s: f64| {
            let (mut a, mut b) = (r12_l, r13_l);
            if k < 3 {
                a[k] += s
            } else {
                b[k - 3] += s
            }
            iterative::solve(&levers, &a, &b, &PASSES).unwrap().attitude
        };
        let g = lever_error(&nudge(d), &nudge(-d)) / (2.0 * d);
        variance += sigma * sigma * g.component_mul(&g);
    }
    let (mean, std) = noise_statistics(&r_b, &truth, sigma, 3000);
    for k in 0..3 {
        let expected = variance[k].sqrt();
        assert!(
            (std[k] / expected - 1.0).abs() < 0.07,
            "axis {k}: {} vs {expected}",
            std[k]
        );
        assert!(
            mean[k].abs() < 4.0 * expected / 3000f64.sqrt(),
            "axis {k} bias {}",
            mean[k]
        );
    }
}

#[test]
fn bad_lever_input_is_an_error_not_a_panic() {
    let p = [
        Vec3::zeros(),
        Vec3::new(0.1, 2.0, 0.1),
        Vec3::new(1.0, 0.1, -0.1),
    ];
    // Coincident antennas, non-finite levers, antennas in the wrong places.
    assert!(matches!(
        AntennaLevers::new(p[0], p[0], p[2]),
        Err(AttitudeError::Geometry(_))
    ));
    assert!(matches!(
        AntennaLevers::new(p[0], Vec3::new(f64::NAN, 1.0, 0.0), p[2]),
        Err(AttitudeError::Geometry(_))
    ));
    assert!(matches!(
        AntennaLevers::new(p[0], -p[1], p[2]),
        Err(AttitudeError::Geometry(_))
    ));
    assert!(matches!(
        AntennaLevers::new(p[0], p[2], p[1]),
        Err(AttitudeError::Geometry(_))
    ));

    let levers = AntennaLevers::new(p[0], p[1], p[2]).unwrap();
    let truth = LeverAttitude {
        yaw_rad: 0.3,
        pitch_rad: 0.5,
        roll_rad: -0.6,
    };
    let (a, b) = enu_baselines(&p, &truth);
    let solve = |a: Vec3, b: Vec3, c: &LsConfig| iterative::solve(&levers, &a, &b, c);
    assert!(solve(a, b, &PASSES).is_ok());
    assert!(matches!(
        solve(Vec3::new(0.0, f64::INFINITY, 0.0), b, &PASSES),
        Err(AttitudeError::Measurement(_))
    ));
    // One pass is not enough for this tilt and misalignment.
    let one = LsConfig {
        max_iterations: 1,
        ..PASSES
    };
    assert!(matches!(
        solve(a, b, &one),
        Err(AttitudeError::NotConverged { .. })
    ));
    // Baselines that do not fit the levers: too steep for their length, swapped,
    // stretched, vertical.
    for (x, y) in [
        (a + Vec3::new(0.0, 0.0, 3.0), b),
        (b, a),
        (1.3 * a, b),
        (Vec3::new(0.0, 0.0, a.norm()), b),
    ] {
        let r = solve(x, y, &PASSES);
        assert!(
            matches!(
                r,
                Err(AttitudeError::Measurement(_) | AttitudeError::Singular(_))
            ),
            "{r:?}"
        );
    }
    assert!(matches!(
        solve(
            a,
            b,
            &LsConfig {
                tolerance_rad: 0.0,
                ..PASSES
            }
        ),
        Err(AttitudeError::Config(_))
    ));
}
