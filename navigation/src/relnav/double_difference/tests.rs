//! The filter on a synthetic geometry: two receivers 200 km apart on one LEO orbit
//! (integrated with the filter's own gravity field), eight satellites, perfect single
//! differences of range (code) and of range plus integer ambiguities (phase) on two
//! signals, no ionosphere, no clocks. After 600 s the filter must have the baseline to a
//! micrometre and the double-difference integers exactly, all 14 fixed; a wrong integer
//! forced into the hold must be released by the float twin's check and refixed, by each
//! of its two tests alone and by both. With the satellites' positions off by a metre
//! (broadcast orbits), the filter with orbit-error states keeps the right integers and a
//! baseline within its covariance; without them it does neither.

use super::config::{DoubleDifferenceConfig, HeldTest};
use super::dynamics::{gravity_field, propagate_pair};
use super::filter::{Anchor, DdEpoch, DdFilter, Key, Pairing, SatPair, SignalSd};
use super::fixing::{AmbiguityCount, check_held, resolve};
use nalgebra::{DMatrix, DVector};
use rand::{Rng, SeedableRng};
use skyforge_gnss::signal::Signal;
use skyforge_orbits::ephemeris::{SatId, System};
use skyforge_orbits::propagate::ForceModel;
use skyforge_orbits::{Mat3, Vec3};

const SIGNALS: [Signal; 2] = [Signal::GpsL1Ca, Signal::GpsL2];

/// The pair, its satellites (fixed in space at GPS radius, spread over its sky) and their
/// single-difference integers per signal.
struct Synthetic {
    forces: ForceModel,
    states: [(Vec3, Vec3); 2],
    sats: Vec<(SatId, Vec3, [i64; 2])>,
    /// Each satellite's orbit error, true minus the position the filter is given (m).
    orbit_errors: Vec<Vec3>,
}

impl Synthetic {
    fn new() -> Self {
        let start = hifitime::Epoch::from_gregorian_utc_at_midnight(2023, 3, 12);
        let forces = gravity_field(&Default::default(), start);
        let mu = forces.gm();
        let (r, inc) = (6.878e6_f64, 89f64.to_radians());
        let v = (mu / r).sqrt();
        let orbit = |u: f64| {
            let (s, c) = u.sin_cos();
            (
                Vec3::new(r * c, r * s * inc.cos(), r * s * inc.sin()),
                Vec3::new(-v * s, v * c * inc.cos(), v * c * inc.sin()),
            )
        };
        let states = [orbit(0.3), orbit(0.3 - 200e3 / r)];
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(7);
        let sats: Vec<_> = (0..8)
            .map(|k| {
                let az = f64::from(k) * 0.8;
                let tilt = 0.3 + 0.1 * f64::from(k % 3);
                let up = states[0].0.normalize();
                let east = Vec3::z().cross(&up).normalize();
                let north = up.cross(&east);
                let dir = (up * tilt.cos() + (east * az.cos() + north * az.sin()) * tilt.sin())
                    .normalize();
                let id = SatId {
                    system: System::Gps,
                    prn: k as u8 + 1,
                };
                let n = [
                    rng.random_range(-100_000..100_000),
                    rng.random_range(-100_000..100_000),
                ];
                (id, states[0].0 + dir * 2.0e7, n)
            })
            .collect();
        Self {
            forces,
            states,
            orbit_errors: vec![Vec3::zeros(); sats.len()],
            sats,
        }
    }

    /// The same with each satellite's orbit off by `sigma_m` per axis (normal, seeded).
    fn with_orbit_errors(sigma_m: f64) -> Self {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(11);
        let mut normal = || -> f64 { rng.sample(rand_distr::StandardNormal) };
        let mut pair = Self::new();
        for e in &mut pair.orbit_errors {
            *e = Vec3::new(normal(), normal(), normal()) * sigma_m;
        }
        pair
    }

    /// A loose dynamics model: the float epochs' error is forgotten within the run; the
    /// held integers checked by `held_test`.
    fn filter(&self, held_test: HeldTest) -> DdFilter {
        let config = DoubleDifferenceConfig {
            acceleration_sigma_mps2: 1e-4,
            held_test,
            ..Default::default()
        };
        DdFilter::new(config, self.forces.clone())
    }

    /// The epoch `step` seconds in (the pair moved on from the last call's), its anchor
    /// and the true baseline.
    fn epoch(&mut self, step: u32) -> (Anchor, (Vec3, Vec3), DdEpoch) {
        if step > 0 {
            self.states = propagate_pair(&self.forces, self.states, 1.0);
        }
        let [target, chaser] = self.states;
        let anchor = Anchor {
            t_s: f64::from(step),
            r_eci_m: target.0,
            v_eci_mps: target.1,
        };
        let sats = (self.sats.iter().zip(&self.orbit_errors))
            .map(|((sat, at, n), error)| {
                let truly = at + error;
                let sd = (truly - chaser.0).norm() - (truly - target.0).norm();
                SatPair {
                    sat: *sat,
                    at_target_m: *at,
                    at_chaser_m: *at,
                    clock_sd_m: 0.0,
                    elevation_rad: [1.0, 1.0],
                    signals: (SIGNALS.iter().zip(n))
                        .map(|(&signal, &n)| SignalSd {
                            signal,
                            code_m: sd,
                            phase_cycles: sd / signal.wavelength_m() + n as f64,
                            slip: false,
                        })
                        .collect(),
                }
            })
            .collect();
        let epoch = DdEpoch {
            r_target_ecef_m: target.0,
            c_eci_ecef: Mat3::identity(),
            v_chaser_ecef_mps: chaser.1,
            tag_difference_s: 0.0,
            sats,
        };
        (anchor, (chaser.0 - target.0, chaser.1 - target.1), epoch)
    }

    /// The largest error of `filter`'s double-difference ambiguities on `pairings`
    /// (cycles).
    fn integer_error(&self, filter: &DdFilter, pairings: &[Pairing]) -> f64 {
        let n = |sat: SatId, signal: Signal| {
            let i = filter.index(Key::Ambiguity(sat, signal)).unwrap();
            filter.x[i]
        };
        let truth_n = |sat: SatId, f: usize| self.sats.iter().find(|s| s.0 == sat).unwrap().2[f];
        (pairings.iter())
            .map(|p| {
                let f = SIGNALS.iter().position(|s| *s == p.signal).unwrap();
                let dd = n(p.sat, p.signal) - n(p.reference, p.signal);
                let want = (truth_n(p.sat, f) - truth_n(p.reference, f)) as f64;
                (dd - want).abs()
            })
            .fold(0.0, f64::max)
    }
}

/// Move `pairing`'s held double difference one cycle off (a wrong fix: the state moved,
/// its covariance still that of a held integer).
fn force_wrong_integer(filter: &mut DdFilter, pairing: &Pairing) {
    let i = (filter.index(Key::Ambiguity(pairing.sat, pairing.signal))).unwrap();
    filter.x[i] += 1.0;
}

#[test]
fn perfect_ranges_give_the_baseline_and_the_integers() {
    let mut pair = Synthetic::new();
    let mut filter = pair.filter(HeldTest::default());
    let mut twin: Option<DdFilter> = None;
    let (mut count, mut releases) = (AmbiguityCount::default(), 0);
    let mut truth = (Vec3::zeros(), Vec3::zeros());
    for step in 0..600 {
        let (anchor, true_baseline, epoch) = pair.epoch(step);
        truth = true_baseline;
        match twin.as_mut() {
            Some(twin) => {
                filter.predict(anchor);
                twin.predict(anchor);
            }
            None => {
                let off = Vec3::new(3.0, -2.0, 4.0);
                filter.start(anchor, (truth.0 + off, truth.1), (10.0, 1.0), 2.0);
                twin = Some(filter.clone());
            }
        }
        let pairings = filter.update(f64::from(step), &epoch);
        let twin = twin.as_mut().unwrap();
        twin.update(f64::from(step), &epoch);
        releases += usize::from(check_held(&mut filter, twin, &pairings));
        count = resolve(&mut filter, &pairings);
        if step == 599 {
            assert!(pair.integer_error(&filter, &pairings) < 1e-6);
        }
    }
    let (b, _) = filter.baseline();
    assert!((b - truth.0).norm() < 1e-6, "{} m", (b - truth.0).norm());
    assert_eq!((count.fixed, count.float), (14, 0));
    assert_eq!(releases, 0, "right integers released");
}

/// The epoch at which the check by `held_test` first releases the held integers when one
/// is forced one cycle off at `forced_at`; the integers right again at the end.
fn release_of_a_wrong_integer(held_test: HeldTest, forced_at: u32) -> Option<u32> {
    let mut pair = Synthetic::new();
    let mut filter = pair.filter(held_test);
    let mut twin: Option<DdFilter> = None;
    let mut released_at = None;
    for step in 0..600 {
        let (anchor, truth, epoch) = pair.epoch(step);
        match twin.as_mut() {
            Some(twin) => {
                filter.predict(anchor);
                twin.predict(anchor);
            }
            None => {
                filter.start(anchor, truth, (10.0, 1.0), 2.0);
                twin = Some(filter.clone());
            }
        }
        let pairings = filter.update(f64::from(step), &epoch);
        let twin = twin.as_mut().unwrap();
        twin.update(f64::from(step), &epoch);
        if step == forced_at {
            // Fixed by now; one integer then forced one cycle off.
            assert!(pair.integer_error(&filter, &pairings) < 1e-6);
            force_wrong_integer(&mut filter, &pairings[0]);
            assert!(pair.integer_error(&filter, &pairings) > 0.9);
        }
        if check_held(&mut filter, twin, &pairings) && released_at.is_none() {
            released_at = Some(step);
        }
        resolve(&mut filter, &pairings);
        if step == 599 {
            assert!(pair.integer_error(&filter, &pairings) < 1e-6);
        }
    }
    released_at
}

#[test]
fn a_wrong_held_integer_is_released_and_refixed() {
    let forced_at = 300;
    // At the check of the very epoch it was forced, by either test alone and by both: the
    // twin's float values are then precise to millicycles, so they resolve, with the
    // tests, to the true integers, and the held value is a cycle from them where the
    // covariance of the difference allows millicycles.
    for held_test in [
        HeldTest::TwinLambda,
        HeldTest::Consistency,
        HeldTest::TwinLambdaAndConsistency,
    ] {
        let released_at = release_of_a_wrong_integer(held_test, forced_at);
        assert_eq!(
            released_at,
            Some(forced_at),
            "{held_test:?}: {released_at:?}"
        );
    }
}

#[test]
fn the_held_tests_by_name_and_the_ranges_checked() {
    for (name, test) in [
        ("twin-lambda", HeldTest::TwinLambda),
        ("consistency", HeldTest::Consistency),
        (
            "twin-lambda+consistency",
            HeldTest::TwinLambdaAndConsistency,
        ),
    ] {
        let c: DoubleDifferenceConfig = toml::from_str(&format!("held_test = \"{name}\"")).unwrap();
        assert_eq!(c.held_test, test);
    }
    let c = DoubleDifferenceConfig {
        consistency_false_alarm: 0.0,
        ..Default::default()
    };
    let e = c.check().unwrap_err().to_string();
    assert!(
        e.contains("double_difference.consistency_false_alarm = 0"),
        "{e}"
    );
    // Orbit errors off unless set; a negative sigma refused.
    let c: DoubleDifferenceConfig = toml::from_str("orbit_error_sigma_m = 1.0").unwrap();
    assert_eq!(DoubleDifferenceConfig::default().orbit_error_sigma_m, 0.0);
    assert!(c.check().is_ok());
    let c = DoubleDifferenceConfig {
        orbit_error_sigma_m: -1.0,
        ..Default::default()
    };
    let e = c.check().unwrap_err().to_string();
    assert!(
        e.contains("double_difference.orbit_error_sigma_m = -1"),
        "{e}"
    );
}

/// Hold the true double-difference integers of `pairings` in `filter` (a right fix).
fn hold_true_integers(pair: &Synthetic, filter: &mut DdFilter, pairings: &[Pairing]) {
    let n = filter.x.len();
    let rows: Vec<(DVector<f64>, f64)> = (pairings.iter())
        .map(|p| {
            let f = SIGNALS.iter().position(|s| *s == p.signal).unwrap();
            let truth = |sat: SatId| pair.sats.iter().find(|s| s.0 == sat).unwrap().2[f];
            let mut d = DVector::zeros(n);
            d[filter.index(Key::Ambiguity(p.sat, p.signal)).unwrap()] = 1.0;
            d[filter.index(Key::Ambiguity(p.reference, p.signal)).unwrap()] = -1.0;
            (d, (truth(p.sat) - truth(p.reference)) as f64)
        })
        .collect();
    let d = DMatrix::from_fn(rows.len(), n, |i, j| rows[i].0[j]);
    let a = DVector::from_iterator(rows.len(), rows.iter().map(|r| r.1));
    let innovation = a - &d * &filter.x;
    filter.measure(
        &d,
        &innovation,
        &DMatrix::from_diagonal_element(rows.len(), rows.len(), 1e-12),
    );
}

/// A 600-s run of [`Synthetic`] through `filter` and its float twin, the true integers
/// held from the first epoch: how often the check released them, the largest integer
/// error at the end (cycles), the last epoch's count and the baseline's NEES
/// `e^T P^-1 e` at the end (3 degrees of freedom).
fn run_held(pair: &mut Synthetic, mut filter: DdFilter) -> (usize, f64, AmbiguityCount, f64) {
    let mut twin: Option<DdFilter> = None;
    let (mut releases, mut integer_error, mut count) = (0, 0.0, AmbiguityCount::default());
    let mut truth = Vec3::zeros();
    for step in 0..600 {
        let (anchor, true_baseline, epoch) = pair.epoch(step);
        truth = true_baseline.0;
        match twin.as_mut() {
            Some(twin) => {
                filter.predict(anchor);
                twin.predict(anchor);
            }
            None => {
                filter.start(anchor, true_baseline, (10.0, 1.0), 2.0);
                twin = Some(filter.clone());
            }
        }
        let pairings = filter.update(f64::from(step), &epoch);
        let twin = twin.as_mut().unwrap();
        twin.update(f64::from(step), &epoch);
        if step == 0 {
            hold_true_integers(pair, &mut filter, &pairings);
        }
        releases += usize::from(check_held(&mut filter, twin, &pairings));
        count = resolve(&mut filter, &pairings);
        integer_error = pair.integer_error(&filter, &pairings);
    }
    let e = filter.baseline().0 - truth;
    let p = filter.p.fixed_view::<3, 3>(0, 0).into_owned();
    let nees = e.dot(&(p.try_inverse().unwrap() * e));
    (releases, integer_error, count, nees)
}

#[test]
fn orbit_error_states_keep_right_integers_under_broadcast_orbits() {
    // Every satellite a metre off per axis: centimetres in the single differences across
    // 200 km, constant for the run while their direction turns with the geometry. The
    // right integers held from the start; the consistency test judges them.
    let sigma_m = 1.0;
    let filter = |orbit_error_sigma_m: f64| {
        let mut f = Synthetic::new().filter(HeldTest::Consistency);
        f.config.orbit_error_sigma_m = orbit_error_sigma_m;
        f
    };
    let without = run_held(&mut Synthetic::with_orbit_errors(sigma_m), filter(0.0));
    let with = run_held(&mut Synthetic::with_orbit_errors(sigma_m), filter(sigma_m));
    eprintln!("without the states: {without:?}\nwith them: {with:?}");
    let (releases, integer_error, count, nees) = with;
    assert_eq!(releases, 0, "right integers released");
    assert!(integer_error < 1e-6, "{integer_error} cycles");
    assert_eq!((count.fixed, count.float), (14, 0));
    // chi-square with 3 degrees of freedom: 16.3 at 0.999.
    assert!(nees < 16.3, "NEES {nees}");
    let (releases, ..) = without;
    assert!(releases > 0, "{without:?}");
}
