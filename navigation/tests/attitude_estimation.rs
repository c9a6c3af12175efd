//! The attitude module against independent oracles: finite differences, exact data,
//! Davenport's q-method, Monte Carlo, a direct per-baseline frame rotation, a simulated
//! attitude profile with known truth, and bad inputs.

use nalgebra::{DMatrix, DVector, Matrix3, Matrix4, SymmetricEigen, Vector3};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, StandardNormal};
use skyforge_navigation::attitude::EkfAttitude;
use skyforge_navigation::attitude::UkfAttitude;
use skyforge_navigation::attitude::build;
use skyforge_navigation::attitude::least_squares::{LsConfig, solve};
use skyforge_navigation::attitude::ned_baselines_from_ecef;
use skyforge_navigation::attitude::vec_r_jacobian;
use skyforge_navigation::attitude::{AttitudeConfig, AttitudeMethod};
use skyforge_navigation::attitude::{
    AttitudeError, AttitudeEstimate, BodyGeometry, NedBaselines, YawPitchRoll, angle_error,
    wrap_diff, wrap_pi,
};
use skyforge_navigation::attitude::{AttitudeFilter, FilterInit};
use skyforge_orbits::frames::c_ecef_ned;
use skyforge_orbits::frames::{Geodetic, geodetic_to_ecef};
use skyforge_orbits::{Mat3, Vec3};
use std::f64::consts::{PI, TAU};

const DEG: f64 = PI / 180.0;

fn rng(seed: u64) -> ChaCha8Rng {
    ChaCha8Rng::seed_from_u64(seed)
}

fn n01(r: &mut ChaCha8Rng) -> f64 {
    StandardNormal.sample(r)
}

fn gauss3(r: &mut ChaCha8Rng) -> Vec3 {
    Vec3::new(n01(r), n01(r), n01(r))
}

/// The least-squares attitude (default settings, no start value) from the reference-frame
/// baselines `b` with covariance `q`; both must be valid and the solution must succeed.
fn ls_attitude(g: &BodyGeometry, b: &[Vec3], q: DMatrix<f64>) -> AttitudeEstimate {
    solve(
        g,
        &NedBaselines::new(b, q).unwrap(),
        None,
        &LsConfig::default(),
    )
    .unwrap()
}

/// Yaw and roll anywhere, pitch within +/-80 deg (away from gimbal lock).
fn random_attitude(r: &mut ChaCha8Rng) -> YawPitchRoll {
    YawPitchRoll::new(
        r.random_range(-PI..PI),
        r.random_range(-80.0 * DEG..80.0 * DEG),
        r.random_range(-PI..PI),
    )
}

/// m baselines of 0.5-2 m in random directions (redrawn until not collinear).
fn random_geometry(r: &mut ChaCha8Rng, m: usize) -> BodyGeometry {
    loop {
        let b: Vec<Vec3> = (0..m)
            .map(|_| gauss3(r).normalize() * r.random_range(0.5..2.0))
            .collect();
        if let Ok(g) = BodyGeometry::new(&b) {
            return g;
        }
    }
}

/// A random symmetric positive definite n x n matrix with entries of size `scale`.
fn random_spd(r: &mut ChaCha8Rng, n: usize, scale: f64) -> DMatrix<f64> {
    let a = DMatrix::<f64>::from_fn(n, n, |_, _| n01(r));
    (&a * a.transpose() / n as f64 + DMatrix::identity(n, n) * 0.1) * scale
}

/// Test 1: Eq. 2.5-10 against central differences of `YawPitchRoll::c_body_ref` (eq. 2.5-6).
#[test]
fn jacobian_matches_finite_differences_at_random_angles() {
    let mut r = rng(1);
    let d = 1e-6;
    let mut worst: f64 = 0.0;
    for _ in 0..200 {
        let xi = random_attitude(&mut r);
        let j = vec_r_jacobian(&xi);
        let base = [xi.yaw_rad, xi.pitch_rad, xi.roll_rad];
        for k in 0..3 {
            let (mut plus, mut minus) = (base, base);
            plus[k] += d;
            minus[k] -= d;
            let cp = YawPitchRoll::new(plus[0], plus[1], plus[2]).c_body_ref();
            let cm = YawPitchRoll::new(minus[0], minus[1], minus[2]).c_body_ref();
            let fd = (cp - cm) / (2.0 * d);
            // nalgebra stores column-major: as_slice() is vec().
            for (row, v) in fd.as_slice().iter().enumerate() {
                worst = worst.max((v - j[(row, k)]).abs());
            }
        }
    }
    // Central-difference truncation ~ d^2 / 6 ~ 2e-13, rounding ~ 1e-16 / d ~ 1e-10.
    assert!(worst < 1e-8, "largest |J - FD| = {worst:e}");
}

/// Test 2: Exact baselines: the LS returns the true angles.
#[test]
fn noise_free_least_squares_recovers_random_attitudes() {
    let mut r = rng(2);
    let mut worst: f64 = 0.0;
    for trial in 0..300 {
        let m = 2 + trial % 3;
        let g = random_geometry(&mut r, m);
        let truth = random_attitude(&mut r);
        let b = g.in_reference(&truth);
        let q = random_spd(&mut r, 3 * m, 1e-6);
        let est = ls_attitude(&g, &b, q);
        worst = worst.max(angle_error(&est.angles, &truth).amax());
    }
    assert!(worst < 1e-9, "largest angle error {worst:e} rad");
}

/// Davenport's q-method (Shuster & Oh 1981 notation): the attitude matrix A (reference ->
/// body) maximising sum a_i b_i . A r_i is given by the eigenvector of the largest
/// eigenvalue of K = [[S - sigma I, z], [z^T, sigma]], B = sum a_i b_i r_i^T, S = B + B^T,
/// sigma = tr B, z = [B23 - B32, B31 - B13, B12 - B21]; q = [q_vec, q4] and
/// A = (q4^2 - |q_vec|^2) I + 2 q_vec q_vec^T - 2 q4 [q_vec x]. Returns A^T (body ->
/// reference, the thesis' R(xi)).
fn q_method(body: &[Vec3], reference: &[Vec3], weights: &[f64]) -> Mat3 {
    let mut b = Mat3::zeros();
    for ((bi, ri), a) in body.iter().zip(reference).zip(weights) {
        b += *a * bi * ri.transpose();
    }
    let s = b + b.transpose();
    let sigma = b.trace();
    let z = Vector3::new(
        b[(1, 2)] - b[(2, 1)],
        b[(2, 0)] - b[(0, 2)],
        b[(0, 1)] - b[(1, 0)],
    );
    let mut k = Matrix4::zeros();
    k.fixed_view_mut::<3, 3>(0, 0)
        .copy_from(&(s - Mat3::identity() * sigma));
    k.fixed_view_mut::<3, 1>(0, 3).copy_from(&z);
    k.fixed_view_mut::<1, 3>(3, 0).copy_from(&z.transpose());
    k[(3, 3)] = sigma;
    let eig = SymmetricEigen::new(k);
    let imax = eig.eigenvalues.imax();
    let q = eig.eigenvectors.column(imax);
    let qv = Vector3::new(q[0], q[1], q[2]);
    let q4 = q[3];
    let cross = Mat3::new(0.0, -qv.z, qv.y, qv.z, 0.0, -qv.x, -qv.y, qv.x, 0.0);
    let a =
        Mat3::identity() * (q4 * q4 - qv.dot(&qv)) + 2.0 * qv * qv.transpose() - 2.0 * q4 * cross;
    a.transpose()
}

/// Test 3: With Q_BB = s^2 I the LS minimises sum |v_i - R b_i|^2, Wahba's cost with equal
/// weights: its minimum is the q-method's rotation.
#[test]
fn isotropic_least_squares_equals_the_q_method() {
    let mut r = rng(3);
    // The oracle itself on exact data first.
    let g = random_geometry(&mut r, 3);
    let truth = random_attitude(&mut r);
    let v = g.in_reference(&truth);
    assert!((q_method(g.baselines(), &v, &[1.0; 3]) - truth.c_body_ref()).amax() < 1e-12);

    let mut worst_angle: f64 = 0.0;
    for trial in 0..200 {
        let m = 2 + trial % 3;
        let g = random_geometry(&mut r, m);
        let truth = random_attitude(&mut r);
        let sigma = 0.01; // 1 cm per component: a noisy problem
        let v: Vec<Vec3> = g
            .baselines()
            .iter()
            .map(|b| truth.c_body_ref() * b + gauss3(&mut r) * sigma)
            .collect();
        let q = DMatrix::identity(3 * m, 3 * m) * sigma * sigma;
        let est = ls_attitude(&g, &v, q);
        let c_q = q_method(g.baselines(), &v, &vec![1.0; m]);
        let oracle = YawPitchRoll::from_c_ref_body(&c_q.transpose());
        worst_angle = worst_angle.max(angle_error(&est.angles, &oracle).amax());
    }
    assert!(
        worst_angle < 1e-8,
        "largest LS - q-method angle {worst_angle:e} rad"
    );
}

/// The thesis set-up of T-1.2-2 / T-5.4-3: three antennas, two 1 m baselines from a
/// shared master (body X and body Y), antenna position errors (NED, m) with covariance
/// `sigma_ant` independent between antennas, so the baseline errors are correlated:
/// Q_BB = [[2 S, S], [S, 2 S]].
fn two_baseline_setup(sigma_ant: &Mat3) -> (BodyGeometry, DMatrix<f64>) {
    let g = BodyGeometry::new(&[Vec3::new(1.0, 0.0, 0.0), Vec3::new(0.0, 1.0, 0.0)]).unwrap();
    let mut q = DMatrix::zeros(6, 6);
    for i in 0..2 {
        for j in 0..2 {
            let f = if i == j { 2.0 } else { 1.0 };
            q.view_mut((3 * i, 3 * j), (3, 3))
                .copy_from(&(sigma_ant * f));
        }
    }
    (g, q)
}

/// Baselines of the three-antenna set-up with drawn antenna errors (`l_ant`: Cholesky
/// factor of the antenna covariance), drawn antenna by antenna (not from Q_BB).
fn draw_two_baselines(
    r: &mut ChaCha8Rng,
    g: &BodyGeometry,
    truth: &YawPitchRoll,
    l_ant: &Mat3,
) -> Vec<Vec3> {
    let e0 = l_ant * gauss3(r);
    g.baselines()
        .iter()
        .map(|b| truth.c_body_ref() * b + l_ant * gauss3(r) - e0)
        .collect()
}

/// An antenna error covariance (m^2) like the thesis's T-5.4-3 NED errors (baselines
/// about 0.8, 0.8, 1.7 mm per axis) times `scale`, with N-E and E-D correlation.
fn antenna_covariance(scale: f64) -> Mat3 {
    let s = Vector3::new(0.57e-3, 0.56e-3, 1.2e-3) * scale;
    let rho = Mat3::new(1.0, 0.3, 0.0, 0.3, 1.0, -0.4, 0.0, -0.4, 1.0);
    Mat3::from_diagonal(&s) * rho * Mat3::from_diagonal(&s)
}

/// Test 4: The LS covariance (eq. 2.5-13) against Monte Carlo. N = 4000 draws: the relative
/// standard error of a sample standard deviation is 1 / sqrt(2 (N - 1)) = 1.1 %, so a 5 %
/// bound is 4.5 of those; the standard error of a sample correlation is at most
/// 1 / sqrt(N) = 0.016, so 0.06 is about 4 of those; the linearisation error is of order
/// sigma / baseline (< 0.5 %). The post-fit chi-square has 3m - 3 = 3 degrees of freedom:
/// its sample mean has standard error sqrt(6 / N) = 0.039.
#[test]
fn monte_carlo_covariance_matches_eq_2_5_13() {
    let mut r = rng(4);
    // Phase noise a few mm: antenna errors 3x the T-5.4-3 ones (about 2-5 mm).
    let sigma_ant = antenna_covariance(3.0);
    let l_ant = sigma_ant.cholesky().unwrap().l();
    let (g, q) = two_baseline_setup(&sigma_ant);
    let truth = YawPitchRoll::new(30.0 * DEG, 10.0 * DEG, -5.0 * DEG);
    let n = 4000;
    let mut errors = Vec::with_capacity(n);
    let mut predicted = Matrix3::zeros();
    let mut chi2 = 0.0;
    for _ in 0..n {
        let b = draw_two_baselines(&mut r, &g, &truth, &l_ant);
        let est = ls_attitude(&g, &b, q.clone());
        errors.push(angle_error(&est.angles, &truth));
        predicted += est.covariance / n as f64;
        chi2 += est.chi_square / n as f64;
    }
    let mean: Vector3<f64> = errors.iter().sum::<Vector3<f64>>() / n as f64;
    let sample: Matrix3<f64> = errors
        .iter()
        .map(|e| (e - mean) * (e - mean).transpose())
        .sum::<Matrix3<f64>>()
        / (n - 1) as f64;
    for k in 0..3 {
        let (s, p) = (sample[(k, k)].sqrt(), predicted[(k, k)].sqrt());
        eprintln!(
            "axis {k}: MC std {:.5} deg, eq. 2.5-13 std {:.5} deg, ratio {:.4}, mean {:.2e} deg",
            s / DEG,
            p / DEG,
            s / p,
            mean[k] / DEG
        );
        assert!(
            (s / p - 1.0).abs() < 0.05,
            "axis {k}: MC std / predicted = {}",
            s / p
        );
        assert!(
            mean[k].abs() < 4.0 * p / (n as f64).sqrt(),
            "axis {k} bias {}",
            mean[k]
        );
        for l in 0..k {
            let rho_s = sample[(k, l)] / (sample[(k, k)] * sample[(l, l)]).sqrt();
            let rho_p = predicted[(k, l)] / (predicted[(k, k)] * predicted[(l, l)]).sqrt();
            eprintln!("corr {k}{l}: MC {rho_s:.4}, predicted {rho_p:.4}");
            assert!((rho_s - rho_p).abs() < 0.06);
        }
    }
    eprintln!("mean post-fit chi-square {chi2:.4} (3 dof)");
    assert!((chi2 - 3.0).abs() < 0.16);
}

/// Test 5: Eqs. 2.4-66, 2.4-67 against rotating each baseline and each covariance block, and
/// against geometry: a baseline straight up the ellipsoid normal is (0, 0, -1) in NED.
#[test]
fn frame_transform_matches_per_baseline_rotation() {
    let mut r = rng(5);
    for _ in 0..50 {
        let geo = Geodetic {
            lat_rad: r.random_range(-1.5..1.5),
            lon_rad: r.random_range(-PI..PI),
            h_m: r.random_range(-100.0..800e3),
        };
        let pos = geodetic_to_ecef(&geo);
        let f = c_ecef_ned(geo.lat_rad, geo.lon_rad);
        let m = 3;
        let b_ecef: Vec<Vec3> = (0..m).map(|_| gauss3(&mut r)).collect();
        let q_ecef = random_spd(&mut r, 3 * m, 1e-6);
        let ned = ned_baselines_from_ecef(&b_ecef, &q_ecef, &pos).unwrap();
        for (i, b) in b_ecef.iter().enumerate() {
            assert!((ned.baselines()[i] - f * b).amax() < 1e-9);
            for j in 0..m {
                let block: Mat3 = q_ecef.fixed_view::<3, 3>(3 * i, 3 * j).into_owned();
                let got: Mat3 = ned
                    .covariance()
                    .fixed_view::<3, 3>(3 * i, 3 * j)
                    .into_owned();
                assert!((got - f * block * f.transpose()).amax() < 1e-15);
            }
        }
        let up = geodetic_to_ecef(&Geodetic {
            h_m: geo.h_m + 1.0,
            ..geo
        }) - pos;
        let ned = ned_baselines_from_ecef(&[up], &(DMatrix::identity(3, 3) * 1e-6), &pos).unwrap();
        assert!((ned.baselines()[0] - Vec3::new(0.0, 0.0, -1.0)).amax() < 1e-8);
    }
}

/// The smooth profile of test 6: sinusoids of 10, 8 and 12 deg at 1/300 Hz about yaw
/// 178 deg (so yaw crosses +/-180 deg), pitch 3 deg, roll -2 deg. Returns the angles and
/// their rates (rad/s).
fn profile(t: f64) -> (YawPitchRoll, Vector3<f64>) {
    let w = TAU / 300.0;
    let amp = PROFILE_AMPLITUDE_DEG * DEG;
    let centre = Vector3::new(178.0, 3.0, -2.0) * DEG;
    let phase = Vector3::new(0.0, 1.0, 2.0);
    let a = Vector3::from_fn(|k, _| centre[k] + amp[k] * (w * t + phase[k]).sin());
    let rate = Vector3::from_fn(|k, _| amp[k] * w * (w * t + phase[k]).cos());
    (YawPitchRoll::new(wrap_pi(a[0]), a[1], a[2]), rate)
}

const PROFILE_AMPLITUDE_DEG: Vector3<f64> = Vector3::new(10.0, 8.0, 12.0);

/// Per-axis RMS of angle errors, rate errors, and the mean NEES (3 and 6 dof) and
/// innovation chi-square per degree of freedom of one filter over `runs` runs of `epochs`
/// 1 Hz epochs (the first `skip` left out), plus the single-epoch LS angle RMS on the same
/// measurements.
#[derive(Debug)]
struct FilterStats {
    ls_rms: Vector3<f64>,
    angle_rms: Vector3<f64>,
    rate_rms: Vector3<f64>,
    nees3: f64,
    nees6: f64,
    nis_per_dof: f64,
}

fn run_filter(
    config: &AttitudeConfig,
    seed: u64,
    runs: usize,
    epochs: usize,
    skip: usize,
    mut truth_of_run: impl FnMut(&mut ChaCha8Rng) -> Vec<(YawPitchRoll, Vector3<f64>)>,
) -> FilterStats {
    let sigma_ant = antenna_covariance(1.0);
    let l_ant = sigma_ant.cholesky().unwrap().l();
    let (g, q) = two_baseline_setup(&sigma_ant);
    let mut r = rng(seed);
    let (mut ls_sq, mut f_sq, mut rate_sq) = (Vector3::zeros(), Vector3::zeros(), Vector3::zeros());
    let (mut nees3, mut nees6, mut nis, mut count) = (0.0, 0.0, 0.0, 0usize);
    for _ in 0..runs {
        let truth_run = truth_of_run(&mut r);
        assert_eq!(truth_run.len(), epochs);
        let mut filter = build(config, g.clone()).unwrap();
        assert_eq!(filter.method(), config.method);
        for (k, (truth, rate)) in truth_run.iter().enumerate() {
            if k > 0 {
                filter.predict(1.0).unwrap();
            }
            let b = draw_two_baselines(&mut r, &g, truth, &l_ant);
            let meas = NedBaselines::new(&b, q.clone()).unwrap();
            let info = filter.update(&meas).unwrap();
            assert_eq!(info.initialised, k == 0);
            if k < skip {
                continue;
            }
            let ls = solve(&g, &meas, None, &LsConfig::default()).unwrap();
            let s = filter.state().unwrap();
            let e_ls = angle_error(&ls.angles, truth);
            let e_a = angle_error(&s.angles, truth);
            let e_r = s.rates_rad_s.unwrap() - rate;
            ls_sq += e_ls.component_mul(&e_ls);
            f_sq += e_a.component_mul(&e_a);
            rate_sq += e_r.component_mul(&e_r);
            let e6 = DVector::from_vec(vec![e_a[0], e_a[1], e_a[2], e_r[0], e_r[1], e_r[2]]);
            let p = &s.covariance;
            let p3 = p.view((0, 0), (3, 3)).into_owned();
            let e3 = DVector::from_column_slice(e_a.as_slice());
            nees3 += e3.dot(&p3.cholesky().unwrap().solve(&e3));
            nees6 += e6.dot(&p.clone().cholesky().unwrap().solve(&e6));
            nis += info.chi_square / info.dof as f64;
            count += 1;
        }
    }
    let c = count as f64;
    let stats = FilterStats {
        ls_rms: (ls_sq / c).map(f64::sqrt),
        angle_rms: (f_sq / c).map(f64::sqrt),
        rate_rms: (rate_sq / c).map(f64::sqrt),
        nees3: nees3 / c,
        nees6: nees6 / c,
        nis_per_dof: nis / c,
    };
    eprintln!(
        "{:?}: LS rms (deg) {:.4} {:.4} {:.4}; filter rms {:.4} {:.4} {:.4}; rate rms (deg/s) {:.5} {:.5} {:.5}; NEES3 {:.3} NEES6 {:.3} NIS/dof {:.3}",
        config.method,
        stats.ls_rms[0] / DEG,
        stats.ls_rms[1] / DEG,
        stats.ls_rms[2] / DEG,
        stats.angle_rms[0] / DEG,
        stats.angle_rms[1] / DEG,
        stats.angle_rms[2] / DEG,
        stats.rate_rms[0] / DEG,
        stats.rate_rms[1] / DEG,
        stats.rate_rms[2] / DEG,
        stats.nees3,
        stats.nees6,
        stats.nis_per_dof,
    );
    stats
}

/// The NEES bands for R = 20 runs: if the filter is consistent, the NEES averaged over
/// the runs at one epoch is chi2(3R) / R (angles) or chi2(6R) / R (with rates); their
/// 0.5 % and 99.5 % quantiles (Wilson-Hilferty) are [1.78, 4.60] and [4.19, 8.18].
/// Averaging further over (correlated) epochs only narrows the spread, so a consistent
/// filter's time-and-run average lies within these bands.
const RUNS: usize = 20;
const NEES3_BAND: (f64, f64) = (1.78, 4.60);
const NEES6_BAND: (f64, f64) = (4.19, 8.18);

/// Test 6a: Consistency where the filters' model is the truth: the attitude is drawn from the
/// process model itself (white angular acceleration with PSD S = 1e-9 rad^2/s^3 per
/// axis, eqs. 2.5-16 / 4.3-28..4.3-30, initial rates N(0, (2e-4 rad/s)^2) as the filters
/// assume), measured at 1 Hz with exactly the Q_BB the filters are given. 600 epochs,
/// the first 100 left out; yaw starts at 179 deg so runs cross +/-180 deg.
#[test]
fn kf_and_ukf_are_consistent_on_their_own_process_model() {
    let s_psd = 1e-9;
    let rate0 = 2e-4;
    let epochs = 600;
    for method in [AttitudeMethod::Kf, AttitudeMethod::Ukf] {
        let config = AttitudeConfig {
            method,
            rate_psd_rad2_s3: [s_psd; 3],
            initial_rate_sigma_rad_s: rate0,
            ..AttitudeConfig::default()
        };
        let q6 = skyforge_navigation::attitude::process_noise::<6>(1.0, &[s_psd; 3]);
        let l6 = q6.cholesky().unwrap().l();
        let phi = skyforge_navigation::attitude::transition::<6>(1.0);
        let stats = run_filter(&config, 61, RUNS, epochs, 100, |r| {
            let mut x = nalgebra::Vector6::new(
                179.0 * DEG,
                2.0 * DEG,
                -3.0 * DEG,
                rate0 * n01(r),
                rate0 * n01(r),
                rate0 * n01(r),
            );
            (0..epochs)
                .map(|k| {
                    if k > 0 {
                        let w = nalgebra::Vector6::from_fn(|_, _| n01(r));
                        x = phi * x + l6 * w;
                    }
                    (
                        YawPitchRoll::new(wrap_pi(x[0]), x[1], x[2]),
                        Vector3::new(x[3], x[4], x[5]),
                    )
                })
                .collect()
        });
        assert!(
            (NEES3_BAND.0..=NEES3_BAND.1).contains(&stats.nees3),
            "{method:?} NEES(3) {}",
            stats.nees3
        );
        assert!(
            (NEES6_BAND.0..=NEES6_BAND.1).contains(&stats.nees6),
            "{method:?} NEES(6) {}",
            stats.nees6
        );
        for k in 0..3 {
            assert!(stats.angle_rms[k] < stats.ls_rms[k], "{method:?} axis {k}");
        }
    }
}

/// Test 6b: The smooth profile (10, 8, 12 deg at 1/300 Hz, yaw across +/-180 deg), 1 Hz,
/// thesis T-5.4-3-sized baseline noise, 600 epochs x 20 runs, the first 100 epochs left
/// out, filters with the default S = 1e-8 rad^2/s^3 (the profile's largest angular
/// acceleration is 12 deg (2 pi / 300 s)^2 = 9e-5 rad/s^2).
///
/// * Filters help: their angle error RMS is below the single-epoch LS's on every axis.
/// * Rates: the RMS rate error is below a tenth of the rate amplitude on every axis.
/// * Not overconfident beyond the consistency band: the sinusoid is not the filters'
///   white-acceleration model, so their NEES need not be 3 (6); measured 3.9 (6.6), a
///   little above, since the profile's acceleration is larger than S = 1e-8 allows for.
///   Only the upper ends of the bands of 6a are required here.
#[test]
fn kf_and_ukf_track_a_smooth_profile() {
    let rate_amp = PROFILE_AMPLITUDE_DEG * DEG * TAU / 300.0;
    let epochs = 600;
    for method in [AttitudeMethod::Kf, AttitudeMethod::Ukf] {
        let config = AttitudeConfig {
            method,
            ..AttitudeConfig::default()
        };
        let stats = run_filter(&config, 62, RUNS, epochs, 100, |_| {
            (0..epochs).map(|k| profile(k as f64)).collect()
        });
        for k in 0..3 {
            assert!(
                stats.angle_rms[k] < stats.ls_rms[k],
                "{method:?} axis {k}: filter {} LS {}",
                stats.angle_rms[k],
                stats.ls_rms[k]
            );
            assert!(
                stats.rate_rms[k] < 0.1 * rate_amp[k],
                "{method:?} axis {k}: rate rms {} amplitude {}",
                stats.rate_rms[k],
                rate_amp[k]
            );
        }
        assert!(
            stats.nees3 < NEES3_BAND.1,
            "{method:?} NEES(3) {}",
            stats.nees3
        );
        assert!(
            stats.nees6 < NEES6_BAND.1,
            "{method:?} NEES(6) {}",
            stats.nees6
        );
    }
}

/// A filter given an initial state can use a single baseline: the roll about it is not
/// observed, so its variance only grows, and nothing is NaN.
#[test]
fn filters_accept_one_baseline_with_a_prior() {
    let g = BodyGeometry::new(&[Vec3::new(1.0, 0.0, 0.0)]).unwrap();
    let truth = YawPitchRoll::new(1.0, 0.2, 0.1);
    let init = FilterInit {
        angles: truth,
        rates_rad_s: Vector3::zeros(),
        covariance: nalgebra::Matrix6::identity() * 1e-4,
    };
    let config = AttitudeConfig::default();
    let meas = NedBaselines::new(
        &[truth.c_body_ref() * Vec3::x()],
        DMatrix::identity(3, 3) * 1e-6,
    )
    .unwrap();
    let mut filters: Vec<Box<dyn AttitudeFilter>> = vec![
        Box::new(EkfAttitude::new(&config, g.clone(), Some(init)).unwrap()),
        Box::new(UkfAttitude::new(&config, g.clone(), Some(init)).unwrap()),
    ];
    for f in &mut filters {
        for _ in 0..10 {
            f.predict(1.0).unwrap();
            f.update(&meas).unwrap();
        }
        let s = f.state().unwrap();
        assert!(s.covariance.iter().all(|v| v.is_finite()));
        assert!(s.covariance[(2, 2)] > s.covariance[(0, 0)] * 10.0);
        assert!(wrap_diff(s.angles.yaw_rad, truth.yaw_rad).abs() < 1e-3);
    }
    // Without a prior a single baseline cannot start a filter.
    let mut kf = build(
        &AttitudeConfig {
            method: AttitudeMethod::Kf,
            ..config
        },
        g,
    )
    .unwrap();
    assert_eq!(kf.update(&meas).unwrap_err(), AttitudeError::SingleBaseline);
}

/// Test 7: Bad inputs: clear errors, no panics.
#[test]
fn bad_inputs_are_errors() {
    let x = Vec3::new(1.0, 0.0, 0.0);
    let y = Vec3::new(0.0, 1.0, 0.0);
    // Geometry.
    assert!(matches!(
        BodyGeometry::new(&[]),
        Err(AttitudeError::Geometry(_))
    ));
    assert!(matches!(
        BodyGeometry::new(&[x, Vec3::new(f64::NAN, 0.0, 0.0)]),
        Err(AttitudeError::Geometry(_))
    ));
    assert!(matches!(
        BodyGeometry::new(&[x, Vec3::zeros()]),
        Err(AttitudeError::Geometry(_))
    ));
    let collinear = BodyGeometry::new(&[x, -2.0 * x, 0.5 * x]);
    assert!(matches!(collinear, Err(AttitudeError::Geometry(ref s)) if s.contains("collinear")));
    // Measurement.
    let i6 = DMatrix::<f64>::identity(6, 6) * 1e-6;
    assert!(matches!(
        NedBaselines::new(&[], DMatrix::zeros(0, 0)),
        Err(AttitudeError::Measurement(_))
    ));
    assert!(matches!(
        NedBaselines::new(&[x, Vec3::new(0.0, f64::INFINITY, 0.0)], i6.clone()),
        Err(AttitudeError::Measurement(_))
    ));
    assert!(matches!(
        NedBaselines::new(&[x, y], DMatrix::identity(3, 3)),
        Err(AttitudeError::Measurement(_))
    ));
    let mut nan_q = i6.clone();
    nan_q[(2, 2)] = f64::NAN;
    assert!(matches!(
        NedBaselines::new(&[x, y], nan_q),
        Err(AttitudeError::Measurement(_))
    ));
    let mut asym = i6.clone();
    asym[(0, 1)] = 1e-7;
    assert!(matches!(
        NedBaselines::new(&[x, y], asym),
        Err(AttitudeError::Covariance(_))
    ));
    let mut indefinite = i6.clone();
    indefinite[(4, 4)] = -1e-6;
    assert!(matches!(
        NedBaselines::new(&[x, y], indefinite),
        Err(AttitudeError::Covariance(_))
    ));
    let v = DVector::from_vec(vec![1.0, 2.0, 3.0, 4.0, 5.0, 6.0]);
    let singular = &v * v.transpose(); // rank 1, positive semi-definite
    assert!(matches!(
        NedBaselines::new(&[x, y], singular),
        Err(AttitudeError::Covariance(_))
    ));
    // Count mismatch, for the LS and every stage.
    let g2 = BodyGeometry::new(&[x, y]).unwrap();
    let three = NedBaselines::new(&[x, y, x + y], DMatrix::identity(9, 9) * 1e-6).unwrap();
    assert!(matches!(
        solve(&g2, &three, None, &LsConfig::default()),
        Err(AttitudeError::BaselineCount {
            geometry: 2,
            measured: 3
        })
    ));
    for method in [
        AttitudeMethod::LeastSquares,
        AttitudeMethod::Kf,
        AttitudeMethod::Ukf,
    ] {
        let mut f = build(
            &AttitudeConfig {
                method,
                ..AttitudeConfig::default()
            },
            g2.clone(),
        )
        .unwrap();
        assert!(f.state().is_none());
        assert!(matches!(
            f.update(&three),
            Err(AttitudeError::BaselineCount { .. })
        ));
        assert!(matches!(f.predict(-1.0), Err(AttitudeError::Filter(_))));
        assert!(matches!(f.predict(f64::NAN), Err(AttitudeError::Filter(_))));
    }
    // One baseline in the LS.
    let g1 = BodyGeometry::new(&[x]).unwrap();
    let one = NedBaselines::new(&[y], DMatrix::identity(3, 3) * 1e-6).unwrap();
    assert_eq!(
        solve(&g1, &one, None, &LsConfig::default()),
        Err(AttitudeError::SingleBaseline)
    );
    // Non-convergence is reported, not returned as an answer.
    let meas = NedBaselines::new(&[x, y], i6.clone()).unwrap();
    let far = YawPitchRoll::new(2.0, 0.5, 1.0);
    let one_iter = LsConfig {
        max_iterations: 1,
        ..LsConfig::default()
    };
    assert!(matches!(
        solve(&g2, &meas, Some(far), &one_iter),
        Err(AttitudeError::NotConverged { iterations: 1, .. })
    ));
    assert!(matches!(
        solve(
            &g2,
            &meas,
            Some(YawPitchRoll::new(f64::NAN, 0.0, 0.0)),
            &LsConfig::default()
        ),
        Err(AttitudeError::Measurement(_))
    ));
    // Configuration.
    let bad = AttitudeConfig {
        rate_psd_rad2_s3: [1e-8, -1.0, 1e-8],
        ..AttitudeConfig::default()
    };
    assert!(matches!(
        build(&bad, g2.clone()),
        Err(AttitudeError::Config(_))
    ));
    let bad = AttitudeConfig {
        least_squares: LsConfig {
            tolerance_rad: 0.0,
            ..LsConfig::default()
        },
        ..AttitudeConfig::default()
    };
    assert!(matches!(
        build(&bad, g2.clone()),
        Err(AttitudeError::Config(_))
    ));
    // A bad initial covariance.
    let init = FilterInit {
        angles: YawPitchRoll::default(),
        rates_rad_s: Vector3::zeros(),
        covariance: -nalgebra::Matrix6::identity(),
    };
    assert!(matches!(
        UkfAttitude::new(&AttitudeConfig::default(), g2, Some(init)),
        Err(AttitudeError::Covariance(_))
    ));
}

/// At gimbal lock (pitch +/-90 deg) yaw and roll are not separable in eq. 2.5-10's angles:
/// the LS either reports it (singular normal matrix, no convergence) or returns the same
/// rotation with finite numbers; never a panic or NaN.
#[test]
fn gimbal_lock_is_reported_or_solved_never_nan() {
    let g = BodyGeometry::new(&[Vec3::new(1.0, 0.0, 0.0), Vec3::new(0.0, 1.0, 0.0)]).unwrap();
    for pitch in [90.0 * DEG, -90.0 * DEG, 89.999_999 * DEG] {
        let truth = YawPitchRoll::new(0.4, pitch, 0.1);
        let b = g.in_reference(&truth);
        let meas = NedBaselines::new(&b, DMatrix::identity(6, 6) * 1e-6).unwrap();
        match solve(&g, &meas, None, &LsConfig::default()) {
            Ok(est) => {
                assert!(est.covariance.iter().all(|v| v.is_finite()));
                assert!((est.angles.c_body_ref() - truth.c_body_ref()).amax() < 1e-6);
            }
            Err(e) => assert!(
                matches!(
                    e,
                    AttitudeError::Singular(_) | AttitudeError::NotConverged { .. }
                ),
                "{e}"
            ),
        }
    }
}
