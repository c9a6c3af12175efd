//! Issue #3 acceptance: for two antennas 1 m apart (the thesis LEO's ant1 and ant2), the
//! synthesised carrier-phase difference equals the truth (the light-time ranges of the
//! two antennas, their phase-centre offset and variation, and a reflected path on the
//! second antenna) to 0.1 mm. Checked by correlating the samples against the known code and
//! carrier, independently of the receiver crate.

mod common;

use skyforge_gnss::codes::gps_ca;
use skyforge_gnss::sample_format::SampleFormat;
use skyforge_gnss::signal::Signal;
use skyforge_orbits::constants::C_MPS;
use skyforge_signals::antenna::{AntennaGrid, PhaseCentre};
use skyforge_signals::errors::{IonoConfig, IonoModel};
use skyforge_signals::errors::{MultipathConfig, TapConfig};
use skyforge_signals::errors::{TropoConfig, TropoModel};
use skyforge_signals::synth::SignalConfig;
use skyforge_signals::synth::render::{Synthesiser, append_to};
use skyforge_signals::synth::{AntennaEpoch, LinkTerms};
use skyforge_signals::truth::QuinticHermite;
use skyforge_signals::truth::{GeometryChunk, GeometryTruth};

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
    assert_eq!(world.antennas[0].pco_m, skyforge_orbits::Vec3::zeros());
    let (txs, store, sats) = common::gps_transmitters(&world);
    // The second antenna gets, for GPS L1 C/A, a phase-centre offset and a phase-centre
    // variation grid (5 mm x sin(zenith) cos(azimuth)) of its own, a different offset for
    // the other signals (which L1 C/A must not follow), and a reflected path.
    world.antennas[1].pco_m = skyforge_orbits::Vec3::new(0.0, 0.01, 0.1);
    let l1_pco_m = skyforge_orbits::Vec3::new(0.002, -0.003, 0.06);
    let (zen, az): (Vec<f64>, Vec<f64>) = (
        (0..=18).map(|i| f64::from(i) * 5.0).collect(),
        (0..=36).map(|j| f64::from(j) * 10.0).collect(),
    );
    let values = zen
        .iter()
        .flat_map(|z| {
            az.iter()
                .map(move |a| 0.005 * z.to_radians().sin() * a.to_radians().cos())
        })
        .collect();
    let l1_centre = PhaseCentre {
        pco_m: l1_pco_m,
        pcv_m: Some(AntennaGrid {
            zenith_deg: zen,
            azimuth_deg: az,
            values,
        }),
    };
    world.antennas[1].phase_centres = vec![(Signal::GpsL1Ca, l1_centre)];
    let tap = TapConfig {
        antenna: Some(world.antennas[1].name.clone()),
        satellite: None,
        delay_m: 2.0,
        relative_amplitude: 0.3,
        phase_deg: 40.0,
        doppler_hz: 0.0,
    };
    let multipath = MultipathConfig {
        taps: vec![tap.clone()],
        surfaces: Vec::new(),
    };
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
        format: SampleFormat::Cf32,
        cn0_dbhz: 70.0,
        truth_rate_hz: 0,
        ..SignalConfig::default()
    };
    let iono = IonoConfig {
        model: IonoModel::Off,
        ..IonoConfig::default()
    };
    let tropo = TropoConfig {
        model: TropoModel::Off,
        ..TropoConfig::default()
    };
    let terms = LinkTerms {
        signal: &cfg,
        ionosphere: &iono,
        troposphere: &tropo,
        multipath: &multipath,
        antennas,
    };
    let mut synth = Synthesiser::new(&cfg, std::slice::from_ref(tx), 2, 7).unwrap();
    let mut out = vec![Vec::new(), Vec::new()];
    for k in 1..=2 {
        let links = (0..2)
            .map(|a| {
                let at = AntennaEpoch::new(&chunk.platform[k], &antennas[a]);
                terms.link_end(
                    chunk.t_s[k],
                    0.0,
                    a,
                    &at,
                    tx.sat,
                    tx.signal,
                    chunk.link(k, a, s),
                )
            })
            .collect();
        let Ok(()) = synth.push_epoch(chunk.t_s[k], links, &mut append_to(&mut out));
    }
    // Phase-centre delay of each antenna at the two epochs (linear in between).
    let centre = |a: usize, k: usize| {
        let g = chunk.link(k, a, s);
        antennas[a].phase_centre_delay_m(tx.signal, g.antenna_azimuth_rad, g.antenna_elevation_rad)
    };
    let centre_at = |a: usize, t: f64| {
        let (c1, c2) = (centre(a, 1), centre(a, 2));
        c1 + (c2 - c1) * (t - chunk.t_s[1]) / (chunk.t_s[2] - chunk.t_s[1])
    };
    let samples: Vec<Vec<(f32, f32)>> = out.iter().map(|b| common::cf32_samples(b)).collect();
    let n = (FS_HZ * 1e-3) as usize;
    assert_eq!(samples[0].len(), 1000 * n);

    // Replica: the C/A code of the satellite at the code phase of antenna 1, and a carrier at
    // antenna 1's Doppler; both antennas are correlated with the same replica, so only
    // their phase difference matters. The data bit is common to both and cancels.
    let code = gps_ca(tx.sat.prn).unwrap();
    let lambda = tx.signal.wavelength_m();
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
        // z1 conj(z2), rotated by the true phase difference: phi1 - phi2 = (rho2 + c2 - rho1
        // - c1) / lambda (c: phase-centre delays) minus the phase the reflection adds to
        // antenna 2's correlation: arg(R(d) + a R(d + delay) e^{j(theta - 2 pi delay /
        // lambda)}), R the triangular code correlation, d antenna 2's code offset from the
        // replica.
        let tm = t0 + 0.5e-3;
        let chip_m = C_MPS / tx.chip_rate_hz;
        let corr = |x: f64| (1.0 - x.abs() / chip_m).max(0.0);
        let d = r2.value(tm) + centre_at(1, tm) - r1.value(tm);
        let psi = tap.phase_deg.to_radians() - std::f64::consts::TAU * tap.delay_m / lambda;
        let reflected = tap.relative_amplitude * corr(d + tap.delay_m);
        let mp = (reflected * psi.sin()).atan2(corr(d) + reflected * psi.cos());
        let truth_cycles = (r2.value(tm) + centre_at(1, tm) - r1.value(tm) - centre_at(0, tm))
            / lambda
            - mp / std::f64::consts::TAU;
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
