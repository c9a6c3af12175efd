//! Geometry truth throughput: one hour of the bundled thesis LEO scenario (3 antennas, all
//! embedded GPS + BeiDou satellites, 1 Hz). Multiply by 24 for the 24 h acceptance run.

use criterion::{Criterion, criterion_group, criterion_main};
use skyforge_signals::truth::GeometryTruth;

fn one_hour(c: &mut Criterion) {
    let scenario = skyforge_scenarios::resolve("thesis-leo").expect("bundled scenario");
    let mut world = scenario.build().expect("embedded data");
    let window = world.platform.window(-2.0, 3602.0).expect("propagation");
    let truth = GeometryTruth::new(&world.ephemerides, &world.satellites, &world.antennas, 1.0);
    let mut group = c.benchmark_group("geometry");
    group.sample_size(10);
    group.bench_function("thesis-leo 1 h, 3 antennas, 1 Hz", |b| {
        b.iter(|| truth.chunk(&window, 0.0, 3601))
    });
    group.finish();
}

criterion_group!(benches, one_hour);
criterion_main!(benches);
