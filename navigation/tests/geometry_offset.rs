//! Thesis section 4.2: the iterative attitude of Ardalan (4.2.1) and the joint LS of the
//! attitude and the geometry deformation (4.2.2), against data made with known angles.

use nalgebra::{DMatrix, DVector};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, StandardNormal};
use skyforge_navigation::attitude::least_squares::{self, LsConfig};
use skyforge_navigation::attitude::{
    AttitudeError, BodyGeometry, NedBaselines, YawPitchRoll, angle_error, wrap_diff,
};
use skyforge_navigation::geometry_offset::iterative::{self, AntennaLevers, LeverAttitude};
use skyforge_navigation::geometry_offset::joint_ls::{self, DeformationModel};
use skyforge_orbits::{Mat3, Vec3};

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

// ---------------------------------------------------------------- 4.2.2 joint LS

/// Thesis fig. 4.2-3 in the body frame of eq. 4.3-3 (x nose, y right wing, z down), m:
/// baselines from the fin antenna 0 to the left wing tip, the nose, the right wing tip.
fn aircraft() -> BodyGeometry {
    BodyGeometry::new(&[
        Vec3::new(7.5, -10.0, 2.0),
        Vec3::new(16.0, 0.0, 2.5),
        Vec3::new(7.5, 10.0, 2.0),
    ])
    .unwrap()
}

/// Per-antenna white noise `sigma` (4 antennas, baselines from antenna 0):
/// `Q = sigma^2 (I_3 + 1 1^T) (x) I_3`.
fn antenna_covariance(sigma: f64) -> DMatrix<f64> {
    (DMatrix::identity(3, 3) + DMatrix::from_element(3, 3, 1.0)).kronecker(&DMatrix::identity(3, 3))
        * sigma
        * sigma
}

fn measure(
    truth_geometry: &BodyGeometry,
    xi: &YawPitchRoll,
    q: DMatrix<f64>,
    noise: &[Vec3],
) -> NedBaselines {
    let r = xi.c_body_ref();
    let b: Vec<Vec3> = truth_geometry
        .baselines()
        .iter()
        .zip(noise)
        .map(|(b, e)| r * b + e)
        .collect();
    NedBaselines::new(&b, q).unwrap()
}

fn random_ypr(rng: &mut ChaCha8Rng) -> YawPitchRoll {
    YawPitchRoll::new(
        rng.random_range(-3.1..3.1),
        rng.random_range(-1.2..1.2),
        rng.random_range(-3.1..3.1),
    )
}

#[test]
fn jacobian_matches_central_differences() {
    let g = aircraft();
    let model = DeformationModel::wing_and_lateral_flexure();
    let (xi, p) = (YawPitchRoll::new(0.7, -0.3, 2.2), [0.04, -0.02]);
    let f = |x: &[f64; 5]| {
        model
            .deformed(&g, &x[3..])
            .unwrap()
            .predict(&YawPitchRoll::new(x[0], x[1], x[2]))
    };
    let h = joint_ls::jacobian(&model.deformed(&g, &p).unwrap(), &model, &xi).unwrap();
    let x0 = [xi.yaw_rad, xi.pitch_rad, xi.roll_rad, p[0], p[1]];
    for k in 0..5 {
        let (mut plus, mut minus) = (x0, x0);
        plus[k] += 1e-6;
        minus[k] -= 1e-6;
        let fd = (f(&plus) - f(&minus)) / 2e-6;
        assert!((fd - h.column(k)).amax() < 1e-7, "column {k}");
    }
}

/// Exact baselines of a flexed aircraft: both thesis models give the angles and the
/// flexure exactly (the nominal-geometry LS is off by far more), from the Wahba start
/// and from the nominal LS attitude.
#[test]
fn recovers_angles_and_flexure_exactly() {
    let g = aircraft();
    let mut rng = ChaCha8Rng::seed_from_u64(4222);
    let cfg = LsConfig::default();
    for (model, p_true) in [
        (DeformationModel::wing_flexure(), vec![0.06]),
        (
            DeformationModel::wing_and_lateral_flexure(),
            vec![0.06, -0.035],
        ),
    ] {
        let flexed = model.deformed(&g, &p_true).unwrap();
        for draw in 0..50 {
            let xi = random_ypr(&mut rng);
            let meas = measure(&flexed, &xi, antenna_covariance(2e-3), &[Vec3::zeros(); 3]);
            let nominal_ls = least_squares::solve(&g, &meas, None, &cfg).unwrap();
            assert!(angle_error(&nominal_ls.angles, &xi).amax() > 1e-4);
            let start = (draw % 2 == 0).then_some(nominal_ls.angles);
            let est = joint_ls::solve(&g, &model, &meas, start, &cfg).unwrap();
            assert!(
                angle_error(&est.angles, &xi).amax() < 1e-9,
                "{est:?} vs {xi:?}"
            );
            let p_err = (&est.parameters - DVector::from_vec(p_true.clone())).amax();
            assert!(p_err < 1e-9, "{p_err}");
            assert!(est.chi_square < 1e-12);
            assert_eq!(est.covariance.shape(), (3 + p_true.len(), 3 + p_true.len()));
        }
    }
}

/// With correlated antenna noise, the normalised estimation error squared of
/// `[yaw, pitch, roll, fw, fl]` averages 5 and the chi-square 4 (= 9 - 5) over 400 draws
/// (standard errors of the means 0.16 and 0.14; tolerance 0.6).
#[test]
fn nees_and_chi_square_are_consistent() {
    let (g, model) = (aircraft(), DeformationModel::wing_and_lateral_flexure());
    let p_true = [0.03, 0.02];
    let flexed = model.deformed(&g, &p_true).unwrap();
    let sigma = 3e-3;
    let mut rng = ChaCha8Rng::seed_from_u64(9);
    let n = 400;
    let (mut nees, mut chi2) = (0.0, 0.0);
    for _ in 0..n {
        let xi = random_ypr(&mut rng);
        let antennas: Vec<Vec3> = (0..4).map(|_| gauss3(&mut rng, sigma)).collect();
        let noise: Vec<Vec3> = antennas[1..].iter().map(|a| a - antennas[0]).collect();
        let meas = measure(&flexed, &xi, antenna_covariance(sigma), &noise);
        let est = joint_ls::solve(&g, &model, &meas, None, &LsConfig::default()).unwrap();
        let a = angle_error(&est.angles, &xi);
        let e = DVector::from_vec(vec![
            a[0],
            a[1],
            a[2],
            est.parameters[0] - p_true[0],
            est.parameters[1] - p_true[1],
        ]);
        let w = est.covariance.clone().cholesky().unwrap();
        nees += e.dot(&w.solve(&e)) / n as f64;
        chi2 += est.chi_square / n as f64;
    }
    assert!((nees - 5.0).abs() < 0.6, "mean NEES {nees}");
    assert!((chi2 - 4.0).abs() < 0.6, "mean chi-square {chi2}");
}

/// A pattern that is an infinitesimal rotation of `B_0` (`w x b_k` on every baseline) is
/// absorbed by the attitude; so is a repeated pattern. The wing flexure on the same data
/// is fine.
#[test]
fn unobservable_patterns_are_refused() {
    let g = aircraft();
    let w = Vec3::new(0.2, -0.5, 0.8);
    let rotation: Vec<Vec3> = g.baselines().iter().map(|b| w.cross(b)).collect();
    let meas = measure(
        &g,
        &YawPitchRoll::new(0.3, 0.1, -0.2),
        antenna_covariance(2e-3),
        &[Vec3::zeros(); 3],
    );
    let cfg = LsConfig::default();
    let fw = DeformationModel::wing_flexure().patterns()[0].clone();
    for patterns in [
        vec![rotation.clone()],
        vec![fw.clone(), rotation],
        vec![fw.clone(), fw.clone()],
    ] {
        let model = DeformationModel::new(patterns).unwrap();
        let r = joint_ls::solve(&g, &model, &meas, None, &cfg);
        assert!(matches!(r, Err(AttitudeError::Singular(_))), "{r:?}");
    }
    let ok = joint_ls::solve(
        &g,
        &DeformationModel::new(vec![fw]).unwrap(),
        &meas,
        None,
        &cfg,
    )
    .unwrap();
    assert!(ok.parameters[0].abs() < 1e-9);
}

#[test]
fn bad_joint_input_is_an_error_not_a_panic() {
    let g = aircraft();
    let cfg = LsConfig::default();
    let meas = measure(
        &g,
        &YawPitchRoll::default(),
        antenna_covariance(2e-3),
        &[Vec3::zeros(); 3],
    );
    let geometry_err =
        |p: Vec<Vec<Vec3>>| matches!(DeformationModel::new(p), Err(AttitudeError::Geometry(_)));
    assert!(geometry_err(vec![]));
    assert!(geometry_err(vec![vec![Vec3::x(); 3], vec![Vec3::y(); 2]]));
    assert!(geometry_err(vec![vec![Vec3::new(f64::NAN, 0.0, 0.0); 3]]));
    assert!(geometry_err(vec![vec![Vec3::zeros(); 3]]));
    // Patterns of 2 columns for 3 baselines; 3 baselines measured for 2 in B_0.
    let two = DeformationModel::new(vec![vec![Vec3::z(); 2]]).unwrap();
    assert!(matches!(
        joint_ls::solve(&g, &two, &meas, None, &cfg),
        Err(AttitudeError::Geometry(_))
    ));
    let g2 = BodyGeometry::new(&g.baselines()[..2]).unwrap();
    assert!(matches!(
        joint_ls::solve(&g2, &two, &meas, None, &cfg),
        Err(AttitudeError::BaselineCount { .. })
    ));
    // Two baselines, four parameters: 7 unknowns from 6 observations.
    let meas2 = measure(
        &g2,
        &YawPitchRoll::default(),
        antenna_covariance(2e-3).view((0, 0), (6, 6)).into(),
        &[Vec3::zeros(); 2],
    );
    let four = DeformationModel::new(vec![
        vec![Vec3::x(), Vec3::y()],
        vec![Vec3::y(), Vec3::z()],
        vec![Vec3::z(), Vec3::x()],
        vec![Vec3::x(), Vec3::x()],
    ])
    .unwrap();
    assert!(matches!(
        joint_ls::solve(&g2, &four, &meas2, None, &cfg),
        Err(AttitudeError::Singular(_))
    ));
    let model = DeformationModel::wing_flexure();
    let nan_start = Some(YawPitchRoll::new(f64::NAN, 0.0, 0.0));
    assert!(matches!(
        joint_ls::solve(&g, &model, &meas, nan_start, &cfg),
        Err(AttitudeError::Measurement(_))
    ));
    let one = LsConfig {
        max_iterations: 1,
        ..cfg
    };
    let tilted = measure(
        &g,
        &YawPitchRoll::new(1.0, 0.2, 0.3),
        antenna_covariance(2e-3),
        &[Vec3::zeros(); 3],
    );
    assert!(matches!(
        joint_ls::solve(&g, &model, &tilted, Some(YawPitchRoll::default()), &one),
        Err(AttitudeError::NotConverged { .. })
    ));
    // A flexure so large the deformed wing baselines coincide with the nose's direction
    // is not a geometry.
    let collapse = DeformationModel::new(vec![vec![
        Vec3::new(8.5, 10.0, 0.5),
        Vec3::zeros(),
        Vec3::new(8.5, -10.0, 0.5),
    ]])
    .unwrap();
    assert!(matches!(
        collapse.deformed(&g, &[1.0]),
        Err(AttitudeError::Geometry(_))
    ));
}
