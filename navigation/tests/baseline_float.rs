//! The double-difference baseline model (thesis 2.3, 2.4) on observations built from a
//! known plane-wave geometry: exact recovery without noise, and the predicted covariances
//! (eqs. 2.4-63, 2.4-65) against Monte Carlo scatter with the noise of eqs. 2.4-9/2.4-10.

mod baseline_support;

use baseline_support::{clocks, noise_model, observe, scene, solve, true_integers};
use nalgebra::{DMatrix, DVector};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use skyforge_gnss::observation::ObsRecord;
use skyforge_gnss::signal::Signal;
use skyforge_navigation::baseline::{BaselineError, DdLayout, FloatBaselines};

#[test]
fn noise_free_geometry_is_recovered_exactly_with_clocks_cancelled() {
    let mut rng = ChaCha8Rng::seed_from_u64(1);
    let scene = scene(&mut rng, 8, 7);
    let sat_clocks = clocks(&mut rng, scene.views.len());
    let obs: Vec<_> = (0..3)
        .map(|a| observe(&scene, a, (1e4 * (a as f64 + 1.0), &sat_clocks), None))
        .collect();
    let float = solve(&scene, &obs, &noise_model());
    // Two systems, one reference each: 15 satellites give 13 double differences.
    assert_eq!(float.model.ambiguity_count(), 13);
    let truth = true_integers(&scene, &float);
    for (est, t) in float.ambiguity_vector().iter().zip(&truth) {
        assert!((est - *t as f64).abs() < 1e-5, "{est} vs {t}");
    }
    let fixed = float.fix(&truth).unwrap();
    for k in 0..2 {
        assert!((float.baselines.column(k) - scene.baselines[k]).norm() < 1e-6);
        // Phases of ~1e8 cycles carry ~1e-8 cycles of rounding: micrometres.
        assert!((fixed.baselines.column(k) - scene.baselines[k]).norm() < 1e-6);
    }
}

/// Sample covariance of rows of `samples` (each a vec of length d).
fn sample_covariance(samples: &[DVector<f64>]) -> DMatrix<f64> {
    let n = samples.len() as f64;
    let mean = samples
        .iter()
        .fold(DVector::zeros(samples[0].len()), |a, s| a + s)
        / n;
    samples
        .iter()
        .fold(DMatrix::zeros(mean.len(), mean.len()), |a, s| {
            let d = s - &mean;
            a + &d * d.transpose()
        })
        / (n - 1.0)
}

/// Per-component standard deviations and the inter-baseline correlation of x agree with
/// the predicted covariance. With N independent epochs the relative standard error of a
/// sample standard deviation is 1/sqrt(2N) (2.2 % at N = 1000); 10 % is over 4 of them.
/// A correlation's standard error is (1 - r^2)/sqrt(N) (0.024 at r = 0.5): 0.1 is 4.
fn assert_matches(samples: &[DVector<f64>], predicted: &DMatrix<f64>, what: &str) {
    let cov = sample_covariance(samples);
    for i in 0..predicted.nrows() {
        let ratio = (cov[(i, i)] / predicted[(i, i)]).sqrt();
        assert!(
            (ratio - 1.0).abs() < 0.10,
            "{what} component {i}: std ratio {ratio}"
        );
    }
    let corr = |c: &DMatrix<f64>| c[(0, 3)] / (c[(0, 0)] * c[(3, 3)]).sqrt();
    let (sample, model) = (corr(&cov), corr(predicted));
    assert!(
        (sample - model).abs() < 0.1,
        "{what}: correlation {sample} vs {model}"
    );
}

#[test]
fn float_and_fixed_covariances_match_monte_carlo() {
    let mut rng = ChaCha8Rng::seed_from_u64(2);
    let scene = scene(&mut rng, 9, 0);
    let noise = noise_model();
    let sat_clocks = clocks(&mut rng, scene.views.len());
    let mut float_samples = Vec::new();
    let mut fixed_samples = Vec::new();
    let mut predicted = None;
    for _ in 0..1000 {
        let obs: Vec<_> = (0..3)
            .map(|a| observe(&scene, a, (0.0, &sat_clocks), Some((&noise, &mut rng))))
            .collect();
        let float = solve(&scene, &obs, &noise);
        let fixed = float.fix(&true_integers(&scene, &float)).unwrap();
        let err = |b: &nalgebra::Matrix3xX<f64>| {
            DVector::from_iterator(
                6,
                (0..2).flat_map(|k| {
                    (b.column(k) - scene.baselines[k])
                        .iter()
                        .copied()
                        .collect::<Vec<_>>()
                }),
            )
        };
        float_samples.push(err(&float.baselines));
        fixed_samples.push(err(&fixed.baselines));
        predicted.get_or_insert((float.baseline_covariance(), fixed.covariance));
    }
    let (float_cov, fixed_cov) = predicted.unwrap();
    assert_matches(&float_samples, &float_cov, "float");
    assert_matches(&fixed_samples, &fixed_cov, "fixed");
    // Fixing turns decimetre code-driven baselines into millimetre ones.
    assert!(fixed_cov[(0, 0)] < 1e-2 * float_cov[(0, 0)]);
}

/// One noisy epoch of 8 GPS satellites seen by three antennas (seeded): the float solution
/// and the true integers.
fn noisy_gps_epoch(seed: u64) -> (FloatBaselines, Vec<i64>) {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let scene = scene(&mut rng, 8, 0);
    let noise = noise_model();
    let obs: Vec<_> = (0..3)
        .map(|a| observe(&scene, a, (0.0, &[0.0; 8]), Some((&noise, &mut rng))))
        .collect();
    let float = solve(&scene, &obs, &noise);
    let truth = true_integers(&scene, &float);
    (float, truth)
}

#[test]
fn partial_fix_lies_between_float_and_full_fix() {
    let (float, truth) = noisy_gps_epoch(3);
    let nm = truth.len();
    let full = float.fix(&truth).unwrap().covariance.trace();
    let rows = 5;
    let z_t = DMatrix::identity(nm, nm).rows(0, rows).into_owned();
    let partial = float
        .fix_combinations(&z_t, &truth[..rows])
        .unwrap()
        .covariance
        .trace();
    let none = float.baseline_covariance().trace();
    assert!(
        full < partial && partial < none,
        "{full} < {partial} < {none}"
    );
}

#[test]
fn too_few_antennas_or_satellites_are_errors() {
    let mut rng = ChaCha8Rng::seed_from_u64(4);
    let scene = scene(&mut rng, 3, 1);
    let obs: Vec<_> = (0..2)
        .map(|a| observe(&scene, a, (0.0, &[0.0; 4]), None))
        .collect();
    let refs: Vec<&[ObsRecord]> = obs.iter().map(Vec::as_slice).collect();
    let signals = [Signal::GpsL1Ca, Signal::BdsB1I];
    assert_eq!(
        DdLayout::select(&refs[..1], &scene.views, &signals),
        Err(BaselineError::TooFewAntennas(1))
    );
    // Three GPS satellites give two double differences; the lone BeiDou none.
    assert_eq!(
        DdLayout::select(&refs, &scene.views, &signals),
        Err(BaselineError::TooFewDoubleDifferences { found: 2 })
    );
}

#[test]
fn a_satellite_missing_phase_on_one_antenna_is_left_out() {
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    let scene = scene(&mut rng, 6, 0);
    let mut obs: Vec<_> = (0..3)
        .map(|a| observe(&scene, a, (0.0, &[0.0; 6]), None))
        .collect();
    obs[2][3].carrier_phase_cycles = None;
    let float = solve(&scene, &obs, &noise_model());
    assert_eq!(float.model.ambiguity_count(), 4);
    assert!(
        float
            .model
            .layout
            .ambiguity_ids()
            .all(|(_, s, r)| s != scene.views[3].sat && r != scene.views[3].sat)
    );
}

/// Conditioning on the true integers of all but one ambiguity leaves that one within a few
/// conditional sigmas of truth, with a chi-square-sized fit statistic; wrong integers
/// make the statistic explode.
#[test]
fn conditioning_on_held_integers_is_the_gaussian_conditional() {
    let (float, truth) = noisy_gps_epoch(6);
    let nm = truth.len();
    let held: Vec<(usize, i64)> = (1..nm).map(|i| (i, truth[i])).collect();
    let c = float.conditioned(&held).unwrap();
    assert_eq!(c.free, vec![0]);
    let sigma = c.covariance[(0, 0)].sqrt();
    assert!((c.ambiguities[0] - truth[0] as f64).abs() < 5.0 * sigma);
    // The conditional sigma is far below the unconditional one (the held phases fix
    // the baselines).
    assert!(sigma < 0.1 * float.ambiguity_covariance()[(0, 0)].sqrt());
    // Its fit statistic is that of a chi-square with nm - 1 degrees of freedom: below
    // the 1e-6 quantile bound of about nm - 1 + 10 sqrt(2 (nm - 1)).
    let dof = (nm - 1) as f64;
    assert!(
        c.held_statistic < dof + 10.0 * (2.0 * dof).sqrt(),
        "{}",
        c.held_statistic
    );
    // Wrong integers by one cycle on every held ambiguity: the statistic explodes.
    let wrong: Vec<(usize, i64)> = held.iter().map(|&(i, v)| (i, v + 1)).collect();
    assert!(float.conditioned(&wrong).unwrap().held_statistic > 100.0 * dof);
    // Nothing held: the float ambiguities themselves.
    let none = float.conditioned(&[]).unwrap();
    assert_eq!(none.ambiguities, float.ambiguity_vector());
}
