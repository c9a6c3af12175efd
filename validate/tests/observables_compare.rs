//! Tests of `skyforge_validate::observables::compare` on observations with known errors.

mod observables_support;

use hifitime::Duration;
use observables_support::{Rec, normal, obs_file, range, wavelength};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use skyforge_gnss::signal::Signal;
use skyforge_orbits::constants::C_MPS;
use skyforge_orbits::ephemeris::System;
use skyforge_validate::observables::compare::{
    CompareOptions, PhaseArc, SampleSpan, compare_signals, compare_with,
};
use skyforge_validate::observables::{ObsComparison, ObsError, ObsFile, ObsRecord, compare};

const SATS: [(&str, f64, f64); 6] = [
    // name, zenith time (s), pseudorange bias (m)
    ("G02", -21500.0, 0.8),
    ("G05", 21500.0, -0.4),
    ("G10", 9000.0, 0.0),
    ("G17", -9000.0, 1.5),
    ("C07", 15000.0, 0.0),
    ("C12", -15000.0, -1.0),
];
/// About GNSS-SDR's at 45 dB-Hz.
const SIGMA_CODE_M: f64 = 2.0;
const SIGMA_PHASE_M: f64 = 0.001;
const SIGMA_DOPPLER_HZ: f64 = 0.5;
const CN0_BIAS_DB: f64 = -0.5;
/// Receiver clock of the sample clock: offset (s) at time `t` (s), and its rate.
fn rx_clock(t: f64) -> (f64, f64) {
    (3e-5 + 2e-8 * t + 1e-12 * t * t, 2e-8 + 2e-12 * t)
}

/// Truth at whole seconds 0..=130.
fn truth() -> ObsFile {
    let epochs: Vec<(f64, Vec<Rec>)> = (0..=130)
        .map(|k| {
            let t = k as f64;
            let (dt, ddt) = rx_clock(t);
            let recs = SATS
                .iter()
                .map(|&(sat, tz, _)| {
                    let (rho, rate) = range(tz, t);
                    let lambda = wavelength(sat);
                    let pr = rho + C_MPS * dt;
                    Rec {
                        sat,
                        pr,
                        phase: pr / lambda,
                        dop: -(rate + C_MPS * ddt) / lambda,
                        cn0: 45.0,
                        lli: 0,
                    }
                })
                .collect();
            (t, recs)
        })
        .collect();
    obs_file(&epochs, "GPS")
}

/// A receiver whose tags run `d = 73 ms + 1e-9 t` ahead of the sample clock, tagging
/// at fractional seconds, with code biases, white noise, arbitrary ambiguities and a
/// slip of 7 cycles on G05 (LLI set) at epoch 50; tags shifted by `tag_error_s` more
/// than the pseudoranges say.
fn estimate(seed: u64, tag_error_s: f64) -> ObsFile {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let epochs: Vec<(f64, Vec<Rec>)> = (0..100)
        .map(|k| {
            let tag = ((10.0734563 + k as f64) * 1e7).round() / 1e7;
            let d = 7.3e-2 + 1e-9 * tag;
            let t = tag - d;
            let (dt, ddt) = rx_clock(t);
            let recs = SATS
                .iter()
                .enumerate()
                .map(|(i, &(sat, tz, bias))| {
                    let (rho, rate) = range(tz, t);
                    let lambda = wavelength(sat);
                    let pr = rho + C_MPS * dt;
                    let slip = sat == "G05" && k >= 50;
                    let ambiguity = 1000.0 * i as f64 + 0.37 + if slip { 7.0 } else { 0.0 };
                    Rec {
                        sat,
                        pr: pr + C_MPS * d + bias + SIGMA_CODE_M * normal(&mut rng),
                        phase: (pr + C_MPS * d + SIGMA_PHASE_M * normal(&mut rng)) / lambda
                            + ambiguity,
                        dop: -(rate + C_MPS * ddt) / lambda
                            + 3.0
                            + SIGMA_DOPPLER_HZ * normal(&mut rng),
                        cn0: 45.0 + CN0_BIAS_DB + 0.2 * normal(&mut rng),
                        lli: u8::from(sat == "G05" && k == 50),
                    }
                })
                .collect();
            (tag + tag_error_s, recs)
        })
        .collect();
    obs_file(&epochs, "GPS")
}

/// `est` within `k` standard errors of `truth` for a std from `dof` degrees of freedom.
fn std_close(est: Option<f64>, truth: f64, dof: usize, k: f64) {
    let est = est.unwrap();
    let se = truth / (2.0 * dof as f64).sqrt();
    assert!((est - truth).abs() < k * se, "{est} vs {truth} (se {se})");
}

#[test]
fn known_errors_are_measured() {
    let c = compare(&estimate(7, 0.0), &truth()).unwrap();
    assert_eq!((c.estimate_epochs, c.matched_epochs), (100, 100));
    assert!(c.satellites_without_truth.is_empty());
    let d = c.time_offset_s.mean.unwrap();
    assert!((d - (7.3e-2 + 60e-9)).abs() < 2e-9, "{d}");
    // Per system: 4 GPS x 100 samples, 99 + 3 dof taken; 2 BDS: 99 + 1.
    let gps = c.pseudorange_m.per_system[0];
    assert_eq!(gps.stats.count, 400);
    std_close(gps.stats.std, SIGMA_CODE_M, 400 - 100 - 3, 3.0);
    std_close(
        c.pseudorange_m.overall.std,
        SIGMA_CODE_M,
        600 - 200 - 4,
        3.0,
    );
    // Relative biases: GPS biases minus their mean (0.475).
    for s in c
        .pseudorange_m
        .per_satellite
        .iter()
        .filter(|s| s.sat.system == System::Gps)
    {
        let bias = SATS.iter().find(|x| x.0 == s.sat.to_string()).unwrap().2;
        let m = s.stats.mean.unwrap();
        assert!(
            (m - (bias - 0.475)).abs() < 4.0 * SIGMA_CODE_M / 10.0,
            "{} {m}",
            s.sat
        );
    }
    // Phase: the per-epoch time offset's error (ns) puts only rho_dot * error (um) in.
    std_close(
        c.carrier_phase_m.overall.std,
        SIGMA_PHASE_M,
        600 - 200 - 7,
        3.0,
    );
    std_close(
        c.doppler_hz.overall.std,
        SIGMA_DOPPLER_HZ,
        600 - 200 - 4,
        3.0,
    );
    let cn0 = c.cn0_dbhz.overall;
    assert!((cn0.mean.unwrap() - CN0_BIAS_DB).abs() < 3.0 * 0.2 / 600f64.sqrt());
    std_close(cn0.std, 0.2, 599, 3.0);
    // Arcs: G05 split at the slip; ambiguity differences are whole cycles.
    let g05: Vec<&PhaseArc> = c
        .arcs
        .iter()
        .filter(|a| a.sat.to_string() == "G05")
        .collect();
    assert_eq!(g05.len(), 2);
    assert_eq!((g05[0].epochs, g05[1].epochs), (50, 50));
    assert!(((g05[1].offset_cycles - g05[0].offset_cycles) - 7.0).abs() < 0.02);
    assert_eq!(c.arcs.len(), 7);
    assert!(c.arcs.iter().all(|a| a.integer_like), "{:?}", c.arcs);
    assert_eq!(c.arcs.iter().filter(|a| a.reference).count(), 2);
    let tag = c.tag_error.unwrap();
    assert!(
        tag.delta_s.abs() < 4.0 * tag.std_error_s.max(1e-3),
        "{tag:?}"
    );
    // JSON keys the CLI and the interop test rely on.
    let v = serde_json::to_value(&c).unwrap();
    assert_eq!(v["pseudorange_m"]["per_satellite"][0]["sat"], "G02");
    assert_eq!(v["carrier_phase_m"]["per_system"][1]["system"], "BeiDou");
}

/// Tags 14 s late (BDT read as GPST, or the reverse) leave biases lambda D delta, which
/// the tag-error regression finds; shifting the tags back removes them.
#[test]
fn a_tag_error_is_found_and_corrected() {
    let est = estimate(8, 14.0);
    let bad = compare(&est, &truth()).unwrap();
    let tag = bad.tag_error.unwrap();
    assert!((tag.delta_s - 14.0).abs() < 0.01, "{tag:?}");
    let worst = bad
        .pseudorange_m
        .per_satellite
        .iter()
        .fold(0.0f64, |m, s| m.max(s.stats.mean.unwrap().abs()));
    assert!(worst > 1000.0, "{worst}");
    let opts = CompareOptions {
        tag_offset_s: -14.0,
        ..CompareOptions::default()
    };
    let good = compare_with(&est, &truth(), &opts).unwrap();
    std_close(good.pseudorange_m.overall.std, SIGMA_CODE_M, 396, 3.0);
    assert!(good.tag_error.unwrap().delta_s.abs() < 0.01);
}

/// The estimate's sample times are 10.0004563 + k s (k = 0..100) after the truth's first
/// epoch: a window from 20 s to 39.5 s keeps k = 10..=29, and reports their span.
#[test]
fn a_sample_time_window_keeps_the_epochs_measured_inside_it() {
    let truth = truth();
    let t0 = truth.epochs[0].time;
    let at = |s: f64| t0 + Duration::from_seconds(s);
    let opts = CompareOptions {
        window: Some(SampleSpan {
            first: at(20.0),
            last: at(39.5),
        }),
        ..CompareOptions::default()
    };
    let c = compare_with(&estimate(7, 0.0), &truth, &opts).unwrap();
    assert_eq!((c.estimate_epochs, c.matched_epochs), (100, 20));
    for (got, want) in [
        (c.sample_span.first, 20.0004563),
        (c.sample_span.last, 39.0004563),
    ] {
        let err = (got - at(want)).to_seconds();
        assert!(err.abs() < 1e-6, "{got} vs {want}: {err}");
    }
    assert_eq!(c.pseudorange_m.per_satellite[0].stats.count, 20);
    let outside = CompareOptions {
        window: Some(SampleSpan {
            first: at(200.0),
            last: at(300.0),
        }),
        ..CompareOptions::default()
    };
    assert!(matches!(
        compare_with(&estimate(7, 0.0), &truth, &outside),
        Err(ObsError::EmptyWindow { .. })
    ));
}

#[test]
fn no_overlap_is_an_error() {
    let late = estimate(9, 1000.0);
    assert!(matches!(
        compare(&late, &truth()),
        Err(ObsError::NoOverlap { .. })
    ));
}

/// `f` with a GPS L5 observation beside each GPS one: the same values, the pseudorange
/// `offset_m` longer.
fn with_l5(mut f: ObsFile, offset_m: f64) -> ObsFile {
    for e in &mut f.epochs {
        let l5: Vec<_> = e
            .sats
            .iter()
            .filter(|r| r.sat.system == System::Gps)
            .map(|r| ObsRecord {
                signal: Signal::GpsL5,
                pseudorange_m: r.pseudorange_m.map(|p| p + offset_m),
                ..*r
            })
            .collect();
        e.sats.extend(l5);
    }
    f
}

#[test]
fn a_truth_of_two_signals_is_compared_on_the_estimates_signal_alone() {
    let alone = compare(&estimate(7, 0.0), &truth()).unwrap();
    let beside_l5 = compare(&estimate(7, 0.0), &with_l5(truth(), 5.0)).unwrap();
    assert_eq!(alone, beside_l5);
}

#[test]
fn an_estimate_of_two_signals_is_compared_signal_by_signal() {
    let (est, tru) = (with_l5(estimate(7, 0.0), 5.0), with_l5(truth(), 5.0));
    assert!(matches!(
        compare(&est, &tru),
        Err(ObsError::SeveralSignals(s)) if s == "GPS gps-l1ca, gps-l5"
    ));
    let each = compare_signals(&est, &tru, &CompareOptions::default()).unwrap();
    let layers: Vec<&[Signal]> = each.iter().map(|c| c.signals.as_slice()).collect();
    assert_eq!(
        layers,
        [&[Signal::GpsL1Ca, Signal::BdsB1I][..], &[Signal::GpsL5][..]]
    );
    let l1 = compare(&estimate(7, 0.0), &truth()).unwrap();
    assert_eq!(each[0].comparison, l1);
    // L5's errors are L1's: the same values 5 m longer in both files.
    let gps = |c: &ObsComparison| -> Vec<(String, Option<f64>, Option<f64>)> {
        c.pseudorange_m
            .per_satellite
            .iter()
            .filter(|s| s.sat.system == System::Gps)
            .map(|s| (s.sat.to_string(), s.stats.mean, s.stats.std))
            .collect()
    };
    let (a, b) = (gps(&each[1].comparison), gps(&l1));
    assert_eq!(a.len(), 4);
    for ((sa, ma, da), (sb, mb, db)) in a.iter().zip(&b) {
        assert_eq!(sa, sb);
        assert!(
            (ma.unwrap() - mb.unwrap()).abs() < 1e-6,
            "{sa}: {ma:?} vs {mb:?}"
        );
        assert!(
            (da.unwrap() - db.unwrap()).abs() < 1e-6,
            "{sa}: {da:?} vs {db:?}"
        );
    }
}
