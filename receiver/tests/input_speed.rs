//! Read throughput of the block reader: 3 antennas at 4.092 Msps, blocks of 1 ms, every
//! container. Measures and prints (MB/s of file bytes, and the multiple of real time);
//! asserts nothing about time. Run: `cargo test --release -p skyforge-receiver --test
//! input_speed -- --ignored --nocapture`. The files are freshly written, so they are read
//! from the page cache: this is the reader's own cost, not the disk's.

use serde_json::json;
use skyforge_receiver::input::{BlockReader, InputParams, Recording, SampleFormat};
use std::io::Write;
use std::time::Instant;

const FS_HZ: f64 = 4.092e6;
const ANTENNAS: usize = 3;
const SECONDS: usize = 10;

#[test]
#[ignore = "speed measurement: cargo test --release --test input_speed -- --ignored --nocapture"]
fn read_speed_three_antennas_at_4_092_msps() {
    let dir = tempfile::tempdir().unwrap();
    for format in SampleFormat::ALL {
        let bps = format.bytes_per_sample();
        let mut recs = Vec::new();
        for a in 0..ANTENNAS {
            let name = format!("ant{a}.{}", format.sigmf_datatype());
            let mut f = std::io::BufWriter::new(
                std::fs::File::create(dir.path().join(format!("{name}.sigmf-data"))).unwrap(),
            );
            let mut x: u32 = 12345 + a as u32;
            let mut chunk = vec![0u8; 1 << 20];
            let mut left = SECONDS * FS_HZ as usize * bps;
            while left > 0 {
                for b in chunk.iter_mut() {
                    x = x.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
                    // Small values only for cf32 (no NaNs): keep the top byte of each word 0x3f.
                    *b = (x >> 24) as u8;
                }
                if format == SampleFormat::Cf32 {
                    for w in chunk.chunks_exact_mut(4) {
                        w[3] = 0x3f;
                    }
                }
                let n = left.min(chunk.len());
                f.write_all(&chunk[..n]).unwrap();
                left -= n;
            }
            f.flush().unwrap();
            let meta = json!({
                "global": {"core:datatype": format.sigmf_datatype(), "core:sample_rate": FS_HZ,
                           "core:version": "1.0.0", "skyforge:if_hz": 1.023e6},
                "captures": [{"core:sample_start": 0, "core:frequency": 1575.42e6 - 1.023e6}],
            });
            let path = dir.path().join(format!("{name}.sigmf-meta"));
            std::fs::write(&path, meta.to_string()).unwrap();
            recs.push(Recording::open(&path, &InputParams::default()).unwrap());
        }
        // Best of three passes (the first may still compete with the write-back).
        for pass in 0..3 {
            let started = Instant::now();
            let (mut reader, report) = BlockReader::open(&recs, 4092).unwrap();
            let mut bufs = reader.buffers();
            let mut check = 0.0f32;
            while let Some(b) = reader.read_block(&mut bufs).unwrap() {
                check += bufs[0][b.len - 1].re;
            }
            let s = started.elapsed().as_secs_f64();
            let bytes = (report.common_samples as usize * bps * ANTENNAS) as f64;
            println!(
                "{format} pass {pass}: {ANTENNAS} antennas x {SECONDS} s at {FS_HZ} sps: {:.0} MB/s, {:.0} Msps per antenna, {:.0}x real time (check {check})",
                bytes / s / 1e6,
                report.common_samples as f64 / s / 1e6,
                report.duration_s() / s
            );
        }
    }
}

#[test]
#[ignore = "speed measurement: cargo test --release --test input_speed -- --ignored --nocapture"]
fn decode_speed_in_memory() {
    use num_complex::Complex32;
    use skyforge_receiver::input::IfMixer;
    use skyforge_receiver::input::{decode_cf32, decode_ci8, decode_ci16, decode_ri8};
    let n = 4092;
    let blocks = 20_000;
    let bytes: Vec<u8> = (0..8 * n).map(|k| (k * 37 % 251) as u8 & 0x3f).collect();
    let mut out = vec![Complex32::new(0.0, 0.0); n];
    let mut real = vec![0.0f32; n];
    let mut mixer = IfMixer::new(1.023e6 + 3.0, FS_HZ, n);
    for format in SampleFormat::ALL {
        let started = Instant::now();
        let mut check = 0.0f32;
        for _ in 0..blocks {
            let b = &bytes[..n * format.bytes_per_sample()];
            match format {
                SampleFormat::Ci8 => _ = decode_ci8(b, &mut out),
                SampleFormat::Ci16 => _ = decode_ci16(b, &mut out),
                SampleFormat::Cf32 => _ = decode_cf32(b, &mut out),
                SampleFormat::Ri8 => {
                    decode_ri8(b, &mut real);
                    mixer.mix(&real, &mut out);
                }
            }
            check += out[n - 1].re;
        }
        let s = started.elapsed().as_secs_f64();
        let samples = (n * blocks) as f64;
        println!(
            "{format} decode only: {:.0} MB/s, {:.0} Msps (check {check})",
            samples * format.bytes_per_sample() as f64 / s / 1e6,
            samples / s / 1e6
        );
    }
}
