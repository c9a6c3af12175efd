use super::*;
use crate::geometry_offset::shape::{align, invariants, rotation, shape_nees};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal};

/// Thesis eq. 4.3-33: the nominal body baselines.
fn thesis_b0() -> [Vec3; 2] {
    [Vec3::new(0.99, -0.02, -0.03), Vec3::new(0.03, 1.02, 0.01)]
}

/// Thesis eq. 4.3-35: the true body baselines.
fn thesis_true() -> [Vec3; 2] {
    [Vec3::new(1.0, 0.0, 0.0), Vec3::new(0.0, 1.0, 0.0)]
}

/// A smooth attitude: a yaw turn at a constant rate plus a sinusoid on every axis.
#[derive(Debug, Clone, Copy)]
struct Profile {
    start_rad: [f64; 3],
    yaw_rate_rad_s: f64,
    amplitude_rad: [f64; 3],
    period_s: [f64; 3],
    phase_rad: [f64; 3],
}

impl Profile {
    /// The profile of most tests: a slow turn with sinusoids of 1-3 deg.
    fn slow() -> Self {
        Self {
            start_rad: [0.4, 0.0, 0.01],
            yaw_rate_rad_s: 1e-3,
            amplitude_rad: [0.05, 0.035, 0.017],
            period_s: [600.0, 600.0, 300.0],
            phase_rad: [0.0, std::f64::consts::FRAC_PI_2, 0.0],
        }
    }

    /// A random one: any heading, turns up to 0.1 deg/s, sinusoids up to 4 deg with
    /// periods of 200-1200 s.
    fn random(rng: &mut ChaCha8Rng) -> Self {
        use rand::Rng;
        let mut three = |lo: f64, hi: f64| [0; 3].map(|_| rng.random_range(lo..hi));
        let start = three(-0.05, 0.05);
        let amplitude = three(0.0, 0.07);
        let period = three(200.0, 1200.0);
        let phase = three(0.0, std::f64::consts::TAU);
        Self {
            start_rad: [rng.random_range(-3.1..3.1), start[1], start[2]],
            yaw_rate_rad_s: rng.random_range(-1.7e-3..1.7e-3),
            amplitude_rad: amplitude,
            period_s: period,
            phase_rad: phase,
        }
    }

    /// The attitude at `t` s.
    fn at(&self, t: f64) -> YawPitchRoll {
        let axis = |i: usize| {
            self.start_rad[i]
                + self.amplitude_rad[i]
                    * (std::f64::consts::TAU * t / self.period_s[i] + self.phase_rad[i]).sin()
        };
        YawPitchRoll::new(axis(0) + self.yaw_rate_rad_s * t, axis(1), axis(2))
    }
}

/// The slow profile at `t` s.
fn profile(t: f64) -> YawPitchRoll {
    Profile::slow().at(t)
}

/// Baselines of `body` turned by `profile(t)` with white noise `sigma_m` per component.
fn measure(t: f64, body: &[Vec3; 2], sigma_m: f64, rng: &mut ChaCha8Rng) -> NedBaselines {
    measure_on(&Profile::slow(), t, body, sigma_m, rng)
}

/// Baselines of `body` turned by `p` at `t` with white noise `sigma_m` per component.
fn measure_on(
    p: &Profile,
    t: f64,
    body: &[Vec3; 2],
    sigma_m: f64,
    rng: &mut ChaCha8Rng,
) -> NedBaselines {
    let r = p.at(t).c_body_ref();
    let n = Normal::new(0.0, sigma_m).unwrap();
    let b: Vec<Vec3> = body
        .iter()
        .map(|b| r * b + Vec3::from_fn(|_, _| n.sample(rng)))
        .collect();
    NedBaselines::new(&b, DMatrix::identity(6, 6) * sigma_m * sigma_m).unwrap()
}

/// The estimator over `epochs` 1 Hz epochs of `truth` on `p` with 1 mm noise.
fn run_on(p: &Profile, truth: &[Vec3; 2], epochs: usize, rng: &mut ChaCha8Rng) -> OffsetEstimator {
    let nominal = BodyGeometry::new(&thesis_b0()).unwrap();
    let mut f = OffsetEstimator::new(OffsetConfig::default(), nominal).unwrap();
    for k in 0..epochs {
        let t = k as f64;
        f.push(t, measure_on(p, t, truth, 1e-3, rng)).unwrap();
    }
    f
}

/// The same on the slow profile.
fn run(truth: &[Vec3; 2], epochs: usize, rng: &mut ChaCha8Rng) -> OffsetEstimator {
    run_on(&Profile::slow(), truth, epochs, rng)
}

fn estimated(s: &OffsetState) -> [Vec3; 2] {
    let b0 = thesis_b0();
    [b0[0] + s.offsets_m[0], b0[1] + s.offsets_m[1]]
}

#[test]
fn process_noise_is_the_integral_of_the_continuous_model() {
    // Q = int_0^T Phi(s) G Phi(s)^T ds, white noise on the rates and on the offset rate.
    let (t, s, b) = (0.8, [1e-3, 2e-3, 5e-4], 3e-4);
    let mut g = Covariance::zeros();
    for axis in 0..3 {
        g[(RATES + axis, RATES + axis)] = s[axis];
    }
    g[(OFFSET_RATE, OFFSET_RATE)] = b;
    let steps = 4000;
    let mut num = Covariance::zeros();
    for i in 0..steps {
        let tau = (i as f64 + 0.5) * t / steps as f64;
        let phi = transition(tau);
        num += phi * g * phi.transpose() * (t / steps as f64);
    }
    assert!((num - process_noise(t, &s, b)).amax() < 1e-9);
}

#[test]
fn one_step_moves_every_stacked_epoch_and_every_offset_on() {
    let mut x = State::zeros();
    x[RATES] = 0.1;
    x[RATES + 2] = -0.2;
    x[OFFSET_RATE] = 1e-3;
    let y = transition(2.0) * x;
    for slot in 0..WINDOW {
        assert_eq!(y[3 * slot], 0.2);
        assert_eq!(y[3 * slot + 1], 0.0);
        assert_eq!(y[3 * slot + 2], -0.4);
    }
    for k in 0..6 {
        assert_eq!(y[OFFSETS + k], 2e-3);
    }
}

#[test]
fn a_rotation_of_the_antennas_and_the_inverse_rotation_of_the_attitude_measure_alike() {
    // Why part of dB0 is unobservable (docs/geometry.md): turn the true geometry by Q in
    // the body frame and every attitude by Q^T, and h(X) (eq. 4.3-15) does not change.
    let b0 = thesis_b0();
    let truth = thesis_true();
    let q = rotation(&Vec3::new(0.2, -0.7, 0.4), 0.025);
    let mut x = State::zeros();
    let mut y = State::zeros();
    for slot in 0..WINDOW {
        let a = profile(slot as f64 * 17.0);
        let turned = YawPitchRoll::from_c_ref_body(&(a.c_body_ref() * q.transpose()).transpose());
        for (i, (u, v)) in [
            (a.yaw_rad, turned.yaw_rad),
            (a.pitch_rad, turned.pitch_rad),
            (a.roll_rad, turned.roll_rad),
        ]
        .into_iter()
        .enumerate()
        {
            x[3 * slot + i] = u;
            y[3 * slot + i] = v;
        }
    }
    for k in 0..2 {
        let (dx, dy) = (truth[k] - b0[k], q * truth[k] - b0[k]);
        for a in 0..3 {
            x[OFFSETS + 3 * k + a] = dx[a];
            y[OFFSETS + 3 * k + a] = dy[a];
        }
    }
    let (hx, hy) = (measurement(&x, &b0, false), measurement(&y, &b0, false));
    assert!((hx - hy).amax() < 1e-12);
    // ... while the offsets themselves differ by centimetres.
    assert!((x - y).rows(OFFSETS, 6).amax() > 0.01);
}

#[test]
fn recovers_the_shape_of_the_thesis_geometry() {
    let mut rng = ChaCha8Rng::seed_from_u64(43);
    let f = run(&thesis_true(), 3000, &mut rng);
    let s = f.state().unwrap();
    let est = estimated(&s);
    let e = invariants(&est) - invariants(&thesis_true());
    assert!(e.amax() < 2e-4, "lengths and dot product off by {e:?}");
    // Turned to the nominal orientation, estimate and truth agree component by component.
    let (a, b) = (
        align(&est, &thesis_b0()).unwrap(),
        align(&thesis_true(), &thesis_b0()).unwrap(),
    );
    for k in 0..2 {
        assert!((a.baselines[k] - b.baselines[k]).amax() < 5e-4);
    }
    let corrected = f.corrected_geometry().unwrap();
    assert!((corrected.baselines()[0] - est[0]).amax() < 1e-15);
}

#[test]
fn the_offsets_are_consistent_with_the_reported_covariance() {
    // Random offsets of a few centimetres (not the thesis's), random attitude profiles,
    // random seeds, the default settings (orientation held at the nominal one). The error of the three invariants
    // is chi-square with 3 degrees of freedom; so is that of the six offsets against the
    // truth turned to the nominal orientation (the other three directions are held).
    let draws = 20;
    let normal = Normal::new(0.0, 0.03).unwrap();
    let (mut shape, mut offsets) = (Vec::new(), Vec::new());
    for seed in 0..draws {
        let mut rng = ChaCha8Rng::seed_from_u64(100 + seed);
        let b0 = thesis_b0();
        let truth = [0, 1].map(|k| b0[k] + Vec3::from_fn(|_, _| normal.sample(&mut rng)));
        let profile = Profile::random(&mut rng);
        let s = run_on(&profile, &truth, 2000, &mut rng).state().unwrap();
        let est = estimated(&s);
        let p = s.offsets_covariance_m2;
        shape.push(shape_nees(&est, &p, &truth).unwrap());
        let aligned = align(&truth, &b0).unwrap().baselines;
        let e = nalgebra::Vector6::from_iterator(
            (0..6).map(|i| est[i / 3][i % 3] - aligned[i / 3][i % 3]),
        );
        offsets.push(e.dot(&p.cholesky().unwrap().solve(&e)));
    }
    // The mean of 20 chi-square(3) draws: 3 with a standard deviation of sqrt(6 / 20) =
    // 0.55; accept [1.5, 4.7] (about three sigmas; the filter is only first-order right).
    for (what, nees) in [("shape", shape), ("offsets", offsets)] {
        let mean = nees.iter().sum::<f64>() / draws as f64;
        println!("mean NEES of the {what} over {draws} draws: {mean:.2}");
        assert!((1.5..4.7).contains(&mean), "mean NEES {mean}: {nees:?}");
    }
}

#[test]
fn the_thesis_weighting_counts_each_epoch_four_times() {
    let config = |w| OffsetConfig {
        window_weighting: w,
        ..OffsetConfig::default()
    };
    let sigma = |w| {
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        let nominal = BodyGeometry::new(&thesis_b0()).unwrap();
        let mut f = OffsetEstimator::new(config(w), nominal).unwrap();
        for k in 0..1500 {
            f.push(k as f64, measure(k as f64, &thesis_true(), 1e-3, &mut rng))
                .unwrap();
        }
        f.state().unwrap().offsets_covariance_m2[(0, 0)].sqrt()
    };
    let ratio = sigma(WindowWeighting::Once) / sigma(WindowWeighting::Thesis);
    // The length of baseline 1 is set by the measurements alone: sigma ratio sqrt(4).
    assert!((1.7..2.3).contains(&ratio), "{ratio}");
}

#[test]
fn epochs_off_the_grid_and_wrong_geometries_are_errors() {
    let nominal = BodyGeometry::new(&thesis_b0()).unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(1);
    let mut f = OffsetEstimator::new(OffsetConfig::default(), nominal).unwrap();
    assert_eq!(
        f.push(0.0, measure(0.0, &thesis_true(), 1e-3, &mut rng))
            .unwrap(),
        Step::Filling
    );
    assert!(
        f.push(1.5, measure(1.5, &thesis_true(), 1e-3, &mut rng))
            .is_err()
    );
    assert!(
        f.push(0.0, measure(0.0, &thesis_true(), 1e-3, &mut rng))
            .is_err()
    );
    // A gap of whole periods refills the window: three more epochs, then the start.
    for t in [5.0, 6.0, 7.0] {
        assert_eq!(
            f.push(t, measure(t, &thesis_true(), 1e-3, &mut rng))
                .unwrap(),
            Step::Filling
        );
    }
    assert_eq!(
        f.push(8.0, measure(8.0, &thesis_true(), 1e-3, &mut rng))
            .unwrap(),
        Step::Started
    );
    assert!(matches!(
        f.push(9.0, measure(9.0, &thesis_true(), 1e-3, &mut rng))
            .unwrap(),
        Step::Updated { dof: 27, .. }
    ));
    let three = BodyGeometry::new(&[Vec3::x(), Vec3::y(), Vec3::z()]).unwrap();
    assert!(OffsetEstimator::new(OffsetConfig::default(), three).is_err());
    let bad = OffsetConfig {
        period_s: 0.0,
        ..OffsetConfig::default()
    };
    assert!(bad.check().is_err());
}

#[test]
fn config_from_toml_as_docs_geometry_md_writes_it() {
    let doc: OffsetConfig = toml::from_str(
        "rate_psd_rad2_s3 = [1e-9, 1e-9, 1e-9]\noffset_rate_psd_m2_s3 = 1e-15\nperiod_s = 1.0\nkappa = 0.5\ninitial_offset_sigma_m = 0.05\ninitial_rate_sigma_rad_s = 0.01\ninitial_offset_rate_sigma_m_s = 1e-6\nwindow_weighting = \"once\"\norientation = \"nominal\"\n",
    )
    .unwrap();
    assert_eq!(doc, OffsetConfig::default());
    let thesis: OffsetConfig =
        toml::from_str("window_weighting = \"thesis\"\norientation = \"free\"\n").unwrap();
    assert_eq!(thesis.window_weighting, WindowWeighting::Thesis);
    assert_eq!(thesis.orientation, Orientation::Free);
    assert!(toml::from_str::<OffsetConfig>("orientation = \"body\"").is_err());
    assert!(toml::from_str::<OffsetConfig>("kapa = 0.5").is_err());
}
