//! Correlator throughput (issue #4 speed bar: at least 5e8 channel-samples/s on the
//! 2-core machine with 3 correlators and complex input). One 1 ms block at 4.092 Msps is
//! correlated by 24 channels (12 GPS + 12 BeiDou PRNs, distinct Doppler and code phase),
//! single-threaded and with rayon over the channels. A second group correlates 1 ms at
//! 20.46 Msps for 12 PRNs of each signal, one thread, with the taps the receiver tracks
//! the signal with. A third runs whole channel trackers (correlator, loops, lock
//! detectors, bit sync) over 0.2 s of a GPS signal.

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use num_complex::Complex;
use rayon::prelude::*;
use skyforge_gnss::signal::Signal;
use skyforge_receiver::tracking::TrackingConfig;
use skyforge_receiver::tracking::{ChannelTracker, FrontEnd, Handover};
use skyforge_receiver::tracking::{Correlator, NcoState, TapSet};

const FS_HZ: f64 = 4.092e6;
const BLOCK: usize = 4092;

fn channels(taps: TapSet) -> Vec<(Correlator, NcoState)> {
    (1..=12u8)
        .flat_map(|prn| [(Signal::GpsL1Ca, prn), (Signal::BdsB1I, prn + 6)])
        .map(|(signal, prn)| {
            let code = signal.code(prn).unwrap_or_default();
            let nco = NcoState {
                carrier_phase_cycles: 0.1 * f64::from(prn),
                carrier_cycles_per_sample: (250.0 * f64::from(prn) - 1500.0) / FS_HZ,
                code_phase_chips: 3.7 * f64::from(prn),
                code_chips_per_sample: signal.chip_rate_hz() / FS_HZ,
            };
            (Correlator::new(&code, taps).expect("valid taps"), nco)
        })
        .collect()
}

/// Sample rate and 1 ms block of the per-signal groups.
const WIDE_FS_HZ: f64 = 20.46e6;
const WIDE_BLOCK: usize = 20_460;

/// 12 channels of `signal` at 20.46 Msps with the taps the receiver tracks it with
/// (`tracking::channel`'s choice): early, prompt and late of a signal without a pilot;
/// of the pilot code with the data code's prompt beside them otherwise, on BOC(1,1)
/// half-chips for Galileo E1 and BeiDou B1C. Empty where the codes are not at hand (E1
/// without the ICD's tables).
fn signal_channels(signal: Signal) -> Vec<(Correlator, NcoState)> {
    (1..=12u8)
        .filter_map(|prn| {
            let data = signal.code(prn).ok()?;
            let nco = NcoState {
                carrier_phase_cycles: 0.1 * f64::from(prn),
                carrier_cycles_per_sample: (250.0 * f64::from(prn) - 1500.0) / WIDE_FS_HZ,
                code_phase_chips: 37.7 * f64::from(prn),
                code_chips_per_sample: signal.chip_rate_hz() / WIDE_FS_HZ,
            };
            let corr = match signal.pilot(prn).ok() {
                Some(p) if signal.replica_boc11() => {
                    Correlator::pilot_and_data_boc11(&p.primary, &data, 0.15)
                }
                Some(p) => Correlator::pilot_and_data(&p.primary, &data, 0.5),
                None => Correlator::new(
                    &data,
                    TapSet::Three {
                        early_late_spacing_chips: 0.5,
                    },
                ),
            };
            Some((corr.ok()?, nco))
        })
        .collect()
}

fn samples() -> Vec<Complex<f32>> {
    noise_block(BLOCK)
}

fn noise_block(len: usize) -> Vec<Complex<f32>> {
    let mut x: u32 = 1;
    (0..len)
        .map(|_| {
            x = x.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
            let re = (x >> 16) as f32 / 32768.0 - 1.0;
            x = x.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
            let im = (x >> 16) as f32 / 32768.0 - 1.0;
            Complex::new(re, im)
        })
        .collect()
}

fn correlators(c: &mut Criterion) {
    let block = samples();
    let mut group = c.benchmark_group("correlator_1ms_4092ksps");
    for (name, taps) in [
        (
            "3taps",
            TapSet::Three {
                early_late_spacing_chips: 0.5,
            },
        ),
        (
            "5taps",
            TapSet::Five {
                early_late_spacing_chips: 0.5,
                very_spacing_chips: 1.0,
            },
        ),
    ] {
        let mut chans = channels(taps);
        group.throughput(Throughput::Elements((chans.len() * BLOCK) as u64));
        group.bench_function(format!("{name}_24ch_1thread"), |b| {
            b.iter(|| {
                chans
                    .iter_mut()
                    .map(|(corr, nco)| corr.correlate(&block, nco)[0].re)
                    .sum::<f64>()
            })
        });
        group.bench_function(format!("{name}_24ch_rayon"), |b| {
            b.iter(|| {
                chans
                    .par_iter_mut()
                    .map(|(corr, nco)| corr.correlate(&block, nco)[0].re)
                    .sum::<f64>()
            })
        });
    }
    group.finish();
    let wide = noise_block(WIDE_BLOCK);
    let mut group = c.benchmark_group("correlator_1ms_20460ksps");
    for signal in [
        Signal::GpsL1Ca,
        Signal::GpsL5,
        Signal::GalE5a,
        Signal::GalE1,
        Signal::BdsB1C,
        Signal::BdsB2a,
    ] {
        let mut chans = signal_channels(signal);
        if chans.is_empty() {
            eprintln!("{}: no codes at hand, skipped", signal.name());
            continue;
        }
        group.throughput(Throughput::Elements((chans.len() * WIDE_BLOCK) as u64));
        group.bench_function(format!("{}_12ch_1thread", signal.tag()), |b| {
            b.iter(|| {
                chans
                    .iter_mut()
                    .map(|(corr, nco)| corr.correlate(&wide, nco)[0].re)
                    .sum::<f64>()
            })
        });
    }
    group.finish();
}

/// 0.2 s of GPS PRN 1 at 1 kHz Doppler, code epoch at sample 0, in LCG noise (about
/// 44 dB-Hz).
fn gps_signal(n: usize) -> Vec<Complex<f32>> {
    let code = Signal::GpsL1Ca.code(1).unwrap_or_default();
    let dp = Signal::GpsL1Ca.chip_rate_hz() * (1.0 + 1000.0 / 1575.42e6) / FS_HZ;
    let mut x: u32 = 7;
    let mut noise = move || {
        x = x.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
        ((x >> 16) as f32 / 32768.0 - 1.0) * 1.7
    };
    (0..n)
        .map(|i| {
            let chip = f64::from(code[((i as f64 * dp) as usize) % code.len()]);
            let phi = std::f64::consts::TAU * 1000.0 * i as f64 / FS_HZ;
            let a = 0.12 * chip;
            Complex::new(
                (a * phi.cos()) as f32 + noise(),
                (a * phi.sin()) as f32 + noise(),
            )
        })
        .collect()
}

fn channels_tracking(c: &mut Criterion) {
    let n = (0.2 * FS_HZ) as usize;
    let samples = gps_signal(n);
    let handover = Handover {
        signal: Signal::GpsL1Ca,
        prn: 1,
        sample_index: 0,
        code_phase_samples: 0.0,
        doppler_hz: 1010.0,
        doppler_rate_hzps: 0.0,
    };
    let front_end = FrontEnd {
        sample_rate_hz: FS_HZ,
        if_hz: 0.0,
    };
    // The channel must hold lock over the whole span, or the figure would be inflated.
    let mut check =
        ChannelTracker::new(handover, front_end, TrackingConfig::default()).expect("valid channel");
    let records = check.process(&samples, 0).expect("one block");
    assert!(
        records.len() >= 199,
        "one record per code period: {}",
        records.len()
    );
    assert!(
        records
            .iter()
            .skip(150)
            .all(|r| r.locked && !r.loss_of_lock),
        "{:?}",
        records
            .iter()
            .map(|r| (r.locked, r.pll_lock_indicator as f32))
            .collect::<Vec<_>>()
    );
    let channels = 8;
    let mut group = c.benchmark_group("channel_tracker_0.2s_4092ksps");
    group.sample_size(10);
    group.throughput(Throughput::Elements((channels * n) as u64));
    group.bench_function(format!("{channels}ch_rayon_4092_sample_blocks"), |b| {
        b.iter(|| {
            (0..channels)
                .into_par_iter()
                .map(|_| {
                    let mut ch =
                        ChannelTracker::new(handover, front_end, TrackingConfig::default())
                            .expect("valid channel");
                    samples
                        .chunks(4092)
                        .enumerate()
                        .map(|(k, block)| {
                            ch.process(block, (k * 4092) as u64)
                                .map(|r| r.len())
                                .unwrap_or(0)
                        })
                        .sum::<usize>()
                })
                .sum::<usize>()
        })
    });
    group.finish();
}

criterion_group!(benches, correlators, channels_tracking);
criterion_main!(benches);
