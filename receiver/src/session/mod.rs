//! A receive session: recordings (SigMF or raw, several antennas on one sample clock,
//! one or two bands) opened as block readers, the receiver configured from a TOML file and
//! assisted from a navigation file, then run block by block with every epoch handed to an
//! [`EpochSink`]. The caller picks the writers (RINEX, HDF5, CSV, NMEA, or anything that
//! keeps the reports in memory) by implementing the trait; [`RinexObsFiles`] is the
//! RINEX observation writer every caller shares.

mod rinex_files;

pub use rinex_files::RinexObsFiles;

use crate::input::{BlockReader, Finding, InputParams, InputReport, Recording, StreamReader};
use crate::pipeline::{
    ApproximateState, BandInput, EpochReport, Receiver, ReceiverConfig, ReceiverFile,
    ReceiverSetup, ReceiverSummary,
};
use skyforge_gnss::signal::Signal;
use skyforge_orbits::bounded_read::read_text;
use skyforge_orbits::ephemeris::rinex_nav::{parse_nav, read_nav_file};
use skyforge_orbits::ephemeris::rinex_nav_iono::{BroadcastIono, parse_iono, read_iono_file};
use std::path::{Path, PathBuf};

/// Largest receiver configuration file read.
const CONFIG_MAX_BYTES: u64 = 1 << 20;

/// Samples per block: 20 ms at the sample rate (covers every search of the default
/// settings; longer searches get longer blocks).
const BLOCK_S: f64 = 0.02;
/// Code periods a block holds at least: a search with aligned windows and the default two
/// non-coherent sums reads three.
const SEARCH_PERIODS: f64 = 3.0;

/// Highest sample rate the receiver takes (Hz): its acquisition FFTs and buffers grow
/// with the rate (about 1.5 GB of memory at this rate).
pub const MAX_SAMPLE_RATE_HZ: f64 = 100e6;

/// An error a sink reports (a file that cannot be written, say).
pub type SinkError = Box<dyn std::error::Error + Send + Sync>;

/// Receives every epoch the receiver forms, in time order.
pub trait EpochSink {
    fn epoch(&mut self, report: &EpochReport) -> Result<(), SinkError>;
}

/// Why a session could not be set up or run.
#[derive(Debug, thiserror::Error)]
pub enum SessionError {
    /// The input (files, settings, configuration) is unusable: the user's to fix.
    #[error("{0}")]
    Input(String),
    /// The run ended without an observation: nothing detected, or nothing tracked and
    /// timed (the samples hold no usable signal; what was found, and why).
    #[error("{0}")]
    NoSignal(String),
    /// The receiver failed on valid input.
    #[error(transparent)]
    Pipeline(#[from] crate::pipeline::PipelineError),
    #[error("{0}")]
    Sink(SinkError),
}

/// Read and check a receiver configuration file (`None`: the defaults, no approximate
/// state).
pub fn read_config(
    path: Option<&Path>,
) -> Result<(ReceiverConfig, Option<ApproximateState>), SessionError> {
    let Some(path) = path else {
        return Ok((ReceiverConfig::default(), None));
    };
    let text = read_text(path, CONFIG_MAX_BYTES, "receiver configuration")
        .map_err(|e| SessionError::Input(format!("{}: cannot read: {e}", path.display())))?;
    parse_config(&text, &path.display().to_string())
}

/// Parse and check the text of a receiver configuration file; `source` names it in errors.
pub fn parse_config(
    text: &str,
    source: &str,
) -> Result<(ReceiverConfig, Option<ApproximateState>), SessionError> {
    let input = |e: &dyn std::fmt::Display| SessionError::Input(format!("{source}: {e}"));
    let file: ReceiverFile = toml::from_str(text).map_err(|e| input(&e))?;
    file.resolve().map_err(|e| input(&e))
}

/// A RINEX navigation file (ephemerides and ionosphere) for the receiver.
#[derive(Debug, Clone, PartialEq)]
pub enum NavSource {
    /// A file on disk (gzip or plain).
    File(PathBuf),
    /// A file's text, kept in memory; `source` names it in errors.
    Text { source: String, text: String },
}

/// What a receiver can be told besides the samples.
#[derive(Debug, Clone, Default)]
pub struct Assistance {
    /// Navigation data: a RINEX navigation file.
    pub nav: Option<NavSource>,
    /// The approximate state at the first sample.
    pub approximate: Option<ApproximateState>,
}

/// The recordings grouped by band, each group opened as one block reader.
#[derive(Debug)]
struct Bands {
    readers: Vec<BlockReader>,
    inputs: Vec<BandInput>,
    reports: Vec<InputReport>,
    antenna_names: Vec<String>,
}

/// Where the recordings' samples come from.
enum Samples {
    /// Each recording's data file.
    Files,
    /// Recording `i`'s bytes from `readers[i]`, `samples` samples each.
    Streams {
        readers: Vec<Option<StreamReader>>,
        samples: u64,
    },
}

impl Samples {
    /// The block reader of `recs`, recordings `indices` of the session's list.
    fn open(
        &mut self,
        recs: &[Recording],
        indices: &[usize],
        block_len: usize,
    ) -> Result<(BlockReader, InputReport), SessionError> {
        let input = |e: &dyn std::fmt::Display| SessionError::Input(e.to_string());
        match self {
            Self::Files => BlockReader::open(recs, block_len).map_err(|e| input(&e)),
            Self::Streams { readers, samples } => {
                let streams = indices
                    .iter()
                    .map(|&i| readers.get_mut(i).and_then(Option::take))
                    .collect::<Option<Vec<_>>>()
                    .ok_or_else(|| {
                        SessionError::Input("a recording without its sample stream".into())
                    })?;
                BlockReader::open_streams(recs, streams, *samples, block_len).map_err(|e| input(&e))
            }
        }
    }
}

/// Why `r`'s signal is not known: a signal the receiver does not track yet (named in the
/// file name, as SkyForge names Galileo E5a recordings), or nothing that names one.
fn unknown_signal(r: &Recording) -> String {
    let path = r.source_path();
    if !r.carried.is_empty() {
        let tags: Vec<&str> = r.carried.iter().map(|s| s.tag()).collect();
        return format!(
            "{}: holds {}, none of which the bundled receiver receives",
            path.display(),
            tags.join(", ")
        );
    }
    let untracked = path
        .file_name()
        .and_then(|n| Signal::any_from_file_name(&n.to_string_lossy()));
    let received: Vec<&str> = Signal::RECEIVED.iter().map(|s| s.tag()).collect();
    let received = received.join(", ");
    match untracked {
        Some(s) => format!(
            "{}: holds {s}, which the bundled receiver does not receive yet (it receives {received})",
            path.display()
        ),
        None => format!(
            "{}: which signal it holds is unknown (no SigMF centre frequency in a GNSS band, no band in the file name): give --signal one of {received}",
            path.display()
        ),
    }
}

/// The signals recording `r` is read for, each with its copy of `r`: its one signal, or
/// every received signal of a recording that carries several (read once per signal; the
/// others noted).
fn read_for(r: Recording, params: &InputParams) -> Result<Vec<(Signal, Recording)>, SessionError> {
    if let Some(signal) = r.signal.or(params.signal) {
        return Ok(vec![(signal, r)]);
    }
    let (received, other): (Vec<Signal>, Vec<Signal>) =
        r.carried.iter().partition(|s| s.is_received());
    if received.is_empty() {
        return Err(SessionError::Input(unknown_signal(&r)));
    }
    let mut noted = r.clone();
    noted
        .findings
        .extend(other.iter().map(|s| Finding::SignalNotReceived {
            path: r.source_path().to_owned(),
            signal: s.tag().to_owned(),
        }));
    Ok(received
        .into_iter()
        .enumerate()
        .map(|(k, s)| {
            let copy = if k == 0 { noted.clone() } else { r.clone() };
            (
                s,
                Recording {
                    signal: Some(s),
                    ..copy
                },
            )
        })
        .collect())
}

fn open_bands(
    recordings: Vec<Recording>,
    params: &InputParams,
    mut samples: Samples,
) -> Result<Bands, SessionError> {
    let mut groups: Vec<(Signal, Vec<usize>, Vec<Recording>)> = Vec::new();
    for (i, r) in recordings.into_iter().enumerate() {
        for (signal, r) in read_for(r, params)? {
            match groups.iter_mut().find(|g| g.0 == signal) {
                Some(g) => {
                    g.1.push(i);
                    g.2.push(r);
                }
                None => groups.push((signal, vec![i], vec![r])),
            }
        }
    }
    let mut bands = Bands {
        readers: Vec::new(),
        inputs: Vec::new(),
        reports: Vec::new(),
        antenna_names: Vec::new(),
    };
    let first = groups
        .first()
        .and_then(|g| g.2.first())
        .ok_or_else(|| SessionError::Input("no sample files given".into()))?;
    let fs = first.sample_rate_hz;
    for (signal, _, _) in &groups {
        let min = signal.chip_rate_hz();
        if !(fs >= min && fs <= MAX_SAMPLE_RATE_HZ) {
            return Err(SessionError::Input(format!(
                "{}: the sample rate (core:sample_rate or --fs) is {fs} Hz; {} needs {min} to {MAX_SAMPLE_RATE_HZ} Hz",
                first.source_path().display(),
                signal.name()
            )));
        }
    }
    // Three code periods of B1C (10 ms) are what an aligned-window search with two
    // non-coherent sums reads: its blocks are 30 ms, the others' 20 ms.
    let block_s = groups
        .iter()
        .map(|(signal, _, _)| SEARCH_PERIODS * signal.code_period_s())
        .fold(BLOCK_S, f64::max);
    let block_len = (block_s * fs).round() as usize;
    for (signal, indices, recs) in groups {
        let (reader, report) = samples.open(&recs, &indices, block_len)?;
        if (reader.sample_rate_hz() - fs).abs() > 1e-6 * fs {
            return Err(SessionError::Input(format!(
                "the {} recordings are sampled at {} Hz, the {} ones at {fs} Hz: one receive run needs one sample clock",
                signal.name(),
                reader.sample_rate_hz(),
                bands
                    .inputs
                    .first()
                    .map_or("first", |b: &BandInput| b.signal.name()),
            )));
        }
        let antennas = report
            .antennas
            .iter()
            .map(|a| bands.antenna_index(&a.antenna))
            .collect();
        bands.inputs.push(BandInput {
            signal,
            if_hz: reader.output_if_hz(),
            antennas,
        });
        bands.readers.push(reader);
        bands.reports.push(report);
    }
    Ok(bands)
}

impl Bands {
    /// The receiver's index of antenna `name`, added when new.
    fn antenna_index(&mut self, name: &str) -> usize {
        match self.antenna_names.iter().position(|n| n == name) {
            Some(i) => i,
            None => {
                self.antenna_names.push(name.to_owned());
                self.antenna_names.len() - 1
            }
        }
    }

    /// What was found in the input, for messages.
    fn describe(&self) -> String {
        let mut s = String::new();
        for (b, r) in self.inputs.iter().zip(&self.reports) {
            s.push_str(&format!(
                "  {}: {} recording(s) at {} Hz, {:.1} s in common",
                b.signal.name(),
                r.antennas.len(),
                r.sample_rate_hz,
                r.duration_s()
            ));
            for a in &r.antennas {
                s.push_str(&format!(
                    "\n    {} ({}, {} samples)",
                    a.antenna,
                    a.path.display(),
                    a.samples_in_file
                ));
            }
            for f in &r.findings {
                s.push_str(&format!("\n    note: {f}"));
            }
            s.push('\n');
        }
        s
    }
}

/// A receiver with its recordings open, ready to run.
#[derive(Debug)]
pub struct ReceiveSession {
    bands: Bands,
    receiver: Receiver,
    config: ReceiverConfig,
    approximate: Option<ApproximateState>,
}

impl ReceiveSession {
    /// Open `files` (described by `params` where they do not describe themselves), read
    /// the assistance and set the receiver up with `config`.
    pub fn open(
        files: &[PathBuf],
        params: &InputParams,
        assistance: &Assistance,
        config: ReceiverConfig,
    ) -> Result<Self, SessionError> {
        let recordings = files
            .iter()
            .map(|f| Recording::open(f, params).map_err(|e| SessionError::Input(e.to_string())))
            .collect::<Result<Vec<_>, _>>()?;
        let bands = open_bands(recordings, params, Samples::Files)?;
        Self::with_bands(bands, assistance, config)
    }

    /// As [`Self::open`], with recording `i`'s samples read from `streams[i]` as a
    /// synthesis session beside the receiver renders them (`samples` per recording; see
    /// [`crate::input::stream`]); `recordings` describe them as their SigMF metadata would.
    pub fn open_streams(
        recordings: Vec<Recording>,
        streams: Vec<StreamReader>,
        samples: u64,
        assistance: &Assistance,
        config: ReceiverConfig,
    ) -> Result<Self, SessionError> {
        let samples = Samples::Streams {
            readers: streams.into_iter().map(Some).collect(),
            samples,
        };
        let bands = open_bands(recordings, &InputParams::default(), samples)?;
        Self::with_bands(bands, assistance, config)
    }

    /// The receiver of `bands`, assisted by `assistance` and set up with `config`.
    fn with_bands(
        bands: Bands,
        assistance: &Assistance,
        config: ReceiverConfig,
    ) -> Result<Self, SessionError> {
        let input = |e: &dyn std::fmt::Display| SessionError::Input(e.to_string());
        let (ephemerides, iono) = match &assistance.nav {
            None => (Vec::new(), BroadcastIono::default()),
            Some(NavSource::File(path)) => (
                read_nav_file(path).map_err(|e| input(&e))?,
                read_iono_file(path).map_err(|e| input(&e))?,
            ),
            Some(NavSource::Text { source, text }) => (
                parse_nav(text, source).map_err(|e| input(&e))?,
                parse_iono(text, source).map_err(|e| input(&e))?,
            ),
        };
        let setup = ReceiverSetup {
            sample_rate_hz: bands.readers[0].sample_rate_hz(),
            bands: bands.inputs.clone(),
            antenna_names: bands.antenna_names.clone(),
            start_time: bands.reports.iter().find_map(|r| r.start_utc),
            ephemerides,
            iono_gps: iono.gps,
            iono_bds: iono.bds,
            approximate: assistance.approximate,
        };
        let receiver = Receiver::new(setup, config.clone())
            .map_err(|e| SessionError::Input(format!("receiver settings: {e}")))?;
        Ok(Self {
            bands,
            receiver,
            config,
            approximate: assistance.approximate,
        })
    }

    /// The antennas, in the receiver's index order.
    pub fn antenna_names(&self) -> &[String] {
        &self.bands.antenna_names
    }

    /// The signals received, one per band.
    pub fn signals(&self) -> Vec<Signal> {
        self.bands.inputs.iter().map(|b| b.signal).collect()
    }

    /// The configuration the receiver runs with.
    pub fn config(&self) -> &ReceiverConfig {
        &self.config
    }

    /// The approximate state the receiver was given.
    pub fn approximate(&self) -> Option<ApproximateState> {
        self.approximate
    }

    /// Samples every band holds in common.
    pub fn common_samples(&self) -> u64 {
        self.bands
            .readers
            .iter()
            .map(BlockReader::common_samples)
            .min()
            .unwrap_or(0)
    }

    /// What was read, for messages.
    pub fn describe_input(&self) -> String {
        self.bands.describe()
    }

    /// Run over every common sample, handing each epoch to `sink`; `progress` is told the
    /// samples processed and the counters after each block. Fails with
    /// [`SessionError::Input`] when the recordings are too short for one search, and with
    /// [`SessionError::NoSignal`] when they hold no detectable signal or give no
    /// observation epoch (no satellite tracked and timed on any antenna): nothing for the
    /// caller to write.
    pub fn run(
        &mut self,
        sink: &mut dyn EpochSink,
        mut progress: impl FnMut(u64, &ReceiverSummary),
    ) -> Result<ReceiverSummary, SessionError> {
        let mut buffers: Vec<Vec<Vec<_>>> = self
            .bands
            .readers
            .iter()
            .map(BlockReader::buffers)
            .collect();
        let mut observed_epochs = 0;
        loop {
            let mut block = None;
            for (reader, bufs) in self.bands.readers.iter_mut().zip(buffers.iter_mut()) {
                let b = reader
                    .read_block(bufs)
                    .map_err(|e| SessionError::Input(e.to_string()))?;
                block = match (block, b) {
                    (None, b) => b,
                    (Some(a), Some(b)) => Some(if b.len < a.len { b } else { a }),
                    (Some(_), None) => None,
                };
            }
            let Some(block) = block else { break };
            if block.len < self.receiver.samples_per_search() && block.first_sample == 0 {
                return Err(SessionError::Input(format!(
                    "the recordings hold {} common samples; a search needs {}\n{}",
                    block.len,
                    self.receiver.samples_per_search(),
                    self.describe_input()
                )));
            }
            let reports = self
                .receiver
                .process(&buffers, block.first_sample, block.len)?;
            observed_epochs += reports
                .iter()
                .filter(|r| !r.observations.is_empty())
                .count();
            for r in &reports {
                sink.epoch(r).map_err(SessionError::Sink)?;
            }
            progress(
                block.first_sample + block.len as u64,
                &self.receiver.summary(),
            );
        }
        let summary = self.receiver.summary();
        if summary.detections == 0 {
            return Err(SessionError::NoSignal(format!(
                "no signal found: {} searches over {} antenna(s), none above the detection threshold.\nWhat was read:\n{}",
                summary.searches,
                self.bands.antenna_names.len(),
                self.describe_input()
            )));
        }
        if observed_epochs == 0 {
            return Err(SessionError::NoSignal(no_epoch_message(
                &summary,
                &self.describe_input(),
            )));
        }
        Ok(summary)
    }
}

/// Why a run that detected something formed no observation epoch ("no signal": not one
/// epoch with an observation of any satellite on any antenna).
fn no_epoch_message(s: &ReceiverSummary, input: &str) -> String {
    let tracked: usize = s.tracked.iter().map(Vec::len).sum();
    let timed: usize = s.timed.iter().map(Vec::len).sum();
    let why = if tracked == 0 {
        "no detection reached carrier lock (false alarms, or a signal too weak)"
    } else if timed == 0 {
        "no tracked satellite was timed: a pseudorange needs a decoded navigation \
         subframe (GPS L1 C/A and BeiDou D1 send one every 6 s; the recording must hold \
         several seconds of signal)"
    } else {
        "the recording ends before the first observation epoch"
    };
    format!(
        "no observation epoch: {} detection(s), {tracked} satellite(s) tracked, {timed} timed; \
         {why}.\nWhat was read:\n{input}",
        s.detections
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use skyforge_gnss::sample_format::SampleFormat as WriterFormat;
    use skyforge_gnss::sigmf::RecordingMeta;

    /// A recording's description as SkyForge writes it for `signals` on one carrier.
    fn recording(signals: &[Signal], params: &InputParams) -> Recording {
        let meta = RecordingMeta {
            format: WriterFormat::Ci8,
            sample_rate_hz: 20.46e6,
            centre_frequency_hz: signals[0].carrier_hz(),
            if_hz: 0.0,
            datetime_utc: "2023-03-12T00:00:00.000000000Z".into(),
            antenna_name: "ant1".into(),
            antenna_position_body_m: [0.0; 3],
            scenario: "test".into(),
            seed: 1,
            vehicle: None,
            description: "test".into(),
            signals: signals.to_vec(),
        };
        let path = Path::new("ant1.band.sigmf-meta");
        Recording::from_sigmf_json(path, &meta.to_json(), params).unwrap()
    }

    /// A recording of several signals is read once per signal the receiver receives, the
    /// others noted; a signal given on the command line picks one.
    #[test]
    fn a_recording_of_several_signals_is_read_for_each_received_one() {
        let none = InputParams::default();
        let both = recording(&[Signal::GpsL5, Signal::GalE5a], &none);
        assert_eq!(both.signal, None);
        let read = read_for(both, &none).unwrap();
        let signals: Vec<Signal> = read.iter().map(|(s, _)| *s).collect();
        assert_eq!(signals, [Signal::GpsL5, Signal::GalE5a]);
        assert!(read.iter().all(|(s, r)| r.signal == Some(*s)));
        assert!(read.iter().all(|(_, r)| r.findings.is_empty()));

        // GPS L2 is a signal the bundled receiver does not receive.
        let read = read_for(recording(&[Signal::GpsL1Ca, Signal::GpsL2], &none), &none).unwrap();
        assert_eq!(read.len(), 1);
        assert_eq!(read[0].0, Signal::GpsL1Ca);
        let noted: Vec<String> = read[0].1.findings.iter().map(|f| f.to_string()).collect();
        assert_eq!(
            noted,
            [
                "ant1.band.sigmf-meta also holds gps-l2, which the bundled receiver does not receive: it is read for the other signals"
            ]
        );
        let e = read_for(recording(&[Signal::GpsL2, Signal::BdsB3I], &none), &none).unwrap_err();
        assert_eq!(
            e.to_string(),
            "ant1.band.sigmf-meta: holds gps-l2, bds-b3i, none of which the bundled receiver receives"
        );

        let l5 = InputParams {
            signal: Some(Signal::GpsL5),
            ..InputParams::default()
        };
        let read = read_for(recording(&[Signal::GpsL5, Signal::GalE5a], &l5), &l5).unwrap();
        assert_eq!(read.len(), 1);
        assert_eq!(read[0].0, Signal::GpsL5);
        assert!(read[0].1.findings.is_empty());
    }
}
