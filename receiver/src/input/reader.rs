//! Several antennas' recordings read together on one sample clock, in aligned blocks of
//! complex f32 samples (format module docs for the full scale; real IF is mixed to complex
//! baseband by [`IfMixer`]). Streams: memory is a few buffers of one block, whatever the
//! file length.

use super::error::{Finding, InputError};
use super::format::{SampleFormat, decode_cf32, decode_ci8, decode_ci16, decode_ri8};
use super::if_mixer::IfMixer;
use super::recording::{InputParams, Recording};
use super::stream::StreamReader;
use hifitime::{Duration, Epoch};
use num_complex::Complex32;
use rayon::prelude::*;
use skyforge_gnss::signal::Signal;
use std::fs::File;
use std::io::{BufReader, Read, Seek, SeekFrom};
use std::path::{Path, PathBuf};

/// Buffered bytes per file (blocks larger than this are read straight into the block
/// buffer).
const READ_BUFFER_BYTES: usize = 1 << 18;

/// A start-time offset this close to a whole number of samples counts as whole.
const WHOLE_SAMPLE_TOLERANCE: f64 = 1e-3;

/// Relative difference of two sample rates below which they are the same clock.
const RATE_TOLERANCE: f64 = 1e-12;

/// Difference of two complex recordings' IFs below which they are the same (Hz).
const IF_TOLERANCE_HZ: f64 = 1e-6;

/// What was found about one antenna's file.
#[derive(Debug, Clone, PartialEq)]
pub struct AntennaInput {
    pub antenna: String,
    pub path: PathBuf,
    pub format: SampleFormat,
    /// Whole samples in the file (after the first capture's `core:sample_start`).
    pub samples_in_file: u64,
    /// Samples skipped at the start to align with the latest-starting file.
    pub skipped_samples: u64,
}

/// What the reader found in the input, for the user.
#[derive(Debug, Clone, PartialEq)]
pub struct InputReport {
    pub antennas: Vec<AntennaInput>,
    /// Common sample rate (Hz).
    pub sample_rate_hz: f64,
    /// Samples every antenna delivers.
    pub common_samples: u64,
    /// UTC time of the first delivered sample, when the metadata gives it.
    pub start_utc: Option<Epoch>,
    /// The signal the recordings hold, when known.
    pub signal: Option<Signal>,
    /// Problems worked around and other notable facts.
    pub findings: Vec<Finding>,
}

impl InputReport {
    /// Duration of the common part (s).
    pub fn duration_s(&self) -> f64 {
        self.common_samples as f64 / self.sample_rate_hz
    }
}

impl std::fmt::Display for InputReport {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let signal = self
            .signal
            .map_or("unknown signal".into(), |s| s.to_string());
        writeln!(
            f,
            "{} antenna(s), {signal}, {} samples/s: {} common samples ({} s)",
            self.antennas.len(),
            self.sample_rate_hz,
            self.common_samples,
            self.duration_s()
        )?;
        if let Some(t) = self.start_utc {
            writeln!(f, "  first sample at {t}")?;
        }
        for a in &self.antennas {
            writeln!(
                f,
                "  {}: {} ({}, {} samples, {} skipped at the start)",
                a.antenna,
                a.path.display(),
                a.format,
                a.samples_in_file,
                a.skipped_samples
            )?;
        }
        for finding in &self.findings {
            writeln!(f, "  note: {finding}")?;
        }
        Ok(())
    }
}

/// One delivered block.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Block {
    /// Index of the block's first sample on the common clock (0: the first common sample).
    pub first_sample: u64,
    /// Samples in the block per antenna (the block length, less at the end).
    pub len: usize,
}

/// How one antenna's bytes become complex samples.
#[derive(Debug)]
enum Decoder {
    Ci8,
    Ci16,
    Cf32,
    /// Real samples, then mixed from the IF to baseband.
    Ri8 {
        real: Vec<f32>,
        mixer: IfMixer,
    },
}

/// What a source's samples are read from: a file, or bytes in memory
/// ([`BlockReader::open_in_memory`]).
trait SampleBytes: Read + Seek + Send + std::fmt::Debug {}
impl<T: Read + Seek + Send + std::fmt::Debug> SampleBytes for T {}

/// One antenna's open file.
#[derive(Debug)]
struct Source {
    path: PathBuf,
    bytes_per_sample: usize,
    file: BufReader<Box<dyn SampleBytes>>,
    bytes: Vec<u8>,
    decoder: Decoder,
}

impl Source {
    /// Reads the next `n` samples into `out[..n]`; `at` (the block's first common sample)
    /// and `expected` (the common length) are for the message when the file ends early.
    fn read(
        &mut self,
        n: usize,
        out: &mut [Complex32],
        at: u64,
        expected: u64,
    ) -> Result<(), InputError> {
        let bytes = &mut self.bytes[..n * self.bytes_per_sample];
        self.file.read_exact(bytes).map_err(|e| {
            if e.kind() == std::io::ErrorKind::UnexpectedEof {
                InputError::ShrankWhileReading {
                    path: self.path.clone(),
                    at,
                    expected,
                }
            } else {
                InputError::io(&self.path, e)
            }
        })?;
        match &mut self.decoder {
            Decoder::Ci8 => {
                decode_ci8(bytes, out);
            }
            Decoder::Ci16 => {
                decode_ci16(bytes, out);
            }
            Decoder::Cf32 => {
                decode_cf32(bytes, out);
            }
            Decoder::Ri8 { real, mixer } => {
                let real = &mut real[..n];
                decode_ri8(bytes, real);
                mixer.mix(real, out);
            }
        }
        Ok(())
    }
}

/// Reads several antennas' recordings in aligned blocks.
#[derive(Debug)]
pub struct BlockReader {
    sources: Vec<Source>,
    block_len: usize,
    sample_rate_hz: f64,
    output_if_hz: f64,
    common_samples: u64,
    position: u64,
    /// Read the antennas' blocks on rayon's threads side by side: files and memory, not
    /// streams, whose producer (the synthesiser) needs those threads to write them.
    side_by_side: bool,
}

/// Checks that every recording can share the first one's sample clock and processing.
fn check_compatible(recordings: &[Recording]) -> Result<(), InputError> {
    let Some(first) = recordings.first() else {
        return Err(InputError::NoRecordings);
    };
    let reference = first.antenna.clone();
    for r in recordings {
        r.check()?;
        let (antenna, path) = (r.antenna.clone(), r.data_path.clone());
        let scale = first.sample_rate_hz.abs().max(r.sample_rate_hz.abs());
        if (r.sample_rate_hz - first.sample_rate_hz).abs() > RATE_TOLERANCE * scale {
            return Err(InputError::RateMismatch {
                antenna,
                path,
                rate_hz: r.sample_rate_hz,
                reference,
                reference_rate_hz: first.sample_rate_hz,
            });
        }
        if r.format != first.format {
            return Err(InputError::FormatMismatch {
                antenna,
                path,
                format: r.format,
                reference,
                reference_format: first.format,
            });
        }
        if r.format.is_complex() && (r.if_hz - first.if_hz).abs() > IF_TOLERANCE_HZ {
            return Err(InputError::IfMismatch {
                antenna,
                path,
                if_hz: r.if_hz,
                reference,
                reference_if_hz: first.if_hz,
            });
        }
        if let Some(other) = recordings.iter().find(|o| o.signal.is_some())
            && r.signal.is_some()
            && r.signal != other.signal
        {
            let name = |s: Option<Signal>| s.map_or(String::new(), |s| s.tag().to_string());
            return Err(InputError::SignalMismatch {
                antenna,
                path,
                signal: name(r.signal),
                reference: other.antenna.clone(),
                reference_signal: name(other.signal),
            });
        }
    }
    Ok(())
}

/// Each recording's start on the common clock (samples after the earliest start), from
/// the global sample indices when all give one, else from the start times when all give
/// one, else all 0.
fn start_offsets(recordings: &[Recording], findings: &mut Vec<Finding>) -> Vec<u64> {
    let fs = recordings[0].sample_rate_hz;
    let indices: Option<Vec<u64>> = recordings.iter().map(|r| r.global_index).collect();
    if let Some(idx) = indices {
        let min = idx.iter().copied().min().unwrap_or(0);
        return idx.iter().map(|&i| i - min).collect();
    }
    let times: Option<Vec<Epoch>> = recordings.iter().map(|r| r.start_utc).collect();
    if let Some(times) = times {
        let Some(&earliest) = times.iter().min() else {
            return Vec::new();
        };
        return times
            .iter()
            .zip(recordings)
            .map(|(&t, r)| {
                let offset = (t - earliest).to_seconds() * fs;
                let rounded = offset.round();
                if (offset - rounded).abs() > WHOLE_SAMPLE_TOLERANCE {
                    findings.push(Finding::FractionalStart {
                        antenna: r.antenna.clone(),
                        offset_samples: offset,
                        rounded: rounded as u64,
                    });
                }
                rounded as u64
            })
            .collect();
    }
    let unknown: Vec<&str> = recordings
        .iter()
        .filter(|r| r.global_index.is_none() && r.start_utc.is_none())
        .map(|r| r.antenna.as_str())
        .collect();
    if recordings.len() > 1 && unknown.len() < recordings.len() {
        findings.push(Finding::StartUnknown {
            antennas: unknown.join(", "),
        });
    }
    vec![0; recordings.len()]
}

impl BlockReader {
    /// Opens `recordings` (one per antenna, in this order) for blocks of `block_len`
    /// samples: checks that they share a sample clock, format, IF and signal, aligns their
    /// starts (global sample index or start time), and finds the common length. Returns
    /// the reader and the report of what was found.
    pub fn open(
        recordings: &[Recording],
        block_len: usize,
    ) -> Result<(Self, InputReport), InputError> {
        Self::open_with(
            recordings,
            block_len,
            |_, r| std::fs::metadata(&r.data_path).map(|m| m.len()),
            |_, r| File::open(&r.data_path).map(|f| Box::new(f) as Box<dyn SampleBytes>),
        )
    }

    /// As [`Self::open`], with recording `i`'s sample file given as the bytes `data[i]`
    /// instead of read from its `data_path` (a recording without bytes is a missing file):
    /// for tests and fuzzing without temporary files.
    pub fn open_in_memory(
        recordings: &[Recording],
        data: Vec<Vec<u8>>,
        block_len: usize,
    ) -> Result<(Self, InputReport), InputError> {
        let missing = || std::io::Error::from(std::io::ErrorKind::NotFound);
        Self::open_with(
            recordings,
            block_len,
            |i, _| data.get(i).map(|d| d.len() as u64).ok_or_else(missing),
            |i, _| {
                let bytes = data.get(i).ok_or_else(missing)?.clone();
                Ok(Box::new(std::io::Cursor::new(bytes)) as Box<dyn SampleBytes>)
            },
        )
    }

    /// As [`Self::open`], with recording `i`'s bytes read from `streams[i]` as a synthesis
    /// session beside the receiver renders them ([`super::stream`]); every stream holds
    /// `samples` samples, which a stream cannot tell by itself.
    pub fn open_streams(
        recordings: &[Recording],
        streams: Vec<StreamReader>,
        samples: u64,
        block_len: usize,
    ) -> Result<(Self, InputReport), InputError> {
        let missing = || std::io::Error::from(std::io::ErrorKind::NotFound);
        let mut streams: Vec<Option<StreamReader>> = streams.into_iter().map(Some).collect();
        let count = streams.len();
        let (reader, report) = Self::open_with(
            recordings,
            block_len,
            |i, r| {
                let bytes = samples.saturating_mul(r.format.bytes_per_sample() as u64);
                (i < count)
                    .then(|| bytes.saturating_add(r.header_bytes.saturating_add(r.trailing_bytes)))
                    .ok_or_else(missing)
            },
            |i, _| {
                let stream = streams
                    .get_mut(i)
                    .and_then(Option::take)
                    .ok_or_else(missing)?;
                Ok(Box::new(stream) as Box<dyn SampleBytes>)
            },
        )?;
        let reader = Self {
            side_by_side: false,
            ..reader
        };
        Ok((reader, report))
    }

    /// [`Self::open`] with recording `i`'s sample file length and contents given by
    /// `file_len(i, r)` and `open_file(i, r)`.
    fn open_with(
        recordings: &[Recording],
        block_len: usize,
        file_len: impl Fn(usize, &Recording) -> std::io::Result<u64>,
        mut open_file: impl FnMut(usize, &Recording) -> std::io::Result<Box<dyn SampleBytes>>,
    ) -> Result<(Self, InputReport), InputError> {
        check_compatible(recordings)?;
        if block_len == 0 {
            return Err(InputError::InvalidParameter {
                name: "block length",
                value: "0".into(),
                allowed: "at least 1 sample".into(),
            });
        }
        let fs = recordings[0].sample_rate_hz;
        let mut findings: Vec<Finding> =
            recordings.iter().flat_map(|r| r.findings.clone()).collect();
        // Whole samples in each file.
        let mut in_file = Vec::with_capacity(recordings.len());
        for (i, r) in recordings.iter().enumerate() {
            let len = file_len(i, r).map_err(|e| InputError::io(&r.data_path, e))?;
            let bps = r.format.bytes_per_sample() as u64;
            let payload = len.saturating_sub(r.header_bytes.saturating_add(r.trailing_bytes));
            if payload % bps != 0 {
                return Err(InputError::PartialSample {
                    antenna: r.antenna.clone(),
                    path: r.data_path.clone(),
                    format: r.format,
                    file_bytes: len,
                    sample_bytes: payload,
                    leftover_bytes: payload % bps,
                    bytes_per_sample: bps as usize,
                });
            }
            in_file.push((payload / bps).saturating_sub(r.first_sample));
        }
        // Align the starts: the latest-starting file defines common sample 0.
        let starts = start_offsets(recordings, &mut findings);
        let latest = starts.iter().copied().max().unwrap_or(0);
        let mut available = Vec::with_capacity(recordings.len());
        for ((r, &start), &n) in recordings.iter().zip(&starts).zip(&in_file) {
            let skip = latest - start;
            if n <= skip {
                return Err(InputError::NoCommonSamples {
                    reason: if n == 0 {
                        format!(
                            "antenna {} ({}) holds no whole sample",
                            r.antenna,
                            r.data_path.display()
                        )
                    } else {
                        format!(
                            "antenna {} ({}) ends after {n} samples, before the latest-starting file begins ({skip} samples after it starts)",
                            r.antenna,
                            r.data_path.display()
                        )
                    },
                });
            }
            if skip > 0 {
                findings.push(Finding::StartAligned {
                    antenna: r.antenna.clone(),
                    path: r.data_path.clone(),
                    skipped_samples: skip,
                    skipped_s: skip as f64 / fs,
                });
            }
            available.push(n - skip);
        }
        let common = available.iter().copied().min().unwrap_or(0);
        let longest = available
            .iter()
            .zip(recordings)
            .max_by_key(|(n, _)| **n)
            .map_or(String::new(), |(_, r)| r.antenna.clone());
        for (r, &n) in recordings.iter().zip(&available) {
            let most = available.iter().copied().max().unwrap_or(n);
            if n < most {
                findings.push(Finding::Shorter {
                    antenna: r.antenna.clone(),
                    path: r.data_path.clone(),
                    missing_samples: most - n,
                    missing_s: (most - n) as f64 / fs,
                    longest: longest.clone(),
                    common_samples: common,
                });
            }
        }
        // Buffers hold a block, or the whole common part when that is shorter.
        let buffer_len = usize::try_from(common).map_or(block_len, |c| c.min(block_len));
        // Open every file at its first common sample.
        let mut sources = Vec::with_capacity(recordings.len());
        let mut report_antennas = Vec::with_capacity(recordings.len());
        for (i, ((r, &start), &n)) in recordings.iter().zip(&starts).zip(&in_file).enumerate() {
            let skip = latest - start;
            let bps = r.format.bytes_per_sample();
            let offset = (r.first_sample.saturating_add(skip))
                .saturating_mul(bps as u64)
                .saturating_add(r.header_bytes);
            let mut file = open_file(i, r).map_err(|e| InputError::io(&r.data_path, e))?;
            file.seek(SeekFrom::Start(offset))
                .map_err(|e| InputError::io(&r.data_path, e))?;
            let decoder = match r.format {
                SampleFormat::Ci8 => Decoder::Ci8,
                SampleFormat::Ci16 => Decoder::Ci16,
                SampleFormat::Cf32 => Decoder::Cf32,
                SampleFormat::Ri8 => Decoder::Ri8 {
                    real: vec![0.0; buffer_len],
                    mixer: IfMixer::new(r.if_hz, fs, buffer_len),
                },
            };
            sources.push(Source {
                path: r.data_path.clone(),
                bytes_per_sample: bps,
                file: BufReader::with_capacity(READ_BUFFER_BYTES, file),
                bytes: vec![0; buffer_len * bps],
                decoder,
            });
            report_antennas.push(AntennaInput {
                antenna: r.antenna.clone(),
                path: r.data_path.clone(),
                format: r.format,
                samples_in_file: n,
                skipped_samples: skip,
            });
        }
        let start_utc = recordings.iter().zip(&starts).find_map(|(r, &s)| {
            Some(r.start_utc? + Duration::from_seconds((latest - s) as f64 / fs))
        });
        let first = &recordings[0];
        let report = InputReport {
            antennas: report_antennas,
            sample_rate_hz: fs,
            common_samples: common,
            start_utc,
            signal: recordings.iter().find_map(|r| r.signal),
            findings,
        };
        let reader = Self {
            sources,
            block_len: buffer_len,
            sample_rate_hz: fs,
            output_if_hz: if first.format.is_complex() {
                first.if_hz
            } else {
                0.0
            },
            common_samples: common,
            position: 0,
            side_by_side: true,
        };
        Ok((reader, report))
    }

    /// [`Self::open`] of the recordings at `paths` (one per antenna), each described by
    /// [`Recording::open`] with the command-line `params`.
    pub fn open_paths<P: AsRef<Path>>(
        paths: &[P],
        params: &InputParams,
        block_len: usize,
    ) -> Result<(Self, InputReport), InputError> {
        let recordings = paths
            .iter()
            .map(|p| Recording::open(p.as_ref(), params))
            .collect::<Result<Vec<_>, _>>()?;
        Self::open(&recordings, block_len)
    }

    /// Number of antennas.
    pub fn antennas(&self) -> usize {
        self.sources.len()
    }

    /// Samples per block (the requested length, or the common length when shorter).
    pub fn block_len(&self) -> usize {
        self.block_len
    }

    /// The common sample rate (Hz).
    pub fn sample_rate_hz(&self) -> f64 {
        self.sample_rate_hz
    }

    /// Where the carrier sits in the delivered complex samples (Hz): the recording's IF for
    /// complex input, 0 for real input (mixed to baseband).
    pub fn output_if_hz(&self) -> f64 {
        self.output_if_hz
    }

    /// Samples every antenna delivers in total.
    pub fn common_samples(&self) -> u64 {
        self.common_samples
    }

    /// Index of the next sample to be delivered.
    pub fn position(&self) -> u64 {
        self.position
    }

    /// One buffer per antenna, with room for a block: pass them to [`Self::read_block`]
    /// again and again (no allocation per block).
    pub fn buffers(&self) -> Vec<Vec<Complex32>> {
        (0..self.sources.len())
            .map(|_| Vec::with_capacity(self.block_len))
            .collect()
    }

    /// Reads the next block of every antenna into `out` (one buffer per antenna, each
    /// resized to the block's length); `None` after the last common sample.
    pub fn read_block(&mut self, out: &mut [Vec<Complex32>]) -> Result<Option<Block>, InputError> {
        if out.len() != self.sources.len() {
            return Err(InputError::BufferCount {
                given: out.len(),
                antennas: self.sources.len(),
            });
        }
        let left = self.common_samples - self.position;
        if left == 0 {
            return Ok(None);
        }
        let n = usize::try_from(left).map_or(self.block_len, |l| l.min(self.block_len));
        let (at, expected) = (self.position, self.common_samples);
        let read = |(src, buf): (&mut Source, &mut Vec<Complex32>)| {
            buf.resize(n, Complex32::new(0.0, 0.0));
            src.read(n, buf, at, expected)
        };
        if self.side_by_side {
            // Copying and decoding a block is a tenth of a run's work.
            (self.sources.par_iter_mut())
                .zip(out.par_iter_mut())
                .try_for_each(read)?;
        } else {
            self.sources
                .iter_mut()
                .zip(out.iter_mut())
                .try_for_each(read)?;
        }
        let block = Block {
            first_sample: self.position,
            len: n,
        };
        self.position += n as u64;
        Ok(Some(block))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rec(name: &str, start: Option<Epoch>) -> Recording {
        let params = InputParams {
            format: Some(SampleFormat::Ci8),
            sample_rate_hz: Some(2e6),
            ..InputParams::default()
        };
        let mut r = Recording::raw(Path::new(name), &params).unwrap();
        r.start_utc = start;
        r
    }

    #[test]
    fn start_offsets_come_from_times_and_say_when_they_are_not_whole_samples() {
        let t0 = Epoch::from_gregorian_utc_at_midnight(2024, 1, 1);
        // 2 MHz: 0.6 us is 1.2 samples.
        let recs = [
            rec("a", Some(t0 + Duration::from_seconds(0.6e-6))),
            rec("b", Some(t0)),
            rec("c", Some(t0 + Duration::from_seconds(3e-6))),
        ];
        let mut findings = Vec::new();
        let starts = start_offsets(&recs, &mut findings);
        assert_eq!(starts, [1, 0, 6]);
        match findings.as_slice() {
            [
                Finding::FractionalStart {
                    antenna,
                    offset_samples,
                    rounded: 1,
                },
            ] => {
                assert_eq!(antenna, "a");
                assert!((offset_samples - 1.2).abs() < 1e-9);
            }
            other => panic!("{other:?}"),
        }
        // No start information at all: simultaneous, nothing to say.
        let mut findings = Vec::new();
        assert_eq!(
            start_offsets(&[rec("a", None), rec("b", None)], &mut findings),
            [0, 0]
        );
        assert!(findings.is_empty());
    }

    /// Everything a reader delivers: its report and every block's samples.
    fn read_all(opened: (BlockReader, InputReport)) -> (InputReport, Vec<Vec<Complex32>>) {
        let (mut reader, report) = opened;
        let mut bufs = reader.buffers();
        let mut samples = vec![Vec::new(); reader.antennas()];
        while reader.read_block(&mut bufs).unwrap().is_some() {
            for (all, b) in samples.iter_mut().zip(&bufs) {
                all.extend_from_slice(b);
            }
        }
        (report, samples)
    }

    #[test]
    fn bytes_in_memory_read_as_the_same_bytes_in_a_file() {
        let dir = tempfile::tempdir().unwrap();
        // 10 whole ci8 samples; the second antenna starts 3 samples later.
        let data: Vec<u8> = (0u8..20).map(|b| b.wrapping_mul(37)).collect();
        let t0 = Epoch::from_gregorian_utc_at_midnight(2024, 1, 1);
        let mut recs = [
            rec("a", Some(t0)),
            rec("b", Some(t0 + Duration::from_seconds(1.5e-6))),
        ];
        for r in &mut recs {
            r.data_path = dir.path().join(&r.antenna);
            std::fs::write(&r.data_path, &data).unwrap();
        }
        let from_files = read_all(BlockReader::open(&recs, 4).unwrap());
        let in_memory =
            read_all(BlockReader::open_in_memory(&recs, vec![data.clone(); 2], 4).unwrap());
        assert_eq!(from_files, in_memory);
        assert_eq!(from_files.1[0].len(), 7);
        // A partial sample is the same error either way.
        let odd = [data.as_slice(), &[1]].concat();
        for r in &recs {
            std::fs::write(&r.data_path, &odd).unwrap();
        }
        let partial = |e: InputError| matches!(e, InputError::PartialSample { .. });
        assert!(BlockReader::open(&recs, 4).is_err_and(partial));
        assert!(BlockReader::open_in_memory(&recs, vec![odd.clone(); 2], 4).is_err_and(partial));
        // A recording without bytes is a missing file.
        match BlockReader::open_in_memory(&recs, vec![data], 4) {
            Err(InputError::Missing { path }) => assert_eq!(path, recs[1].data_path),
            other => panic!("{other:?}"),
        }
    }
}
