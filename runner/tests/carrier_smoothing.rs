//! Carrier-smoothed code at the observation level (`PvtConfig::carrier_smoothing`, the
//! book's growing-memory filter, eqs. 5-60..5-64): the same observations fixed with raw
//! and with smoothed code.

mod support;

use skyforge_gnss::signal::Signal;
use skyforge_navigation::pvt::{PvtConfig, SmoothingConfig};
use skyforge_runner::ObservationRun;

/// A 10 min static site, GPS L1 C/A, 0.3 m white code noise and 3 mm carrier noise, the
/// ionosphere as `ionosphere` sets it (on one frequency its code-carrier divergence biases
/// a growing memory).
fn run(seed: u64, ionosphere: &str) -> ObservationRun {
    let dir = tempfile::tempdir().expect("tempdir");
    let time = "[time]\n\
        start = \"2023-03-12T11:00:00 GPST\"  # assumed: as the dual-frequency test\n\
        duration_s = 600.0  # assumed: 10 min of 1 s epochs\n";
    // assumed: 0.3 m code (the PVT's own sigma_a), 3 mm carrier (the book's "a few mm").
    let tail = format!(
        "[errors.ionosphere]\n{ionosphere}\n{}",
        support::observation_level("", 0.3, 0.003)
    );
    support::run_static_site("carrier-smoothing", seed, time, &tail, dir.path())
}

/// RMS of the 3-D position error (m) of the first antenna's fixes after the first minute.
fn rms_error_m(run: &ObservationRun, pvt: &PvtConfig) -> f64 {
    support::fix_rms_m(run, pvt, &[Signal::GpsL1Ca], 60.0, 530)
}

/// After a minute of smoothing (60 epochs: code noise / sqrt(61)) the fix error is well
/// under a third of the raw code's (# assumed bar: a third, where the filter's memory
/// alone predicts about an eighth), on two seeds.
#[test]
fn smoothed_code_fixes_are_several_times_closer_than_raw_ones() {
    let smoothed = PvtConfig {
        carrier_smoothing: Some(SmoothingConfig {
            code_sigma_m: 0.3,
            phase_sigma_m: 0.003,
            ..SmoothingConfig::default()
        }),
        ..PvtConfig::default()
    };
    for seed in 1..=2 {
        let r = run(seed, "model = \"off\"");
        let (raw, smooth) = (
            rms_error_m(&r, &PvtConfig::default()),
            rms_error_m(&r, &smoothed),
        );
        eprintln!("seed {seed}: RMS 3-D error raw {raw:.3} m, smoothed {smooth:.3} m");
        assert!(smooth < raw / 3.0, "seed {seed}: {smooth} vs {raw}");
    }
}

/// On one frequency the ionosphere moves code and carrier apart at twice its rate, which a
/// growing memory turns into a bias and a capped memory (`max_epochs`) bounds: with a
/// threefold ionosphere at midday (# assumed: large enough to show it in 10 min) the
/// fixes on code smoothed over at most 60 epochs (# assumed: a minute) are closer than on
/// code smoothed over the whole run, on two seeds.
#[test]
fn a_capped_memory_bounds_the_ionospheric_divergence() {
    let smoothing = |max_epochs| PvtConfig {
        carrier_smoothing: Some(SmoothingConfig {
            code_sigma_m: 0.3,
            phase_sigma_m: 0.003,
            max_epochs,
            ..SmoothingConfig::default()
        }),
        ..PvtConfig::default()
    };
    for seed in 1..=2 {
        let r = run(seed, "model = \"klobuchar\"\nscale = 3.0");
        let raw = rms_error_m(&r, &PvtConfig::default());
        let growing = rms_error_m(&r, &smoothing(None));
        let capped = rms_error_m(&r, &smoothing(Some(60)));
        eprintln!(
            "seed {seed}: RMS 3-D error raw {raw:.3} m, growing memory {growing:.3} m, 60 epochs {capped:.3} m"
        );
        assert!(capped < growing, "seed {seed}: {capped} vs {growing}");
    }
}
