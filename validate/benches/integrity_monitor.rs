//! The B-value monitor over paper 002's lab (issue #15 bar: 1800 s of four receivers at
//! 1 Hz in well under a second). The observation-level run of the bundled `integrity-lab`
//! scenario (1800 epochs, four stations, GPS + BeiDou, about 20 satellites above the
//! mask) is made once; `monitor/lab-1800s` times `integrity::files::run_files` over it:
//! alignment, mapping to the common point, Hatch filters, divergence, B values, alarms.

use criterion::{Criterion, criterion_group, criterion_main};
use skyforge_navigation::integrity::{run_files, stations};
use skyforge_runner::observation_run;
use skyforge_validate::integrity::scenario;
use std::hint::black_box;

fn monitor(c: &mut Criterion) {
    let run = observation_run(&scenario(&[], 2002, None).expect("lab")).expect("run");
    let cfg = skyforge_navigation::integrity::MonitorConfig::parse(
        skyforge_scenarios::BUNDLED_MONITOR_CONFIG,
    )
    .expect("bundled configuration");
    let stations = stations(&run.measured, &run.antennas, &cfg).expect("station positions");
    let mut group = c.benchmark_group("monitor");
    group.sample_size(10);
    group.bench_function("lab-1800s", |b| {
        b.iter(|| {
            let mut values = 0usize;
            run_files(
                &run.measured,
                stations.clone(),
                run.ephemerides.clone(),
                cfg.clone(),
                |e| values += e.sats.len(),
            )
            .expect("monitor");
            black_box(values)
        })
    });
    group.finish();
}

criterion_group!(benches, monitor);
criterion_main!(benches);
