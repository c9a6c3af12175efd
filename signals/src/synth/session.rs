//! A streaming synthesis session: from the scenario's world (origin, constellations,
//! platform, antennas) and its signal and error settings to I/Q blocks per band and
//! antenna, the geometry and signal truth of the transmitted signals and the observation
//! truth at whole seconds, handed as they are made to small sink traits. The caller picks
//! the writers (SigMF/raw files, HDF5, RINEX) by implementing the traits; nothing here
//! knows about files except through them.
//!
//! Memory is bounded by one chunk of geometry epochs plus one slice of samples
//! ([`super::render::SLICE_BYTES`]), whatever the duration and the sample rate
//! ([`super::budget`] gives the bound).

use super::config::{BLOCK_S, RecordingLayout, SignalConfig};
use super::constellation::{self, TransmitterError};
use super::filter::BandFilter;
use super::link_terms::{AntennaEpoch, LinkTerms};
use super::quantise::QuantiseError;
use super::render::{LinkTruth, Synthesiser};
use super::transmitter::Transmitter;
use crate::antenna::Antenna;
use crate::errors::clock::{ClockModel, RelativisticOffset, proper_rate};
use crate::errors::events::EventSchedule;
use crate::errors::ionosphere::{IonoConfig, IonoModel, KlobucharCoeffs};
use crate::errors::seed::{Stream, stream_rng};
use crate::errors::{ErrorsConfig, SatelliteErrors, clock::OscillatorConfig};
use crate::interference::{
    Jammer, JammerConfig, JammerLink, JammerWaveform, LOCK_THRESHOLD_DBHZ, cn0_loss_db,
};
use crate::obs_model::ObservationModel;
use crate::truth::geometry::{GeometryChunk, GeometryTruth, StreamError};
use hifitime::Epoch;
use skyforge_gnss::observation::ObsRecord;
use skyforge_gnss::sample_format::SampleFormat;
use skyforge_gnss::signal::Signal;
use skyforge_orbits::Vec3;
use skyforge_orbits::check::Invalid;
use skyforge_orbits::ephemeris::{
    BroadcastEphemeris, EphemerisStore, NavHeader, SatId, System, TimeSystemCorr,
};
use skyforge_orbits::platform::{Platform, PlatformError, PlatformState};
use skyforge_orbits::time::{GstGpsOffset, TimeOrigin};
use std::collections::BTreeMap;

/// Geometry epochs the renderer interpolates between (s).
pub const GEOMETRY_STEP_S: f64 = 1.0;
/// Synthesis blocks in a second.
const BLOCKS_PER_SECOND: u64 = (1.0 / BLOCK_S) as u64;

/// Longest receiver-clock step at the observation level, in blocks (0.1 s): its flicker
/// components then start at a 0.1 s time constant, and the clock's Allan deviation stays
/// within 2.5 % of the model's from 1 s and within 1 % from 10 s (`errors::clock::model`),
/// while a run steps it 100 times less often than the signal level's 1 ms.
pub const OBSERVATION_CLOCK_STEP_BLOCKS: u64 = 100;

/// An error a sink reports (a file that cannot be written, say).
pub type SinkError = Box<dyn std::error::Error + Send + Sync>;

/// Receives the sample bytes of every band and antenna, block by block, in time order.
pub trait SampleSink {
    /// Bytes of band `band`'s recording of antenna `antenna` (index into the world's
    /// antennas), following the bytes given before.
    fn samples(&mut self, band: usize, antenna: usize, bytes: &[u8]) -> Result<(), SinkError>;
}

/// Receives the truth of the transmitted signals.
pub trait TruthSink {
    /// Link truth of antenna `antenna` recorded by one band since the last call; a
    /// record's transmitter `tx` is satellite `sat_index[tx]` of the session's
    /// [`SynthSession::satellites`].
    fn signal(
        &mut self,
        antenna: usize,
        records: &[LinkTruth],
        sat_index: &[usize],
    ) -> Result<(), SinkError>;
    /// One chunk of geometry epochs, after its samples.
    fn geometry(&mut self, chunk: &GeometryChunk) -> Result<(), SinkError>;
    /// The `jammers`' links at geometry epoch `t_s` (`links[a * n + j]` for antenna `a`
    /// and jammer `j` of `n`), before the epoch's samples; never called without jammers.
    fn jammers(
        &mut self,
        _t_s: f64,
        _jammers: &[Jammer],
        _links: &[JammerLink],
    ) -> Result<(), SinkError> {
        Ok(())
    }
}

/// Receives the observation truth of each antenna at whole seconds.
pub trait ObservationSink {
    /// Antenna `antenna`'s observations at `at` (GPS time of the receiver clock), sorted by
    /// satellite; `position_ecef_m` is the antenna's true position at the geometry epoch
    /// that ends the interval `at` opens (within a second of `at`: for a file header's
    /// approximate position).
    fn epoch(
        &mut self,
        antenna: usize,
        at: Epoch,
        position_ecef_m: &Vec3,
        records: &[ObsRecord],
    ) -> Result<(), SinkError>;
}

/// A sink that keeps nothing: for the products a caller does not want.
#[derive(Debug, Clone, Copy, Default)]
pub struct Discard;

impl SampleSink for Discard {
    fn samples(&mut self, _: usize, _: usize, _: &[u8]) -> Result<(), SinkError> {
        Ok(())
    }
}

impl TruthSink for Discard {
    fn signal(&mut self, _: usize, _: &[LinkTruth], _: &[usize]) -> Result<(), SinkError> {
        Ok(())
    }
    fn geometry(&mut self, _: &GeometryChunk) -> Result<(), SinkError> {
        Ok(())
    }
}

impl ObservationSink for Discard {
    fn epoch(&mut self, _: usize, _: Epoch, _: &Vec3, _: &[ObsRecord]) -> Result<(), SinkError> {
        Ok(())
    }
}

/// Where a session's products go.
pub struct Sinks<'s> {
    pub samples: &'s mut dyn SampleSink,
    pub truth: &'s mut dyn TruthSink,
    pub observations: &'s mut dyn ObservationSink,
    /// The observation-level observables (nothing at the signal level).
    pub measurements: &'s mut dyn ObservationSink,
    /// Told the number of geometry epochs completed after each chunk.
    pub progress: &'s mut dyn FnMut(usize),
}

impl std::fmt::Debug for Sinks<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Sinks").finish_non_exhaustive()
    }
}

/// Why a session could not be set up or run.
#[derive(Debug, thiserror::Error)]
pub enum SynthError {
    /// A setting of the scenario is invalid; the field path is in the error.
    #[error("{0}")]
    Invalid(Invalid),
    #[error("{0} transmitters: {1}")]
    Transmitters(Signal, TransmitterError),
    #[error("receiver clock: {0}")]
    Clock(Invalid),
    #[error("signal configuration: {0}")]
    Quantiser(#[from] QuantiseError),
    #[error(transparent)]
    Platform(#[from] PlatformError),
    #[error("{0}")]
    Sink(SinkError),
}

/// The world a session synthesises: what the scenario builds.
#[derive(Debug)]
pub struct SynthWorld<'a> {
    pub origin: &'a TimeOrigin,
    /// Ephemerides of the enabled constellations (those valid at the start are broadcast).
    pub ephemerides: &'a EphemerisStore,
    pub satellites: &'a [SatId],
    /// Propagated as the session streams.
    pub platform: &'a mut Platform,
    pub antennas: &'a [Antenna],
    pub duration_s: f64,
    /// GST - GPST: Galileo's satellite clocks keep it, its messages broadcast it.
    pub gst_gps: GstGpsOffset,
    /// The satellites' orbit and clock errors, drawn for the run (none: the signals follow
    /// the broadcast ephemerides).
    pub satellite_errors: Option<&'a SatelliteErrors>,
}

/// The transmitters of one band, written to one recording per antenna: one signal's, or
/// (`[signal] recordings = "per-band"`) those of every signal on one carrier.
#[derive(Debug, Clone, PartialEq)]
pub struct Band {
    /// The signals recorded, in the order their transmitters come; never empty.
    signals: Vec<Signal>,
    /// Index of the band's first transmitter among the session's, band by band.
    pub first: usize,
    /// Its transmitters (one per satellite and signal).
    pub count: usize,
}

impl Band {
    /// The band of one signal, its `count` transmitters from the session's `first`.
    pub fn new(signal: Signal, first: usize, count: usize) -> Self {
        Self {
            signals: vec![signal],
            first,
            count,
        }
    }

    /// The band with `signal`'s `count` transmitters added after its own.
    fn with(mut self, signal: Signal, count: usize) -> Self {
        self.signals.push(signal);
        self.count += count;
        self
    }

    /// The signals recorded.
    pub fn signals(&self) -> &[Signal] {
        &self.signals
    }

    /// The band's first signal: its carrier is the band's.
    pub fn signal(&self) -> Signal {
        self.signals[0]
    }

    /// The recording's tag: the signal's (`gps-l1ca`), or the signals' joined by `+`
    /// (`gps-l1ca+gal-e1`).
    pub fn tag(&self) -> String {
        let tags: Vec<&str> = self.signals.iter().map(|s| s.tag()).collect();
        tags.join("+")
    }

    /// The signals' names, for people (`GPS L1 C/A + GAL E1`).
    pub fn name(&self) -> String {
        let names: Vec<&str> = self.signals.iter().map(|s| s.name()).collect();
        names.join(" + ")
    }

    /// Whether the band records `signal`.
    pub fn records(&self, signal: Signal) -> bool {
        self.signals.contains(&signal)
    }
}

/// What a finished session reports.
#[derive(Debug, Clone, PartialEq)]
pub struct SynthReport {
    /// The platform's centre-of-mass position and velocity (ECEF) at the start.
    pub start_state: Option<(Vec3, Vec3)>,
    /// Sample components clipped by the quantisers.
    pub clipped: u64,
}

/// A synthesis set up and ready to stream.
#[derive(Debug)]
pub struct SynthSession<'a> {
    world: SynthWorld<'a>,
    signal: &'a SignalConfig,
    errors: &'a ErrorsConfig,
    seed: u64,
    /// The ionosphere the signals follow (GPS coefficients as broadcast).
    iono: IonoConfig,
    bands: Vec<Band>,
    /// Every band's transmitters, band by band ([`Band::first`] counts in them).
    transmitters: Vec<Transmitter>,
    /// The transmitting satellites, each once, in the order they first transmit.
    sats: Vec<SatId>,
    /// Each transmitter's satellite: its index in `sats`.
    sat_of: Vec<usize>,
    /// The ephemerides as broadcast (quantised in the messages), one per satellite of
    /// `sats`: the orbits the signals follow.
    broadcast: Vec<BroadcastEphemeris>,
    clocks: Vec<ClockModel>,
    events: EventSchedule,
    filter: Option<BandFilter>,
    /// Set for the observation level: observables from truth and this model, no samples.
    observation_model: Option<ObservationModel>,
    /// Observed-only signals drawn besides the synthesised ones (observation level).
    observed: Vec<Signal>,
    /// The jammers ([`Self::with_jammers`]).
    jammers: Vec<Jammer>,
}

/// The satellites of `transmitters`, each once in the order they first appear, and each
/// transmitter's index among them.
fn satellites_of(transmitters: &[Transmitter]) -> (Vec<SatId>, Vec<usize>) {
    let mut sats: Vec<SatId> = Vec::new();
    let sat_of = transmitters
        .iter()
        .map(|t| {
            sats.iter().position(|&s| s == t.sat).unwrap_or_else(|| {
                sats.push(t.sat);
                sats.len() - 1
            })
        })
        .collect();
    (sats, sat_of)
}

/// The bands of `per_signal` (each signal's transmitters, in order) laid out by `layout`,
/// and their transmitters band by band; a signal without transmitters gets no band.
fn group_bands<T>(
    layout: RecordingLayout,
    per_signal: Vec<(Signal, Vec<T>)>,
) -> (Vec<Band>, Vec<T>) {
    let mut groups: Vec<(Band, Vec<T>)> = Vec::new();
    for (sig, txs) in per_signal.into_iter().filter(|(_, t)| !t.is_empty()) {
        match groups
            .iter_mut()
            .find(|(b, _)| layout.together(b.signal(), sig))
        {
            Some((band, list)) => {
                *band = band.clone().with(sig, txs.len());
                list.extend(txs);
            }
            None => groups.push((Band::new(sig, 0, txs.len()), txs)),
        }
    }
    let mut bands = Vec::new();
    let mut transmitters = Vec::new();
    for (band, txs) in groups {
        bands.push(Band {
            first: transmitters.len(),
            ..band
        });
        transmitters.extend(txs);
    }
    (bands, transmitters)
}

/// Every satellite's ephemeris at the start (the set its message will carry).
fn ephemerides_at_start(world: &SynthWorld<'_>) -> Vec<BroadcastEphemeris> {
    world
        .satellites
        .iter()
        .filter_map(|&s| world.ephemerides.select(s, 0.0).map(|b| b.eph.clone()))
        .collect()
}

/// Blocks per receiver-clock step at the observation level, whose truth samples the clock
/// only every `truth_every` blocks: the largest divisor of that up to
/// [`OBSERVATION_CLOCK_STEP_BLOCKS`], so that every truth record falls on a step.
fn observation_clock_step(truth_every: u64) -> u64 {
    let (mut a, mut b) = (truth_every, OBSERVATION_CLOCK_STEP_BLOCKS);
    while b != 0 {
        (a, b) = (b, a % b);
    }
    a.max(1)
}

/// One oscillator for the receiver, or one per antenna; every band gets a clone, so the
/// bands of one receiver share its clock.
fn receiver_clocks(
    osc: Option<&OscillatorConfig>,
    n_antennas: usize,
    seed: u64,
    step_blocks: u64,
) -> Result<Vec<ClockModel>, SynthError> {
    let Some(osc) = osc else {
        return Ok(Vec::new());
    };
    let h = osc
        .power_law()
        .map_err(|e| SynthError::Invalid(e.within("errors.receiver_clock")))?;
    let count = if osc.per_antenna { n_antennas } else { 1 };
    (0..count)
        .map(|i| {
            ClockModel::new(
                &h,
                osc.bias_s,
                osc.drift,
                step_blocks as f64 * BLOCK_S,
                stream_rng(seed, Stream::ReceiverClock, i as u32),
            )
            .map_err(SynthError::Clock)
        })
        .collect()
}

impl<'a> SynthSession<'a> {
    /// Set up the transmitters (navigation messages from the ephemerides valid at the
    /// start), receiver clocks, fault events and front-end filter.
    pub fn new(
        world: SynthWorld<'a>,
        signal: &'a SignalConfig,
        errors: &'a ErrorsConfig,
        seed: u64,
    ) -> Result<Self, SynthError> {
        let ephs = ephemerides_at_start(&world);
        let start = world.origin.start();
        let mut iono = errors.ionosphere.clone();
        let mut per_signal = Vec::new();
        for system in [System::Gps, System::Beidou, System::Galileo] {
            for sig in signal.signals_of(system) {
                let txs = constellation::transmitters(sig, &ephs, start, &iono, &world.gst_gps)
                    .map_err(|e| SynthError::Transmitters(sig, e))?;
                per_signal.push((sig, txs));
            }
        }
        let (bands, transmitters) = group_bands(signal.recordings, per_signal);
        // The signal follows the coefficients as broadcast (quantised in the message).
        if let Some((alpha, beta)) = transmitters
            .iter()
            .filter(|t| t.sat.system == System::Gps)
            .find_map(Transmitter::broadcast_iono)
        {
            iono.gps = KlobucharCoeffs { alpha, beta };
        }
        let (sats, sat_of) = satellites_of(&transmitters);
        // A satellite on several signals follows its first signal's message (the others
        // quantise the same ephemeris their own way).
        let broadcast = sats
            .iter()
            .map(|&sat| {
                let first = sat_of.iter().position(|&i| sats[i] == sat).unwrap_or(0);
                transmitters[first].broadcast_ephemeris()
            })
            .collect();
        let clocks = receiver_clocks(
            errors.receiver_clock.as_ref(),
            world.antennas.len(),
            seed,
            1,
        )?;
        let antenna_names: Vec<&str> = world.antennas.iter().map(|a| a.name.as_str()).collect();
        let events = EventSchedule::new(&errors.events, &antenna_names, &sats)
            .map_err(|e| SynthError::Invalid(e.within("errors.events")))?;
        let filter = signal
            .filter
            .as_ref()
            .map(|f| {
                BandFilter::new(
                    f,
                    signal.sample_rate_hz,
                    signal.if_hz,
                    signal.format.is_complex(),
                )
            })
            .transpose()
            .map_err(|e| SynthError::Invalid(e.within("signal.filter")))?;
        Ok(Self {
            world,
            signal,
            errors,
            seed,
            iono,
            bands,
            transmitters,
            sats,
            sat_of,
            broadcast,
            clocks,
            events,
            filter,
            observation_model: None,
            observed: Vec::new(),
            jammers: Vec::new(),
        })
    }

    /// The samples receive `jammers` (`[[jammers]]`), each J/S referred to a satellite
    /// at `[signal] cn0_dbhz` at the platform's start. At the observation level (call
    /// [`Self::observation_level`] first) noise jammers lower each link's C/N0 by the
    /// effective-C/N0 relation over the band `[signal] sample_rate_hz` and the link is
    /// lost below [`LOCK_THRESHOLD_DBHZ`]; a CW there is an error.
    pub fn with_jammers(mut self, jammers: &[JammerConfig]) -> Result<Self, SynthError> {
        if jammers.is_empty() {
            return Ok(self);
        }
        let cw = jammers
            .iter()
            .position(|j| j.waveform == JammerWaveform::Cw);
        if let (Some(k), true) = (cw, self.observation_model.is_some()) {
            return Err(SynthError::Invalid(Invalid::new(
                format!("jammers[{k}].waveform"),
                "\"cw\"",
                "the observation level models noise jammers only (a CW's effect depends on the code's line spectrum: render samples)",
            )));
        }
        let (start, _) = self.start_state()?;
        let cn0 = self.signal.cn0_dbhz;
        self.jammers = (jammers.iter())
            .map(|j| Jammer::new(j, cn0, &start))
            .collect();
        Ok(self)
    }

    /// Run at the observation level: no samples; at each whole second `model` turns every
    /// link's truth into observables for [`Sinks::measurements`], of each transmitter's
    /// signal and of the observed-only signals `observed` of its system (GPS L2/L5, BDS
    /// B2I/B3I: [`Synthesiser::with_observed`]). A synthesised signal in `observed`, one
    /// listed twice, one of a system without satellites, or one the model has no noise
    /// for, is an error.
    pub fn observation_level(
        mut self,
        model: ObservationModel,
        observed: &[Signal],
    ) -> Result<Self, SynthError> {
        let field = "observation.observed_signals";
        for (i, s) in observed.iter().enumerate() {
            if observed[..i].contains(s) {
                return Err(SynthError::Invalid(Invalid::new(
                    field,
                    s.tag(),
                    "is listed twice",
                )));
            }
            if !self.signals().iter().any(|b| b.system() == s.system()) {
                return Err(SynthError::Invalid(Invalid::new(
                    field,
                    s.tag(),
                    "its system has no satellites in this scenario (enable it under [gnss])",
                )));
            }
            if s.is_default_fix() || self.bands.iter().any(|b| b.records(*s)) {
                return Err(SynthError::Invalid(Invalid::new(
                    field,
                    s.tag(),
                    "is tracked by the bundled receiver or transmitted in this scenario ([signal] signals); list observed-only signals: gps-l2, gps-l5, bds-b2i, bds-b3i, gal-e1, other than the transmitted ones",
                )));
            }
            if !model.has_noise_for(*s) {
                return Err(SynthError::Invalid(Invalid::new(
                    field,
                    s.tag(),
                    "the calibrated noise model has no calibration for it (set [observation.noise] model = \"elevation\" or \"constant\")",
                )));
            }
        }
        // The transmitted signals need noise too: the calibrated model holds only the
        // signals the bundled receiver tracks (not yet Galileo E5a).
        if let Some(signal) = self
            .signals()
            .into_iter()
            .find(|&s| !model.has_noise_for(s))
        {
            return Err(SynthError::Invalid(Invalid::new(
                "observation.noise.model",
                "\"calibrated\"",
                format!(
                    "the calibrated noise model has no calibration for {} (set [observation.noise] model = \"elevation\" or \"constant\")",
                    signal.tag()
                ),
            )));
        }
        self.observation_model = Some(model);
        self.observed = observed.to_vec();
        Ok(self)
    }

    /// The world being synthesised.
    pub fn world(&self) -> &SynthWorld<'a> {
        &self.world
    }

    /// What every recording of this synthesis shares, for its metadata: the scenario's
    /// name and seed (the one `--seed` takes: a vehicle's receiver streams are keyed by
    /// it and the vehicle's name) and, in a scenario of several, the vehicle's name.
    pub fn recording_info(&self, scenario: &str, seed: u64, vehicle: Option<&str>) -> RunInfo {
        RunInfo {
            format: self.signal.format,
            sample_rate_hz: self.signal.sample_rate_hz,
            if_hz: self.signal.if_hz,
            start: self.world.origin.start(),
            scenario: scenario.to_owned(),
            seed,
            vehicle: vehicle.map(str::to_owned),
        }
    }

    /// The bands with transmitters, GPS first.
    pub fn bands(&self) -> &[Band] {
        &self.bands
    }

    /// Every signal observed: each band's, then the observed-only signals
    /// ([`Self::observation_level`]).
    pub fn signals(&self) -> Vec<Signal> {
        let bands = self.bands.iter().flat_map(|b| b.signals.iter().copied());
        bands.chain(self.observed.iter().copied()).collect()
    }

    /// The transmitting satellites, each once, in the order they first transmit (band by
    /// band): the satellites of the geometry truth.
    pub fn satellites(&self) -> &[SatId] {
        &self.sats
    }

    /// The satellite and signal of each of `band`'s transmitters.
    pub fn band_transmitters(&self, band: &Band) -> Vec<(SatId, Signal)> {
        self.transmitters[band.first..band.first + band.count]
            .iter()
            .map(|t| (t.sat, t.signal))
            .collect()
    }

    /// The ephemerides as broadcast, one per satellite in [`Self::satellites`] order.
    pub fn broadcast_ephemerides(&self) -> &[BroadcastEphemeris] {
        &self.broadcast
    }

    /// The Klobuchar coefficients the signals follow, per system (empty when the
    /// ionosphere is off): the RINEX navigation header's `IONOSPHERIC CORR`.
    pub fn broadcast_iono(&self) -> Vec<(System, [f64; 4], [f64; 4])> {
        if self.iono.model == IonoModel::Off {
            return Vec::new();
        }
        vec![
            (System::Gps, self.iono.gps.alpha, self.iono.gps.beta),
            (System::Beidou, self.iono.bds.alpha, self.iono.bds.beta),
        ]
    }

    /// The navigation file a receiver of this session's signals needs: its broadcast
    /// ephemerides, ionosphere and (with Galileo) GST - GPST as RINEX 3.04 navigation,
    /// written by `skyforge`.
    pub fn write_navigation(&self, out: &mut impl std::io::Write) -> std::io::Result<()> {
        let ephs = self.broadcast_ephemerides();
        let iono = self.broadcast_iono();
        let galileo = ephs.iter().any(|e| e.sat.system == System::Galileo);
        let gst_gps = galileo.then(|| {
            let g = &self.world.gst_gps;
            let (t_ref_sow, week) = g.reference(self.world.origin);
            TimeSystemCorr {
                a0_s: g.a0_s,
                a1: g.a1,
                t_ref_sow,
                week,
            }
        });
        let header = NavHeader {
            program: "skyforge",
            iono: &iono,
            gst_gps,
        };
        skyforge_orbits::ephemeris::write_nav(ephs, &header, out)
    }

    /// Whether the signals carry an ionospheric delay.
    pub fn ionosphere_on(&self) -> bool {
        self.iono.model != IonoModel::Off
    }

    /// Whether samples are rendered (not at the observation level).
    pub fn renders_samples(&self) -> bool {
        self.observation_model.is_none()
    }

    /// The signal settings.
    pub fn signal_config(&self) -> &SignalConfig {
        self.signal
    }

    /// Samples the front-end filter needs beyond each end of a block (0 without one).
    pub fn filter_margin(&self) -> usize {
        self.filter.as_ref().map_or(0, BandFilter::half)
    }

    /// Blocks per step of the receiver clock: one when samples are rendered; at the
    /// observation level, [`observation_clock_step`] of the truth interval.
    fn clock_step_blocks(&self) -> u64 {
        match self.observation_model {
            Some(_) => observation_clock_step(self.truth_every_blocks()),
            None => 1,
        }
    }

    /// Blocks between signal-truth records (0: none); the observation level needs the
    /// truth at whole seconds at least.
    pub fn truth_every_blocks(&self) -> u64 {
        match self.signal.truth_every_blocks() {
            0 if self.observation_model.is_some() => BLOCKS_PER_SECOND,
            every => every,
        }
    }

    /// The platform's position and velocity (ECEF) at the start: the approximate state a
    /// receiver of these samples can be given before they are rendered (what the run's
    /// report gives afterwards).
    pub fn start_state(&mut self) -> Result<(Vec3, Vec3), SynthError> {
        let st = self.world.platform.window(0.0, 0.0)?.state(0.0);
        Ok((st.r_ecef_m, st.v_ecef_mps))
    }

    /// Stream the whole span into `sinks`, computing geometry `chunk_epochs` epochs at a
    /// time.
    pub fn run(self, chunk_epochs: usize, sinks: Sinks<'_>) -> Result<SynthReport, SynthError> {
        let truth_every = self.truth_every_blocks();
        let clocks = match self.clock_step_blocks() {
            1 => self.clocks.clone(),
            step => receiver_clocks(
                self.errors.receiver_clock.as_ref(),
                self.world.antennas.len(),
                self.seed,
                step,
            )?,
        };
        let world = self.world;
        let signal = self.signal;
        let n_ant = world.antennas.len();
        let observation_level = self.observation_model.is_some();
        let mut synths = self
            .bands
            .iter()
            .enumerate()
            .map(|(i, b)| {
                let s = Synthesiser::new(
                    signal,
                    &self.transmitters[b.first..b.first + b.count],
                    n_ant,
                    self.seed,
                )?
                .with_truth_every(truth_every)
                .with_clocks(clocks.clone())
                .with_events(self.events.clone())
                .with_jammers(&self.jammers, self.seed);
                // Observed-only signals come from their system's first band alone.
                let first_band_of = |system: System| {
                    self.bands
                        .iter()
                        .position(|o| o.signals.iter().any(|s| s.system() == system))
                };
                let observed: Vec<Signal> = (self.observed.iter().copied())
                    .filter(|o| first_band_of(o.system()) == Some(i))
                    .collect();
                let s = if observation_level {
                    s.without_samples().with_observed(observed)
                } else {
                    s
                };
                match &self.filter {
                    Some(f) => s.with_filter(f.clone()),
                    None => Ok(s),
                }
            })
            .collect::<Result<Vec<_>, QuantiseError>>()?;
        let terms = LinkTerms {
            signal,
            ionosphere: &self.iono,
            troposphere: &self.errors.troposphere,
            multipath: &self.errors.multipath,
            antennas: world.antennas,
        };
        let group_delays: Vec<f64> = (self.transmitters.iter())
            .map(|t| t.signal.broadcast_group_delay_s(&t.broadcast_ephemeris()))
            .collect();
        let tx_signals: Vec<Signal> = self.transmitters.iter().map(|t| t.signal).collect();
        let store = EphemerisStore::new(self.broadcast, world.origin);
        let sats = self.sats;
        let truth = GeometryTruth::new(&store, &sats, world.antennas, GEOMETRY_STEP_S)
            .with_gst_gps(world.gst_gps);
        let truth = match world.satellite_errors {
            Some(errors) => truth.with_satellite_errors(errors),
            None => truth,
        };
        let mut running = Running {
            origin: world.origin,
            antennas: world.antennas,
            bands: &self.bands,
            sats: &sats,
            sat_of: &self.sat_of,
            group_delays: &group_delays,
            tx_signals: &tx_signals,
            terms,
            synths: &mut synths,
            start_state: None,
            sinks,
            model: self.observation_model,
            elevations: vec![0.0; n_ant * sats.len()],
            relativity: (self.errors.receiver_clock.as_ref())
                .filter(|c| c.relativity)
                .map(|_| RelativisticOffset::new()),
            jammers: &self.jammers,
            jammer_links: Vec::new(),
            jammed_band_hz: self.signal.sample_rate_hz,
        };
        truth
            .stream(world.platform, world.duration_s, chunk_epochs, |chunk| {
                running.chunk(&chunk)
            })
            .map_err(|e| match e {
                StreamError::Platform(e) => SynthError::Platform(e),
                StreamError::Sink(e) => SynthError::Sink(e),
            })?;
        Ok(SynthReport {
            start_state: running.start_state,
            clipped: synths.iter().map(Synthesiser::clipped).sum(),
        })
    }
}

/// The state of a running session.
struct Running<'r, 't, 's> {
    origin: &'r TimeOrigin,
    antennas: &'r [Antenna],
    bands: &'r [Band],
    /// The satellites of the geometry truth.
    sats: &'r [SatId],
    /// Each transmitter's satellite (index into `sats`), [`Band::first`]-indexed.
    sat_of: &'r [usize],
    /// Each transmitter's broadcast group delay (s), [`Band::first`]-indexed.
    group_delays: &'r [f64],
    /// Each transmitter's signal, [`Band::first`]-indexed.
    tx_signals: &'r [Signal],
    terms: LinkTerms<'r>,
    synths: &'r mut [Synthesiser<'t>],
    start_state: Option<(Vec3, Vec3)>,
    sinks: Sinks<'s>,
    model: Option<ObservationModel>,
    /// Link elevations (rad) at the previous geometry epoch, antenna-major: the epoch the
    /// whole-second truth of the current interval belongs to.
    elevations: Vec<f64>,
    /// The receiver clocks' relativistic offset along the platform's trajectory
    /// (`[errors.receiver_clock] relativity`).
    relativity: Option<RelativisticOffset>,
    /// The session's jammers, their links at the latest epoch (`a * n + j`), and the band
    /// the observation level's noise jammers fill (the sample rate).
    jammers: &'r [Jammer],
    jammer_links: Vec<JammerLink>,
    jammed_band_hz: f64,
}

impl Running<'_, '_, '_> {
    /// Every jammer's link to every antenna at the epoch `t_s` (platform state `st`):
    /// handed to each recording, which keeps those of the jammers its band sees, and to
    /// the truth.
    fn jammer_links(&mut self, t_s: f64, st: &PlatformState) -> Result<(), SinkError> {
        self.jammer_links = (self.antennas.iter())
            .flat_map(|a| {
                let r = st.r_ecef_m + st.c_body_ecef * a.true_body_m;
                (self.jammers.iter()).map(move |j| j.link(a, &r, &st.c_body_ecef))
            })
            .collect();
        for synth in self.synths.iter_mut() {
            synth.set_jammer_links(t_s, &self.jammer_links);
        }
        self.sinks
            .truth
            .jammers(t_s, self.jammers, &self.jammer_links)
    }

    /// Render, hand over and record one chunk of geometry epochs.
    fn chunk(&mut self, chunk: &GeometryChunk) -> Result<(), SinkError> {
        for k in 0..chunk.t_s.len() {
            self.epoch(chunk, k)?;
        }
        (self.sinks.progress)(chunk.t_s.len());
        self.sinks.truth.geometry(chunk)
    }

    /// The samples up to geometry epoch `k` of `chunk`, their signal truth and, at a whole
    /// second, the observation truth.
    fn epoch(&mut self, chunk: &GeometryChunk, k: usize) -> Result<(), SinkError> {
        let n_ant = self.antennas.len();
        let st = &chunk.platform[k];
        self.start_state.get_or_insert((st.r_ecef_m, st.v_ecef_mps));
        if let Some(offset) = self.relativity.as_mut() {
            let point = offset.push(chunk.t_s[k], proper_rate(&st.r_ecef_m, &st.v_ecef_mps));
            for synth in self.synths.iter_mut() {
                synth.set_clock_relativity(point);
            }
        }
        let at_antenna: Vec<AntennaEpoch> = self
            .antennas
            .iter()
            .map(|a| AntennaEpoch::new(st, a))
            .collect();
        if !self.jammers.is_empty() {
            self.jammer_links(chunk.t_s[k], st)?;
        }
        let at = self.origin.epoch_at(chunk.t_s[k]);
        let sow = |system: System| system.week_sow(at).1;
        // The observation epochs of this step, by tick of the observation interval: their
        // time, and per antenna the truth's records and the model's.
        let step_s = self.model.as_ref().map_or(1.0, ObservationModel::step_s);
        let mut ticks: BTreeMap<i64, ObsTick> = BTreeMap::new();
        let n_sats = self.sats.len();
        for (b, (band, synth)) in self.bands.iter().zip(self.synths.iter_mut()).enumerate() {
            let links = (0..n_ant * band.count)
                .map(|l| {
                    let (a, tx) = (l / band.count, band.first + l % band.count);
                    let s = self.sat_of[tx];
                    let sat = self.sats[s];
                    self.terms
                        .link_end(
                            chunk.t_s[k],
                            sow(sat.system),
                            a,
                            &at_antenna[a],
                            sat,
                            self.tx_signals[tx],
                            chunk.link(k, a, s),
                        )
                        .map(|end| end.with_group_delay(self.group_delays[tx]))
                })
                .collect();
            let samples = &mut *self.sinks.samples;
            synth.push_epoch(chunk.t_s[k], links, &mut |a, bytes| {
                samples.samples(b, a, bytes)
            })?;
            let truth = synth.take_truth();
            for (tick, r) in truth
                .iter()
                .filter_map(|r| Some((on_grid(r.t_s, step_s)?, r)))
            {
                let epoch = ticks
                    .entry(tick)
                    .or_insert_with(|| ObsTick::new(r.t_s, n_ant));
                let s = self.sat_of[band.first + r.tx];
                let sat = self.sats[s];
                epoch.truth[r.antenna].push(ObsRecord::complete(
                    sat,
                    r.signal,
                    r.pseudorange_m,
                    r.carrier_phase_cycles,
                    r.doppler_hz,
                    r.cn0_dbhz,
                ));
                let jamming = (self.jammers, &self.jammer_links[..], self.jammed_band_hz);
                let loss = match self.jammer_links.is_empty() {
                    true => 0.0,
                    false => jamming_loss_db(jamming, r.antenna, r.signal, r.t_s),
                };
                let jammed = LinkTruth {
                    cn0_dbhz: r.cn0_dbhz - loss,
                    ..*r
                };
                if let Some(model) = self.model.as_mut()
                    && (loss == 0.0 || jammed.cn0_dbhz >= LOCK_THRESHOLD_DBHZ)
                {
                    let elevation = self.elevations[r.antenna * n_sats + s];
                    let observed = model.observe(r.antenna, sat, r.signal, &jammed, elevation);
                    epoch.measured[r.antenna].push(observed);
                }
            }
            // The truth file holds the transmitted signal's truth.
            for a in 0..n_ant {
                let records: Vec<_> = truth
                    .iter()
                    .filter(|r| r.antenna == a && band.records(r.signal))
                    .copied()
                    .collect();
                let sat_index = &self.sat_of[band.first..band.first + band.count];
                self.sinks.truth.signal(a, &records, sat_index)?;
            }
        }
        for epoch in ticks.into_values() {
            let at = self.origin.epoch_at(epoch.t_s);
            let (mut truth, mut measured) = (epoch.truth, epoch.measured);
            for (a, (records, measured)) in truth.iter_mut().zip(&mut measured).enumerate() {
                records.sort_by_key(|r| r.sat);
                let r0 = st.r_ecef_m + st.c_body_ecef * self.antennas[a].true_body_m;
                self.sinks.observations.epoch(a, at, &r0, records)?;
                if self.model.is_some() {
                    measured.sort_by_key(|r| r.sat);
                    self.sinks.measurements.epoch(a, at, &r0, measured)?;
                }
            }
        }
        if self.model.is_some() {
            for a in 0..n_ant {
                for s in 0..n_sats {
                    self.elevations[a * n_sats + s] = chunk.link(k, a, s).elevation_rad;
                }
            }
        }
        Ok(())
    }
}

/// The effective-C/N0 loss (dB) at antenna `a` of a link of `signal` at `t_s`: the noise
/// `jammers` on then whose band (`band_hz` wide, the samples') holds its carrier, with
/// their `links` (`a * n + j`).
fn jamming_loss_db(
    (jammers, links, band_hz): (&[Jammer], &[JammerLink], f64),
    a: usize,
    signal: Signal,
    t_s: f64,
) -> f64 {
    let n = jammers.len();
    let on = (jammers.iter().zip(&links[a * n..(a + 1) * n]))
        .filter(|(j, _)| j.config.on_at(t_s))
        .filter(|(j, _)| j.config.in_band(signal.carrier_hz(), band_hz))
        .map(|(_, l)| l.jn0_dbhz);
    cn0_loss_db(on, band_hz)
}

/// One observation epoch within a geometry step: its time and, per antenna, the truth's
/// records and the observation model's.
struct ObsTick {
    t_s: f64,
    truth: Vec<Vec<ObsRecord>>,
    measured: Vec<Vec<ObsRecord>>,
}

impl ObsTick {
    fn new(t_s: f64, antennas: usize) -> Self {
        Self {
            t_s,
            truth: vec![Vec::new(); antennas],
            measured: vec![Vec::new(); antennas],
        }
    }
}

/// The tick of `t_s` on the grid of `step_s` (whole seconds, or the observation level's
/// interval), when it lies on it: within a microsecond, far below the truth's interval.
fn on_grid(t_s: f64, step_s: f64) -> Option<i64> {
    let tick = (t_s / step_s).round();
    ((t_s - tick * step_s).abs() < 1e-6).then_some(tick as i64)
}

/// What every recording of a synthesis shares.
#[derive(Debug, Clone, PartialEq)]
pub struct RunInfo {
    pub format: SampleFormat,
    pub sample_rate_hz: f64,
    pub if_hz: f64,
    /// Time of the first sample.
    pub start: Epoch,
    pub scenario: String,
    /// The scenario's seed (what `--seed` takes).
    pub seed: u64,
    /// The vehicle synthesised, in a scenario of several.
    pub vehicle: Option<String>,
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Per band, the signals on one carrier share a recording, their transmitters one
    /// after the other; per signal (the default), each has its own as before.
    #[test]
    fn signals_on_one_carrier_share_a_band_when_recorded_per_band() {
        let per_signal = || {
            vec![
                (Signal::GpsL1Ca, vec!["G1", "G2"]),
                (Signal::GpsL5, vec!["G1"]),
                (Signal::BdsB1I, vec![]),
                (Signal::GalE5a, vec!["E1", "E2", "E3"]),
                (Signal::GalE1, vec!["E1"]),
            ]
        };
        let (bands, txs) = group_bands(RecordingLayout::PerBand, per_signal());
        assert_eq!(txs, ["G1", "G2", "E1", "G1", "E1", "E2", "E3"]);
        let l1 = Band::new(Signal::GpsL1Ca, 0, 2).with(Signal::GalE1, 1);
        let l5 = Band::new(Signal::GpsL5, 3, 1).with(Signal::GalE5a, 3);
        assert_eq!(bands, [l1, l5]);
        assert_eq!(bands[0].tag(), "gps-l1ca+gal-e1");
        assert_eq!(bands[1].name(), "GPS L5 + GAL E5a");
        let (bands, txs) = group_bands(RecordingLayout::PerSignal, per_signal());
        assert_eq!(txs, ["G1", "G2", "G1", "E1", "E2", "E3", "E1"]);
        let expected = [
            Band::new(Signal::GpsL1Ca, 0, 2),
            Band::new(Signal::GpsL5, 2, 1),
            Band::new(Signal::GalE5a, 3, 3),
            Band::new(Signal::GalE1, 6, 1),
        ];
        assert_eq!(bands, expected);
        assert_eq!(bands[0].tag(), "gps-l1ca");
    }

    #[test]
    fn the_observation_level_clock_steps_on_every_truth_record() {
        // Truth at 1, 2, 4, 8, 25, 40 and 1000 Hz (blocks between records: divisors of 1000).
        for (every, step) in [
            (1000, 100),
            (500, 100),
            (250, 50),
            (125, 25),
            (40, 20),
            (25, 25),
            (1, 1),
        ] {
            assert_eq!(
                observation_clock_step(every),
                step,
                "truth every {every} blocks"
            );
            assert_eq!(every % step, 0);
        }
    }
}
