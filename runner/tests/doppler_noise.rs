//! Doppler noise at the observation level (`[observation] doppler_noise`): the same static
//! site with and without it, on the bundled calibration.

mod support;

use skyforge_gnss::signal::Signal;
use skyforge_runner::ObservationRun;
use skyforge_signals::obs_model::LoopNoise;

fn run(doppler_noise: bool) -> ObservationRun {
    let dir = tempfile::tempdir().expect("tempdir");
    let time = "[time]\n\
        start = \"2023-03-12T11:00:00 GPST\"  # assumed: as the other static-site tests\n\
        duration_s = 600.0  # assumed: 10 min of 1 s epochs\n";
    let tail = format!("[observation]\nlevel = \"observation\"\ndoppler_noise = {doppler_noise}\n");
    support::run_static_site("doppler-noise", 5, time, &tail, dir.path())
}

/// The Doppler's error against the truth has the std the calibration gives at 45 dB-Hz
/// (GPS L1 C/A: 15.33 x the PLL's 0.052 Hz, within 5 %: several thousand draws), the
/// code and carrier are those of the run without it, and without it the Doppler is the
/// truth's.
#[test]
fn the_doppler_gets_the_calibrated_noise_and_nothing_else_moves() {
    let (with, without) = (run(true), run(false));
    let calibration: skyforge_signals::obs_model::Calibration =
        toml::from_str(skyforge_scenarios::BUNDLED_CALIBRATION).unwrap();
    let c = calibration.of(Signal::GpsL1Ca).unwrap();
    let loops: LoopNoise = c.loops;
    let want = c.doppler_factor.unwrap() * loops.doppler_sigma_hz(45.0);
    let mut errors = Vec::new();
    for ((a, b), t) in with.measured[0]
        .epochs
        .iter()
        .zip(&without.measured[0].epochs)
        .zip(&with.truth[0].epochs)
    {
        for ((ra, rb), rt) in a.sats.iter().zip(&b.sats).zip(&t.sats) {
            assert_eq!(
                (ra.sat, ra.pseudorange_m, ra.carrier_phase_cycles),
                (rb.sat, rb.pseudorange_m, rb.carrier_phase_cycles)
            );
            assert_eq!(rb.doppler_hz, rt.doppler_hz);
            errors.push(ra.doppler_hz.unwrap() - rt.doppler_hz.unwrap());
        }
    }
    assert!(errors.len() > 3000, "{}", errors.len());
    let n = errors.len() as f64;
    let mean = errors.iter().sum::<f64>() / n;
    let std = (errors.iter().map(|e| (e - mean).powi(2)).sum::<f64>() / (n - 1.0)).sqrt();
    eprintln!("Doppler error std {std:.3} Hz, calibrated {want:.3} Hz, mean {mean:.4} Hz");
    assert!((std / want - 1.0).abs() < 0.05, "{std} vs {want}");
}
