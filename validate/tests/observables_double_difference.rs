//! Tests of `skyforge_validate::observables::double_difference` on observations with known errors.

mod observables_support;

use observables_support::{Rec, normal, obs_file, range, wavelength};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use skyforge_orbits::ephemeris::System;
use skyforge_validate::observables::double_difference::{
    DdOptions, zero_baseline, zero_baseline_with,
};
use skyforge_validate::observables::{ObsError, ObsFile};

/// name, zenith time (s), code bias in A and in B (m), ambiguity in A and B (cycles).
type Sat = (&'static str, f64, f64, f64, f64, f64);
const SATS: [Sat; 6] = [
    ("G02", -21500.0, 0.3, 0.1, 11.0, -4.0),
    ("G05", 21500.0, 0.0, -0.2, 3.0, 8.0),
    ("G10", 9000.0, 0.5, 0.0, -2.0, 0.0),
    ("G17", -9000.0, 0.0, 0.0, 5.0, 5.0),
    ("C04", 15000.0, 0.0, 0.0, 1.0, 2.0),
    ("C07", -15000.0, 0.2, -0.1, 0.0, 9.0),
];

/// One receiver on the shared oscillator (tags `d = 1 ms` ahead of the sample clock),
/// 120 epochs; G10 only from epoch 20; receiver B (`b`) slips G05 by 3 cycles at epoch
/// 60; tags `tag_shift_s` later than A's.
fn receiver(b: bool, seed: u64, sigma_code: f64, sigma_phase: f64, tag_shift_s: f64) -> ObsFile {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let epochs: Vec<(f64, Vec<Rec>)> = (0..120)
        .map(|k| {
            let tag = 100.25 + k as f64 + tag_shift_s;
            let t = tag - 1e-3;
            let recs = SATS
                .iter()
                .filter(|s| s.0 != "G10" || k >= 20)
                .map(|&(sat, tz, bias_a, bias_b, n_a, n_b)| {
                    let (rho, rate) = range(tz, t);
                    let lambda = wavelength(sat);
                    let slip = b && sat == "G05" && k >= 60;
                    let (bias, n) = if b { (bias_b, n_b) } else { (bias_a, n_a) };
                    let n = n + if slip { 3.0 } else { 0.0 };
                    Rec {
                        sat,
                        pr: rho + bias + sigma_code * normal(&mut rng),
                        phase: (rho + sigma_phase * normal(&mut rng)) / lambda + n,
                        dop: -rate / lambda,
                        cn0: 45.0,
                        lli: u8::from(b && sat == "G05" && k == 60),
                    }
                })
                .collect();
            (tag, recs)
        })
        .collect();
    obs_file(&epochs, "GPS")
}

fn sat(name: &str) -> &'static Sat {
    SATS.iter().find(|s| s.0 == name).unwrap()
}

#[test]
fn zero_baseline_noise_and_biases_are_measured() {
    let (sc, sp) = (0.5, 0.001);
    let zb = zero_baseline(
        &receiver(false, 1, sc, sp, 0.0),
        &receiver(true, 2, sc, sp, 0.0),
    )
    .unwrap();
    assert_eq!(zb.common_epochs, 120);
    let gps = zb.system(System::Gps).unwrap();
    // G10 misses 20 epochs; G02, G05, G17 tie: the lowest PRN.
    assert_eq!(gps.reference.to_string(), "G02");
    assert_eq!(gps.pairs.len(), 3);
    let r = sat("G02");
    for p in &gps.pairs {
        let s = sat(&p.sat.to_string());
        let n = if s.0 == "G10" { 100 } else { 120 };
        assert_eq!(p.pseudorange_m.count, n);
        // Independent noise in four terms: std 2 sigma.
        let se = |sigma: f64, n: usize| 2.0 * sigma / (2.0 * n as f64).sqrt();
        let code_std = p.pseudorange_m.std.unwrap();
        assert!((code_std - 2.0 * sc).abs() < 3.0 * se(sc, n), "{code_std}");
        let mean = (s.2 - s.3) - (r.2 - r.3);
        let code_mean = p.pseudorange_m.mean.unwrap();
        assert!((code_mean - mean).abs() < 3.0 * 2.0 * sc / (n as f64).sqrt());
        let phase_std = p.carrier_phase_m.std.unwrap();
        assert!(
            (phase_std - 2.0 * sp).abs() < 3.0 * se(sp, n),
            "{phase_std}"
        );
        assert!(p.carrier_phase_m.mean.unwrap().abs() < 4.0 * 2.0 * sp / (n as f64).sqrt());
        let integer = (s.4 - s.5) - (r.4 - r.5);
        match s.0 {
            "G05" => {
                assert_eq!(p.arcs.len(), 2);
                assert_eq!(p.arcs[0].integer_cycles, integer);
                assert_eq!(p.arcs[1].integer_cycles, integer - 3.0);
                assert_eq!((p.arcs[0].epochs, p.arcs[1].epochs), (60, 60));
            }
            _ => {
                assert_eq!(p.arcs.len(), 1);
                assert_eq!(p.arcs[0].integer_cycles, integer);
            }
        }
        assert!(p.arcs.iter().all(|a| a.fraction_cycles.abs() < 0.01));
    }
    let bds = zb.system(System::Beidou).unwrap();
    assert_eq!(bds.reference.to_string(), "C04");
    assert_eq!(bds.pairs.len(), 1);
    // Pooled over GPS pairs: count and a std near 2 sigma.
    assert_eq!(gps.pseudorange_m.count, 340);
    assert!((gps.carrier_phase_m.std.unwrap() - 2.0 * sp).abs() < 0.2 * sp);
}

/// B tags 0.9 us later than A; without the Doppler move, each pair would keep
/// (rho_dot_i - rho_dot_ref) x 0.9 us, up to 0.8 mm.
#[test]
fn a_tag_difference_is_moved_out_with_the_doppler() {
    let a = receiver(false, 3, 0.0, 0.0, 0.0);
    let b = receiver(true, 4, 0.0, 0.0, 9e-7);
    let zb = zero_baseline(&a, &b).unwrap();
    assert!((zb.max_tag_difference_s - 9e-7).abs() < 1e-9);
    for p in &zb.system(System::Gps).unwrap().pairs {
        // Left: the file's 0.001-cycle rounding (0.2 mm) only.
        let mean = p.carrier_phase_m.mean.unwrap();
        assert!(mean.abs() < 1e-4, "{}: {mean}", p.sat);
    }
    let strict = DdOptions {
        max_tag_difference_s: 5e-7,
    };
    assert!(matches!(
        zero_baseline_with(&a, &b, &strict),
        Err(ObsError::NoCommonEpoch { .. })
    ));
}
