//! Noise-free solutions: a static receiver with a drifting clock, a moving one from a
//! wrong a-priori position, and the clock in the single differences but not the double.

use super::world::{World, quiet};
use crate::tdcp::{TdcpConfig, TdcpEpoch, solve_double, solve_single, time_differences};
use skyforge_orbits::Vec3;
use skyforge_orbits::constants::C_MPS;

const DRIFT: f64 = 1e-7;

/// The differences of the epochs tagged `t1`, `t2` of the antenna along `r(t)`,
/// anchored at the true `r(t1)` and linearised about `r2_hat`.
fn pair(w: &World, (t1, t2): (f64, f64), r: impl Fn(f64) -> Vec3, r2_hat: Vec3) -> TdcpEpoch {
    let prev = w.epoch(t1, r(t1), &mut quiet);
    let cur = w.epoch(t2, r(t2), &mut quiet);
    let config = TdcpConfig::default();
    time_differences(&prev, &cur, r(t1), r2_hat, &w.store, &w.origin, &config).unwrap()
}

/// Static receiver, clock offset drifting at 1e-7 s/s, 1 Hz: the single-difference
/// solution finds no motion and `c ddt = c x 1e-7 x 1 s = 29.98 m`, the double-difference
/// solution no motion, both to a millimetre.
#[test]
fn static_receiver_with_a_drifting_clock() {
    let w = World::new(DRIFT);
    let epoch = pair(&w, (100.0, 101.0), |_| w.site, w.site);
    assert!(epoch.sats.len() >= 6, "{} satellites", epoch.sats.len());
    let sd = solve_single(&epoch).unwrap();
    let expected_clock_m = C_MPS * DRIFT * 1.0;
    let clock_m = sd.clock_change_m.unwrap();
    println!(
        "SD: |dr| = {:.2e} m, c ddt = {clock_m:.6} m (expected {expected_clock_m:.6}), {} sats",
        sd.delta_r_m.norm(),
        epoch.sats.len()
    );
    assert!(sd.delta_r_m.norm() < 1e-3);
    assert!((clock_m - expected_clock_m).abs() < 1e-3);
    let dd = solve_double(&epoch.double_differences().unwrap()).unwrap();
    println!("DD: |dr| = {:.2e} m", dd.delta_r_m.norm());
    assert!(dd.delta_r_m.norm() < 1e-3);
    assert!(dd.clock_change_m.is_none());
    assert_eq!(dd.covariance.shape(), (3, 3));
    assert_eq!(sd.covariance.shape(), (4, 4));
}

/// A receiver moving at 20 m/s (north-east and climbing), 1 Hz, linearised about the
/// previous position (20 m wrong): both solutions land on the true position to a
/// millimetre after the Gauss-Newton iterations, and needed more than one.
#[test]
fn moving_receiver_from_the_previous_position() {
    let w = World::new(DRIFT);
    let v = w.ned(12.0, 15.0, -4.0).normalize() * 20.0;
    let r = |t: f64| w.site + v * (t - 100.0);
    let epoch = pair(&w, (100.0, 101.0), r, r(100.0));
    let sd = solve_single(&epoch).unwrap();
    let dd = solve_double(&epoch.double_differences().unwrap()).unwrap();
    for (name, s) in [("SD", &sd), ("DD", &dd)] {
        let error = (s.r2_m - r(101.0)).norm();
        println!(
            "{name}: displacement {:.6} m, error {error:.2e} m, {} iterations",
            s.displacement_m().norm(),
            s.iterations
        );
        assert!((s.displacement_m().norm() - 20.0).abs() < 1e-3);
        assert!(error < 1e-3);
        assert!(s.iterations >= 2);
    }
    assert!((sd.clock_change_m.unwrap() - C_MPS * DRIFT).abs() < 1e-3);
}

/// Paper 001 Fig. 2 without noise: a static receiver at 10 Hz whose clock drifts at
/// 1e-7 s/s. With the true positions, each single difference's prefit residual is the
/// clock's change, `c x 1e-7 x 0.1 s = 3.0 m`; each double difference is zero.
#[test]
fn single_differences_show_the_clock_double_differences_do_not() {
    let w = World::new(DRIFT);
    let (mut sd, mut dd) = (Vec::new(), Vec::new());
    for k in 0..50 {
        let t1 = 200.0 + 0.1 * f64::from(k);
        let epoch = pair(&w, (t1, t1 + 0.1), |_| w.site, w.site);
        sd.extend(epoch.sats.iter().map(|s| s.z_m));
        dd.extend(epoch.double_differences().unwrap().z_m.iter().copied());
    }
    let mean = |x: &[f64]| x.iter().sum::<f64>() / x.len() as f64;
    let expected_m = C_MPS * DRIFT * 0.1;
    let (sd_mean, dd_mean) = (mean(&sd), mean(&dd));
    let dd_max = dd.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    println!(
        "SD mean {sd_mean:.6} m (c drift dt = {expected_m:.6}), DD mean {dd_mean:.2e} m, \
         max |DD| {dd_max:.2e} m over {} DDs",
        dd.len()
    );
    assert!((sd_mean - expected_m).abs() < 1e-3);
    assert!(dd_mean.abs() < 1e-3 && dd_max < 1e-3);
}
