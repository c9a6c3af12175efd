//! RAIM of the single-point fix on real broadcast geometry (a static ground site, GPS
//! only): protection levels against a brute-force bias injection through the solver,
//! the distribution of the fault-free statistic, and the detection probability at the
//! detection noncentrality.

mod pvt_support;

use pvt_support::{World, world, world_of};

use rand::SeedableRng;
use rand_chacha::ChaCha20Rng;
use rand_distr::{Distribution, StandardNormal};
use skyforge_gnss::signal::Signal;
use skyforge_navigation::pvt::{Fix, IntegrityStatus, Measurement, PvtConfig, PvtError, solve};
use skyforge_navigation::pvt::{chi2_survival, detection_parameters};
use skyforge_orbits::Vec3;
use skyforge_orbits::constants::{C_MPS, OMEGA_E_GPS};
use skyforge_orbits::ephemeris::{SatId, System};
use skyforge_orbits::frames::{Geodetic, ecef_to_geodetic, geodetic_to_ecef};
use skyforge_orbits::frames::{az_el, c_ecef_ned};

fn site() -> Vec3 {
    geodetic_to_ecef(&Geodetic {
        lat_rad: 30f64.to_radians(),
        lon_rad: 114f64.to_radians(),
        h_m: 50.0,
    })
}

/// The fix of `meas` at `t` with `cfg`, no a-priori position.
fn fix_at(w: &World, t: f64, meas: &[Measurement], cfg: &PvtConfig) -> Result<Fix, PvtError> {
    solve(meas, t, &w.store, &w.origin, cfg, None)
}

/// No atmosphere in the measurements and none in the solver: the test is about the
/// statistics, not the media models.
fn config() -> PvtConfig {
    PvtConfig {
        troposphere: false,
        ..PvtConfig::default()
    }
}

/// Noise-free pseudoranges (m) and elevations (rad) of the GPS satellites above 12 deg for a
/// receiver at `r` with a perfect clock at `t_s`: light time in the rotating frame, the
/// satellite clock with its group delay.
fn pseudoranges(w: &World, t_s: f64, r: &Vec3) -> Vec<(SatId, f64, f64)> {
    pseudoranges_of(w, t_s, r, &[System::Gps])
}

/// The signal measured on a satellite of `system`: GPS L1 C/A, Galileo E1.
fn signal_of(system: System) -> Signal {
    match system {
        System::Galileo => Signal::GalE1,
        _ => Signal::GpsL1Ca,
    }
}

/// [`pseudoranges`] of the satellites of `systems`, each on [`signal_of`] its system.
fn pseudoranges_of(w: &World, t_s: f64, r: &Vec3, systems: &[System]) -> Vec<(SatId, f64, f64)> {
    let g = ecef_to_geodetic(r);
    let c = c_ecef_ned(g.lat_rad, g.lon_rad);
    w.store
        .satellites()
        .into_iter()
        .filter(|s| systems.contains(&s.system))
        .filter_map(|sat| {
            let eph = w.store.select(sat, t_s)?;
            let at = |tau: f64| {
                let (p, _) = eph.state_ecef(t_s - tau);
                let (s, co) = (OMEGA_E_GPS * tau).sin_cos();
                Vec3::new(co * p.x + s * p.y, -s * p.x + co * p.y, p.z)
            };
            let mut tau = 0.07;
            for _ in 0..10 {
                tau = (at(tau) - r).norm() / C_MPS;
            }
            let los = (at(tau) - r).normalize();
            let (_, el) = az_el(&(c * los));
            let delay_s = signal_of(sat.system).broadcast_group_delay_s(&eph.eph);
            let sat_clock_m = C_MPS * (eph.clock_offset_s(t_s - tau) - delay_s);
            (el > 12f64.to_radians()).then_some((sat, C_MPS * tau - sat_clock_m, el))
        })
        .collect()
}

/// The measurements with `bias` (m) added to satellite `biased` and `noise` (m) to all.
fn measurements(
    clean: &[(SatId, f64, f64)],
    biased: Option<(usize, f64)>,
    noise: &[f64],
) -> Vec<Measurement> {
    clean
        .iter()
        .enumerate()
        .map(|(i, &(sat, pr, _))| {
            let bias = biased.filter(|b| b.0 == i).map_or(0.0, |b| b.1);
            Measurement {
                sat,
                pseudorange_m: pr + bias + noise.get(i).copied().unwrap_or(0.0),
                doppler_hz: None,
                signal: signal_of(sat.system),
            }
        })
        .collect()
}

/// The sigma the solver assigns at elevation `el` (its default weighting).
fn sigma(cfg: &PvtConfig, el: f64) -> f64 {
    cfg.sigma_a_m.hypot(cfg.sigma_b_m / el.sin())
}

/// Horizontal and vertical error (m) of `fix` against `r`.
fn errors(fix: &Fix, r: &Vec3) -> (f64, f64) {
    let g = ecef_to_geodetic(r);
    let e = c_ecef_ned(g.lat_rad, g.lon_rad) * (fix.r_ecef_m - r);
    (e.x.hypot(e.y), e.z.abs())
}

#[test]
fn protection_levels_equal_the_error_of_a_bias_at_lambda_det_injected_through_the_solver() {
    // Oracle: for each satellite in turn, a bias whose statistic (the solver's own chi2 of
    // the biased noise-free fix, test off) equals lambda_det; the solver's position error
    // must be that satellite's slope times sqrt(lambda_det), and HPL the largest of them.
    let (w, r, t) = (world(false), site(), 5400.0);
    let cfg = config();
    let clean = pseudoranges(&w, t, &r);
    assert!(clean.len() >= 6, "{} satellites", clean.len());
    let fix = fix_at(&w, t, &measurements(&clean, None, &[]), &cfg).unwrap();
    let p = fix.protection.clone().unwrap();
    assert_eq!(p.status, IntegrityStatus::Available);
    assert!(!p.alarm && p.hpl_m > 0.0 && p.hpl_m < cfg.raim_hal_m);
    let (_, lambda) = detection_parameters(fix.dof, cfg.raim_pfa, cfg.raim_pmd).unwrap();
    assert_eq!(p.lambda_det, lambda);
    let off = PvtConfig {
        raim_pfa: 0.0,
        ..cfg.clone()
    };
    let (mut worst_h, mut worst_v) = (0.0f64, 0.0f64);
    for (i, slope) in p.slopes.iter().enumerate() {
        let solve_with =
            |b: f64| fix_at(&w, t, &measurements(&clean, Some((i, b)), &[]), &off).unwrap();
        let unit = solve_with(1.0);
        let b = (lambda / unit.chi2).sqrt();
        let biased = solve_with(b);
        assert!((biased.chi2 / lambda - 1.0).abs() < 1e-4, "{}", biased.chi2);
        let (h, v) = errors(&biased, &r);
        let want_h = slope.horizontal_m * lambda.sqrt();
        let want_v = slope.vertical_m * lambda.sqrt();
        assert!(
            (h - want_h).abs() < 1e-3 + 1e-4 * want_h,
            "sat {i}: {h} vs {want_h}"
        );
        assert!(
            (v - want_v).abs() < 1e-3 + 1e-4 * want_v,
            "sat {i}: {v} vs {want_v}"
        );
        worst_h = worst_h.max(h);
        worst_v = worst_v.max(v);
    }
    assert!((p.hpl_m - worst_h).abs() < 1e-3 + 1e-4 * worst_h);
    assert!((p.vpl_m - worst_v).abs() < 1e-3 + 1e-4 * worst_v);
}

#[test]
fn fault_free_statistic_follows_the_chi_square_distribution() {
    // Kolmogorov-Smirnov: the survival probability of each fix's statistic at its own
    // degrees of freedom is uniform on (0, 1) when the noise has the weights' sigmas.
    let (w, r) = (world(false), site());
    let off = PvtConfig {
        raim_pfa: 0.0,
        ..config()
    };
    let mut rng = ChaCha20Rng::seed_from_u64(15);
    let n = 1200;
    let mut u: Vec<f64> = (0..n)
        .map(|k| {
            let t = 60.0 + 61.0 * k as f64;
            let clean = pseudoranges(&w, t, &r);
            let noise: Vec<f64> = clean
                .iter()
                .map(|&(_, _, el)| {
                    sigma(&off, el)
                        * <StandardNormal as Distribution<f64>>::sample(&StandardNormal, &mut rng)
                })
                .collect();
            let fix = fix_at(&w, t, &measurements(&clean, None, &noise), &off).unwrap();
            chi2_survival(fix.dof, fix.chi2)
        })
        .collect();
    u.sort_by(f64::total_cmp);
    let d = u
        .iter()
        .enumerate()
        .map(|(i, &x)| {
            (x - i as f64 / n as f64)
                .abs()
                .max(((i + 1) as f64 / n as f64 - x).abs())
        })
        .fold(0.0, f64::max);
    // The 1 % critical value of the one-sample KS statistic, 1.628 / sqrt(n).
    assert!(d < 1.628 / (n as f64).sqrt(), "KS D = {d}");
    // And a tail quantile: the 5 % upper tail holds 5 % of the fixes within 3 sigma.
    let tail = u.iter().filter(|&&x| x < 0.05).count() as f64 / n as f64;
    let se = (0.05 * 0.95 / n as f64).sqrt();
    assert!((tail - 0.05).abs() < 3.0 * se, "tail {tail}");
}

#[test]
fn detection_probability_at_lambda_det_is_one_minus_pmd() {
    // The worst satellite biased so that its statistic has noncentrality lambda_det, noise
    // of the weights' sigmas on all: the test fires with probability 1 - P_md.
    let (w, r, t) = (world(false), site(), 5400.0);
    let clean = pseudoranges(&w, t, &r);
    let mut rng = ChaCha20Rng::seed_from_u64(515);
    for (pmd, draws) in [(0.1, 1500), (1e-3, 1500)] {
        let cfg = PvtConfig {
            raim_pmd: pmd,
            ..config()
        };
        let fix0 = fix_at(&w, t, &measurements(&clean, None, &[]), &cfg).unwrap();
        let p = fix0.protection.unwrap();
        let worst = (0..p.slopes.len())
            .max_by(|&a, &b| {
                p.slopes[a]
                    .horizontal_m
                    .total_cmp(&p.slopes[b].horizontal_m)
            })
            .unwrap();
        let off = PvtConfig {
            raim_pfa: 0.0,
            ..cfg.clone()
        };
        let unit = fix_at(&w, t, &measurements(&clean, Some((worst, 1.0)), &[]), &off).unwrap();
        let b = (p.lambda_det / unit.chi2).sqrt();
        let missed = (0..draws)
            .filter(|_| {
                let noise: Vec<f64> = clean
                    .iter()
                    .map(|&(_, _, el)| {
                        sigma(&cfg, el)
                            * <StandardNormal as Distribution<f64>>::sample(
                                &StandardNormal,
                                &mut rng,
                            )
                    })
                    .collect();
                let fix =
                    fix_at(&w, t, &measurements(&clean, Some((worst, b)), &noise), &cfg).unwrap();
                !fix.protection.is_some_and(|p| p.alarm)
            })
            .count();
        let rate = missed as f64 / draws as f64;
        let se = (pmd * (1.0 - pmd) / draws as f64).sqrt();
        assert!(
            (rate - pmd).abs() < 3.0 * se + 0.5 / draws as f64,
            "pmd {pmd}: {rate} ({missed} of {draws})"
        );
    }
}

#[test]
fn a_large_bias_is_detected_and_its_satellite_excluded() {
    let (w, r, t) = (world(false), site(), 5400.0);
    let cfg = config();
    let clean = pseudoranges(&w, t, &r);
    for i in 0..clean.len() {
        let fix = fix_at(&w, t, &measurements(&clean, Some((i, 300.0)), &[]), &cfg).unwrap();
        let p = fix.protection.clone().unwrap();
        assert!(p.alarm, "sat {i}");
        assert_eq!(fix.excluded, vec![clean[i].0]);
        assert_eq!(p.status, IntegrityStatus::Excluded);
        assert!(errors(&fix, &r).0 < 1e-3);
    }
    // The test off: no protection at all.
    let off = PvtConfig {
        raim_pfa: 0.0,
        ..cfg
    };
    let fix = fix_at(&w, t, &measurements(&clean, None, &[]), &off).unwrap();
    assert_eq!(fix.protection, None);
}

#[test]
fn exclusion_by_the_normalised_residual_finds_faults_the_weighted_residual_misses() {
    // A day of real geometry, every satellite in turn biased by 300 m (noise-free). The
    // largest weighted residual |v_i| / sigma_i (of the same fix with the test off) points
    // at another satellite in some of these cases; the solver, which excludes by the
    // largest normalised residual, must still exclude the biased one in every case.
    let (w, r) = (world(false), site());
    let cfg = config();
    let off = PvtConfig {
        raim_pfa: 0.0,
        ..cfg.clone()
    };
    let (mut cases, mut weighted_wrong) = (0, 0);
    for k in 0..96 {
        let t = 450.0 + 900.0 * k as f64;
        let clean = pseudoranges(&w, t, &r);
        for (i, &(sat, _, _)) in clean.iter().enumerate() {
            let meas = measurements(&clean, Some((i, 300.0)), &[]);
            let plain = fix_at(&w, t, &meas, &off).unwrap();
            let weighted_pick = plain
                .used
                .iter()
                .max_by(|a, b| {
                    (a.1 / sigma(&cfg, a.2))
                        .abs()
                        .total_cmp(&(b.1 / sigma(&cfg, b.2)).abs())
                })
                .map(|u| u.0);
            let fix = fix_at(&w, t, &meas, &cfg).unwrap();
            if !fix.protection.as_ref().is_some_and(|p| p.alarm) {
                continue;
            }
            cases += 1;
            weighted_wrong += usize::from(weighted_pick != Some(sat));
            assert_eq!(fix.excluded, vec![sat], "t {t}: {sat} biased");
            assert!(errors(&fix, &r).0 < 1e-3, "t {t}: {sat} biased");
        }
    }
    assert!(cases > 500, "{cases} detected cases");
    assert!(
        weighted_wrong > 0,
        "no case where the weighted residual picks another satellite in {cases}"
    );
    println!("{weighted_wrong} of {cases} cases: the weighted residual picks another satellite");
}

/// RAIM across systems: GPS L1 C/A with Galileo E1 on the nominal constellations, the
/// Galileo pseudoranges 30 m longer (a receiver whose Galileo channels run late: the
/// solver's second clock takes it), noise-free. Without a fault the fix is exact with no
/// alarm; a 300 m bias on any satellite of either system raises the alarm and excludes
/// that satellite, and the fix is exact again.
#[test]
fn raim_detects_and_excludes_a_fault_on_either_system_of_a_gps_galileo_fix() {
    let (w, r, t) = (world_of(false, true), site(), 5400.0);
    let cfg = config();
    let clean: Vec<(SatId, f64, f64)> = pseudoranges_of(&w, t, &r, &[System::Gps, System::Galileo])
        .into_iter()
        .map(|(sat, pr, el)| {
            let isb = if sat.system == System::Galileo {
                30.0
            } else {
                0.0
            };
            (sat, pr + isb, el)
        })
        .collect();
    let count = |system| clean.iter().filter(|c| c.0.system == system).count();
    assert!(
        count(System::Gps) >= 5 && count(System::Galileo) >= 4,
        "{clean:?}"
    );
    let fix = fix_at(&w, t, &measurements(&clean, None, &[]), &cfg).unwrap();
    assert!(errors(&fix, &r).0 < 1e-3 && errors(&fix, &r).1 < 1e-3);
    let p = fix.protection.clone().unwrap();
    assert!(!p.alarm && fix.excluded.is_empty());
    assert_eq!(p.status, IntegrityStatus::Available);
    for i in 0..clean.len() {
        let fix = fix_at(&w, t, &measurements(&clean, Some((i, 300.0)), &[]), &cfg).unwrap();
        let p = fix.protection.clone().unwrap();
        assert!(p.alarm, "{}", clean[i].0);
        assert_eq!(fix.excluded, vec![clean[i].0]);
        assert_eq!(p.status, IntegrityStatus::Excluded);
        let (h, v) = errors(&fix, &r);
        assert!(h < 1e-3 && v < 1e-3, "{}: {h} {v}", clean[i].0);
    }
}
