//! The whole chain as a user runs it, in one call, for any table that needs it: synthesise
//! a scenario's I/Q into SigMF recordings with the broadcast navigation file and the
//! rounded start state (`receiver.toml`) beside them, run the bundled receiver over the
//! recordings with that assistance into RINEX observation files (the writer `skyforge
//! receive` uses), and hand back each antenna's observations as read from them.
//!
//! [`StreamedChain`] runs the same two sessions side by side with no recording in
//! between: the receiver reads the samples as the synthesiser renders them (`skyforge
//! synth --receive`), for runs whose I/Q would not fit on disk.

use skyforge_gnss::observation::{ObsEpoch, ObsFile, ObsReadError, ObsRecord, read_obs_file};
use skyforge_gnss::signal::Signal;
use skyforge_receiver::input::{InputError, InputParams, Recording, SampleFeed, sample_stream};
use skyforge_receiver::pipeline::{ReceiverConfig, ReceiverSummary, assistance_toml};
use skyforge_receiver::session::{
    Assistance, EpochSink, NavSource, ReceiveSession, RinexObsFiles, SessionError, read_config,
};
use skyforge_scenarios::Scenario;
use skyforge_signals::synth::RunInfo;
use skyforge_signals::synth::{
    Discard, ObservationSink, SampleSink, SinkError, Sinks, SynthError, SynthReport, SynthSession,
    TruthSink,
};
use skyforge_signals::synth::{SigmfRecordings, recording_name};
use std::path::{Path, PathBuf};

/// Geometry epochs per streamed chunk (as `skyforge synth`'s default).
const CHUNK_EPOCHS: usize = 10;
/// Frames (one band's and antenna's slice of samples each) on their way from the
/// synthesiser to the receiver: two rounds of four antennas' 1 s slices at 4 Msps ci8 are
/// 64 MB.
const FRAMES_IN_FLIGHT: usize = 8;

/// Why the chain could not run.
#[derive(Debug, thiserror::Error)]
pub enum ChainError {
    #[error("scenario: {0}")]
    Scenario(Box<skyforge_scenarios::ScenarioError>),
    #[error("scenario {0} has no [signal] table")]
    NoSignal(String),
    #[error("synthesis: {0}")]
    Synth(#[from] SynthError),
    #[error("receiver: {0}")]
    Receive(#[from] SessionError),
    #[error("{path}: {error}")]
    Io {
        path: PathBuf,
        error: std::io::Error,
    },
    #[error("reading back the observations: {0}")]
    Observations(#[from] ObsReadError),
    #[error("describing the streamed recordings: {0}")]
    Stream(#[from] InputError),
    #[error("the synthesis thread panicked")]
    SynthPanicked,
}

/// What the chain produced.
#[derive(Debug, Clone)]
pub struct ChainOutput {
    /// The antennas, in the scenario's order.
    pub antennas: Vec<String>,
    /// Each antenna's observations (as its RINEX file holds them).
    pub observations: Vec<ObsFile>,
    /// Each antenna's observation truth at whole seconds, scenario order.
    pub truth: Vec<ObsFile>,
    /// The receiver configuration the observations were made with.
    pub config: ReceiverConfig,
    /// The receiver's counters.
    pub summary: ReceiverSummary,
}

/// The observation truth of every antenna, kept in memory.
#[derive(Debug)]
struct TruthCollector {
    files: Vec<ObsFile>,
}

impl ObservationSink for TruthCollector {
    fn epoch(
        &mut self,
        antenna: usize,
        at: hifitime::Epoch,
        _position_ecef_m: &skyforge_orbits::Vec3,
        records: &[ObsRecord],
    ) -> Result<(), SinkError> {
        self.files[antenna].epochs.push(ObsEpoch {
            time: at,
            sats: records.to_vec(),
        });
        Ok(())
    }
}

impl ChainOutput {
    /// The observations of antenna `name`.
    pub fn of(&self, name: &str) -> Option<&ObsFile> {
        self.antennas
            .iter()
            .position(|a| a == name)
            .map(|i| &self.observations[i])
    }
}

/// Synthesise `scenario` into `work` (an existing directory; the recordings can take
/// gigabytes) and run the receiver over every recording, with `config` or, when `None`,
/// with the settings of the `receiver.toml` written beside the recordings (its defaults
/// and the rounded start state: what `skyforge receive --config` reads).
pub fn synth_and_receive(
    scenario: &Scenario,
    work: &Path,
    config: Option<ReceiverConfig>,
) -> Result<ChainOutput, ChainError> {
    let io = |path: &Path| {
        let path = path.to_path_buf();
        move |error| ChainError::Io { path, error }
    };
    let signal = scenario
        .signal
        .as_ref()
        .ok_or_else(|| ChainError::NoSignal(scenario.name.clone()))?;
    let mut world = scenario
        .build()
        .map_err(|e| ChainError::Scenario(Box::new(e)))?;
    let session = SynthSession::new(
        world.synth_world(),
        signal,
        &scenario.errors,
        scenario.receiver_seed(),
    )?
    .with_jammers(&scenario.jammers)?;
    let bands = session.bands().to_vec();
    let info = session.recording_info(&scenario.name, scenario.seed, scenario.vehicle.as_deref());
    let antennas = session.world().antennas;
    let nav_path = work.join("nav.rnx");
    let mut nav = Vec::new();
    session
        .write_navigation(&mut nav)
        .and_then(|()| std::fs::write(&nav_path, nav))
        .map_err(io(&nav_path))?;
    let mut recordings = SigmfRecordings::create(work, &bands, antennas).map_err(io(work))?;
    let mut truth = TruthCollector {
        files: antennas
            .iter()
            .map(|a| ObsFile {
                source: PathBuf::from(format!("{} observation truth", a.name)),
                approx_ecef_m: None,
                codes: Default::default(),
                epochs: Vec::new(),
                marker: None,
                dropped: Vec::new(),
            })
            .collect(),
    };
    let report = session.run(
        CHUNK_EPOCHS,
        Sinks {
            samples: &mut recordings,
            truth: &mut Discard,
            observations: &mut truth,
            measurements: &mut Discard,
            progress: &mut |_| {},
        },
    )?;
    recordings.finish(&info).map_err(io(work))?;
    let assist_path = work.join("receiver.toml");
    let assist_text = report
        .start_state
        .map(|(r, v)| assistance_toml(&r, &v))
        .unwrap_or_default();
    std::fs::write(&assist_path, assist_text).map_err(io(&assist_path))?;
    let (file_config, approximate) = read_config(Some(&assist_path))?;
    let config = config.unwrap_or(file_config);
    let files: Vec<PathBuf> = world
        .antennas
        .iter()
        .flat_map(|a| {
            bands
                .iter()
                .map(move |b| work.join(format!("{}.sigmf-meta", recording_name(&a.name, b))))
        })
        .collect();
    let assistance = Assistance {
        nav: Some(NavSource::File(nav_path)),
        approximate,
    };
    let receiver_config = config.clone();
    let mut receiver = ReceiveSession::open(&files, &InputParams::default(), &assistance, config)?;
    let antennas = receiver.antenna_names().to_vec();
    let rx_dir = work.join("receive");
    std::fs::create_dir_all(&rx_dir).map_err(io(&rx_dir))?;
    let mut sink = RinexObsFiles::new(
        &rx_dir,
        &antennas,
        &receiver.signals(),
        approximate.map(|a| a.r_ecef_m),
        1.0 / receiver.config().observation_rate_hz,
    );
    let summary = receiver.run(&mut sink, |_, _| {})?;
    sink.finish().map_err(io(&rx_dir))?;
    let observations = antennas
        .iter()
        .map(|name| read_obs_file(&rx_dir.join(format!("{name}.obs.rnx"))))
        .collect::<Result<_, _>>()?;
    let config = receiver_config.clone();
    Ok(ChainOutput {
        antennas,
        observations,
        truth: truth.files,
        config,
        summary,
    })
}

/// The receiver's sample feed as the synthesis session's sample sink: a band's samples go
/// to the receiver's input of each signal it receives in the band.
#[derive(Debug)]
struct Feed {
    feed: SampleFeed,
    /// The receiver inputs of each synthesis band.
    inputs_of: Vec<Vec<usize>>,
}

impl SampleSink for Feed {
    fn samples(&mut self, band: usize, antenna: usize, bytes: &[u8]) -> Result<(), SinkError> {
        for &input in self.inputs_of.get(band).into_iter().flatten() {
            self.feed.send(input, antenna, bytes)?;
        }
        Ok(())
    }
}

/// What a streamed synthesis hands to the caller: the truth of the transmitted signals
/// and the observation truth (the samples go to the receiver). The sinks run on the
/// synthesis thread.
pub struct StreamSinks<'s> {
    pub truth: &'s mut (dyn TruthSink + Send),
    pub observations: &'s mut (dyn ObservationSink + Send),
    /// Told the number of geometry epochs completed after each chunk.
    pub progress: &'s mut (dyn FnMut(usize) + Send),
}

impl std::fmt::Debug for StreamSinks<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("StreamSinks").finish_non_exhaustive()
    }
}

/// A synthesis session wired to a receiver that reads its samples as they are rendered:
/// the receiver sees the recordings `skyforge synth` would write (the same SigMF
/// description, the same bytes), without the files.
#[derive(Debug)]
pub struct StreamedChain<'a> {
    session: SynthSession<'a>,
    feed: Feed,
    receiver: ReceiveSession,
}

impl<'a> StreamedChain<'a> {
    /// The receiver of `session`'s recordings (described by `info` as their SigMF
    /// metadata would be), assisted by `assistance` and set up with `config`.
    pub fn open(
        session: SynthSession<'a>,
        info: &RunInfo,
        assistance: &Assistance,
        config: ReceiverConfig,
    ) -> Result<Self, ChainError> {
        let bands = session.bands().to_vec();
        let antennas = session.world().antennas;
        // One receiver input per band and signal received in it (a recording of several
        // signals is read once per signal, as from files).
        let inputs: Vec<(usize, Signal)> = (bands.iter().enumerate())
            .flat_map(|(k, b)| {
                let received = b.signals().iter().filter(|s| s.is_received());
                received.map(move |&s| (k, s))
            })
            .collect();
        let mut inputs_of = vec![Vec::new(); bands.len()];
        for (i, &(k, _)) in inputs.iter().enumerate() {
            inputs_of[k].push(i);
        }
        let (feed, streams) = sample_stream(inputs.len(), antennas.len(), FRAMES_IN_FLIGHT);
        // Input-major, as the feed numbers its sources.
        let recordings = inputs
            .iter()
            .flat_map(|&(k, s)| {
                let b = &bands[k];
                antennas.iter().map(move |a| (b, s, a))
            })
            .map(|(b, signal, a)| {
                let meta = info.meta(b, &a.name, a.nominal_body_m.into());
                let label = format!("{} (streamed)", recording_name(&a.name, b));
                // The signal is known here; its carrier alone does not tell GPS L5 from
                // Galileo E5a.
                let params = InputParams {
                    signal: Some(signal),
                    ..InputParams::default()
                };
                Recording::from_sigmf_json(std::path::Path::new(&label), &meta.to_json(), &params)
            })
            .collect::<Result<Vec<_>, _>>()?;
        let bytes_per_sample = info.format.bytes_per_sample() as u64;
        let samples = session.budget(CHUNK_EPOCHS, 1).recording_bytes / bytes_per_sample;
        let receiver =
            ReceiveSession::open_streams(recordings, streams, samples, assistance, config)?;
        Ok(Self {
            session,
            feed: Feed { feed, inputs_of },
            receiver,
        })
    }

    /// The receiver, set up and waiting for samples.
    pub fn receiver(&self) -> &ReceiveSession {
        &self.receiver
    }

    /// Synthesise on a thread of its own, computing geometry `chunk_epochs` epochs at a
    /// time into `sinks`, while the receiver hands each epoch to `epochs` and reports its
    /// progress to `progress` (as [`ReceiveSession::run`]). A synthesis error comes first:
    /// it also ends the receiver's input early.
    pub fn run(
        self,
        chunk_epochs: usize,
        sinks: StreamSinks<'_>,
        epochs: &mut dyn EpochSink,
        progress: impl FnMut(u64, &ReceiverSummary),
    ) -> Result<(SynthReport, ReceiverSummary), ChainError> {
        let Self {
            session,
            mut feed,
            mut receiver,
        } = self;
        std::thread::scope(|scope| {
            let synth = scope.spawn(move || {
                session.run(
                    chunk_epochs,
                    Sinks {
                        samples: &mut feed,
                        truth: sinks.truth,
                        observations: sinks.observations,
                        measurements: &mut Discard,
                        progress: sinks.progress,
                    },
                )
            });
            let received = receiver.run(epochs, progress);
            // The readers go with the receiver: a synthesiser still sending fails at once.
            drop(receiver);
            let report = synth.join().map_err(|_| ChainError::SynthPanicked)??;
            Ok((report, received?))
        })
    }
}
