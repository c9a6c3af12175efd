//! The throughput configuration: GPS L1 C/A, 12 satellites, thermal noise on,
//! 4.092 Msps complex, 8-bit output, to a null sink (the bytes stay in memory) and to a
//! `ci8` file on disk. One second of signal for one antenna per iteration;
//! channel-samples per second = 12 x 4.092e6 / time.

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use skyforge_gnss::sample_format::SampleFormat;
use skyforge_orbits::ephemeris::nominal;
use skyforge_signals::synth::SignalConfig;
use skyforge_signals::synth::constellation;
use skyforge_signals::synth::render::{LinkEnd, Synthesiser, append_to};
use std::io::Write;

const CHANNELS: usize = 12;
const FS_HZ: f64 = 4.092e6;

fn synth(c: &mut Criterion) {
    let start = hifitime::Epoch::from_gregorian_str("2023-03-12T00:00:00 GPST").expect("epoch");
    let ephs = nominal::gps(start);
    let iono = skyforge_signals::errors::IonoConfig::default();
    let txs = constellation::gps_l1ca(&ephs[..CHANNELS], start, &iono.gps).expect("transmitters");
    // Plausible ground-receiver links: 20-26 Mm, +-800 m/s.
    let links: Vec<Option<LinkEnd>> = (0..CHANNELS)
        .map(|k| {
            Some(LinkEnd {
                range_m: 2.0e7 + 5.0e5 * k as f64,
                range_rate_mps: -800.0 + 140.0 * k as f64,
                range_accel_mps2: 0.1,
                sat_clock_s: 1e-5,
                sat_clock_drift: 1e-11,
                iono_m: 5.0,
                tropo_m: 2.5,
                antenna_m: 0.0,
                antenna_by_signal_m: Vec::new(),
                cn0_dbhz: 45.0,
                reflections: Vec::new(),
            })
        })
        .collect();
    let cfg = SignalConfig {
        sample_rate_hz: FS_HZ,
        if_hz: 0.0,
        format: SampleFormat::Ci8,
        bits: Some(8),
        truth_rate_hz: 0,
        ..SignalConfig::default()
    };
    let mut group = c.benchmark_group("synth");
    group.sample_size(10);
    group.throughput(Throughput::Elements((CHANNELS as f64 * FS_HZ) as u64));
    // One second of signal for one antenna, rendered from scratch, as ci8 bytes.
    let mut second = 0u64;
    let mut render_second = || {
        let mut synth = Synthesiser::new(&cfg, &txs, 1, 1).expect("synthesiser");
        let mut out = vec![Vec::new()];
        let t0 = second as f64;
        let Ok(()) = synth.push_epoch(t0, links.clone(), &mut append_to(&mut out));
        let Ok(()) = synth.push_epoch(t0 + 1.0, links.clone(), &mut append_to(&mut out));
        second += 1;
        out.swap_remove(0)
    };
    group.bench_function(
        "12 GPS channels, 4.092 Msps ci8, noise, 1 s, null sink",
        |b| b.iter(|| render_second().len()),
    );
    let dir = tempfile::tempdir().expect("temporary directory");
    let mut file = std::fs::File::create(dir.path().join("ant1.ci8")).expect("sample file");
    group.bench_function(
        "12 GPS channels, 4.092 Msps ci8, noise, 1 s, to disk",
        |b| {
            b.iter(|| {
                let bytes = render_second();
                file.write_all(&bytes).expect("write");
                bytes.len()
            });
        },
    );
    group.finish();
}

criterion_group!(benches, synth);
criterion_main!(benches);
