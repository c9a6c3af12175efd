//! The synthesised samples carry what the signal truth says, term by term: a receiver
//! clock (offset and drift), ionosphere, troposphere, phase-centre delay and the fault
//! events (power step, code step, phase jump, outage). Each 1 ms block is correlated
//! against a replica built only from the truth record of that block (code phase from the
//! pseudorange, carrier from the accumulated phase and the Doppler), independently of the
//! receiver crate: the prompt must have the truth's amplitude and zero phase, and the
//! early/late correlators must balance.

mod common;

use skyforge_gnss::sample_format::SampleFormat;
use skyforge_orbits::constants::C_MPS;
use skyforge_signals::errors::{EventConfig, EventKind, EventSchedule};
use skyforge_signals::synth::Transmitter;
use skyforge_signals::synth::render::{LinkEnd, LinkTruth, Synthesiser, append_to};
use skyforge_signals::synth::{BLOCK_S, SignalConfig};
use std::f64::consts::TAU;

const FS_HZ: f64 = 4.0e6;
/// Far above any real signal, so that thermal noise does not hide a systematic error
/// (the link's C/N0 is not range-checked below the scenario level).
const CN0_DBHZ: f64 = 90.0;

fn event(kind: EventKind, start_s: f64, end_s: f64, value: f64) -> EventConfig {
    EventConfig {
        kind,
        antenna: None,
        satellite: None,
        start_s,
        end_s,
        value,
    }
}

/// Prompt, early and late correlations (E/L at -+ half a chip) of one block against the
/// replica of truth record `r`.
fn correlate(tx: &Transmitter, samples: &[(f32, f32)], r: &LinkTruth) -> [(f64, f64); 3] {
    let t_sv = r.t_s - r.pseudorange_m / C_MPS;
    let chips_per_sample = tx.chip_rate_hz / FS_HZ * (1.0 + r.doppler_hz / 1575.42e6);
    let mut signs = Vec::new();
    let (k0, phase0) = tx.chip_at(t_sv - 1e-6);
    tx.chip_signs(k0, 4200, &mut signs);
    // Chip position of sample i relative to chip k0.
    let offset0 = phase0 + 1e-6 * tx.chip_rate_hz;
    let mut z = [(0.0, 0.0); 3];
    for (i, &(x, y)) in samples.iter().enumerate() {
        // Baseband phase = IF t - carrier phase (IF 0 here); the carrier phase falls at the
        // Doppler.
        let phi = -TAU * (r.carrier_phase_cycles - r.doppler_hz * i as f64 / FS_HZ);
        let (s, c) = (-phi).sin_cos();
        let (re, im) = (
            f64::from(x) * c - f64::from(y) * s,
            f64::from(x) * s + f64::from(y) * c,
        );
        for (k, dz) in [0.0, -0.5, 0.5].iter().enumerate() {
            let chip = (offset0 + i as f64 * chips_per_sample - dz).floor() as usize;
            let sign = f64::from(signs[chip]);
            z[k].0 += re * sign;
            z[k].1 += im * sign;
        }
    }
    z
}

#[test]
fn samples_follow_the_truth_of_every_term() {
    let (txs, sats, chunk) = common::gps_links("interop-gps-static", 1, 10.0, 3);
    let s = (0..sats.len())
        .find(|&s| (0..=1).all(|k| chunk.link(k, 0, s).visible))
        .expect("a visible GPS satellite");
    let tx = &txs[s];

    let cfg = SignalConfig {
        sample_rate_hz: FS_HZ,
        format: SampleFormat::Cf32,
        truth_rate_hz: 1000,
        ..SignalConfig::default()
    };
    let clock = common::tcxo_clock();
    let events = [
        event(EventKind::PowerStep, 0.10, 0.30, -6.0),
        event(EventKind::CodeStep, 0.20, 0.50, 15.0),
        event(EventKind::PhaseJump, 0.40, 0.70, 0.25),
        event(EventKind::IonoRamp, 0.60, 0.80, 20.0),
        event(EventKind::Outage, 0.90, 0.95, f64::NAN),
    ];
    let schedule = EventSchedule::new(&events, &["ant1"], &sats).unwrap();
    let txs_one = std::slice::from_ref(tx);
    let mut synth = Synthesiser::new(&cfg, txs_one, 1, 11)
        .unwrap()
        .with_truth_every(1)
        .with_clocks(vec![clock])
        .with_events(schedule);
    let mut out = vec![Vec::new()];
    for k in 0..=1 {
        let end = LinkEnd::from_geometry(chunk.link(k, 0, s), CN0_DBHZ).map(|e| LinkEnd {
            iono_m: 4.0 + k as f64,
            tropo_m: 2.5,
            antenna_m: 0.03,
            ..e
        });
        let Ok(()) = synth.push_epoch(chunk.t_s[k], vec![end], &mut append_to(&mut out));
    }
    let records = synth.take_truth();
    let samples = common::cf32_samples(&out[0]);
    let n = (FS_HZ * BLOCK_S) as usize;
    assert_eq!(samples.len(), 1000 * n);
    // Outage blocks have no record; every other block has one.
    assert_eq!(records.len(), 950);
    let amplitude = (2.0 * 10f64.powf(CN0_DBHZ / 10.0) / FS_HZ).sqrt();
    let (mut worst_phase, mut worst_el, mut worst_amp): (f64, f64, f64) = (0.0, 0.0, 0.0);
    for r in &records {
        // The terms the truth reports are the ones applied.
        assert!(
            (r.rx_clock_m / C_MPS - 1e-4).abs() < 1e-6,
            "{}",
            r.rx_clock_m
        );
        assert_eq!((r.tropo_m, r.antenna_m), (2.5, 0.03));
        let b = (r.t_s / BLOCK_S).round() as usize;
        let z = correlate(tx, &samples[b * n..(b + 1) * n], r);
        let mag = |z: (f64, f64)| z.0.hypot(z.1);
        let expected = amplitude * 10f64.powf((r.cn0_dbhz - CN0_DBHZ) / 20.0) * n as f64;
        worst_amp = worst_amp.max((mag(z[0]) / expected - 1.0).abs());
        worst_phase = worst_phase.max(z[0].1.atan2(z[0].0).abs());
        worst_el = worst_el.max((mag(z[1]) - mag(z[2])).abs() / (mag(z[1]) + mag(z[2])));
    }
    println!(
        "{}: worst prompt phase {worst_phase:.2e} rad, amplitude {worst_amp:.2e}, E-L imbalance {worst_el:.2e}",
        tx.sat
    );
    // The replica carries the data bits, so the prompt phase is 0 (0.01 rad = 0.3 mm; the
    // 0.25-cycle phase jump would show as 1.57 rad).
    assert!(worst_phase < 0.01, "carrier off by {worst_phase} rad");
    assert!(worst_amp < 0.01, "amplitude off by {worst_amp}");
    // 0.02 of the E+L sum is 0.02 chip of code (6 m): the 15 m code step would show as 0.1.
    assert!(worst_el < 0.02, "code off: E-L imbalance {worst_el}");
    // The outage really silences the signal.
    let quiet = (0.91 / BLOCK_S) as usize;
    let r0 = records.iter().find(|r| r.t_s > 0.85).unwrap();
    let z = correlate(
        tx,
        &samples[quiet * n..(quiet + 1) * n],
        &LinkTruth {
            t_s: quiet as f64 * BLOCK_S,
            ..*r0
        },
    );
    assert!(z[0].0.hypot(z[0].1) < 0.05 * amplitude * n as f64);
}
