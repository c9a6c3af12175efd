//! Reading back what SkyForge's own writer produces: synthesiser output with SigMF metadata
//! (the signal must sit where the geometry puts it, at the amplitude its C/N0 gives), and
//! exact values through the writer's quantiser in every container, in any block size.

use hifitime::Epoch;
use num_complex::{Complex32, Complex64};
use skyforge_gnss::codes::gps_ca;
use skyforge_gnss::sample_format::SampleFormat as WriterFormat;
use skyforge_gnss::sigmf::RecordingMeta;
use skyforge_gnss::signal::Signal;
use skyforge_orbits::constants::C_MPS;
use skyforge_orbits::ephemeris::nominal;
use skyforge_receiver::input::{BlockReader, InputParams, Recording, SampleFormat};
use skyforge_signals::synth::Quantiser;
use skyforge_signals::synth::SignalConfig;
use skyforge_signals::synth::constellation;
use skyforge_signals::synth::render::{LinkEnd, Synthesiser, append_to};
use std::f64::consts::TAU;
use std::path::{Path, PathBuf};

/// An eighth of a C/A chip (m).
const EIGHTH_CHIP_M: f64 = C_MPS / 1.023e6 / 8.0;
const START_UTC: &str = "2023-03-12T00:00:00.000000000Z";

/// Writes `<dir>/<name>.sigmf-data` and its metadata as `skyforge synth` does; returns the
/// metadata path.
fn write_recording(dir: &Path, name: &str, meta: &RecordingMeta, bytes: &[u8]) -> PathBuf {
    std::fs::write(dir.join(format!("{name}.sigmf-data")), bytes).unwrap();
    let path = dir.join(format!("{name}.sigmf-meta"));
    std::fs::write(&path, meta.to_text()).unwrap();
    path
}

fn meta(format: WriterFormat, fs: f64, if_hz: f64, antenna: &str) -> RecordingMeta {
    RecordingMeta {
        format,
        sample_rate_hz: fs,
        centre_frequency_hz: 1575.42e6 - if_hz,
        if_hz,
        datetime_utc: START_UTC.into(),
        antenna_name: antenna.into(),
        antenna_position_body_m: [0.5, -0.25, 0.0],
        scenario: "input-test".into(),
        seed: 7,
        vehicle: None,
        description: "reader test".into(),
        signals: Vec::new(),
    }
}

/// A static link: range `range_m`, nothing else.
fn link(range_m: f64, cn0_dbhz: f64) -> Option<LinkEnd> {
    Some(LinkEnd {
        range_m,
        range_rate_mps: 0.0,
        range_accel_mps2: 0.0,
        sat_clock_s: 0.0,
        sat_clock_drift: 0.0,
        iono_m: 0.0,
        tropo_m: 0.0,
        antenna_m: 0.0,
        antenna_by_signal_m: Vec::new(),
        cn0_dbhz,
        reflections: Vec::new(),
    })
}

/// Synthesises `ms` milliseconds of one GPS satellite for antennas at `ranges_m`; returns
/// each antenna's bytes and the PRN.
fn synthesise(cfg: &SignalConfig, ranges_m: &[f64], cn0_dbhz: f64, ms: u32) -> (Vec<Vec<u8>>, u8) {
    let start = Epoch::from_gregorian_str("2023-03-12T00:00:00 GPST").unwrap();
    let ephs = nominal::gps(start);
    let iono = skyforge_signals::errors::IonoConfig::default();
    let txs = constellation::gps_l1ca(&ephs[..1], start, &iono.gps).unwrap();
    let n = ranges_m.len();
    let mut synth = Synthesiser::new(cfg, &txs, n, 11).unwrap();
    let links: Vec<Option<LinkEnd>> = ranges_m.iter().map(|&r| link(r, cn0_dbhz)).collect();
    let mut out = vec![Vec::new(); n];
    let Ok(()) = synth.push_epoch(0.0, links.clone(), &mut append_to(&mut out));
    let Ok(()) = synth.push_epoch(f64::from(ms) * 1e-3, links, &mut append_to(&mut out));
    (out, txs[0].sat.prn)
}

/// Every delivered sample of every antenna, read in blocks of `block_len`.
fn read_all(recordings: &[Recording], block_len: usize) -> Vec<Vec<Complex32>> {
    let (mut reader, _) = BlockReader::open(recordings, block_len).unwrap();
    let mut bufs = reader.buffers();
    let mut all = vec![Vec::new(); recordings.len()];
    let mut expected_first = 0;
    while let Some(block) = reader.read_block(&mut bufs).unwrap() {
        assert_eq!(block.first_sample, expected_first);
        expected_first += block.len as u64;
        for (a, b) in all.iter_mut().zip(&bufs) {
            assert_eq!(b.len(), block.len);
            a.extend_from_slice(b);
        }
    }
    all
}

/// Mean magnitude over 1 ms windows of the correlation of `y` with the C/A code of `prn`
/// delayed by `delay_s` (zero Doppler): the signal amplitude when the delay is right.
fn correlation(y: &[Complex32], fs: f64, prn: u8, delay_s: f64) -> f64 {
    let code = gps_ca(prn).unwrap();
    let n = (fs * 1e-3).round() as usize;
    let windows = y.len() / n;
    let mut sum = 0.0;
    for w in 0..windows {
        let mut acc = Complex64::new(0.0, 0.0);
        for (k, v) in y.iter().enumerate().skip(w * n).take(n) {
            let chips = (k as f64 / fs - delay_s) * 1.023e6;
            let chip = chips.rem_euclid(1023.0) as usize % 1023;
            acc += Complex64::new(f64::from(v.re), f64::from(v.im)) * f64::from(code[chip]);
        }
        sum += acc.norm() / n as f64;
    }
    sum / windows as f64
}

#[test]
fn synthesised_ci8_recordings_of_two_antennas_hold_the_signal_where_the_geometry_puts_it() {
    let fs = 4.092e6;
    let cfg = SignalConfig {
        sample_rate_hz: fs,
        format: WriterFormat::Ci8,
        bits: Some(8),
        truth_rate_hz: 0,
        ..SignalConfig::default()
    };
    // 67 ms of light time keeps code periods and data bits on whole receiver milliseconds;
    // an eighth of a chip more keeps samples off chip edges (where the writer's and this
    // test's rounding could disagree); the second antenna is 300 m (about one chip)
    // further away.
    let range = 0.067 * C_MPS + EIGHTH_CHIP_M;
    let ranges = [range, range + 300.0];
    let cn0 = 60.0;
    let (bytes, prn) = synthesise(&cfg, &ranges, cn0, 20);
    let dir = tempfile::tempdir().unwrap();
    let recs: Vec<Recording> = ["ant1", "ant2"]
        .iter()
        .zip(&bytes)
        .map(|(name, b)| {
            let path = write_recording(
                dir.path(),
                &format!("{name}.gps-l1ca"),
                &meta(WriterFormat::Ci8, fs, 0.0, name),
                b,
            );
            Recording::open(&path, &InputParams::default()).unwrap()
        })
        .collect();
    for (r, name) in recs.iter().zip(["ant1", "ant2"]) {
        assert_eq!(r.antenna, name);
        assert_eq!(r.format, SampleFormat::Ci8);
        assert_eq!(r.sample_rate_hz, fs);
        assert_eq!(r.if_hz, 0.0);
        assert_eq!(r.signal, Some(Signal::GpsL1Ca));
        assert_eq!(
            r.start_utc,
            Some(Epoch::from_gregorian_utc_at_midnight(2023, 3, 12))
        );
        assert_eq!(r.antenna_position_body_m, Some([0.5, -0.25, 0.0]));
    }
    let (_, report) = BlockReader::open(&recs, 4092).unwrap();
    assert_eq!(report.common_samples, 20 * 4092);
    assert!(report.findings.is_empty(), "{report}");
    assert_eq!(report.signal, Some(Signal::GpsL1Ca));

    let y = read_all(&recs, 4092);
    // Complex baseband: C = A^2, N0 = 2 sigma^2 / fs; the 8-bit writer puts sigma at 25.4
    // units; the reader's full scale is 128 units.
    let amplitude = (2.0 * 10f64.powf(cn0 / 10.0) / fs).sqrt() * 25.4 / 128.0;
    let noise = 25.4 / 128.0;
    for (a, (samples, &range)) in y.iter().zip(&ranges).enumerate() {
        let power =
            samples.iter().map(|v| f64::from(v.norm_sqr())).sum::<f64>() / samples.len() as f64;
        let want = 2.0 * noise * noise + amplitude * amplitude;
        assert!(
            (power / want - 1.0).abs() < 0.02,
            "antenna {a}: power {power}, want {want}"
        );
        let on = correlation(samples, fs, prn, range / C_MPS);
        assert!(
            (on / amplitude - 1.0).abs() < 0.03,
            "antenna {a}: {on} vs {amplitude}"
        );
        // The other antenna's delay is a chip off: no correlation there.
        let other = ranges[1 - a] / C_MPS;
        assert!(correlation(samples, fs, prn, other) < 0.1 * amplitude);
    }
}

#[test]
fn synthesised_real_if_recording_is_mixed_to_baseband() {
    let (fs, f_if) = (8.184e6, 1.9e6);
    let cfg = SignalConfig {
        sample_rate_hz: fs,
        if_hz: f_if,
        format: WriterFormat::Ri8,
        bits: Some(8),
        truth_rate_hz: 0,
        ..SignalConfig::default()
    };
    let range = 0.071 * C_MPS + EIGHTH_CHIP_M;
    let cn0 = 60.0;
    let (bytes, prn) = synthesise(&cfg, &[range], cn0, 10);
    let dir = tempfile::tempdir().unwrap();
    let path = write_recording(
        dir.path(),
        "ant1.gps-l1ca",
        &meta(WriterFormat::Ri8, fs, f_if, "ant1"),
        &bytes[0],
    );
    let rec = Recording::open(&path, &InputParams::default()).unwrap();
    assert_eq!((rec.format, rec.if_hz), (SampleFormat::Ri8, f_if));
    assert_eq!(rec.signal, Some(Signal::GpsL1Ca));
    let (reader, _) = BlockReader::open(std::slice::from_ref(&rec), 1000).unwrap();
    assert_eq!(reader.output_if_hz(), 0.0);
    let y = read_all(&[rec], 1000);
    // Real: C = A^2 / 2, N0 = 2 sigma^2 / fs; mixing by 2 exp(-j IF) leaves a phasor of
    // amplitude A at 0 Hz.
    let amplitude = (4.0 * 10f64.powf(cn0 / 10.0) / fs).sqrt() * 25.4 / 128.0;
    let on = correlation(&y[0], fs, prn, range / C_MPS);
    assert!((on / amplitude - 1.0).abs() < 0.04, "{on} vs {amplitude}");
    assert!(correlation(&y[0], fs, prn, range / C_MPS + 0.4e-3) < 0.1 * amplitude);
}

/// Pseudo-random values in about +-3 full scales of `unit`.
fn values(n: usize, unit: f32, seed: u32) -> Vec<f32> {
    let mut x = seed;
    (0..n)
        .map(|_| {
            x = x.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
            (x as i32) as f32 / i32::MAX as f32 * 3.0 * unit
        })
        .collect()
}

#[test]
fn writer_values_come_back_at_the_documented_full_scale_in_any_block_size() {
    let n = 10_007;
    let dir = tempfile::tempdir().unwrap();
    // (format, bits, noise sigma giving the quantiser a scale of 1 unit per input unit,
    // the unit the values are drawn in, the reader's full scale).
    let cases = [
        (WriterFormat::Ci8, Some(8), 25.4, 40.0, 128.0),
        (WriterFormat::Ci16, Some(16), 4096.0, 10_000.0, 32768.0),
        (WriterFormat::Cf32, None, 1.0, 1.0, 1.0),
    ];
    for (format, bits, sigma, unit, full_scale) in cases {
        let (i, q) = (values(n, unit, 1), values(n, unit, 2));
        let mut bytes = Vec::new();
        Quantiser::new(format, bits, sigma)
            .unwrap()
            .write(&i, &q, &mut bytes);
        let name = format!("ant.{}", format.sigmf_datatype());
        let path = write_recording(dir.path(), &name, &meta(format, 2.6e6, 0.0, "ant"), &bytes);
        let rec = Recording::open(&path, &InputParams::default()).unwrap();
        let reference = read_all(std::slice::from_ref(&rec), 4096);
        assert_eq!(reference[0].len(), n);
        for (k, v) in reference[0].iter().enumerate() {
            // The writer's levels: round half away from zero, saturating (8 and 16 bits).
            let level = |x: f32| match format {
                WriterFormat::Cf32 => x,
                _ => {
                    let max = if format == WriterFormat::Ci8 {
                        127.0
                    } else {
                        32767.0
                    };
                    x.round().clamp(-max, max)
                }
            };
            assert_eq!(v.re, level(i[k]) / full_scale, "{format:?} sample {k}");
            assert_eq!(v.im, level(q[k]) / full_scale, "{format:?} sample {k}");
        }
        for block_len in [1, 37, 4092, 1 << 20] {
            assert_eq!(
                read_all(std::slice::from_ref(&rec), block_len),
                reference,
                "{format:?}, blocks of {block_len}"
            );
        }
    }
    // Real IF: the mixer output depends on the block length only by rounding.
    let (fs, f_if) = (5.456e6, 1.364e6 + 17.0);
    let x = values(n, 40.0, 3);
    let mut bytes = Vec::new();
    Quantiser::new(WriterFormat::Ri8, Some(8), 25.4)
        .unwrap()
        .write(&x, &x, &mut bytes);
    let path = write_recording(
        dir.path(),
        "ant.ri8",
        &meta(WriterFormat::Ri8, fs, f_if, "ant"),
        &bytes,
    );
    let rec = Recording::open(&path, &InputParams::default()).unwrap();
    let reference = read_all(std::slice::from_ref(&rec), 4096);
    for (k, v) in reference[0].iter().enumerate() {
        let level = f64::from(x[k].round().clamp(-127.0, 127.0)) / 128.0;
        let want = Complex64::from_polar(2.0 * level, -TAU * f_if * k as f64 / fs);
        assert!((f64::from(v.re) - want.re).abs() < 1e-5, "ri8 sample {k}");
        assert!((f64::from(v.im) - want.im).abs() < 1e-5, "ri8 sample {k}");
    }
    for block_len in [1, 37, 4092, 1 << 20] {
        let y = read_all(std::slice::from_ref(&rec), block_len);
        for (p, q) in y[0].iter().zip(&reference[0]) {
            assert!((p - q).norm() < 1e-5, "ri8, blocks of {block_len}");
        }
    }
}

#[test]
fn gps_sdr_sim_style_raw_iq_reads_with_command_line_parameters() {
    // 16-bit I/Q at 2.6 Msps, as gps-sdr-sim writes by default: raw ci16.
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("gpssim.bin");
    let iq: Vec<i16> = vec![1000, -1000, 32767, -32768, 0, 5];
    let bytes: Vec<u8> = iq.iter().flat_map(|v| v.to_le_bytes()).collect();
    std::fs::write(&path, bytes).unwrap();
    let params = InputParams {
        format: Some(WriterFormat::Ci16),
        sample_rate_hz: Some(2.6e6),
        if_hz: None,
        signal: Some("gps-l1ca".parse().unwrap()),
    };
    let (_, report) = BlockReader::open_paths(&[&path], &params, 2).unwrap();
    assert_eq!(report.common_samples, 3);
    assert_eq!(report.signal, Some(Signal::GpsL1Ca));
    let rec = Recording::open(&path, &params).unwrap();
    assert_eq!(rec.antenna, "gpssim");
    assert_eq!(rec.centre_frequency_hz, Some(1575.42e6));
    let y = read_all(&[rec], 2);
    let want: Vec<Complex32> = iq
        .chunks(2)
        .map(|c| Complex32::new(f32::from(c[0]) / 32768.0, f32::from(c[1]) / 32768.0))
        .collect();
    assert_eq!(y[0], want);
}
