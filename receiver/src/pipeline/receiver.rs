//! The receiver loop over sample blocks: search, track (channels in parallel), decode,
//! time the code epochs, form observations at the epochs of the receiver clock and solve
//! a fix per antenna.

use super::channel::Channel;
use super::config::{ApproximateState, ReceiverConfig};
use super::epoch_stage::{self, EpochInput, EpochStage};
use super::navdata::NavData;
use super::{AntennaFix, EpochReport};
use crate::acquisition::AcquisitionError;
use crate::acquisition::pcps::DopplerWindow;
use crate::acquisition::{AcquisitionStage, Candidate};
use crate::assist::{Assistance, search_hints};
use crate::navdecode::NavDecodeError;
use crate::observables::{ObservablesBuilder, Observation};
use crate::tracking::TrackingError;
use crate::tracking::channel::{ChannelTracker, FrontEnd, Handover};
use crate::tracking::config::MAX_COHERENT_MS;
use hifitime::Epoch;
use num_complex::Complex32;
use rayon::prelude::*;
use skyforge_gnss::signal::Signal;
use skyforge_orbits::constants::C_MPS;
use skyforge_orbits::ephemeris::KlobucharCoeffs;
use skyforge_orbits::ephemeris::{BroadcastEphemeris, SatId};

/// Typical signal flight time used to start a receiver clock that has no time tag (s).
const NOMINAL_FLIGHT_S: f64 = 0.075;
/// Receiver clock offset from GPS time (s) beyond which a fix re-anchors the clock to GPS
/// time ([`Receiver::steer`]). # assumed: half the microsecond the time tags must keep
/// (issue #32), so that the drift of an oscillator up to 0.5 ppm over a one-second epoch
/// keeps them within it; well above the noise of a fix's clock (nanoseconds).
const STEER_THRESHOLD_S: f64 = 0.5e-6;
/// Satellites a band's first blind search (every PRN on every antenna) must find; with
/// fewer its cold Doppler window widens to [`WIDE_COLD_HALF_WIDTH_HZ`]. # assumed: six,
/// the fewest with which RAIM can exclude a fault; a ground receiver's first search over
/// +/-10 kHz finds more.
const WIDEN_BELOW: usize = 6;
/// Half width of the widened cold window (Hz): a LEO's line-of-sight speed to a GNSS
/// satellite reaches about 9 km/s, 47 kHz at L1, plus the oscillator's offset.
const WIDE_COLD_HALF_WIDTH_HZ: f64 = 50e3;
/// Carriers above this lead their system's lower bands in acquisition (L1 C/A, E1, B1I,
/// B1C lead L5, E5a, B2a): [`leads`]. # assumed: between the L1-family (1559-1610 MHz) and
/// the L2/L5-family bands (1164-1300 MHz).
const LEAD_ABOVE_HZ: f64 = 1.4e9;

/// Whether `signal` is of a lead band ([`LEAD_ABOVE_HZ`]): searched first, and the lower
/// bands of its system at the same antenna searched only for what it found.
fn leads(signal: Signal) -> bool {
    signal.carrier_hz() > LEAD_ABOVE_HZ
}
/// Code periods past an epoch every channel must have tracked before the epoch is formed:
/// a channel reports an integration when it ends, so the first integration starting after
/// the epoch is known only up to two of the longest integrations (plus a code period of
/// slack) later. With it the epoch lies between two reported integration starts and the
/// observables interpolate; extrapolating from the last two instead amplifies the loop
/// noise (by up to 30 % in phase at 20 ms integrations).
const EPOCH_MARGIN_PERIODS: f64 = (2 * MAX_COHERENT_MS + 2) as f64;

/// Why the receiver cannot go on.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum PipelineError {
    #[error("acquisition: {0}")]
    Acquisition(#[from] AcquisitionError),
    #[error("tracking: {0}")]
    Tracking(#[from] TrackingError),
    #[error("navigation decoder: {0}")]
    Decoder(#[from] NavDecodeError),
    #[error("invalid receiver setting {name} = {value}: {allowed}")]
    InvalidSetting {
        name: &'static str,
        value: String,
        allowed: &'static str,
    },
    #[error("band {band}: {got} antenna buffers of {len} samples given, {antennas} expected")]
    BadBlock {
        band: usize,
        got: usize,
        len: usize,
        antennas: usize,
    },
}

/// One band's recordings: the signal and, per recording (in the order of the buffers
/// passed to [`Receiver::process`]), the receiver antenna it belongs to.
#[derive(Debug, Clone, PartialEq)]
pub struct BandInput {
    pub signal: Signal,
    /// IF of the (complex) samples (Hz; 0 for baseband).
    pub if_hz: f64,
    pub antennas: Vec<usize>,
}

/// What the receiver is given besides the samples.
#[derive(Debug, Clone, PartialEq)]
pub struct ReceiverSetup {
    /// Sample rate shared by every recording (Hz).
    pub sample_rate_hz: f64,
    pub bands: Vec<BandInput>,
    /// Antenna names (the receiver's antenna indices index this).
    pub antenna_names: Vec<String>,
    /// Time tag of sample 0 (the recorder's clock), if the recording has one.
    pub start_time: Option<Epoch>,
    /// Assistance: ephemerides and ionosphere (e.g. from a navigation file) and the
    /// approximate state.
    pub ephemerides: Vec<BroadcastEphemeris>,
    pub iono_gps: Option<KlobucharCoeffs>,
    pub iono_bds: Option<KlobucharCoeffs>,
    pub approximate: Option<ApproximateState>,
}

/// Counters of a run.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ReceiverSummary {
    /// Searches run and detections (over all antennas and satellites).
    pub searches: usize,
    pub detections: usize,
    /// Channels that declared loss of lock after having locked.
    pub losses_of_lock: usize,
    /// Detections whose channel never locked (false alarms or too weak), dropped.
    pub unconfirmed_detections: usize,
    /// Per antenna: satellites tracked (carrier lock reached), satellites timed (a
    /// message decoded, or a hand-over from another signal of the satellite).
    pub tracked: Vec<Vec<SatId>>,
    pub timed: Vec<Vec<SatId>>,
    /// Epochs formed and fixes per antenna (of the epochs reported).
    pub epochs: usize,
    pub fixes: Vec<usize>,
    /// Times a fix re-anchored the receiver clock to GPS time, and the sum of the
    /// corrections (s; receiver time minus GPS time removed).
    pub clock_steps: usize,
    pub clock_steered_s: f64,
    /// Bands whose first blind search found fewer than six satellites, with how many,
    /// after which their cold Doppler window widened to +/-50 kHz.
    pub widened: Vec<(Signal, usize)>,
    /// Ephemerides known at the end.
    pub ephemerides: usize,
}

/// The running receiver.
pub struct Receiver {
    setup: ReceiverSetup,
    config: ReceiverConfig,
    searches: Vec<Box<dyn AcquisitionStage>>,
    channels: Vec<Channel>,
    nav: NavData,
    observables: ObservablesBuilder,
    /// GPST (s since the origin) of sample 0 in the receiver's clock, once known.
    clock_offset_s: Option<f64>,
    /// The clock was started from a nominal flight time (no time tag): its epochs are
    /// provisional, not reported, until a fix sets it.
    clock_guessed: bool,
    /// Sum of the re-anchoring corrections applied to `clock_offset_s` (s): the carrier
    /// phases move with the pseudoranges ([`ObservablesBuilder::at`]).
    clock_steps_s: f64,
    /// Per band: the cold Doppler window widened after a first search found too few.
    widened: Vec<bool>,
    next_epoch: Option<i64>,
    next_search_sample: u64,
    /// Searches run so far (rounds over every band and antenna).
    search_rounds: usize,
    epoch_stage: Box<dyn EpochStage>,
    summary: ReceiverSummary,
}

impl Receiver {
    pub fn new(setup: ReceiverSetup, config: ReceiverConfig) -> Result<Self, PipelineError> {
        let fs = setup.sample_rate_hz;
        if !(fs.is_finite() && fs > 0.0) {
            return Err(PipelineError::InvalidSetting {
                name: "sample rate (Hz)",
                value: fs.to_string(),
                allowed: "positive",
            });
        }
        let rate = config.observation_rate_hz;
        if !(1.0..=100.0).contains(&rate) {
            return Err(PipelineError::InvalidSetting {
                name: "observation rate (Hz)",
                value: rate.to_string(),
                allowed: "1 to 100",
            });
        }
        let interval = config.acquisition.reacquire_interval_s;
        if !(interval.is_finite() && interval > 0.0) {
            return Err(PipelineError::InvalidSetting {
                name: "re-acquisition interval (s)",
                value: interval.to_string(),
                allowed: "positive",
            });
        }
        config.tracking.check().map_err(TrackingError::from)?;
        let searches = setup
            .bands
            .iter()
            .map(|b| crate::acquisition::build(b.signal, fs, b.if_hz, &config.acquisition))
            .collect::<Result<Vec<_>, _>>()?;
        let nav = NavData::new(
            setup.ephemerides.clone(),
            setup.iono_gps,
            setup.iono_bds,
            setup.start_time,
        );
        let antennas = setup.antenna_names.len();
        let mut receiver = Self {
            observables: ObservablesBuilder::new(fs),
            searches,
            channels: Vec::new(),
            nav,
            clock_offset_s: None,
            clock_guessed: false,
            clock_steps_s: 0.0,
            widened: vec![false; setup.bands.len()],
            next_epoch: None,
            next_search_sample: 0,
            search_rounds: 0,
            epoch_stage: epoch_stage::build(&config, antennas),
            summary: ReceiverSummary {
                tracked: vec![Vec::new(); antennas],
                timed: vec![Vec::new(); antennas],
                fixes: vec![0; antennas],
                ..ReceiverSummary::default()
            },
            setup,
            config,
        };
        receiver.set_clock_from_start_time();
        Ok(receiver)
    }

    /// Samples each block must hold for a search (blocks shorter than this are tracked but
    /// not searched).
    pub fn samples_per_search(&self) -> usize {
        self.searches
            .iter()
            .map(|s| s.samples_needed())
            .max()
            .unwrap_or(0)
    }

    /// Counters so far.
    pub fn summary(&self) -> ReceiverSummary {
        let mut s = self.summary.clone();
        s.clock_steered_s = self.clock_steps_s;
        s.ephemerides = self
            .nav
            .store()
            .satellites()
            .iter()
            .map(|&sat| self.nav.store().ephemerides(sat).len())
            .sum();
        s
    }

    /// The origin of the receiver's times (start of a GPS week), once known.
    pub fn origin(&self) -> Option<&skyforge_orbits::time::TimeOrigin> {
        self.nav.origin()
    }

    fn set_clock_from_start_time(&mut self) {
        if let (None, Some(start), Some(origin)) = (
            self.clock_offset_s,
            self.setup.start_time,
            self.nav.origin(),
        ) {
            self.clock_offset_s = Some(origin.seconds_since_start(start));
        }
    }

    /// The receiver's GPST estimate (s since the origin) at a (fractional) sample.
    fn receiver_time(&self, sample: f64) -> Option<f64> {
        self.clock_offset_s
            .map(|t0| t0 + sample / self.setup.sample_rate_hz)
    }

    /// Process one block: `bands[b][a]` holds band `b`'s recording `a`, each `len` samples
    /// from sample `first_sample` on (blocks must follow each other without gaps). Returns
    /// the epochs completed.
    pub fn process(
        &mut self,
        bands: &[Vec<Vec<Complex32>>],
        first_sample: u64,
        len: usize,
    ) -> Result<Vec<EpochReport>, PipelineError> {
        for (b, band) in self.setup.bands.iter().enumerate() {
            let ok = bands.get(b).is_some_and(|x| {
                x.len() == band.antennas.len() && x.iter().all(|v| v.len() >= len)
            });
            if !ok {
                return Err(PipelineError::BadBlock {
                    band: b,
                    got: bands.get(b).map_or(0, Vec::len),
                    len,
                    antennas: band.antennas.len(),
                });
            }
        }
        if first_sample >= self.next_search_sample && len >= self.samples_per_search() {
            self.search(bands, first_sample, len)?;
            let step = self.config.acquisition.reacquire_interval_s * self.setup.sample_rate_hz;
            self.next_search_sample = first_sample + step as u64;
        }
        self.channels
            .par_iter_mut()
            .try_for_each(|ch| ch.track(&bands[ch.group][ch.local][..len], first_sample))?;
        let approx = self.clock_offset_s;
        let fs = self.setup.sample_rate_hz;
        let approx_time = move |sample: f64| approx.map(|t0| t0 + sample / fs);
        for ch in &mut self.channels {
            ch.digest(&mut self.nav, &approx_time);
        }
        self.hand_over_timing();
        for ch in &self.channels {
            if ch.ever_locked() && !self.summary.tracked[ch.antenna].contains(&ch.sat) {
                self.summary.tracked[ch.antenna].push(ch.sat);
            }
            if ch.is_timed() && !self.summary.timed[ch.antenna].contains(&ch.sat) {
                self.summary.timed[ch.antenna].push(ch.sat);
            }
        }
        self.set_clock_from_start_time();
        if self.clock_offset_s.is_none() {
            // No time tag: start the clock one nominal flight time after the first timed
            // code epoch; the first fix sets it to GPS time ([`Self::steer`]).
            if let Some(s) = self.channels.iter().find_map(|c| c.queue.front()) {
                self.clock_offset_s = Some(s.t_tx_s + NOMINAL_FLIGHT_S - s.sample_index / fs);
                self.clock_guessed = true;
            }
        }
        for c in self.channels.iter().filter(|c| c.is_lost()) {
            self.observables.drop_channel(c.antenna, c.sat, c.signal());
            if c.ever_locked() {
                self.summary.losses_of_lock += 1;
            } else {
                self.summary.unconfirmed_detections += 1;
            }
        }
        self.channels.retain(|c| !c.is_lost());
        self.epochs(first_sample + len as u64)
    }

    /// Channels not yet timed take their time from the nearest timed code epoch of another
    /// signal of the same satellite at the same antenna where they can
    /// ([`Channel::time_from`]).
    fn hand_over_timing(&mut self) {
        for i in 0..self.channels.len() {
            let ch = &self.channels[i];
            let Some(sample) = ch.awaiting_time() else {
                continue;
            };
            let nearest = self
                .channels
                .iter()
                .filter(|s| s.antenna == ch.antenna && s.sat == ch.sat && s.is_timed())
                .flat_map(|s| s.queue.iter())
                .min_by(|a, b| {
                    let (da, db) = (a.sample_index - sample, b.sample_index - sample);
                    da.abs().total_cmp(&db.abs())
                })
                .copied();
            if let Some(s) = nearest {
                self.channels[i].time_from(&s);
            }
        }
    }

    /// Search every antenna of every band for the satellites it does not track.
    fn search(
        &mut self,
        bands: &[Vec<Vec<Complex32>>],
        first_sample: u64,
        len: usize,
    ) -> Result<(), PipelineError> {
        let fs = self.setup.sample_rate_hz;
        let t_s = self.receiver_time(first_sample as f64);
        let round = self.search_rounds;
        self.search_rounds += 1;
        // (band, satellites found) of each band searched blind in the first round.
        let mut widen = Vec::new();
        // Lead bands first: their detections aid the lower bands' searches this round.
        let lead_band = |b: &usize| leads(self.setup.bands[*b].signal);
        let n_bands = self.setup.bands.len();
        let order: Vec<usize> = (0..n_bands)
            .filter(lead_band)
            .chain((0..n_bands).filter(|b| !lead_band(b)))
            .collect();
        for b in order {
            let band = &self.setup.bands[b];
            let system = band.signal.system();
            let carrier_hz = band.signal.carrier_hz();
            let n_antennas = band.antennas.len();
            let narrow = 2.0 * self.searches[b].doppler_step_hz();
            // PRNs found in this band this round.
            let mut found_here: Vec<u8> = Vec::new();
            // Whether the band was searched blind (over the cold window).
            let mut blind = false;
            for (local, &antenna) in band.antennas.iter().enumerate() {
                let tracked = |prn: u8| {
                    self.channels
                        .iter()
                        .any(|c| c.group == b && c.antenna == antenna && c.sat.prn == prn)
                };
                // The Doppler of a channel of the PRN on another antenna of the band (all
                // antennas share the platform's motion and oscillator: within a few Hz).
                let elsewhere = |prn: u8| {
                    self.channels
                        .iter()
                        .find(|c| c.group == b && c.sat.prn == prn)
                        .map(Channel::doppler_hz)
                };
                // A lower band beside its system's lead band at this antenna is searched
                // only around the Doppler a lead signal found, scaled to its carrier
                // (the motion and the oscillator's offset both scale with frequency): the
                // hand-over of dual-frequency receivers, no blind search.
                let follows = self.lead_band_covers(b, antenna);
                let lead = |prn: u8| {
                    let sat = SatId { system, prn };
                    self.channels
                        .iter()
                        .find(|c| c.sat == sat && leads(c.signal()))
                        .map(|c| c.doppler_hz() * carrier_hz / c.signal().carrier_hz())
                };
                let all = self.candidates(b, antenna, t_s);
                blind |= !follows && all.iter().any(|c| c.cold);
                let candidates: Vec<Candidate> = all
                    .into_iter()
                    .filter(|c| !tracked(c.prn))
                    .filter_map(|c| match (c.cold, elsewhere(c.prn)) {
                        (false, _) => Some(c),
                        // Seen by another antenna: search around its Doppler.
                        (true, Some(doppler)) => Some(Candidate {
                            window: DopplerWindow {
                                centre_hz: doppler,
                                half_width_hz: narrow,
                            },
                            ..c
                        }),
                        (true, None) if follows => lead(c.prn).map(|doppler| Candidate {
                            window: DopplerWindow {
                                centre_hz: doppler,
                                half_width_hz: narrow,
                            },
                            ..c
                        }),
                        // Blind: every antenna at the first search, then each PRN on one
                        // antenna per round in turn.
                        (true, None) => (round == 0
                            || (round + usize::from(c.prn) + local).is_multiple_of(n_antennas))
                        .then_some(c),
                    })
                    .collect();
                self.summary.searches += candidates.len();
                let found = self.searches[b].run(&bands[b][local][..len], &candidates)?;
                for (c, acq) in found {
                    if !found_here.contains(&c.prn) {
                        found_here.push(c.prn);
                    }
                    let sat = SatId { system, prn: c.prn };
                    let handover = Handover {
                        signal: band.signal,
                        prn: c.prn,
                        sample_index: first_sample,
                        code_phase_samples: acq.code_phase_samples,
                        doppler_hz: acq.doppler_hz,
                        doppler_rate_hzps: c.doppler_rate_hzps,
                    };
                    let front_end = FrontEnd {
                        sample_rate_hz: fs,
                        if_hz: band.if_hz,
                    };
                    let tracker = ChannelTracker::new(handover, front_end, self.config.tracking)?;
                    self.channels.push(Channel::new(
                        b,
                        local,
                        antenna,
                        sat,
                        tracker,
                        fs,
                        acq.doppler_hz,
                    )?);
                    self.summary.detections += 1;
                }
            }
            if round == 0 && blind {
                widen.push((b, found_here.len()));
            }
        }
        for (band, found) in widen {
            self.widen_if_too_few(band, found);
        }
        Ok(())
    }

    /// Whether band `b` lies below [`LEAD_ABOVE_HZ`] and a band of its system above it
    /// records `antenna`: then `b` is searched only for what the lead band found.
    fn lead_band_covers(&self, b: usize, antenna: usize) -> bool {
        let signal = self.setup.bands[b].signal;
        !leads(signal)
            && self.setup.bands.iter().any(|l| {
                l.signal.system() == signal.system()
                    && leads(l.signal)
                    && l.antennas.contains(&antenna)
            })
    }

    /// After band `band`'s first blind search (every PRN on every antenna over the cold
    /// window) found `found` satellites: fewer than [`WIDEN_BELOW`] widens its cold window
    /// (a fast platform's Doppler lies beyond +/-10 kHz).
    fn widen_if_too_few(&mut self, band: usize, found: usize) {
        let cold = self.searches[band].cold_window();
        if found < WIDEN_BELOW && cold.half_width_hz < WIDE_COLD_HALF_WIDTH_HZ {
            self.widened[band] = true;
            let signal = self.setup.bands[band].signal;
            self.summary.widened.push((signal, found));
        }
    }

    /// What to search for on `antenna`: the satellites predicted in view (ephemerides, an
    /// approximate time and a position from the last fix or the assistance), else every
    /// PRN over the cold window.
    fn candidates(&self, band: usize, antenna: usize, t_s: Option<f64>) -> Vec<Candidate> {
        let search = &self.searches[band];
        let signal = self.setup.bands[band].signal;
        let system = signal.system();
        if let Some(a) = t_s.and_then(|t| self.assistance(antenna, t)) {
            let store = self.nav.store();
            if store.satellites().iter().any(|s| s.system == system) {
                let floor = 2.0 * search.doppler_step_hz();
                return search_hints(store, &a, signal)
                    .into_iter()
                    .map(|h| Candidate {
                        prn: h.sat.prn,
                        window: DopplerWindow {
                            centre_hz: h.doppler_hz,
                            half_width_hz: h.doppler_window_hz.max(floor),
                        },
                        doppler_rate_hzps: h.doppler_rate_hzps,
                        cold: false,
                    })
                    .collect();
            }
        }
        let mut window = search.cold_window();
        if self.widened[band] {
            window.half_width_hz = WIDE_COLD_HALF_WIDTH_HZ;
        }
        (1..=system.max_prn())
            .map(|prn| Candidate {
                prn,
                window,
                doppler_rate_hzps: 0.0,
                cold: true,
            })
            .collect()
    }

    /// The assistance for `antenna` at `t_s`: its last fix, else the given approximate
    /// state (coasting from the recording start).
    fn assistance(&self, antenna: usize, t_s: f64) -> Option<Assistance> {
        let approx = self.setup.approximate;
        let mask = self.config.pvt.elevation_mask_rad;
        if let Some(fix) = self.epoch_stage.last_fix(antenna) {
            let dt = t_s - fix.t_s;
            return Some(Assistance {
                t_s,
                time_uncertainty_s: 1e-3,
                r_ecef_m: fix.r_ecef_m + fix.v_ecef_mps * dt,
                v_ecef_mps: fix.v_ecef_mps,
                position_uncertainty_m: 100.0 + 10.0 * dt.abs(),
                velocity_uncertainty_mps: 1.0 + 0.01 * dt.abs(),
                oscillator_uncertainty: approx.map_or(1e-6, |a| a.oscillator_uncertainty),
                elevation_mask_rad: mask,
            });
        }
        let a = approx?;
        let t0 = self.receiver_time(0.0)?;
        let dt = t_s - t0;
        Some(Assistance {
            t_s,
            time_uncertainty_s: a.time_uncertainty_s,
            r_ecef_m: a.r_ecef_m + a.v_ecef_mps * dt,
            v_ecef_mps: a.v_ecef_mps,
            position_uncertainty_m: a.position_uncertainty_m + 10.0 * dt.abs(),
            velocity_uncertainty_mps: a.velocity_uncertainty_mps + 0.01 * dt.abs(),
            oscillator_uncertainty: a.oscillator_uncertainty,
            elevation_mask_rad: mask,
        })
    }

    /// Form every epoch whose samples every channel has tracked past, up to `end`.
    fn epochs(&mut self, end: u64) -> Result<Vec<EpochReport>, PipelineError> {
        let fs = self.setup.sample_rate_hz;
        let rate = self.config.observation_rate_hz;
        let margin = EPOCH_MARGIN_PERIODS * 1e-3 * fs;
        let mut reports = Vec::new();
        // The clock may be re-anchored by an epoch's fix: each epoch reads it anew.
        while let Some(t0) = self.clock_offset_s {
            let k = *self
                .next_epoch
                .get_or_insert_with(|| ((t0 * rate).ceil()) as i64);
            let t_k = k as f64 / rate;
            let n_k = (t_k - t0) * fs;
            if n_k + margin > end as f64 {
                break;
            }
            self.next_epoch = Some(k + 1);
            if n_k >= 0.0 {
                reports.extend(self.epoch(n_k, t_k));
            }
        }
        Ok(reports)
    }

    /// Observations and fixes at sample `n_k`, receiver time `t_k`; `None` for an epoch of
    /// a guessed clock (no time tag) before a fix has set it. An epoch whose fix re-anchors
    /// the clock ([`Self::steer`]) is formed again at the same sample on the new clock: its
    /// time tag is the GPS time `t_k` minus the bias (not a whole second), its
    /// pseudoranges and phases and its fix those of that clock.
    fn epoch(&mut self, n_k: f64, mut t_k: f64) -> Option<EpochReport> {
        for ch in &mut self.channels {
            while let Some(s) = ch.queue.pop_front() {
                self.observables.push(ch.antenna, ch.sat, ch.signal(), s);
                if s.sample_index > n_k {
                    break;
                }
            }
        }
        self.summary.epochs += 1;
        let (mut observations, mut fixes) = self.solve_epoch(n_k, t_k);
        let provisional = self.clock_guessed;
        let bias_s = fixes
            .iter()
            .find_map(|f| f.fix.as_ref().ok())
            .map(|f| f.clock_bias_m / C_MPS);
        if let Some(b) = bias_s
            && self.steer(b, n_k)
        {
            // The same sample again on the clock just set: its time tag is GPS time.
            self.observables.keep_pending(&observations);
            t_k -= b;
            (observations, fixes) = self.solve_epoch(n_k, t_k);
        } else if provisional && bias_s.is_none() {
            // A guessed clock and no fix to set it: nothing reported (a fix that finds it
            // within the threshold has set it: reported as it is).
            self.observables.keep_pending(&observations);
            return None;
        }
        for f in fixes.iter().filter(|f| f.fix.is_ok()) {
            self.summary.fixes[f.antenna] += 1;
        }
        let origin = self.nav.origin().map(|o| o.epoch_at(t_k));
        Some(EpochReport {
            sample_index: n_k,
            t_rx: origin.unwrap_or_default(),
            observations,
            fixes,
        })
    }

    /// The observations at sample `n_k`, receiver time `t_k`, and the epoch stage's
    /// results for them.
    fn solve_epoch(&mut self, n_k: f64, t_k: f64) -> (Vec<Observation>, Vec<AntennaFix>) {
        let observations = self.observables.at(n_k, t_k, self.clock_steps_s);
        let fixes = self.epoch_stage.epoch(&EpochInput {
            t_s: t_k,
            observations: &observations,
            nav: &self.nav,
        });
        (observations, fixes)
    }

    /// A fix at sample `n_k` found the receiver clock `bias_s` ahead of GPS time: beyond
    /// [`STEER_THRESHOLD_S`] the clock is re-anchored to GPS time (a clock jump, as a
    /// receiver steering its clock makes), so that the following epochs and every output's
    /// time tags are GPS time. Returns whether it jumped. The clock counts as set from then
    /// on; the next epoch is the first whole one after `n_k` on the new clock.
    fn steer(&mut self, bias_s: f64, n_k: f64) -> bool {
        self.clock_guessed = false;
        let Some(t0) = self.clock_offset_s else {
            return false;
        };
        if !(bias_s.is_finite() && bias_s.abs() > STEER_THRESHOLD_S) {
            return false;
        }
        let t0 = t0 - bias_s;
        self.clock_offset_s = Some(t0);
        self.clock_steps_s -= bias_s;
        self.summary.clock_steps += 1;
        let (fs, rate) = (self.setup.sample_rate_hz, self.config.observation_rate_hz);
        let after = ((t0 + n_k / fs) * rate).floor() as i64 + 1;
        self.next_epoch = Some(self.next_epoch.map_or(after, |k| k.max(after)));
        true
    }
}

impl std::fmt::Debug for Receiver {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Receiver")
            .field("setup", &self.setup)
            .field("channels", &self.channels.len())
            .field("clock_offset_s", &self.clock_offset_s)
            .field("summary", &self.summary)
            .finish_non_exhaustive()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};

    /// One block of noise on every band's single antenna: the first search round.
    fn searches_on_noise(signals: &[Signal]) -> usize {
        let fs = 20.46e6;
        let setup = ReceiverSetup {
            sample_rate_hz: fs,
            bands: signals
                .iter()
                .map(|&signal| BandInput {
                    signal,
                    if_hz: 0.0,
                    antennas: vec![0],
                })
                .collect(),
            antenna_names: vec!["ant1".into()],
            start_time: None,
            ephemerides: Vec::new(),
            iono_gps: None,
            iono_bds: None,
            approximate: None,
        };
        let mut receiver = Receiver::new(setup, ReceiverConfig::default()).unwrap();
        let len = receiver.samples_per_search();
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(1);
        let noise: Vec<Complex32> = (0..len)
            .map(|_| Complex32::new(rng.random_range(-1.0..1.0), rng.random_range(-1.0..1.0)))
            .collect();
        let bands = vec![vec![noise]; signals.len()];
        receiver.process(&bands, 0, len).unwrap();
        receiver.summary().searches
    }

    /// L5 beside L1 C/A at the same antenna is searched only for what L1 C/A found (here,
    /// in noise, nothing); recorded alone it is searched blind, every PRN.
    #[test]
    fn a_lower_band_follows_its_lead_band_and_is_blind_alone() {
        assert_eq!(searches_on_noise(&[Signal::GpsL1Ca, Signal::GpsL5]), 32);
        assert_eq!(searches_on_noise(&[Signal::GpsL5, Signal::GpsL1Ca]), 32);
        assert_eq!(searches_on_noise(&[Signal::GpsL5]), 32);
        // Another system's lead band does not lead: E5a is searched blind beside L1 C/A.
        assert_eq!(
            searches_on_noise(&[Signal::GpsL1Ca, Signal::GalE5a]),
            32 + 36
        );
    }
}
