//! An observation-level run kept in memory: each antenna's observables as `skyforge run`
//! writes them to `observations/`, the observation truth beside them, the platform's
//! true state at every geometry epoch and the broadcast ephemerides: what the attitude
//! chain reads and what it is compared with.

use skyforge_orbits::Vec3;
use skyforge_orbits::ephemeris::BroadcastEphemeris;
use skyforge_orbits::platform::PlatformState;
use skyforge_scenarios::Scenario;
use skyforge_signals::obs_model::{Level, ObservationModel};
use skyforge_signals::observation::{ObsEpoch, ObsFile, ObsRecord};
use skyforge_signals::synth::link::LinkTruth;
use skyforge_signals::synth::session::{
    Discard, GEOMETRY_STEP_S, ObservationSink, SinkError, Sinks, SynthError, SynthSession,
    TruthSink,
};
use skyforge_signals::truth::geometry::GeometryChunk;
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
}

impl From<skyforge_scenarios::ScenarioError> for RunError {
    fn from(e: skyforge_scenarios::ScenarioError) -> Self {
        RunError::Scenario(Box::new(e))
    }
}

/// What an observation-level run produced.
#[derive(Debug, Clone)]
pub struct ObservationRun {
    /// The scenario's start (second 0 of [`Self::platform`]).
    pub start: hifitime::Epoch,
    /// Antenna names, scenario order (the master first).
    pub antennas: Vec<String>,
    /// Nominal body positions (m), what the receiver is told.
    pub nominal_body_m: Vec<Vec3>,
    /// True body positions (m): nominal plus the scenario's `offset_body_m`.
    pub true_body_m: Vec<Vec3>,
    /// Each antenna's observables (noise, multipath, integer ambiguities).
    pub measured: Vec<ObsFile>,
    /// Each antenna's observation truth (no noise, no ambiguity).
    pub truth: Vec<ObsFile>,
    /// The platform at every geometry epoch, by whole seconds since the start.
    pub platform: Vec<PlatformState>,
    /// The broadcast ephemerides (what `nav.rnx` holds).
    pub ephemerides: Vec<BroadcastEphemeris>,
}

impl ObservationRun {
    /// The platform's true state at whole second `t_s` since the start, if simulated.
    pub fn platform_at(&self, t_s: f64) -> Option<&PlatformState> {
        let k = (t_s / GEOMETRY_STEP_S).round();
        (k >= 0.0).then(|| self.platform.get(k as usize)).flatten()
    }
}

/// One file per antenna, filled epoch by epoch.
#[derive(Debug)]
struct Collect(Vec<ObsFile>);

impl ObservationSink for Collect {
    fn epoch(
        &mut self,
        antenna: usize,
        at: hifitime::Epoch,
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

/// The platform states of the geometry chunks.
#[derive(Debug, Default)]
struct PlatformTruth(Vec<PlatformState>);

impl TruthSink for PlatformTruth {
    fn signal(&mut self, _: usize, _: &[LinkTruth], _: usize) -> Result<(), SinkError> {
        Ok(())
    }
    fn geometry(&mut self, chunk: &GeometryChunk) -> Result<(), SinkError> {
        self.0.extend_from_slice(&chunk.platform);
        Ok(())
    }
}

/// Run `scenario` at the observation level (whatever its `[observation] level` says), in
/// memory.
pub fn observation_run(scenario: &Scenario) -> Result<ObservationRun, RunError> {
    let signal = scenario.signal.as_ref().ok_or_else(|| {
        RunError::Setup(
            scenario.name.clone(),
            "has no [signal] table (the links' C/N0)",
        )
    })?;
    if scenario.observation.level != Level::Observation {
        return Err(RunError::Setup(
            scenario.name.clone(),
            "is not an observation-level scenario ([observation] level = \"observation\")",
        ));
    }
    let noise = scenario.observation_noise()?;
    let mut world = scenario.build()?;
    let nominal_body_m = world.antennas.iter().map(|a| a.nominal_body_m).collect();
    let true_body_m = world.antennas.iter().map(|a| a.true_body_m).collect();
    let antennas: Vec<String> = world.antennas.iter().map(|a| a.name.clone()).collect();
    let start = world.origin.start();
    let model = ObservationModel::new(noise, scenario.seed, antennas.len(), GEOMETRY_STEP_S);
    // The signal truth between whole seconds is not kept here: without it (rate 0) the
    // session computes the truth once a second instead of `truth_rate_hz` times (1000 by
    // default); the whole-second records, all the observation level uses, are the same.
    let signal = &skyforge_signals::synth::config::SignalConfig {
        truth_rate_hz: 0,
        ..signal.clone()
    };
    let session = SynthSession::new(world.synth_world(), signal, &scenario.errors, scenario.seed)?
        .observation_level(model);
    let ephemerides = session.broadcast_ephemerides().to_vec();
    let files = |what: &str| {
        Collect(
            antennas
                .iter()
                .map(|a| ObsFile {
                    source: PathBuf::from(format!("{a} {what}")),
                    approx_ecef_m: None,
                    epochs: Vec::new(),
                })
                .collect(),
        )
    };
    let (mut measured, mut truth) = (files("observations"), files("observation truth"));
    let mut platform = PlatformTruth::default();
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
    Ok(ObservationRun {
        start,
        antennas,
        nominal_body_m,
        true_body_m,
        measured: measured.0,
        truth: truth.0,
        platform: platform.0,
        ephemerides,
    })
}
