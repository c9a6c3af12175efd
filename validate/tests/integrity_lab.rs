//! The B-value monitor on paper 002's lab set-up at the observation level: the paper's
//! fault cases, the physical argument behind the one row marked `explained`, and the
//! detection curves on a few seeds (`validate thesis --only P2` runs the full counts).

use skyforge_gnss::signal::Signal;
use skyforge_navigation::integrity::{SatelliteEpoch, Statistic};
use skyforge_validate::draw::Draw;
use skyforge_validate::integrity::detection;
use skyforge_validate::integrity::patterns;
use skyforge_validate::integrity::{Case, FAULT_SATELLITE, MonitoredRun};
use skyforge_validate::integrity::{Sigmas, calibrate_lab, case_run};
use skyforge_validate::report::Verdict;
use std::sync::OnceLock;

/// The lab's thresholds, calibrated once for the tests of this file.
fn sigma() -> &'static Sigmas {
    static SIGMA: OnceLock<Sigmas> = OnceLock::new();
    SIGMA.get_or_init(|| calibrate_lab(0).unwrap())
}

/// The faulted satellite at whole second `t` of `run`.
fn at(run: &MonitoredRun, t: f64) -> &SatelliteEpoch {
    let e = run.epochs.iter().find(|e| e.t_s.round() == t).unwrap();
    e.sats
        .iter()
        .find(|s| s.sat.to_string() == FAULT_SATELLITE)
        .unwrap()
}

/// B value of `stat` at station `m`.
fn b(s: &SatelliteEpoch, m: usize, stat: Statistic) -> f64 {
    s.stations[m].unwrap().b[stat.index()]
}

const C: usize = 2;

#[test]
fn the_calibration_covers_both_signals_and_gps_code_is_noisier() {
    let sigma = sigma();
    let (gps, bds) = (&sigma["gps-l1ca"], &sigma["bds-b1i"]);
    // The C/A chip is twice B1I's: its code noise is larger at the same C/N0.
    let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len() as f64;
    assert!(
        mean(&gps.code_m) > 1.3 * mean(&bds.code_m),
        "{gps:?} {bds:?}"
    );
    // Carrier B values are at the mm level (a few thousandths of a cycle).
    assert!(gps.carrier_cycles.iter().all(|&c| c > 1e-3 && c < 0.05));
}

#[test]
fn a_ramp_at_one_station_shows_in_its_b_values_and_a_common_one_cancels() {
    // The physical argument of the `explained` row: 0.1 m/s from 500 s at C alone.
    let run = case_run(Case::IonoRampAtC, patterns::FIRST_SEED, sigma()).unwrap();
    let s = at(&run, 672.0);
    let ramp_m = 0.1 * (672.0 - 500.0);
    let lambda = Signal::BdsB1I.wavelength_m();
    let carrier = b(s, C, Statistic::Carrier);
    assert!((carrier + ramp_m / lambda).abs() < 0.5, "{carrier} cycles");
    let code = b(s, C, Statistic::Code);
    assert!((code - ramp_m).abs() < 3.0, "{code} m");
    assert!(s.stations[C].unwrap().alarm[Statistic::Carrier.index()]);
    // The same ramp at every station: no B value leaves its fault-free range.
    let common = case_run(Case::IonoRampCommon, patterns::FIRST_SEED, sigma()).unwrap();
    let s = at(&common, 672.0);
    for m in 0..4 {
        assert!(b(s, m, Statistic::Carrier).abs() < s.threshold[Statistic::Carrier.index()]);
        assert!(b(s, m, Statistic::Code).abs() < s.threshold[Statistic::Code.index()]);
    }
}

#[test]
fn the_papers_cases_show_their_patterns_on_two_seeds() {
    let rows = patterns::rows(
        sigma(),
        Draw {
            offset: 0,
            runs: Some(2),
        },
    )
    .unwrap();
    assert_eq!(rows.len(), 16);
    let find = |label: &str| rows.iter().find(|r| r.row == label).unwrap();
    for label in [
        "cycle slip: carrier B at C",
        "cycle slip: carrier B at A, B, D",
        "cycle slip: smoothed-code B at C",
        "cycle slip: smoothed-code B, A, B, D over C",
        "cycle slip: divergence B at C",
        "multipath: smoothed-code B at C crosses 0.5 m",
        "multipath: carrier B at C unchanged",
        "common iono ramp: not detected",
        "iono ramp at C only: B at C beyond its thresholds",
    ] {
        assert_eq!(
            find(label).verdict,
            Verdict::Reproduced,
            "{:?}",
            find(label)
        );
    }
    assert_eq!(
        find("iono ramp at C only: detected").verdict,
        Verdict::Explained
    );
    // The slip's smoothed-code peak is 100 B1I wavelengths x 0.99 (digest 2.4).
    let peak = find("cycle slip: smoothed-code B at C").ours.unwrap();
    assert!((peak - 100.0 * Signal::BdsB1I.wavelength_m() * 0.99).abs() < 0.1);
}

#[test]
fn detection_rises_with_the_fault_size() {
    let rows = detection::rows(
        sigma(),
        Draw {
            offset: 0,
            runs: Some(10),
        },
    )
    .unwrap();
    assert_eq!(rows.len(), 4 * detection::SIZES.len());
    for stat in rows.chunks(detection::SIZES.len()) {
        let p: Vec<f64> = stat.iter().map(|r| r.ours.unwrap()).collect();
        assert_eq!(p[0], 0.0, "false detections: {:?}", stat[0]);
        assert!(p[4] >= 0.7, "{:?}", stat[4]);
        assert!(p[4] >= p[1], "{p:?}");
    }
}

#[test]
fn the_bundled_configuration_is_the_labs_calibration() {
    // `skyforge monitor calibrate integrity-lab --seed 1 --seeds 8` wrote it; the same
    // runs here give the same tables.
    let bundled = skyforge_navigation::integrity::MonitorConfig::parse(
        skyforge_scenarios::BUNDLED_MONITOR_CONFIG,
    )
    .unwrap();
    let fresh = sigma();
    assert_eq!(bundled.thresholds.sigma.len(), fresh.len());
    for (tag, table) in fresh {
        let b = &bundled.thresholds.sigma[tag];
        for stat in Statistic::ALL {
            for (x, y) in b.column(stat).iter().zip(table.column(stat)) {
                assert!(
                    (x - y).abs() <= 1e-12 * y.abs(),
                    "{tag} {stat:?}: {x} vs {y}"
                );
            }
        }
    }
    let lab = skyforge_validate::integrity::config(fresh.clone());
    assert_eq!(bundled.smoothing_s, lab.smoothing_s);
    assert_eq!(bundled.divergence_s, lab.divergence_s);
    assert_eq!(bundled.thresholds.false_alarm, lab.thresholds.false_alarm);
}
