//! Band-limiting filter throughput: 63 taps on 1 ms blocks at 4.092 Msps, complex
//! baseband (real taps on I and Q), complex at an IF (complex taps), and a real IF.

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use skyforge_signals::synth::{BandFilter, FilterConfig};

fn filter(c: &mut Criterion) {
    let fs = 4.092e6;
    let n = 4092;
    let mut group = c.benchmark_group("filter");
    group.throughput(Throughput::Elements(n as u64));
    for (name, bandwidth_hz, if_hz, complex) in [
        (
            "complex baseband, 63 taps, 4092 samples",
            2.046e6,
            0.0,
            true,
        ),
        ("complex at IF, 63 taps, 4092 samples", 2.046e6, 0.5e6, true),
        ("real IF, 63 taps, 4092 samples", 2.0e6, 1.023e6, false),
    ] {
        let cfg = FilterConfig {
            bandwidth_hz,
            taps: 63,
        };
        let Ok(f) = BandFilter::new(&cfg, fs, if_hz, complex) else {
            panic!("bench filter configuration rejected");
        };
        let m = f.half();
        let xi: Vec<f32> = (0..n + 2 * m)
            .map(|k| ((k * 7919) % 255) as f32 - 127.0)
            .collect();
        let xq: Vec<f32> = (0..n + 2 * m)
            .map(|k| ((k * 104_729) % 255) as f32 - 127.0)
            .collect();
        let (mut oi, mut oq) = (vec![0f32; n], vec![0f32; n]);
        group.bench_function(name, |b| b.iter(|| f.apply(&xi, &xq, &mut oi, &mut oq)));
    }
    group.finish();
}

criterion_group!(benches, filter);
criterion_main!(benches);
