//! The fuzz targets of SkyForge's input readers, defined once: `fuzz/` (cargo-fuzz,
//! libFuzzer) runs them for minutes; `tests/replay.rs` replays the committed corpus and
//! regressions through them and runs a short deterministic mutation loop in the default
//! test suite. See `docs/fuzzing.md`.
//!
//! Each target hands its input to a real reader and ignores the result (error messages
//! are formatted, since locating an error is code too): a panic, an abort or an allocation
//! that grows with a number in the input rather than with the input's size is the bug.

use skyforge_gnss::observation::{rinex_read, rinex2_read};
use skyforge_gnss::signal::Signal;
use skyforge_orbits::ephemeris::{rinex_nav, rinex_nav_iono};
use skyforge_receiver::input::{BlockReader, InputParams, Recording, SampleFormat};
use std::path::{Path, PathBuf};
use std::sync::{Once, OnceLock};

/// A fuzz target: one input, any bytes.
pub type Target = fn(&[u8]);

/// Every target by name (the name of its `fuzz/fuzz_targets/<name>.rs`, `fuzz/corpus/<name>/`
/// and `fuzz/regressions/<name>/`).
pub const TARGETS: &[(&str, Target)] = &[
    ("scenario", scenario),
    ("rinex_nav", rinex_nav),
    ("rinex_obs", rinex_obs),
    ("sigmf", sigmf),
    ("raw_samples", raw_samples),
];

/// The target named `name`.
pub fn target(name: &str) -> Option<Target> {
    TARGETS.iter().find(|(n, _)| *n == name).map(|&(_, f)| f)
}

/// An empty directory the scenario target resolves relative paths from (the same one for
/// every run, so runs leave nothing behind): nothing a fuzzed scenario names is read from
/// anywhere else, and `parse` reads no file at all.
fn empty_dir() -> &'static Path {
    static DIR: OnceLock<PathBuf> = OnceLock::new();
    DIR.get_or_init(|| {
        let dir = std::env::temp_dir().join("skyforge-fuzz-empty");
        // Not created (read-only temp): relative paths resolve nowhere, which is as good.
        let _ = std::fs::create_dir_all(&dir);
        dir
    })
}

/// The scenario reader: TOML syntax, schema and every check that needs no file
/// ([`skyforge_scenarios::parse`]).
pub fn scenario(data: &[u8]) {
    let text = String::from_utf8_lossy(data);
    if let Err(e) = skyforge_scenarios::parse(&text, "fuzz.toml", empty_dir()) {
        let _ = e.to_string();
    }
}

/// The RINEX 2/3/4 navigation reader: ephemerides and the ionosphere coefficients.
pub fn rinex_nav(data: &[u8]) {
    // As `read_text_maybe_gz` reads a file.
    let text = String::from_utf8_lossy(data);
    if let Err(e) = rinex_nav::parse_nav(&text, "fuzz.rnx") {
        let _ = e.to_string();
    }
    if let Err(e) = rinex_nav_iono::parse_iono(&text, "fuzz.rnx") {
        let _ = e.to_string();
    }
}

/// Lets the panics that SkyForge catches on purpose unwind to where they are caught
/// instead of reaching the hook in place (libFuzzer's aborts on every panic, caught or
/// not): those of the third-party `rinex` crate inside `rinex_read::parse_rinex`, which
/// turns them into errors. Every other panic goes to the previous hook.
fn let_caught_rinex_panics_unwind() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        let previous = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            let trace = std::backtrace::Backtrace::force_capture().to_string();
            if !trace.contains("rinex_read::parse_rinex") {
                previous(info);
            }
        }));
    });
}

/// The RINEX observation readers: version 3 (through the `rinex` crate) and version 2
/// (SkyForge's own), as `read_obs_file` picks them, and the version 2 reader on every
/// input.
pub fn rinex_obs(data: &[u8]) {
    let_caught_rinex_panics_unwind();
    let text = String::from_utf8_lossy(data);
    if let Err(e) = rinex_read::parse_obs_text(&text, "fuzz.obs") {
        let _ = e.to_string();
    }
    if !rinex2_read::is_rinex2_obs(&text)
        && let Err(e) = rinex2_read::parse_rinex2_obs(&text, Path::new("fuzz.obs"))
    {
        let _ = e.to_string();
    }
}

/// Command-line values that override or fill in a recording's metadata.
fn given_params() -> InputParams {
    InputParams {
        format: Some(SampleFormat::Ci16),
        sample_rate_hz: Some(4e6),
        if_hz: Some(1e3),
        signal: Some(Signal::GpsL1Ca),
    }
}

/// The SigMF metadata reader (`.sigmf-meta` JSON, as `Recording::from_sigmf` reads it),
/// without and with command-line values, and the rate/IF checks.
pub fn sigmf(data: &[u8]) {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    let Ok(json) = serde_json::from_str::<serde_json::Value>(text) else {
        return;
    };
    let path = Path::new("/fuzz/rx.sigmf-meta");
    for params in [InputParams::default(), given_params()] {
        match Recording::from_sigmf_json(path, &json, &params) {
            Ok(r) => {
                if let Err(e) = r.check() {
                    let _ = e.to_string();
                }
                for f in &r.findings {
                    let _ = f.to_string();
                }
            }
            Err(e) => {
                let _ = e.to_string();
            }
        }
    }
}

/// Largest number of antennas the raw-samples target reads together.
const MAX_ANTENNAS: usize = 3;

/// A little-endian `u16` length from the front of `rest`, then that many bytes (fewer
/// when the input ends first).
fn take_prefixed<'a>(rest: &mut &'a [u8]) -> &'a [u8] {
    let (len, tail) = match *rest {
        [a, b, tail @ ..] => (usize::from(u16::from_le_bytes([*a, *b])), tail),
        _ => (0, &[][..]),
    };
    let (part, tail) = tail.split_at(len.min(tail.len()));
    *rest = tail;
    part
}

/// The sample reader: SigMF or raw recordings of one to three antennas, aligned and read
/// block by block from bytes in memory ([`BlockReader::open_in_memory`]).
///
/// Input layout: a control byte (bits 0-1 format, 2-3 antennas - 1, 4-5 block length,
/// 6 command-line values given, 7 sample rate), then per antenna a `u16` length and the
/// `.sigmf-meta` JSON (empty: a raw file described by the command-line values) and a
/// `u16` length and the samples (the last antenna's samples run to the end).
pub fn raw_samples(data: &[u8]) {
    let Some((&control, mut rest)) = data.split_first() else {
        return;
    };
    let format = SampleFormat::ALL[usize::from(control & 3) % SampleFormat::ALL.len()];
    let antennas = usize::from((control >> 2) & 3) % MAX_ANTENNAS + 1;
    let block_len = [1, 7, 1000, 4096][usize::from((control >> 4) & 3)];
    let sample_rate_hz = if control & 0x80 == 0 { 4e6 } else { 2.046e6 };
    let params = InputParams {
        format: Some(format),
        sample_rate_hz: Some(sample_rate_hz),
        // Real samples need 0 < IF < fs / 2.
        if_hz: Some(if format.is_complex() {
            0.0
        } else {
            sample_rate_hz / 4.0
        }),
        signal: None,
    };
    let given = if control & 0x40 == 0 {
        InputParams::default()
    } else {
        params
    };
    let mut recordings = Vec::with_capacity(antennas);
    let mut samples = Vec::with_capacity(antennas);
    for i in 0..antennas {
        let meta = take_prefixed(&mut rest);
        let bytes = if i + 1 == antennas {
            std::mem::take(&mut rest)
        } else {
            take_prefixed(&mut rest)
        };
        let recording = if meta.is_empty() {
            Recording::raw(Path::new(&format!("/fuzz/ant{i}.raw")), &params)
        } else {
            let Ok(json) = serde_json::from_slice::<serde_json::Value>(meta) else {
                return;
            };
            let path = PathBuf::from(format!("/fuzz/ant{i}.sigmf-meta"));
            Recording::from_sigmf_json(&path, &json, &given)
        };
        match recording {
            Ok(r) => recordings.push(r),
            Err(e) => {
                let _ = e.to_string();
                return;
            }
        }
        samples.push(bytes.to_vec());
    }
    let (mut reader, report) = match BlockReader::open_in_memory(&recordings, samples, block_len) {
        Ok(opened) => opened,
        Err(e) => {
            let _ = e.to_string();
            return;
        }
    };
    let _ = report.to_string();
    let mut buffers = reader.buffers();
    loop {
        match reader.read_block(&mut buffers) {
            Ok(Some(_)) => {}
            Ok(None) => break,
            Err(e) => {
                let _ = e.to_string();
                break;
            }
        }
    }
}
