//! Correlator throughput (issue #4 speed bar: at least 5e8 channel-samples/s on the
//! 2-core machine with 3 correlators and complex input). One 1 ms block at 4.092 Msps is
//! correlated by 24 channels (12 GPS + 12 BeiDou PRNs, distinct Doppler and code phase),
//! single-threaded and with rayon over the channels.

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use num_complex::Complex;
use rayon::prelude::*;
use skyforge_receiver::tracking::correlator::{Correlator, NcoState, TapSet};
use skyforge_receiver::tracking::signal::SignalKind;

const FS_HZ: f64 = 4.092e6;
const BLOCK: usize = 4092;

fn channels(taps: TapSet) -> Vec<(Correlator, NcoState)> {
    (1..=12u8)
        .flat_map(|prn| [(SignalKind::GpsL1Ca, prn), (SignalKind::BdsB1I, prn + 6)])
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

fn samples() -> Vec<Complex<f32>> {
    let mut x: u32 = 1;
    (0..BLOCK)
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
}

criterion_group!(benches, correlators);
criterion_main!(benches);
