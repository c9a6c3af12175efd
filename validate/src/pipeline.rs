//! The whole chain as a user runs it, in one call, for any table that needs it: synthesise
//! a scenario's I/Q into SigMF recordings with the broadcast navigation file and the
//! rounded start state (`receiver.toml`) beside them, run the bundled receiver over the
//! recordings with that assistance, and hand back each antenna's observations exactly as
//! its RINEX observation file would hold them (through the one RINEX writer and reader).

use skyforge_orbits::ephemeris::rinex_nav_write::write_nav;
use skyforge_receiver::input::InputParams;
use skyforge_receiver::observables::Observation;
use skyforge_receiver::pipeline::{EpochReport, ReceiverConfig, ReceiverSummary, assistance_toml};
use skyforge_receiver::session::{
    Assistance, EpochSink, ReceiveSession, SessionError, SinkError, read_config,
};
use skyforge_scenarios::Scenario;
use skyforge_signals::observation::rinex_write::{
    ObsHeader, ObsWriter, RECEIVER_TYPE, calendar_gpst,
};
use skyforge_signals::observation::{ObsFile, ObsReadError, parse_obs_text};
use skyforge_signals::synth::session::{Discard, Sinks, SynthError, SynthSession, SynthWorld};
use skyforge_signals::synth::sigmf::{RunInfo, SigmfRecordings, recording_name};
use std::path::{Path, PathBuf};

/// Geometry epochs per streamed chunk (as `skyforge synth`'s default).
const CHUNK_EPOCHS: usize = 10;

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
}

/// What the chain produced.
#[derive(Debug, Clone)]
pub struct ChainOutput {
    /// The antennas, in the scenario's order.
    pub antennas: Vec<String>,
    /// Each antenna's observations (as its RINEX file holds them).
    pub observations: Vec<ObsFile>,
    /// The receiver's counters.
    pub summary: ReceiverSummary,
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
    let world = scenario
        .build()
        .map_err(|e| ChainError::Scenario(Box::new(e)))?;
    let session = SynthSession::new(
        SynthWorld {
            origin: &world.origin,
            ephemerides: &world.ephemerides,
            satellites: &world.satellites,
            platform: world.platform,
            antennas: &world.antennas,
            duration_s: world.duration_s,
        },
        signal,
        &scenario.errors,
        scenario.seed,
    )?;
    let bands = session.bands().to_vec();
    let nav_path = work.join("nav.rnx");
    let mut nav = Vec::new();
    write_nav(
        session.broadcast_ephemerides(),
        "skyforge",
        &session.broadcast_iono(),
        &mut nav,
    )
    .and_then(|()| std::fs::write(&nav_path, nav))
    .map_err(io(&nav_path))?;
    let mut recordings =
        SigmfRecordings::create(work, &bands, &world.antennas).map_err(io(work))?;
    let report = session.run(
        CHUNK_EPOCHS,
        Sinks {
            samples: &mut recordings,
            truth: &mut Discard,
            observations: &mut Discard,
            progress: &mut |_| {},
        },
    )?;
    recordings
        .finish(&RunInfo {
            format: signal.format,
            sample_rate_hz: signal.sample_rate_hz,
            if_hz: signal.if_hz,
            start: world.origin.start(),
            scenario: scenario.name.clone(),
            seed: scenario.seed,
        })
        .map_err(io(work))?;
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
        nav_file: Some(nav_path),
        approximate,
    };
    let mut receiver = ReceiveSession::open(&files, &InputParams::default(), &assistance, config)?;
    let mut sink = RinexText::new(receiver.antenna_names().len(), receiver.systems());
    let summary = receiver.run(&mut sink, |_, _| {})?;
    let antennas = receiver.antenna_names().to_vec();
    let mut observations = Vec::new();
    for (w, name) in sink.texts.into_iter().zip(&antennas) {
        let label = format!("{name}.obs.rnx");
        let bytes = match w {
            Some(w) => w.finish().map_err(io(Path::new(&label)))?.into_inner(),
            None => Vec::new(),
        };
        observations.push(parse_obs_text(&String::from_utf8_lossy(&bytes), &label)?);
    }
    Ok(ChainOutput {
        antennas,
        observations,
        summary,
    })
}

/// RINEX observation text per antenna, in memory: the epochs with observations.
struct RinexText {
    systems: Vec<skyforge_orbits::ephemeris::System>,
    texts: Vec<Option<ObsWriter<std::io::Cursor<Vec<u8>>>>>,
}

impl RinexText {
    fn new(antennas: usize, systems: Vec<skyforge_orbits::ephemeris::System>) -> Self {
        Self {
            systems,
            texts: (0..antennas).map(|_| None).collect(),
        }
    }
}

impl EpochSink for RinexText {
    fn epoch(&mut self, report: &EpochReport) -> Result<(), SinkError> {
        let at = calendar_gpst(report.t_rx);
        for (a, text) in self.texts.iter_mut().enumerate() {
            let mut records: Vec<_> = report
                .observations
                .iter()
                .filter(|o| o.antenna == a)
                .map(Observation::record)
                .collect();
            if records.is_empty() {
                continue;
            }
            records.sort_by_key(|r| r.sat);
            let writer = match text {
                Some(w) => w,
                empty => empty.insert(ObsWriter::with_header(
                    std::io::Cursor::new(Vec::new()),
                    &ObsHeader {
                        marker: "antenna",
                        receiver_type: RECEIVER_TYPE,
                        antenna_type: "SKYFORGE",
                        approx_ecef_m: None,
                        first: at,
                        interval_s: 0.0,
                        systems: &self.systems,
                    },
                )?),
            };
            writer.epoch(at, &records)?;
        }
        Ok(())
    }
}
