//! Renders the antennas' sample streams, one 1 ms block at a time, from the links' state at
//! the geometry epochs ([`LinkEnd`], interpolated by [`Segment`]), each transmitter's code
//! and data, the receiver clock, fault events, thermal noise, an optional band-limiting
//! filter and the quantiser.
//!
//! Signal model of one path (module docs of [`super::link`] for `D_code`, `D_carr`):
//! sample `k` is taken at receiver-clock time `t_rx = k / fs`, i.e. at true time
//! `t = t_rx - dt_rx(t_rx)`; there the code is read at satellite time `t - D_code(t) -
//! (event code + path delay) / c` and the complex baseband phase (cycles) is
//! `IF t_rx - f_c (D_carr(t) + dt_rx + (event carrier + path delay) / c) - event cycles +
//! path phase / 2 pi`: the local oscillator runs on the receiver clock, so its offset
//! enters the carrier phase like the code. Within a block both phases are linear in the
//! sample index (the 1 ms curvature error is below 1e-6 rad at LEO dynamics); every block is
//! re-anchored from f64. Events and C/N0 are evaluated once per block (1 ms resolution).

use super::config::{BLOCK_S, SignalConfig};
use super::filter::BandFilter;
use super::jamming::{Jamming, Span};
use super::mix::{ChannelBlock, Chips, MixScratch, mix_into, mix_pair_into};
use super::noise::ThermalNoise;
use super::quantise::{QuantiseError, Quantiser};
use super::transmitter::Transmitter;
use crate::errors::clock::{ClockModel, ClockSample, OffsetPoint, interpolate};
use crate::errors::events::{EventEffect, EventSchedule};
use crate::errors::multipath::{Path, dll_bias_m};
use crate::interference::{Jammer, JammerLink};
use rayon::prelude::*;
use skyforge_gnss::sample_format::SampleFormat;
use skyforge_gnss::signal::Signal;
use skyforge_orbits::constants::C_MPS;
use std::f64::consts::TAU;

use super::link::Segment;
pub use super::link::{LinkEnd, LinkTruth};

/// Early-late spacing of the DLL the multipath code truth is given for (chips).
const TRUTH_DLL_SPACING_CHIPS: f64 = 1.0;

/// Bytes of rendered samples held at once per antenna before they go to the sink: blocks
/// are rendered in parallel in slices of at most this size (at least one block), so the
/// memory of a run does not grow with the sample rate times the 1 s geometry step.
pub const SLICE_BYTES: usize = 1 << 20;

/// Blocks of `block_bytes` in a slice of at most `slice_bytes` (at least one).
pub fn blocks_per_slice(block_bytes: usize, slice_bytes: usize) -> u64 {
    (slice_bytes / block_bytes.max(1)).max(1) as u64
}

/// A sample sink for [`Synthesiser::push_epoch`] that appends antenna `a`'s bytes to
/// `out[a]` (tests and benchmarks that keep the samples in memory).
pub fn append_to(
    out: &mut [Vec<u8>],
) -> impl FnMut(usize, &[u8]) -> Result<(), std::convert::Infallible> + '_ {
    |a, bytes| {
        out[a].extend_from_slice(bytes);
        Ok(())
    }
}

/// Per-thread buffers.
#[derive(Debug, Default)]
struct Scratch {
    i: Vec<f32>,
    q: Vec<f32>,
    fi: Vec<f32>,
    fq: Vec<f32>,
    chips: Vec<i8>,
    /// The pilot's chips, for signals with one.
    pilot: Vec<i8>,
    /// Sub-chip levels of a multi-level waveform (Galileo E1; BeiDou B1C's in-phase part).
    levels: Vec<f32>,
    /// BeiDou B1C's quadrature sub-chip levels.
    levels_q: Vec<f32>,
    /// This thread's copies of the noise jammers' streams, and a waveform buffer.
    jam_noise: Vec<ThermalNoise>,
    jam_buffer: (Vec<f32>, Vec<f32>),
    /// Per transmitter, the last data bit looked up (`Transmitter::chip_signs_after`).
    bits: Vec<Option<(u64, u8)>>,
    mix: MixScratch,
}

/// One path of one link over one block, ready to mix.
struct PathBlock {
    amplitude: f32,
    /// Satellite time of the code at the span's first and end sample (s).
    t_sv: (f64, f64),
    /// Baseband carrier phase at the span's first and end sample (cycles).
    phase: (f64, f64),
}

/// Synthesises the sample streams of every antenna.
#[derive(Debug)]
pub struct Synthesiser<'a> {
    cfg: SignalConfig,
    transmitters: &'a [Transmitter],
    n_antennas: usize,
    n: usize,
    noise: Vec<ThermalNoise>,
    quantiser: Quantiser,
    clipped: u64,
    previous: Option<(f64, Vec<Option<LinkEnd>>)>,
    /// Record truth every `truth_every` blocks (0: none).
    truth_every: u64,
    /// Render samples (off for the observation level, which needs the truth alone).
    samples: bool,
    truth: Vec<LinkTruth>,
    /// Observed-only signals whose truth is recorded besides each transmitter's own, for
    /// the transmitters of their system (the observation level).
    observed: Vec<Signal>,
    /// Receiver clocks: none (ideal), one shared by every antenna, or one per antenna.
    clocks: Vec<ClockModel>,
    /// Blocks per clock step.
    clock_every: u64,
    /// Each clock's latest sample.
    clock_last: Vec<Option<ClockSample>>,
    /// The clocks' relativistic offset at the previous and the next geometry epoch
    /// ([`Self::set_clock_relativity`]), added to every clock sample between them.
    relativity: Option<(OffsetPoint, OffsetPoint)>,
    events: Option<EventSchedule>,
    /// The jammers this recording's band sees ([`Self::with_jammers`]).
    jamming: Option<Jamming>,
    filter: Option<BandFilter>,
    /// Rendered bytes held at once per antenna ([`SLICE_BYTES`] by default).
    slice_bytes: usize,
    /// The bytes of one slice's blocks.
    slice: Vec<u8>,
}

/// The instant of one truth record: block start in receiver time `t_rx`, true time `t`,
/// the receiver clock's offset `dt_rx` (s) and fractional frequency `freq`.
#[derive(Debug, Clone, Copy)]
struct TruthInstant {
    t_rx: f64,
    t: f64,
    dt_rx: f64,
    freq: f64,
}

/// Noise standard deviation per component (float units before filtering and quantisation).
const NOISE_SIGMA: f32 = 1.0;

impl<'a> Synthesiser<'a> {
    /// A synthesiser for `n_antennas` antennas receiving `transmitters` (checked `cfg`).
    pub fn new(
        cfg: &SignalConfig,
        transmitters: &'a [Transmitter],
        n_antennas: usize,
        seed: u64,
    ) -> Result<Self, QuantiseError> {
        Ok(Self {
            cfg: cfg.clone(),
            transmitters,
            n_antennas,
            n: cfg.samples_per_block(),
            noise: (0..n_antennas)
                .map(|a| ThermalNoise::new(seed, a as u32, NOISE_SIGMA))
                .collect(),
            quantiser: Quantiser::new(cfg.format, cfg.bits, NOISE_SIGMA)?,
            clipped: 0,
            previous: None,
            truth_every: 0,
            samples: true,
            truth: Vec::new(),
            observed: Vec::new(),
            clocks: Vec::new(),
            clock_every: 1,
            clock_last: Vec::new(),
            relativity: None,
            events: None,
            jamming: None,
            filter: None,
            slice_bytes: SLICE_BYTES,
            slice: Vec::new(),
        })
    }

    /// Record [`LinkTruth`] every `every` blocks (1 ms each); 0 turns it off.
    pub fn with_truth_every(mut self, every: u64) -> Self {
        self.truth_every = every;
        self
    }

    /// Render no samples, only truth (the observation level).
    pub fn without_samples(mut self) -> Self {
        self.samples = false;
        self
    }

    /// Also record the truth of `signals` (observed-only: L2, L5, B2I, B3I) for every
    /// transmitter of their system: the same geometry, clocks, troposphere, antenna and
    /// events, the ionosphere scaled to each carrier (`(f_tx / f)^2`, first order), the
    /// reflected paths at its wavelength and chip length, the transmitter's C/N0.
    pub fn with_observed(mut self, signals: Vec<Signal>) -> Self {
        self.observed = signals;
        self
    }

    /// Hold at most `bytes` of rendered samples per antenna at once (at least one block;
    /// the default is [`SLICE_BYTES`]). The samples do not depend on it.
    pub fn with_slice_bytes(mut self, bytes: usize) -> Self {
        self.slice_bytes = bytes;
        self
    }

    /// Receiver clock: one model shared by all antennas, or one per antenna (`clocks.len()
    /// == n_antennas`). Models step at a whole number of blocks ([`BLOCK_S`]: one block
    /// when samples are rendered; the observation level steps them more coarsely); clones
    /// of one model give the same clock to several synthesisers (bands) of one receiver.
    pub fn with_clocks(mut self, clocks: Vec<ClockModel>) -> Self {
        self.clock_every = clocks
            .first()
            .map_or(1, |c| ((c.dt_s() / BLOCK_S).round() as u64).max(1));
        self.clock_last = vec![None; clocks.len()];
        self.clocks = clocks;
        self
    }

    /// Fault events; their satellite is the transmitter's.
    pub fn with_events(mut self, events: EventSchedule) -> Self {
        self.events = (!events.is_empty()).then_some(events);
        self
    }

    /// The session's `jammers` whose frequency lies in this recording's band, their
    /// noise drawn from `seed`'s streams; their links come with
    /// [`Self::set_jammer_links`].
    pub fn with_jammers(mut self, jammers: &[Jammer], seed: u64) -> Self {
        let band_hz = self.transmitters.first().map(|t| t.signal.carrier_hz());
        self.jamming =
            band_hz.and_then(|hz| Jamming::new(jammers, hz, self.cfg.sample_rate_hz, seed));
        self
    }

    /// Every session jammer's link to every antenna at the next epoch handed over
    /// (`links[a * n + j]`, `n` the session's jammers), before [`Self::push_epoch`].
    pub fn set_jammer_links(&mut self, t_s: f64, links: &[JammerLink]) {
        if let Some(j) = self.jamming.as_mut() {
            j.set_links(t_s, links);
        }
    }

    /// A band-limiting front-end filter; the quantiser's scale follows the filtered noise.
    pub fn with_filter(mut self, filter: BandFilter) -> Result<Self, QuantiseError> {
        let sigma = NOISE_SIGMA * filter.noise_power_gain().sqrt() as f32;
        self.quantiser = Quantiser::new(self.cfg.format, self.cfg.bits, sigma)?;
        self.filter = Some(filter);
        Ok(self)
    }

    /// The link truth recorded since the last call.
    pub fn take_truth(&mut self) -> Vec<LinkTruth> {
        std::mem::take(&mut self.truth)
    }

    /// Components clipped by the quantiser so far.
    pub fn clipped(&self) -> u64 {
        self.clipped
    }

    /// The container format.
    pub fn format(&self) -> SampleFormat {
        self.cfg.format
    }

    /// The receiver clock's relativistic offset at the next epoch handed over: the samples
    /// rendered up to it get the offset interpolated from the previous one's (the first
    /// point sets both).
    pub fn set_clock_relativity(&mut self, point: OffsetPoint) {
        let previous = self.relativity.map_or(point, |(_, next)| next);
        self.relativity = Some((previous, point));
    }

    /// Hand over the links at the epoch `t_s` (true time; `links[a * n_tx + tx]`, `None`
    /// when not visible). The blocks whose receiver time lies between the previous epoch
    /// and this one are rendered and handed, per antenna and in order, to `out(a, bytes)`,
    /// at most [`SLICE_BYTES`] (or one block) at a time.
    pub fn push_epoch<E>(
        &mut self,
        t_s: f64,
        links: Vec<Option<LinkEnd>>,
        out: &mut impl FnMut(usize, &[u8]) -> Result<(), E>,
    ) -> Result<(), E> {
        let rendered = match self.previous.take() {
            Some((t_prev, prev)) => self.render_interval(t_prev, &prev, t_s, &links, out),
            None => Ok(()),
        };
        self.previous = Some((t_s, links));
        rendered
    }

    /// Blocks rendered in parallel before their bytes go to the sink.
    fn blocks_per_slice(&self) -> u64 {
        blocks_per_slice(self.cfg.block_bytes(), self.slice_bytes)
    }

    /// Signal amplitude (noise units) of a path at `cn0_dbhz`.
    fn amplitude(&self, cn0_dbhz: f64) -> f64 {
        // Complex: C = A^2, N0 = 2 sigma^2 / fs. Real: C = A^2 / 2, N0 = 2 sigma^2 / fs.
        let per_component = if self.cfg.format.is_complex() {
            2.0
        } else {
            4.0
        };
        (per_component * 10f64.powf(cn0_dbhz / 10.0) / self.cfg.sample_rate_hz).sqrt()
            * f64::from(NOISE_SIGMA)
    }

    /// The clock sample of each receiver clock for each block of `b0..b1` (one empty list
    /// for an ideal clock): the sample of the clock step the block lies in. A clock steps
    /// at every block, or, when its step spans several blocks, at the first block of each.
    fn clock_samples(&mut self, b0: u64, b1: u64) -> Vec<Vec<ClockSample>> {
        if self.clocks.is_empty() {
            return vec![Vec::new()];
        }
        let every = self.clock_every;
        let relativity = self.relativity;
        self.clocks
            .iter_mut()
            .zip(&mut self.clock_last)
            .map(|(clock, last)| {
                (b0..b1)
                    .map(|b| {
                        let sample = match last {
                            Some(s) if b % every != 0 => *s,
                            _ => *last.insert(clock.step()),
                        };
                        match &relativity {
                            Some((a, z)) => {
                                let (offset, rate) = interpolate(a, z, b as f64 * BLOCK_S);
                                ClockSample {
                                    phase_s: sample.phase_s + offset,
                                    freq: sample.freq + rate,
                                    ..sample
                                }
                            }
                            None => sample,
                        }
                    })
                    .collect()
            })
            .collect()
    }

    fn render_interval<E>(
        &mut self,
        t0: f64,
        start: &[Option<LinkEnd>],
        t1: f64,
        end: &[Option<LinkEnd>],
        out: &mut impl FnMut(usize, &[u8]) -> Result<(), E>,
    ) -> Result<(), E> {
        let n_tx = self.transmitters.len();
        let segments: Vec<Vec<Segment>> = (0..self.n_antennas)
            .map(|a| {
                (0..n_tx)
                    .filter_map(|tx| {
                        let (s, e) = (start[a * n_tx + tx].as_ref()?, end[a * n_tx + tx].as_ref()?);
                        Some(Segment::new(tx, t0, t1, s, e))
                    })
                    .collect()
            })
            .collect();
        let (b0, b1) = ((t0 / BLOCK_S).round() as u64, (t1 / BLOCK_S).round() as u64);
        let clocks = self.clock_samples(b0, b1);
        let clock_of = |a: usize| -> &[ClockSample] {
            let c = if clocks.len() > 1 {
                &clocks[a]
            } else {
                &clocks[0]
            };
            c.as_slice()
        };
        if self.truth_every > 0 {
            let mut truth = std::mem::take(&mut self.truth);
            for b in (b0..b1).filter(|b| b % self.truth_every == 0) {
                for (a, segs) in segments.iter().enumerate() {
                    let clock = clock_of(a).get((b - b0) as usize).copied();
                    for seg in segs {
                        self.truth_records(seg, a, b, clock, &mut truth);
                    }
                }
            }
            self.truth = truth;
        }
        if !self.samples {
            return Ok(());
        }
        let per_slice = self.blocks_per_slice();
        // The slice's buffer lives as long as the synthesiser: allocating it anew for
        // every slice cost a page fault and a cleared page per 4 KiB written.
        let mut slice = std::mem::take(&mut self.slice);
        let mut sent = Ok(());
        'antennas: for (a, segs) in segments.iter().enumerate() {
            let clock = clock_of(a);
            let mut from = b0;
            while from < b1 {
                let to = (from + per_slice).min(b1);
                let bytes = self.render_blocks(segs, a, (b0, from..to), clock, &mut slice);
                sent = out(a, bytes);
                if sent.is_err() {
                    break 'antennas;
                }
                from = to;
            }
        }
        self.slice = slice;
        sent
    }

    /// Blocks `range` of antenna `a` rendered in parallel into `slice` (returned: their
    /// bytes, in order); `clock` holds the clock samples from block `first`.
    fn render_blocks<'s>(
        &mut self,
        segments: &[Segment],
        a: usize,
        (first, range): (u64, std::ops::Range<u64>),
        clock: &[ClockSample],
        slice: &'s mut Vec<u8>,
    ) -> &'s [u8] {
        let count = (range.end - range.start) as usize;
        let block_bytes = self.cfg.block_bytes();
        slice.resize(count * block_bytes, 0);
        let noise = &self.noise[a];
        let this = &*self;
        let clipped: u64 = slice
            .par_chunks_mut(block_bytes)
            .enumerate()
            .map_init(
                || (Scratch::default(), noise.clone(), this.quantiser.clone()),
                |(scratch, noise, quantiser), (k, bytes)| {
                    let b = range.start + k as u64;
                    let before = quantiser.clipped();
                    let cs = clock.get((b - first) as usize).copied();
                    this.render_block(segments, a, b, cs, (scratch, noise, quantiser), bytes);
                    quantiser.clipped() - before
                },
            )
            .sum();
        self.clipped += clipped;
        slice
    }

    /// Receiver clock offset (s) and its rate at receiver time `t_rx`, from the sample of
    /// the clock step `t_rx` lies in.
    fn rx_clock(clock: Option<ClockSample>, t_rx: f64) -> (f64, f64) {
        clock.map_or((0.0, 0.0), |c| {
            (c.phase_s + c.freq * (t_rx - c.t_s), c.freq)
        })
    }

    /// The active events on link (`a`, `tx`) at true time `t`.
    fn effect(&self, t: f64, a: usize, tx: usize) -> EventEffect {
        self.events.as_ref().map_or(EventEffect::NONE, |e| {
            e.effect(t, a, self.transmitters[tx].sat)
        })
    }

    /// The truth of link `seg` at antenna `a` and block `b`: one record for the
    /// transmitter's signal and one per observed-only signal ([`Self::with_observed`]);
    /// none during an outage.
    fn truth_records(
        &self,
        seg: &Segment,
        a: usize,
        b: u64,
        clock: Option<ClockSample>,
        out: &mut Vec<LinkTruth>,
    ) {
        let t_rx = b as f64 * BLOCK_S;
        let (dt_rx, freq) = Self::rx_clock(clock, t_rx);
        let t = t_rx - dt_rx;
        let ev = self.effect(t, a, seg.tx);
        if ev.amplitude_factor <= 0.0 {
            return;
        }
        let tx = &self.transmitters[seg.tx];
        let at = TruthInstant {
            t_rx,
            t,
            dt_rx,
            freq,
        };
        let observed = self.observed.iter().filter(|s| s.system() == tx.sat.system);
        for &signal in std::iter::once(&tx.signal).chain(observed) {
            out.push(self.truth_record(seg, a, at, ev, signal));
        }
    }

    /// The truth of `signal` on link `seg` at antenna `a` at `at`, with the events `ev` of
    /// the transmitter's signal: for another signal of the satellite the ionosphere (and
    /// an ionospheric ramp) scaled by `(f_tx / f)^2`, the reflections at its wavelength and
    /// chip length.
    fn truth_record(
        &self,
        seg: &Segment,
        a: usize,
        at: TruthInstant,
        ev: EventEffect,
        signal: Signal,
    ) -> LinkTruth {
        let TruthInstant {
            t_rx,
            t,
            dt_rx,
            freq,
        } = at;
        let fc = signal.carrier_hz();
        let iono_scale = (self.transmitters[seg.tx].signal.carrier_hz() / fc).powi(2);
        let ev = ev.with_iono_scale(iono_scale);
        let chip_rate_hz = signal.chip_rate_hz();
        let s = seg.at_scaled(t, iono_scale, signal);
        let (multipath_code_m, multipath_carrier_m) = if seg.has_reflections() {
            let chip_m = C_MPS / chip_rate_hz;
            let lambda = C_MPS / fc;
            // Relative carrier phase of each path at the correlator.
            let paths: Vec<Path> = seg
                .reflections_at(t)
                .map(|p| p.at_carrier(lambda))
                .collect();
            let code_len = (chip_rate_hz * BLOCK_S).round() as u32;
            (
                dll_bias_m(&paths, chip_m, code_len, TRUTH_DLL_SPACING_CHIPS),
                multipath_carrier_m(&paths, chip_m, lambda),
            )
        } else {
            (0.0, 0.0)
        };
        LinkTruth {
            signal,
            t_s: t_rx,
            antenna: a,
            tx: seg.tx,
            pseudorange_m: C_MPS * (s.code_delay_s + dt_rx) + ev.code_m,
            carrier_phase_cycles: fc * (s.carrier_delay_s + dt_rx + ev.carrier_m / C_MPS)
                + ev.carrier_cycles,
            doppler_hz: -fc * (seg.carrier_delay_rate(t, iono_scale, signal) * (1.0 - freq) + freq),
            cn0_dbhz: s.cn0_dbhz + 20.0 * ev.amplitude_factor.log10(),
            iono_m: s.iono_m,
            tropo_m: s.tropo_m,
            antenna_m: s.antenna_m,
            rx_clock_m: C_MPS * dt_rx,
            sat_clock_m: C_MPS * s.sat_clock_s,
            event_code_m: ev.code_m,
            event_carrier_cycles: ev.carrier_cycles + ev.carrier_m / C_MPS * fc,
            multipath_code_m,
            multipath_carrier_m,
        }
    }

    /// Block `b` of antenna `a`, written to `bytes` (one block's worth).
    fn render_block(
        &self,
        segments: &[Segment],
        a: usize,
        b: u64,
        clock: Option<ClockSample>,
        (s, noise, quantiser): (&mut Scratch, &mut ThermalNoise, &mut Quantiser),
        bytes: &mut [u8],
    ) {
        let n = self.n;
        let fs = self.cfg.sample_rate_hz;
        // The filter needs `half` samples beyond each end of the block.
        let half = self.filter.as_ref().map_or(0, BandFilter::half);
        let m = n + 2 * half;
        s.i.clear();
        s.i.resize(m, 0.0);
        s.q.clear();
        s.q.resize(m, 0.0);
        let t_block = b as f64 * BLOCK_S;
        let (t_rx0, t_rx1) = (t_block - half as f64 / fs, t_block + (n + half) as f64 / fs);
        let (dt0, _) = Self::rx_clock(clock, t_rx0);
        let (dt1, _) = Self::rx_clock(clock, t_rx1);
        let (t0, t1) = (t_rx0 - dt0, t_rx1 - dt1);
        // IF phase at the span's first sample, kept exact over long runs.
        let if_per_block = self.cfg.if_hz * BLOCK_S;
        let if_phase0 = ((if_per_block - if_per_block.floor()) * b as f64).fract()
            - self.cfg.if_hz * half as f64 / fs;
        let if_span = self.cfg.if_hz * m as f64 / fs;
        for seg in segments {
            let ev = self.effect(t0, a, seg.tx);
            if ev.amplitude_factor <= 0.0 {
                continue;
            }
            let tx = &self.transmitters[seg.tx];
            let fc = tx.signal.carrier_hz();
            let (l0, l1) = (seg.at(t0), seg.at(t1));
            let amplitude = self.amplitude(l0.cn0_dbhz) * ev.amplitude_factor;
            // One path with extra delay `delay` (m, code and carrier) and phase (rad).
            let path = |amp: f64, delay: (f64, f64), phase: (f64, f64)| PathBlock {
                amplitude: amp as f32,
                t_sv: (
                    t0 - l0.code_delay_s - (ev.code_m + delay.0) / C_MPS,
                    t1 - l1.code_delay_s - (ev.code_m + delay.1) / C_MPS,
                ),
                phase: (
                    if_phase0
                        - fc * (l0.carrier_delay_s + dt0 + (ev.carrier_m + delay.0) / C_MPS)
                        - ev.carrier_cycles
                        + phase.0 / TAU,
                    if_phase0 + if_span
                        - fc * (l1.carrier_delay_s + dt1 + (ev.carrier_m + delay.1) / C_MPS)
                        - ev.carrier_cycles
                        + phase.1 / TAU,
                ),
            };
            mix_path((seg.tx, tx), &path(amplitude, (0.0, 0.0), (0.0, 0.0)), m, s);
            for (r0, r1) in seg.reflections_at(t0).zip(seg.reflections_at(t1)) {
                if r0.relative_amplitude > 0.0 {
                    let p = path(
                        amplitude * r0.relative_amplitude,
                        (r0.delay_m, r1.delay_m),
                        (r0.phase_rad, r1.phase_rad),
                    );
                    mix_path((seg.tx, tx), &p, m, s);
                }
            }
        }
        let agc = match &self.jamming {
            Some(jamming) => {
                if s.jam_noise.len() != jamming.noise.len() {
                    s.jam_noise = jamming.noise.clone();
                }
                let span = Span {
                    m,
                    first_sample: b * n as u64,
                    t: (t0, t1),
                    dt: (dt0, dt1),
                    if_phase: (if_phase0, if_phase0 + if_span),
                };
                let iq = (&mut s.i[..], &mut s.q[..]);
                jamming.add(a, &span, iq, &mut s.jam_noise, &mut s.jam_buffer)
            }
            None => 1.0,
        };
        // Noise is keyed by the absolute sample index, offset by the filter margin.
        noise.add(b * n as u64, &mut s.i, &mut s.q);
        if agc > 1.0 {
            let gain = (1.0 / agc.sqrt()) as f32;
            s.i.iter_mut()
                .chain(s.q.iter_mut())
                .for_each(|x| *x *= gain);
        }
        match &self.filter {
            Some(f) => {
                s.fi.clear();
                s.fi.resize(n, 0.0);
                s.fq.clear();
                s.fq.resize(n, 0.0);
                f.apply(&s.i, &s.q, &mut s.fi, &mut s.fq);
                quantiser.write_into(&s.fi, &s.fq, bytes);
            }
            None => quantiser.write_into(&s.i, &s.q, bytes),
        }
    }
}

/// Mix one path over a span of `m` samples into the scratch block. A signal with a pilot
/// puts half its power in each component, the pilot in quadrature (+90 deg, a quarter
/// cycle ahead of the data component), as `(d + j p) / sqrt(2)`.
fn mix_path((index, tx): (usize, &Transmitter), p: &PathBlock, m: usize, s: &mut Scratch) {
    if s.bits.len() <= index {
        s.bits.resize(index + 1, None);
    }
    if tx.subchips_per_chip() > 1 {
        return mix_subchips((index, tx), p, m, s);
    }
    let (k0, code_phase) = tx.chip_at(p.t_sv.0);
    let code_per_sample = tx.chip_rate_hz * (p.t_sv.1 - p.t_sv.0) / m as f64;
    let needed = ChannelBlock::chips_needed(code_phase, code_per_sample, m);
    s.chips.clear();
    tx.chip_signs_after(k0, needed, &mut s.chips, &mut s.bits[index]);
    let amplitude = if tx.has_pilot() {
        p.amplitude * std::f32::consts::FRAC_1_SQRT_2
    } else {
        p.amplitude
    };
    let ch = ChannelBlock {
        amplitude,
        carrier_phase_cycles: p.phase.0,
        carrier_cycles_per_sample: (p.phase.1 - p.phase.0) / m as f64,
        code_phase_chips: code_phase,
        code_chips_per_sample: code_per_sample,
        chips: Chips::Signs(&s.chips),
    };
    if tx.has_pilot() {
        s.pilot.clear();
        tx.pilot_chip_signs(k0, needed, &mut s.pilot);
        mix_pair_into(&mut s.i, &mut s.q, &ch, Chips::Signs(&s.pilot), &mut s.mix);
    } else {
        mix_into(&mut s.i, &mut s.q, &ch, &mut s.mix);
    }
}

/// [`mix_path`] of a multi-level waveform: Galileo E1's CBOC, its sub-chips' levels
/// through the one-component kernel, data and pilot summed in phase; BeiDou B1C's QMBOC,
/// its in-phase and quadrature levels through the two-component kernel.
fn mix_subchips((index, tx): (usize, &Transmitter), p: &PathBlock, m: usize, s: &mut Scratch) {
    let (k0, code_phase) = tx.subchip_at(p.t_sv.0);
    let rate = tx.chip_rate_hz * tx.subchips_per_chip() as f64;
    let code_per_sample = rate * (p.t_sv.1 - p.t_sv.0) / m as f64;
    let needed = ChannelBlock::chips_needed(code_phase, code_per_sample, m);
    s.levels.clear();
    let quadrature = tx.signal == Signal::BdsB1C;
    if quadrature {
        s.levels_q.clear();
        let out = (&mut s.levels, &mut s.levels_q);
        tx.qmboc_levels_after(k0, needed, out, &mut s.bits[index]);
    } else {
        tx.cboc_levels_after(k0, needed, &mut s.levels, &mut s.bits[index]);
    }
    let ch = ChannelBlock {
        amplitude: p.amplitude,
        carrier_phase_cycles: p.phase.0,
        carrier_cycles_per_sample: (p.phase.1 - p.phase.0) / m as f64,
        code_phase_chips: code_phase,
        code_chips_per_sample: code_per_sample,
        chips: Chips::Levels(&s.levels),
    };
    if quadrature {
        let q = Chips::Levels(&s.levels_q);
        mix_pair_into(&mut s.i, &mut s.q, &ch, q, &mut s.mix);
    } else {
        mix_into(&mut s.i, &mut s.q, &ch, &mut s.mix);
    }
}

/// Carrier-phase error (m, RINEX sign) of a composite signal whose prompt correlator sits
/// on the direct path: minus the phase of `1 + sum a R(delay) e^{j phase}` in metres, with
/// the ideal triangular correlation R of chips `chip_m` long (`phase` the path's relative
/// carrier phase at the correlator).
fn multipath_carrier_m(paths: &[Path], chip_m: f64, lambda_m: f64) -> f64 {
    let (mut re, mut im) = (1.0, 0.0);
    for p in paths {
        let r = (1.0 - p.delay_m.abs() / chip_m).max(0.0);
        re += p.relative_amplitude * r * p.phase_rad.cos();
        im += p.relative_amplitude * r * p.phase_rad.sin();
    }
    -im.atan2(re) * lambda_m / TAU
}

#[cfg(test)]
mod tests {
    use super::*;
    use hifitime::{Epoch, TimeScale};
    use skyforge_gnss::navmsg::galileo_fnav::{FnavEncoder, FnavParams};
    use skyforge_orbits::ephemeris::nominal;
    use std::f64::consts::FRAC_1_SQRT_2;

    /// A Galileo E5a path mixed alone and noise-free at a fixed carrier phase: after the
    /// carrier is removed, the data chips sit on the real axis and the pilot chips on the
    /// imaginary one (a quarter cycle ahead), each with amplitude 1/sqrt(2).
    #[test]
    fn a_pilot_signal_puts_half_its_power_in_quadrature() {
        let start = Epoch::from_gregorian(2023, 3, 12, 0, 0, 0, 0, TimeScale::GST);
        let eph = nominal::galileo(start).remove(0);
        let week = skyforge_orbits::time::gpst_week_sow(start).0
            - skyforge_orbits::time::GST_WEEK0_IN_GPS_WEEKS
            - 1;
        let nav = FnavEncoder::new(
            &eph,
            std::slice::from_ref(&eph),
            &FnavParams::default(),
            week,
        )
        .expect("encoder");
        let tx = Transmitter::gal_e5a(eph.sat, nav, start).expect("E5a");
        assert!(tx.has_pilot());
        let (m, t0, phase) = (20_460, 0.0123, 0.3);
        let p = PathBlock {
            amplitude: 1.0,
            t_sv: (t0, t0 + 1e-3),
            phase: (phase, phase),
        };
        let mut s = Scratch {
            i: vec![0.0; m],
            q: vec![0.0; m],
            ..Scratch::default()
        };
        mix_path((0, &tx), &p, m, &mut s);
        let (k0, code_phase) = tx.chip_at(t0);
        let per_sample = tx.chip_rate_hz * 1e-3 / m as f64;
        let needed = ChannelBlock::chips_needed(code_phase, per_sample, m);
        let (mut data, mut pilot) = (Vec::new(), Vec::new());
        tx.chip_signs_after(k0, needed, &mut data, &mut None);
        tx.pilot_chip_signs(k0, needed, &mut pilot);
        let (c, sn) = ((TAU * phase).cos(), (TAU * phase).sin());
        let (mut on_data, mut on_pilot, mut cross) = (0.0, 0.0, 0.0);
        for k in 0..m {
            let chip = (code_phase + k as f64 * per_sample).floor() as usize;
            let (i, q) = (f64::from(s.i[k]), f64::from(s.q[k]));
            let (re, im) = (i * c + q * sn, q * c - i * sn);
            on_data += re * f64::from(data[chip]);
            on_pilot += im * f64::from(pilot[chip]);
            cross += re * f64::from(pilot[chip]);
        }
        let n = m as f64;
        assert!(
            (on_data / n - FRAC_1_SQRT_2).abs() < 0.01,
            "{}",
            on_data / n
        );
        assert!(
            (on_pilot / n - FRAC_1_SQRT_2).abs() < 0.01,
            "{}",
            on_pilot / n
        );
        assert!((cross / n).abs() < 0.05, "{}", cross / n);
    }

    /// A BeiDou B1C path mixed alone and noise-free at a fixed carrier phase, 4 samples
    /// per sub-chip: after the carrier is removed, the real axis correlates with the data
    /// chips' BOC(1,1) by 1/2 (1/4 of the power) and with the pilot chips' BOC(6,1) by
    /// sqrt(1/11), the imaginary axis (a quarter cycle ahead) with the pilot chips' BOC(1,1)
    /// by sqrt(29/44) (BDS-SIS-ICD-B1C-1.0 §4.2.2: together the pilot's 3/4), and neither
    /// with the other component's BOC(1,1) beyond the cross-correlation of two codes over
    /// 1023 chips (4 / sqrt(1023) of the amplitude: four standard deviations of random
    /// codes).
    #[test]
    fn b1c_puts_a_quarter_of_its_power_in_phase_and_the_pilot_in_quadrature() {
        use skyforge_gnss::navmsg::BdsCnavParams;
        use skyforge_gnss::navmsg::bds_cnav1::BdsCnav1Encoder;
        use skyforge_gnss::subcarrier::{boc11, boc61};
        use skyforge_orbits::ephemeris::BeidouSet;
        let start = Epoch::from_gregorian(2023, 3, 12, 0, 0, 0, 0, TimeScale::BDT);
        let eph = nominal::beidou(BeidouSet::Bds3, start)
            .into_iter()
            .find(|e| e.sat.prn == 30)
            .expect("C30");
        let week = skyforge_orbits::time::bdt_week_sow(start).0 - 1;
        let nav = BdsCnav1Encoder::new(&eph, &BdsCnavParams::default(), week).expect("encoder");
        let tx = Transmitter::bds_b1c(eph.sat, nav, start).expect("B1C");
        let (m, t0, phase) = (49_104, 0.0123, 0.3);
        let p = PathBlock {
            amplitude: 1.0,
            t_sv: (t0, t0 + 1e-3),
            phase: (phase, phase),
        };
        let mut s = Scratch {
            i: vec![0.0; m],
            q: vec![0.0; m],
            ..Scratch::default()
        };
        mix_path((0, &tx), &p, m, &mut s);
        let (s0, sub_phase) = tx.subchip_at(t0);
        let per_sample = 12.0 * tx.chip_rate_hz * 1e-3 / m as f64;
        let c0 = s0 / 12;
        let (mut data, mut pilot) = (Vec::new(), Vec::new());
        tx.chip_signs(c0, 1100, &mut data);
        tx.pilot_chip_signs(c0, 1100, &mut pilot);
        let (c, sn) = ((TAU * phase).cos(), (TAU * phase).sin());
        let mut sums = [0.0f64; 5];
        for k in 0..m {
            let sub = s0 + (sub_phase + k as f64 * per_sample).floor() as u64;
            let (j, within) = ((sub / 12 - c0) as usize, (sub % 12) as usize);
            let (a, b) = (f64::from(boc11(within)), f64::from(boc61(within)));
            let (d, pl) = (f64::from(data[j]), f64::from(pilot[j]));
            let (i, q) = (f64::from(s.i[k]), f64::from(s.q[k]));
            let (re, im) = (i * c + q * sn, q * c - i * sn);
            for (sum, x) in sums.iter_mut().zip([
                re * d * a,
                re * pl * b,
                im * pl * a,
                re * pl * a,
                im * d * a,
            ]) {
                *sum += x;
            }
        }
        let [on_data, on_pilot_b, on_pilot_a, cross_re, cross_im] = sums.map(|x| x / m as f64);
        println!(
            "B1C: data {on_data:.4}, pilot BOC(6,1) {on_pilot_b:.4}, pilot BOC(1,1) \
             {on_pilot_a:.4}, cross {cross_re:.4} {cross_im:.4}"
        );
        assert!((on_data - 0.5).abs() < 0.01, "{on_data}");
        assert!(
            (on_pilot_b - (1.0f64 / 11.0).sqrt()).abs() < 0.01,
            "{on_pilot_b}"
        );
        assert!(
            (on_pilot_a - (29.0f64 / 44.0).sqrt()).abs() < 0.01,
            "{on_pilot_a}"
        );
        let bound = 4.0 / 1023f64.sqrt();
        assert!(cross_re.abs() < 0.5 * bound, "{cross_re}");
        assert!(
            cross_im.abs() < (29.0f64 / 44.0).sqrt() * bound,
            "{cross_im}"
        );
    }
}
