//! Consistency under white phase noise: the displacement's NEES and the a-posteriori
//! chi-square of both solutions over independent pairs, against 99 % bands computed
//! here; single and double differences give the same position and chi-square.

use super::world::World;
use crate::pvt::chi2_survival;
use crate::tdcp::{Displacement, TdcpConfig, solve_double, solve_single, time_differences};
use rand::SeedableRng;
use rand_distr::{Distribution, Normal};
use skyforge_orbits::Vec3;

const PAIRS: usize = 300;
const SIGMA_M: f64 = 0.003;

/// The two-sided 99 % quantile of the standard normal: `z` with `P(|Z| > z) = 0.01`,
/// i.e. `P(chi2_1 > z^2) = 0.01`, by bisection (2.5758).
fn normal_99() -> f64 {
    let (mut lo, mut hi) = (0.0, 10.0);
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if chi2_survival(1, mid * mid) > 0.01 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// `(r2 - truth)^T P^-1 (r2 - truth)` of the position at `t2`.
fn nees(d: &Displacement, truth: Vec3) -> f64 {
    let e = d.r2_m - truth;
    let p = d.position_covariance();
    e.dot(&(p.try_inverse().unwrap() * e))
}

/// Sums over the pairs: NEES of SD and DD, chi-square of SD and DD, their dof.
#[derive(Default)]
struct Sums {
    nees: [f64; 2],
    chi2: [f64; 2],
    dof: [usize; 2],
}

/// `PAIRS` independent pairs (each its own two epochs, 1 s apart, 20 s between pairs)
/// of a receiver moving at 10 m/s, noise `sigma(el)` on each phase, solved with
/// `config` from the previous true position.
fn run(config: &TdcpConfig, seed: u64, sigma: impl Fn(f64) -> f64) -> Sums {
    let w = World::new(2e-8);
    let v = w.ned(6.0, -8.0, 0.0);
    let r = |t: f64| w.site + v * t;
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    let unit = Normal::new(0.0, 1.0).unwrap();
    let mut noise = |el: f64| sigma(el) * unit.sample(&mut rng);
    let mut sums = Sums::default();
    for k in 0..PAIRS {
        let t1 = 20.0 * k as f64;
        let prev = w.epoch(t1, r(t1), &mut noise);
        let cur = w.epoch(t1 + 1.0, r(t1 + 1.0), &mut noise);
        let epoch =
            time_differences(&prev, &cur, r(t1), r(t1), &w.store, &w.origin, config).unwrap();
        let sd = solve_single(&epoch).unwrap();
        let dd = solve_double(&epoch.double_differences().unwrap()).unwrap();
        // The double differences are the single differences without the clock: same
        // position, same residual statistic.
        assert!((sd.r2_m - dd.r2_m).norm() < 1e-6, "pair {k}");
        assert!(
            (sd.chi2 - dd.chi2).abs() < 1e-6 * (1.0 + sd.chi2),
            "pair {k}"
        );
        assert_eq!(sd.dof, dd.dof);
        let truth = r(t1 + 1.0);
        for (i, d) in [sd, dd].iter().enumerate() {
            sums.nees[i] += nees(d, truth);
            sums.chi2[i] += d.chi2;
            sums.dof[i] += d.dof;
        }
    }
    sums
}

/// The bands: mean NEES in `3 +/- z sqrt(6 / N)` (mean of N chi-square(3)), total
/// chi-square in `dof +/- z sqrt(2 dof)`.
fn check(sums: &Sums, label: &str) {
    let z = normal_99();
    let n = PAIRS as f64;
    let half = z * (6.0 / n).sqrt();
    for (i, name) in ["SD", "DD"].iter().enumerate() {
        let mean_nees = sums.nees[i] / n;
        let dof = sums.dof[i] as f64;
        let chi2_half = z * (2.0 * dof).sqrt();
        println!(
            "{label} {name}: mean NEES {mean_nees:.3} in 3 +/- {half:.3}; \
             chi2 {:.1} for {dof} dof (+/- {chi2_half:.1}), per dof {:.3}",
            sums.chi2[i],
            sums.chi2[i] / dof
        );
        assert!((mean_nees - 3.0).abs() < half, "{label} {name} NEES");
        assert!(
            (sums.chi2[i] - dof).abs() < chi2_half,
            "{label} {name} chi2"
        );
    }
}

/// 3 mm white phase noise, plain weights.
#[test]
fn nees_and_chi_square_are_consistent() {
    let config = TdcpConfig {
        sigma_phase_m: SIGMA_M,
        ..TdcpConfig::default()
    };
    let sums = run(&config, 20_240_601, |_| SIGMA_M);
    check(&sums, "plain");
}

/// Noise `3 mm / sin(el)` and the elevation weighting that models it.
#[test]
fn nees_and_chi_square_are_consistent_with_elevation_weighting() {
    let config = TdcpConfig {
        sigma_phase_m: SIGMA_M,
        elevation_weighting: true,
        ..TdcpConfig::default()
    };
    let sums = run(&config, 77, |el| SIGMA_M / el.sin());
    check(&sums, "weighted");
}
