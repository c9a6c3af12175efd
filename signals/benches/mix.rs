//! Mixing kernel throughput: one GPS L1 C/A channel, 4.092 Msps complex, 1 ms blocks.

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use skyforge_signals::synth::{ChannelBlock, Chips, MixScratch, mix_into};

fn mix(c: &mut Criterion) {
    let n = 4092;
    let chips: Vec<i8> = (0..1100)
        .map(|k| if (k * 7919) % 3 == 0 { -1 } else { 1 })
        .collect();
    let ch = ChannelBlock {
        amplitude: 0.1,
        carrier_phase_cycles: 0.123,
        carrier_cycles_per_sample: 0.0110,
        code_phase_chips: 0.4,
        code_chips_per_sample: 0.25 * (1.0 + 2e-6),
        chips: Chips::Signs(&chips),
    };
    let (mut oi, mut oq) = (vec![0f32; n], vec![0f32; n]);
    let mut scratch = MixScratch::default();
    let mut group = c.benchmark_group("mix");
    group.throughput(Throughput::Elements(n as u64));
    group.bench_function("one channel, 4092 samples", |b| {
        b.iter(|| mix_into(&mut oi, &mut oq, &ch, &mut scratch));
    });
    group.finish();
}

criterion_group!(benches, mix);
criterion_main!(benches);
