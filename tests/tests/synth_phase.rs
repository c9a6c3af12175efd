//! Issue #3 acceptance: for two antennas 1 m apart (the thesis LEO's ant1 and ant2), the
//! synthesised carrier-phase difference equals the truth (the light-time ranges of the
//! two antennas) to 0.1 mm. Checked by correlating the samples against the known code and
//! carrier, independently of the receiver crate.

use skyforge_orbits::constants::C_MPS;
use skyforge_orbits::ephemeris::{BroadcastEphemeris, EphemerisStore, SatId};
use skyforge_signals::codes::gps_ca::gps_ca;
use skyforge_signals::synth::config::SignalConfig;
use skyforge_signals::synth::constellation;
use skyforge_signals::synth::format::SampleFormat;
use skyforge_signals::synth::render::{LinkEnd, Synthesiser};
use skyforge_signals::truth::geometry::{GeometryChunk, GeometryTruth};
use skyforge_signals::truth::interp::QuinticHermite;

const FS_HZ: f64 = 4.0e6;
const BLOCKS: usize = 200;

fn range_curve(chunk: &GeometryChunk, a: usize, s: usize) -> QuinticHermite {
    let (g0, g1) = (chunk.link(1, a, s), chunk.link(2, a, s));
    QuinticHermite::new(
        chunk.t_s[1],
        chunk.t_s[2],
        [g0.range_m, g0.range_rate_mps, g0.range_accel_mps2],
        [g1.range_m, g1.range_rate_mps, g1.range_accel_mps2],
    )
}

#[test]
fn two_antennas_one_metre_apart_carry_the_true_phase_difference() {
    let scenario = skyforge_scenarios::resolve("thesis-leo").unwrap();
    let mut world = scenario.build().unwrap();
    let start = world.origin.start();
    let ephs: Vec<BroadcastEphemeris> = world
        .satellites
        .iter()
        .filter_map(|&s| world.ephemerides.select(s, 0.0).map(|b| b.eph.clone()))
        .collect();
    let iono = skyforge_signals::errors::ionosphere::IonoConfig::default();
    let txs = constellation::gps_l1ca(&ephs, start, &iono.gps).unwrap();
    let store = EphemerisStore::new(
        txs.iter().map(|t| t.broadcast_ephemeris()).collect(),
        &world.origin,
    );
    let sats: Vec<SatId> = txs.iter().map(|t| t.sat).collect();
    let antennas = &world.antennas[..2];
    assert!((antennas[1].true_body_m - antennas[0].true_body_m).norm() - 1.0 < 1e-12);
    let truth = GeometryTruth::new(&store, &sats, antennas, 1.0);
    let window = world.platform.window(-2.0, 10.0).unwrap();
    let chunk = truth.chunk(&window, 0.0, 4);
    let visible = |s: usize| (1..=2).all(|k| (0..2).all(|a| chunk.link(k, a, s).visible));
    let s = (0..sats.len())
        .find(|&s| visible(s))
        .expect("a GPS satellite visible to both antennas");
    let tx = &txs[s];

    // Synthesise the interval [1 s, 2 s] for this satellite alone, as float samples.
    let cfg = SignalConfig {
        sample_rate_hz: FS_HZ,
        if_hz: 0.0,
        format: SampleFormat::Cf32,
        bits: None,
        cn0_dbhz: 70.0,
        truth_rate_hz: 0,
    };
    let mut synth = Synthesiser::new(&cfg, std::slice::from_ref(tx), 2, 7).unwrap();
    let mut out = vec![Vec::new(), Vec::new()];
    for k in 1..=2 {
        synth.push_epoch(
            chunk.t_s[k],
            (0..2)
                .map(|a| LinkEnd::from_geometry(chunk.link(k, a, s)))
                .collect(),
            &mut out,
        );
    }
    let samples: Vec<Vec<(f32, f32)>> = out
        .iter()
        .map(|bytes| {
            bytes
                .chunks_exact(8)
                .map(|c| {
                    (
                        f32::from_le_bytes(c[0..4].try_into().unwrap()),
                        f32::from_le_bytes(c[4..8].try_into().unwrap()),
                    )
                })
                .collect()
        })
        .collect();
    let n = (FS_HZ * 1e-3) as usize;
    assert_eq!(samples[0].len(), 1000 * n);

    // Replica: the C/A code of the satellite at the code phase of antenna 1, and a carrier at
    // antenna 1's Doppler; both antennas are correlated with the same replica, so only
    // their phase difference matters. The data bit is common to both and cancels.
    let code = gps_ca(tx.sat.prn).unwrap();
    let lambda = C_MPS / tx.signal.carrier_hz();
    let (r1, r2) = (range_curve(&chunk, 0, s), range_curve(&chunk, 1, s));
    let clock = chunk.link(1, 0, s);
    let mut acc = (0.0f64, 0.0f64);
    let mut worst_block_m: f64 = 0.0;
    for b in 0..BLOCKS {
        let t0 = 1.0 + b as f64 * 1e-3;
        let tau = r1.value(t0) / C_MPS;
        let tsv = t0 - tau + clock.sat_clock_s;
        let (k0, phase0) = tx.chip_at(tsv);
        let chips_per_sample = tx.chip_rate_hz / FS_HZ * (1.0 - r1.rate(t0) / C_MPS);
        let fd = -r1.rate(t0) / lambda;
        let mut z = [(0.0f64, 0.0f64); 2];
        for i in 0..n {
            let chip =
                ((k0 + (phase0 + i as f64 * chips_per_sample).floor() as u64) % 1023) as usize;
            let c = f64::from(code[chip]);
            let (sn, cs) = (-std::f64::consts::TAU * fd * i as f64 / FS_HZ).sin_cos();
            for (a, za) in z.iter_mut().enumerate() {
                let (x, y) = samples[a][b * n + i];
                let (x, y) = (f64::from(x) * c, f64::from(y) * c);
                za.0 += x * cs - y * sn;
                za.1 += x * sn + y * cs;
            }
        }
        // z1 conj(z2), rotated by the true phase difference (phi1 - phi2 = (rho2 - rho1)/lambda).
        let tm = t0 + 0.5e-3;
        let truth_cycles = (r2.value(tm) - r1.value(tm)) / lambda;
        let (re, im) = (
            z[0].0 * z[1].0 + z[0].1 * z[1].1,
            z[0].1 * z[1].0 - z[0].0 * z[1].1,
        );
        let (sn, cs) = (-std::f64::consts::TAU * truth_cycles).sin_cos();
        let (re, im) = (re * cs - im * sn, re * sn + im * cs);
        worst_block_m = worst_block_m.max(im.atan2(re).abs() / std::f64::consts::TAU * lambda);
        acc.0 += re;
        acc.1 += im;
    }
    let error_m = acc.1.atan2(acc.0) / std::f64::consts::TAU * lambda;
    println!(
        "{}: phase-difference error {:.4} mm over {BLOCKS} ms (worst single ms {:.3} mm); baseline along LOS {:.4} m",
        tx.sat,
        error_m * 1e3,
        worst_block_m * 1e3,
        r2.value(1.1) - r1.value(1.1)
    );
    assert!(error_m.abs() < 1e-4, "phase difference error {error_m} m");
}
