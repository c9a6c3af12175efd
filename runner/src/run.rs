//! A run kept in memory: each antenna's observables as `skyforge run` (observation
//! level) or the receiver on the synthesised samples (signal level, `skyforge synth
//! --receive`) writes them, the observation truth beside them, the platform's true state
//! at every geometry epoch and the broadcast navigation data: what the attitude chain and
//! the studies' metrics read and what they are compared with.

use crate::chain::{ChainError, StreamSinks, StreamedChain};
use hifitime::{Duration, Epoch};
use skyforge_gnss::observation::{ObsEpoch, ObsFile, ObsRecord};
use skyforge_gnss::signal::Signal;
use skyforge_navigation::pvt::{Fix, PvtConfig};
use skyforge_navigation::relative::single_point_fixes;
use skyforge_orbits::Vec3;
use skyforge_orbits::constants::C_MPS;
use skyforge_orbits::ephemeris::KlobucharCoeffs;
use skyforge_orbits::ephemeris::rinex_nav_iono::BroadcastIono;
use skyforge_orbits::ephemeris::{BroadcastEphemeris, EphemerisStore, System};
use skyforge_orbits::platform::Hermite3;
use skyforge_orbits::platform::PlatformState;
use skyforge_orbits::time::TimeOrigin;
use skyforge_receiver::pipeline::{EpochReport, ReceiverConfig, assistance_toml};
use skyforge_receiver::session::{
    Assistance, EpochSink, NavSource, SessionError, SinkError as EpochSinkError, parse_config,
};
use skyforge_scenarios::{Scenario, World};
use skyforge_signals::obs_model::Level;
use skyforge_signals::synth::SignalConfig;
use skyforge_signals::synth::link::LinkTruth;
use skyforge_signals::synth::{
    Discard, GEOMETRY_STEP_S, ObservationSink, SinkError, Sinks, SynthError, SynthSession,
    TruthSink,
};
use skyforge_signals::truth::GeometryChunk;
use std::path::PathBuf;

/// Geometry epochs per streamed chunk (as `skyforge synth`'s default).
const CHUNK_EPOCHS: usize = 10;

/// Why the run could not be made.
#[derive(Debug, thiserror::Error)]
pub enum RunError {
    #[error("scenario: {0}")]
    Scenario(Box<skyforge_scenarios::ScenarioError>),
    #[error("scenario {0}: {1}")]
    Setup(String, &'static str),
    #[error("synthesis: {0}")]
    Synth(#[from] SynthError),
    /// The signal level's synthesis and reception.
    #[error("{0}")]
    Chain(Box<ChainError>),
}

impl From<skyforge_scenarios::ScenarioError> for RunError {
    fn from(e: skyforge_scenarios::ScenarioError) -> Self {
        RunError::Scenario(Box::new(e))
    }
}

impl From<ChainError> for RunError {
    fn from(e: ChainError) -> Self {
        RunError::Chain(Box::new(e))
    }
}

/// What a run produced.
#[derive(Debug, Clone)]
pub struct ObservationRun {
    /// The scenario's start (second 0 of [`Self::platform`]).
    pub start: Epoch,
    /// Antenna names, scenario order (the master first).
    pub antennas: Vec<String>,
    /// Nominal body positions (m), what the receiver is told.
    pub nominal_body_m: Vec<Vec3>,
    /// True body positions (m): nominal plus the scenario's `offset_body_m`.
    pub true_body_m: Vec<Vec3>,
    /// Each antenna's observables: the observation-level model's (noise, multipath,
    /// integer ambiguities) or the receiver's.
    pub measured: Vec<ObsFile>,
    /// Each antenna's observation truth (no noise, no ambiguity).
    pub truth: Vec<ObsFile>,
    /// The platform at every geometry epoch, by whole seconds since the start.
    pub platform: Vec<PlatformState>,
    /// The broadcast ephemerides (what `nav.rnx` holds).
    pub ephemerides: Vec<BroadcastEphemeris>,
    /// The broadcast ionosphere (`nav.rnx`'s header; none when the ionosphere is off).
    pub iono: BroadcastIono,
    /// The first antenna's fixes by the receiver itself (signal level); `None` at the
    /// observation level, where [`Self::first_antenna_fixes`] makes them.
    pub receiver_fixes: Option<Vec<PositionFix>>,
}

/// A single-point fix: the instant it refers to and the position there.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PositionFix {
    /// GPST: the epoch's tag less the receiver clock offset the fix solved for.
    pub at: Epoch,
    pub r_ecef_m: Vec3,
}

impl PositionFix {
    /// `fix`, solved at the epoch tagged `tag` (the receiver's clock).
    pub fn new(tag: Epoch, fix: &Fix) -> Self {
        Self {
            at: tag - Duration::from_seconds(fix.clock_bias_m / C_MPS),
            r_ecef_m: fix.r_ecef_m,
        }
    }
}

impl ObservationRun {
    /// The platform's true state at whole second `t_s` since the start, if simulated.
    pub fn platform_at(&self, t_s: f64) -> Option<&PlatformState> {
        let k = (t_s / GEOMETRY_STEP_S).round();
        (k >= 0.0).then(|| self.platform.get(k as usize)).flatten()
    }

    /// Antenna `antenna`'s true position (ECEF) at `t_s` seconds since the start, inside
    /// the simulated span: the platform's centre by cubic Hermite interpolation of the
    /// geometry epochs' positions and velocities on either side, the lever arm turned by
    /// the nearest epoch's attitude (at most half a step away: 0.5 mm for 1 m at a LEO's
    /// 1 mrad/s).
    pub fn true_position(&self, antenna: usize, t_s: f64) -> Option<Vec3> {
        let body = self.true_body_m.get(antenna)?;
        let last = self.platform.len().checked_sub(2)?;
        if !(0.0..=(last + 1) as f64 * GEOMETRY_STEP_S).contains(&t_s) {
            return None;
        }
        let k = ((t_s / GEOMETRY_STEP_S) as usize).min(last);
        let (a, b) = (&self.platform[k], &self.platform[k + 1]);
        let t0 = k as f64 * GEOMETRY_STEP_S;
        let (centre, _) = Hermite3::with_slopes(
            vec![t0, t0 + GEOMETRY_STEP_S],
            vec![a.r_ecef_m, b.r_ecef_m],
            vec![a.v_ecef_mps, b.v_ecef_mps],
        )
        .eval(t_s);
        Some(centre + self.platform_at(t_s)?.c_body_ecef * body)
    }

    /// The first antenna's single-point fixes: the receiver's own at the signal level; at
    /// the observation level, the receiver's PVT (its default settings with the broadcast
    /// ionosphere, as its epoch stage) over the observations with the broadcast
    /// ephemerides, epoch by epoch from the last position found, as the attitude chain
    /// positions its master.
    pub fn first_antenna_fixes(&self) -> Vec<PositionFix> {
        if let Some(fixes) = &self.receiver_fixes {
            return fixes.clone();
        }
        self.first_antenna_fixes_with(&ReceiverConfig::default().pvt, &Signal::DEFAULT_FIX)
    }

    /// The first antenna's single-point fixes from its observations on `signals` with the
    /// PVT settings `pvt` (the broadcast ionosphere coefficients added), epoch by epoch
    /// from the last position found.
    pub fn first_antenna_fixes_with(
        &self,
        pvt: &PvtConfig,
        signals: &[Signal],
    ) -> Vec<PositionFix> {
        let Some((file, first)) = self
            .measured
            .first()
            .and_then(|f| Some((f, f.epochs.first()?)))
        else {
            return Vec::new();
        };
        let origin = TimeOrigin::new(first.time);
        let store = EphemerisStore::new(self.ephemerides.clone(), &origin);
        let config = PvtConfig {
            iono_gps: self.iono.gps,
            iono_bds: self.iono.bds,
            ..pvt.clone()
        };
        single_point_fixes(file, &store, &origin, signals, &config)
            .iter()
            .zip(&file.epochs)
            .filter_map(|(fix, e)| Some(PositionFix::new(e.time, fix.as_ref().ok()?)))
            .collect()
    }
}

/// One file per antenna, filled epoch by epoch.
#[derive(Debug)]
struct Collect(Vec<ObsFile>);

impl Collect {
    /// An empty file per antenna of `antennas`, labelled `what`.
    fn new(antennas: &[String], what: &str) -> Self {
        Self(
            antennas
                .iter()
                .map(|a| ObsFile {
                    source: PathBuf::from(format!("{a} {what}")),
                    approx_ecef_m: None,
                    codes: Default::default(),
                    epochs: Vec::new(),
                    marker: None,
                    dropped: Vec::new(),
                })
                .collect(),
        )
    }
}

impl ObservationSink for Collect {
    fn epoch(
        &mut self,
        antenna: usize,
        at: Epoch,
        position_ecef_m: &Vec3,
        records: &[ObsRecord],
    ) -> Result<(), SinkError> {
        // The header position a RINEX file of this antenna would carry: the first epoch's.
        self.0[antenna]
            .approx_ecef_m
            .get_or_insert(*position_ecef_m);
        self.0[antenna].epochs.push(ObsEpoch {
            time: at,
            sats: records.to_vec(),
        });
        Ok(())
    }
}

/// The receiver's epochs, kept as its RINEX files and first antenna's fixes would hold
/// them.
#[derive(Debug)]
struct Received {
    files: Collect,
    fixes: Vec<PositionFix>,
}

impl EpochSink for Received {
    fn epoch(&mut self, report: &EpochReport) -> Result<(), EpochSinkError> {
        for (a, file) in self.files.0.iter_mut().enumerate() {
            let sats = report.records(a);
            if !sats.is_empty() {
                file.epochs.push(ObsEpoch {
                    time: report.t_rx,
                    sats,
                });
            }
        }
        let first = report.fixes.iter().find(|f| f.antenna == 0);
        if let Some(fix) = first.and_then(|f| f.fix.as_ref().ok()) {
            self.fixes.push(PositionFix::new(report.t_rx, fix));
        }
        Ok(())
    }
}

/// The platform states of the geometry chunks.
#[derive(Debug, Default)]
struct PlatformTruth(Vec<PlatformState>);

impl TruthSink for PlatformTruth {
    fn signal(&mut self, _: usize, _: &[LinkTruth], _: &[usize]) -> Result<(), SinkError> {
        Ok(())
    }
    fn geometry(&mut self, chunk: &GeometryChunk) -> Result<(), SinkError> {
        self.0.extend_from_slice(&chunk.platform);
        Ok(())
    }
}

/// `scenario`'s signal settings with the signal truth at the observation epochs only
/// (whole seconds, or `[observation] rate_hz`): a run keeps nothing between them, so the
/// session computes the truth that often instead of `truth_rate_hz` times a second (1000
/// by default); those records, all a run uses (the observation truth, and the observation
/// level's observables), and the samples are the same.
fn whole_second_truth(scenario: &Scenario) -> Result<SignalConfig, RunError> {
    let signal = scenario.signal.as_ref().ok_or_else(|| {
        RunError::Setup(
            scenario.name.clone(),
            "has no [signal] table (the links' C/N0)",
        )
    })?;
    Ok(SignalConfig {
        truth_rate_hz: scenario.observation.rate_hz(),
        ..signal.clone()
    })
}

/// The Klobuchar coefficients `session` broadcasts.
fn broadcast_iono(session: &SynthSession<'_>) -> BroadcastIono {
    let iono = session.broadcast_iono();
    let of = |system: System| {
        iono.iter()
            .find(|c| c.0 == system)
            .map(|&(_, alpha, beta)| KlobucharCoeffs { alpha, beta })
    };
    BroadcastIono {
        gps: of(System::Gps),
        bds: of(System::Beidou),
    }
}

/// The run of `world` before it is made: its start and antennas, nothing measured yet.
fn unmade(world: &World) -> ObservationRun {
    ObservationRun {
        start: world.origin.start(),
        antennas: world.antennas.iter().map(|a| a.name.clone()).collect(),
        nominal_body_m: world.antennas.iter().map(|a| a.nominal_body_m).collect(),
        true_body_m: world.antennas.iter().map(|a| a.true_body_m).collect(),
        measured: Vec::new(),
        truth: Vec::new(),
        platform: Vec::new(),
        ephemerides: Vec::new(),
        iono: BroadcastIono::default(),
        receiver_fixes: None,
    }
}

/// Run `scenario` at its level (`[observation] level`), in memory.
pub fn run_at_level(scenario: &Scenario) -> Result<ObservationRun, RunError> {
    match scenario.observation.level {
        Level::Observation => observation_run(scenario),
        Level::Signal => signal_run(scenario),
    }
}

/// Run `scenario` at the observation level, in memory.
pub fn observation_run(scenario: &Scenario) -> Result<ObservationRun, RunError> {
    let signal = &whole_second_truth(scenario)?;
    if scenario.observation.level != Level::Observation {
        return Err(RunError::Setup(
            scenario.name.clone(),
            "is not an observation-level scenario ([observation] level = \"observation\")",
        ));
    }
    let mut world = scenario.build()?;
    let mut run = unmade(&world);
    let antennas = &run.antennas;
    let model = scenario.observation_model(antennas.len(), scenario.observation.step_s())?;
    let session = SynthSession::new(
        world.synth_world(),
        signal,
        &scenario.errors,
        scenario.receiver_seed(),
    )?
    .observation_level(model, &scenario.observation.observed_signals)?
    .with_jammers(&scenario.jammers)?;
    let mut measured = Collect::new(antennas, "observations");
    let mut truth = Collect::new(antennas, "observation truth");
    let mut platform = PlatformTruth::default();
    run.ephemerides = session.broadcast_ephemerides().to_vec();
    run.iono = broadcast_iono(&session);
    session.run(
        CHUNK_EPOCHS,
        Sinks {
            samples: &mut Discard,
            truth: &mut platform,
            observations: &mut truth,
            measurements: &mut measured,
            progress: &mut |_| {},
        },
    )?;
    run.measured = measured.0;
    run.truth = truth.0;
    run.platform = platform.0;
    Ok(run)
}

/// Run `scenario` at the signal level, in memory: its samples synthesised and received as
/// they are rendered ([`StreamedChain`], as `skyforge synth --receive`), the receiver told
/// what `synth` writes beside the recordings (the navigation file, and the defaults of
/// `receiver.toml` with the rounded start state) and nothing else. A receiver that finds
/// no signal leaves the run without observations.
pub fn signal_run(scenario: &Scenario) -> Result<ObservationRun, RunError> {
    signal_run_with(scenario, "")
}

/// [`signal_run`] with the receiver also given `receiver_toml`: tables of its
/// configuration file (`skyforge receive --config`, docs/receiver.md) beside the `[assist]`
/// table `synth` writes, as a user adds them to `receiver.toml` before `skyforge synth
/// --receive --receiver-config` (e.g. `[observables]\nrate_hz = 10.0` for 10 Hz
/// observables). A table the configuration does not know, a value out of its range or a
/// second `[assist]` is an error.
pub fn signal_run_with(
    scenario: &Scenario,
    receiver_toml: &str,
) -> Result<ObservationRun, RunError> {
    let signal = &whole_second_truth(scenario)?;
    let mut world = scenario.build()?;
    let mut run = unmade(&world);
    let mut session = SynthSession::new(
        world.synth_world(),
        signal,
        &scenario.errors,
        scenario.receiver_seed(),
    )?
    .with_jammers(&scenario.jammers)?;
    run.ephemerides = session.broadcast_ephemerides().to_vec();
    run.iono = broadcast_iono(&session);
    let mut nav = Vec::new();
    session
        .write_navigation(&mut nav)
        .map_err(|e| ChainError::Io {
            path: PathBuf::from("nav.rnx (in memory)"),
            error: e,
        })?;
    let (r, v) = session.start_state()?;
    let text = format!("{}\n{receiver_toml}", assistance_toml(&r, &v));
    let (config, approximate) =
        parse_config(&text, "receiver.toml (in memory)").map_err(ChainError::Receive)?;
    let assistance = Assistance {
        nav: Some(NavSource::Text {
            source: "nav.rnx (in memory)".into(),
            text: String::from_utf8_lossy(&nav).into_owned(),
        }),
        approximate,
    };
    let info = session.recording_info(&scenario.name, scenario.seed, scenario.vehicle.as_deref());
    // The receiver numbers the antennas in the scenario's order (the chain hands it the
    // recordings band by band, each band's antennas in that order).
    let chain = StreamedChain::open(session, &info, &assistance, config)?;
    let mut received = Received {
        files: Collect::new(&run.antennas, "received"),
        fixes: Vec::new(),
    };
    for file in &mut received.files.0 {
        file.approx_ecef_m = approximate.map(|a| a.r_ecef_m);
    }
    let mut truth = Collect::new(&run.antennas, "observation truth");
    let mut platform = PlatformTruth::default();
    let sinks = StreamSinks {
        truth: &mut platform,
        observations: &mut truth,
        progress: &mut |_| {},
    };
    match chain.run(CHUNK_EPOCHS, sinks, &mut received, |_, _| {}) {
        Ok(_) | Err(ChainError::Receive(SessionError::NoSignal(_))) => {}
        Err(e) => return Err(e.into()),
    }
    run.measured = received.files.0;
    run.truth = truth.0;
    run.platform = platform.0;
    run.receiver_fixes = Some(received.fixes);
    Ok(run)
}
