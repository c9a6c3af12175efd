//! End-to-end check of real-IF output: `skyforge synth` writes 8-bit real samples (`ri8`) at
//! a 4.092 MHz IF and 16.368 Msps; a correlator written here, independent of the receiver
//! crate, finds each satellite at the code phase, Doppler and carrier phase that truth.h5
//! states, with the scenario's C/N0.
//!
//! Signal model checked (docs/truth-h5.md): a sample at receive time t carries the C/A code
//! at chip `1.023e6 (t - pseudorange / c)` and the carrier phase
//! `IF t - carrier_phase_cycles(t)` (cycles), so `x = A d c cos(2 pi phase) + noise`.

mod support;

use skyforge_gnss::codes::{GPS_CA_CHIP_RATE_HZ, GPS_CA_CODE_LENGTH, gps_ca};
use skyforge_orbits::constants::{C_MPS, F_GPS_L1_HZ};
use std::path::Path;
use std::process::Command;
use support::dataset;

const FS_HZ: f64 = 16.368e6;
const IF_HZ: f64 = 4.092e6;
/// Samples per 1 ms block.
const N: usize = 16_368;
/// Satellites in the scenario (visible from 30 N 114 E at the bundled start time).
const PRNS: [u8; 2] = [5, 24];
/// A satellite not in the signal.
const ABSENT_PRN: u8 = 1;
/// Doppler search step (Hz): 1 ms coherent, so a half-bin away loses 60 % of the power.
const DOPPLER_STEP_HZ: f64 = 500.0;
const DOPPLER_BINS: i32 = 4;
/// Code search half-width (samples; 16 samples per chip).
const CODE_SAMPLES: i32 = 24;

/// Truth of one link at the start of one 1 ms block.
#[derive(Debug, Clone, Copy)]
struct BlockTruth {
    pseudorange_m: f64,
    carrier_phase_cycles: f64,
    doppler_hz: f64,
}

/// Truth of one satellite for every 1 ms block of the run (index = block).
type Blocks = Vec<Option<BlockTruth>>;

/// The bundled GPS interop scenario, 2 s of real samples at an IF, two satellites.
fn write_scenario(dir: &Path) {
    let o = Command::new(env!("CARGO_BIN_EXE_skyforge"))
        .args(["scenarios", "show", "interop-gps-static"])
        .output()
        .expect("run skyforge");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let base = String::from_utf8(o.stdout).expect("UTF-8 scenario");
    let mut text = String::new();
    let mut seen = Vec::new();
    for line in base.lines() {
        let key = line.split('=').next().unwrap_or("").trim();
        let replaced = match key {
            "duration_s" => "duration_s = 2.0".to_string(),
            "sample_rate_hz" => format!("sample_rate_hz = {FS_HZ:e}"),
            "if_hz" => format!("if_hz = {IF_HZ:e}"),
            "format" => "format = \"ri8\"".to_string(),
            "bits" => "bits = 8".to_string(),
            "cn0_dbhz" => "cn0_dbhz = 45.0".to_string(),
            _ => line.to_string(),
        };
        if replaced != line {
            seen.push(key.to_string());
        }
        text.push_str(&replaced);
        text.push('\n');
        if line.trim() == "[gnss.gps]" {
            text.push_str(&format!("prns = {PRNS:?}\n"));
        }
    }
    assert!(
        seen.len() >= 3 && text.contains("prns"),
        "the bundled scenario changed shape: {seen:?}"
    );
    std::fs::write(dir.join("if.toml"), text).expect("write scenario");
}

/// Per PRN, the truth of every 1 ms block (index = block), from truth.h5.
fn read_truth(path: &Path) -> (Vec<(u8, Blocks)>, f64) {
    let file = hdf5::File::open(path).expect("open truth.h5");
    let ids: Vec<hdf5::types::VarLenUnicode> = dataset(&file, "satellites/id");
    let s = file.group("antennas/ant1/signal").expect("signal truth");
    let read = |name: &str| -> Vec<f64> { dataset(&s, name) };
    let (t, pr, cp, dopp) = (
        read("t_s"),
        read("pseudorange_m"),
        read("carrier_phase_cycles"),
        read("doppler_hz"),
    );
    let sat: Vec<u16> = dataset(&s, "sat_index");
    let cn0: Vec<f64> = dataset(&s, "cn0_dbhz");
    let per_prn = PRNS
        .iter()
        .map(|&prn| {
            let mut blocks = vec![None; 2000];
            for i in 0..t.len() {
                if ids[sat[i] as usize].as_str() == format!("G{prn:02}") {
                    blocks[(t[i] * 1e3).round() as usize] = Some(BlockTruth {
                        pseudorange_m: pr[i],
                        carrier_phase_cycles: cp[i],
                        doppler_hz: dopp[i],
                    });
                }
            }
            assert!(
                blocks.iter().all(Option::is_some),
                "G{prn:02} not visible for the whole run"
            );
            (prn, blocks)
        })
        .collect();
    (per_prn, cn0[0])
}

/// Whether a data-bit edge (satellite time a multiple of 20 ms; the scenario starts on a
/// whole GPS second) falls inside block `b`.
fn has_bit_edge(b: usize, truth: &BlockTruth) -> bool {
    let t_sv_ms = b as f64 - truth.pseudorange_m / C_MPS * 1e3;
    let into_bit_ms = t_sv_ms.rem_euclid(20.0);
    into_bit_ms > 19.0 || into_bit_ms == 0.0
}

/// Correlator of one satellite over one 1 ms block: carrier wiped off once per Doppler
/// hypothesis, then the code replica at any code offset.
struct Block {
    z_re: Vec<f64>,
    z_im: Vec<f64>,
    /// Code phase (chips) at the block's first sample, and chips per sample.
    chip0: f64,
    chips_per_sample: f64,
}

impl Block {
    /// Block `b` of `x` wiped off with the truth carrier plus `doppler_offset_hz`.
    fn new(x: &[i8], b: usize, truth: &BlockTruth, doppler_offset_hz: f64) -> Self {
        let t_b = b as f64 * 1e-3;
        let phase0 = (IF_HZ * t_b - truth.carrier_phase_cycles).rem_euclid(1.0);
        let cycles_per_sample = (IF_HZ + truth.doppler_hz + doppler_offset_hz) / FS_HZ;
        let (mut z_re, mut z_im) = (Vec::with_capacity(N), Vec::with_capacity(N));
        for (k, &v) in x[b * N..(b + 1) * N].iter().enumerate() {
            let (s, c) =
                (2.0 * std::f64::consts::PI * (phase0 + cycles_per_sample * k as f64)).sin_cos();
            z_re.push(f64::from(v) * c);
            z_im.push(-f64::from(v) * s);
        }
        let chip_rate = GPS_CA_CHIP_RATE_HZ * (1.0 + truth.doppler_hz / F_GPS_L1_HZ);
        Self {
            z_re,
            z_im,
            chip0: (GPS_CA_CHIP_RATE_HZ * (t_b - truth.pseudorange_m / C_MPS))
                .rem_euclid(GPS_CA_CODE_LENGTH as f64),
            chips_per_sample: chip_rate / FS_HZ,
        }
    }

    /// Correlation with `code` shifted by `offset_chips` from the truth code phase.
    fn correlate(&self, code: &[i8; GPS_CA_CODE_LENGTH], offset_chips: f64) -> (f64, f64) {
        let len = GPS_CA_CODE_LENGTH as f64;
        let start = (self.chip0 + offset_chips).rem_euclid(len);
        let (mut re, mut im) = (0.0, 0.0);
        for k in 0..N {
            let chip = (start + self.chips_per_sample * k as f64) as usize % GPS_CA_CODE_LENGTH;
            let c = f64::from(code[chip]);
            re += self.z_re[k] * c;
            im += self.z_im[k] * c;
        }
        (re, im)
    }
}

fn power((re, im): (f64, f64)) -> f64 {
    re * re + im * im
}

/// Code offsets for the noise floor: spread over the code period, at least 40 chips away
/// from the peak (C/A autocorrelation sidelobes are 24 dB down there, as anywhere).
fn noise_offsets_chips() -> impl Iterator<Item = f64> {
    (0..16).map(|i| 40.0 + 59.0 * f64::from(i))
}

#[test]
fn ri8_at_an_if_correlates_at_the_truth_code_doppler_phase_and_cn0() {
    let tmp = tempfile::tempdir().expect("temp dir");
    write_scenario(tmp.path());
    let o = Command::new(env!("CARGO_BIN_EXE_skyforge"))
        .args(["synth", "if.toml", "--out", "out"])
        .current_dir(tmp.path())
        .output()
        .expect("run skyforge");
    assert!(
        o.status.success(),
        "{}{}",
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr)
    );
    let out = tmp.path().join("out");
    let bytes = std::fs::read(out.join("ant1.gps-l1ca.sigmf-data")).expect("samples");
    assert_eq!(bytes.len(), 2000 * N, "2 s of one-byte real samples");
    let x: Vec<i8> = bytes.iter().map(|&b| b as i8).collect();
    let meta = std::fs::read_to_string(out.join("ant1.gps-l1ca.sigmf-meta")).expect("meta");
    assert!(meta.contains("\"ri8\""), "{meta}");
    let (truth, cn0_dbhz) = read_truth(&out.join("truth.h5"));
    assert_eq!(cn0_dbhz, 45.0);
    let absent = gps_ca(ABSENT_PRN).expect("C/A code");

    for (prn, blocks) in &truth {
        let code = gps_ca(*prn).expect("C/A code");
        let at = |b: usize| blocks[b].expect("truth for every block");

        // Search: 10 ms without a data-bit edge from 0.5 s on, summed non-coherently.
        let first = (500..)
            .find(|&b| (b..b + 10).all(|k| !has_bit_edge(k, &at(k))))
            .expect("a 10 ms span without bit edge");
        let mut best = (f64::MIN, 0, 0);
        let mut best_absent = f64::MIN;
        for m in -DOPPLER_BINS..=DOPPLER_BINS {
            let wiped: Vec<Block> = (first..first + 10)
                .map(|b| Block::new(&x, b, &at(b), f64::from(m) * DOPPLER_STEP_HZ))
                .collect();
            for d in -CODE_SAMPLES..=CODE_SAMPLES {
                let offset = f64::from(d) * GPS_CA_CHIP_RATE_HZ / FS_HZ;
                let p: f64 = wiped
                    .iter()
                    .map(|w| power(w.correlate(&code, offset)))
                    .sum();
                if p > best.0 {
                    best = (p, m, d);
                }
                let p: f64 = wiped
                    .iter()
                    .map(|w| power(w.correlate(&absent, offset)))
                    .sum();
                best_absent = best_absent.max(p);
            }
        }
        let (peak, m, d) = best;
        assert_eq!(m, 0, "G{prn:02}: peak {m} Doppler bins from the truth");
        assert!(
            d.abs() <= 1,
            "G{prn:02}: peak {d} samples from the truth code phase"
        );

        // C/N0 and carrier phase over ~1.8 s of 1 ms blocks at the truth code and Doppler,
        // the noise floor from far code offsets.
        let (mut p_peak, mut p_noise, mut n_peak, mut n_noise) = (0.0, 0.0, 0, 0);
        let (mut sq_re, mut sq_im) = (0.0, 0.0);
        for b in (100..1990).step_by(5).filter(|&b| !has_bit_edge(b, &at(b))) {
            let w = Block::new(&x, b, &at(b), 0.0);
            let (re, im) = w.correlate(&code, 0.0);
            p_peak += re * re + im * im;
            n_peak += 1;
            // The data bit flips the sign: average the doubled phase.
            let r2 = re * re + im * im;
            sq_re += (re * re - im * im) / r2;
            sq_im += 2.0 * re * im / r2;
            for off in noise_offsets_chips() {
                p_noise += power(w.correlate(&code, off));
                n_noise += 1;
            }
        }
        let (p_peak, p_noise) = (p_peak / f64::from(n_peak), p_noise / f64::from(n_noise));
        // Per 1 ms: |Y|^2 = (A N / 2)^2 + sigma^2 N and the floor sigma^2 N, so
        // (peak - floor) / floor = A^2 N / (4 sigma^2) = C/N0 x 1 ms (C = A^2/2, N0 = 2 sigma^2/fs).
        let cn0_est = 10.0 * ((p_peak - p_noise) / p_noise / 1e-3).log10();
        let phase_rad = sq_im.atan2(sq_re) / 2.0;
        println!(
            "G{prn:02}: peak at code {d} samples, Doppler bin {m}; C/N0 {cn0_est:.2} dB-Hz \
             (scenario {cn0_dbhz}); carrier phase error {phase_rad:.4} rad; \
             absent PRN {ABSENT_PRN} / peak: {:.4}",
            best_absent / peak
        );
        assert!(
            (cn0_est - cn0_dbhz).abs() < 1.0,
            "G{prn:02}: C/N0 {cn0_est} dB-Hz, scenario {cn0_dbhz}"
        );
        // 1 ms post-correlation SNR 15 dB: about 0.13 rad per block, 0.01 rad averaged.
        assert!(
            phase_rad.abs() < 0.05,
            "G{prn:02}: carrier phase {phase_rad} rad off the truth"
        );
        // A code that is not transmitted sees only noise: on average 1 / (1 + C/N0 x 1 ms)
        // = 1/33 of the peak, its maximum over the grid about twice that.
        assert!(
            best_absent < 0.2 * peak,
            "PRN {ABSENT_PRN} (not transmitted) correlates at {best_absent} vs {peak}"
        );
    }
}
