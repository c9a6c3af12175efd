//! Renders the antennas' sample streams, one 1 ms block at a time, from geometry truth at
//! its epochs (range, rate and acceleration, interpolated by a quintic Hermite polynomial
//! between epochs) and each transmitter's code and data.
//!
//! Signal model of a link (receive time t, light time tau(t), satellite clock offset
//! dt_sv at transmit time, receiver clock ideal for now):
//! satellite time at transmission t_sv = t - tau + dt_sv, code phase = chip rate x t_sv,
//! data bit from t_sv; complex baseband carrier phase (cycles) = IF t - f_c (tau - dt_sv).
//! Within a block both phases are linear in the sample index (the 1 ms curvature error is
//! below 1e-6 rad at LEO dynamics); every block is re-anchored from f64.

use super::config::{BLOCK_S, SignalConfig};
use super::format::SampleFormat;
use super::mix::{ChannelBlock, MixScratch, mix_into};
use super::noise::ThermalNoise;
use super::quantise::{QuantiseError, Quantiser};
use super::transmitter::Transmitter;
use crate::truth::geometry::LinkGeometry;
use crate::truth::interp::QuinticHermite;
use rayon::prelude::*;
use skyforge_orbits::constants::C_MPS;

/// One end of a link's geometry interval.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LinkEnd {
    pub range_m: f64,
    pub range_rate_mps: f64,
    pub range_accel_mps2: f64,
    pub sat_clock_s: f64,
    pub sat_clock_drift: f64,
    /// Ionospheric group delay at the signal's carrier (m): delays the code, advances the
    /// carrier by the same amount.
    pub iono_m: f64,
}

impl LinkEnd {
    /// The link end of a geometry-truth link, `None` when not visible.
    pub fn from_geometry(g: &LinkGeometry) -> Option<Self> {
        g.visible.then_some(Self {
            range_m: g.range_m,
            range_rate_mps: g.range_rate_mps,
            range_accel_mps2: g.range_accel_mps2,
            sat_clock_s: g.sat_clock_s,
            sat_clock_drift: g.sat_clock_drift,
            iono_m: 0.0,
        })
    }
}

/// Signal truth of one link at the start of one block: what an ideal receiver with a
/// perfect clock would measure (no troposphere, receiver clock or antenna terms yet, so
/// carrier phase x wavelength equals the pseudorange minus twice the ionospheric delay).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LinkTruth {
    /// Receive time (s since the scenario start): the block's first sample.
    pub t_s: f64,
    pub antenna: usize,
    /// Index of the transmitter in the synthesiser's list.
    pub tx: usize,
    /// c (t_receive - t_transmit in satellite time) = range - c dt_sv (m).
    pub pseudorange_m: f64,
    /// Accumulated carrier phase (cycles), RINEX sign (grows with the pseudorange); its
    /// integer ambiguity is zero by construction.
    pub carrier_phase_cycles: f64,
    /// Doppler (Hz), -d(pseudorange)/dt / lambda.
    pub doppler_hz: f64,
    /// Ionospheric group delay in the pseudorange (m); the carrier phase has -iono_m.
    pub iono_m: f64,
}

/// A link over one geometry interval.
#[derive(Debug, Clone, Copy)]
struct Segment {
    tx: usize,
    range: QuinticHermite,
    clock_t0_s: f64,
    clock_s: f64,
    drift: f64,
    /// Ionospheric delay (m) at the interval start and its rate (m/s), linear in between.
    iono_m: f64,
    iono_rate_mps: f64,
}

impl Segment {
    /// (geometric light time, satellite clock offset, ionospheric delay in m) at receive
    /// time `t`.
    fn at(&self, t: f64) -> (f64, f64, f64) {
        let tau = self.range.value(t) / C_MPS;
        let iono = self.iono_m + self.iono_rate_mps * (t - self.clock_t0_s - tau);
        (
            tau,
            self.clock_s + self.drift * (t - tau - self.clock_t0_s),
            iono,
        )
    }
}

/// Per-thread buffers.
#[derive(Debug, Default)]
struct Scratch {
    i: Vec<f32>,
    q: Vec<f32>,
    chips: Vec<i8>,
    mix: MixScratch,
}

/// Synthesises the sample streams of every antenna.
#[derive(Debug)]
pub struct Synthesiser<'a> {
    cfg: SignalConfig,
    transmitters: &'a [Transmitter],
    n_antennas: usize,
    n: usize,
    amplitude: f32,
    noise: Vec<ThermalNoise>,
    quantiser: Quantiser,
    clipped: u64,
    previous: Option<(f64, Vec<Option<LinkEnd>>)>,
    /// Record truth every `truth_every` blocks (0: none).
    truth_every: u64,
    truth: Vec<LinkTruth>,
}

/// Noise standard deviation per component (float units before quantisation).
const NOISE_SIGMA: f32 = 1.0;

impl<'a> Synthesiser<'a> {
    /// A synthesiser for `n_antennas` antennas receiving `transmitters` (checked `cfg`).
    pub fn new(
        cfg: &SignalConfig,
        transmitters: &'a [Transmitter],
        n_antennas: usize,
        seed: u64,
    ) -> Result<Self, QuantiseError> {
        let fs = cfg.sample_rate_hz;
        let cn0 = 10f64.powf(cfg.cn0_dbhz / 10.0);
        // Complex: C = A^2, N0 = 2 sigma^2 / fs. Real: C = A^2 / 2, N0 = 2 sigma^2 / fs.
        let per_component = if cfg.format.is_complex() { 2.0 } else { 4.0 };
        let amplitude = ((per_component * cn0 / fs).sqrt() * f64::from(NOISE_SIGMA)) as f32;
        let quantiser = Quantiser::new(cfg.format, cfg.bits, NOISE_SIGMA)?;
        Ok(Self {
            cfg: cfg.clone(),
            transmitters,
            n_antennas,
            n: cfg.samples_per_block(),
            amplitude,
            noise: (0..n_antennas)
                .map(|a| ThermalNoise::new(seed, a as u32, NOISE_SIGMA))
                .collect(),
            quantiser,
            clipped: 0,
            previous: None,
            truth_every: 0,
            truth: Vec::new(),
        })
    }

    /// Record [`LinkTruth`] every `every` blocks (1 ms each); 0 turns it off.
    pub fn with_truth_every(mut self, every: u64) -> Self {
        self.truth_every = every;
        self
    }

    /// The link truth recorded since the last call.
    pub fn take_truth(&mut self) -> Vec<LinkTruth> {
        std::mem::take(&mut self.truth)
    }

    /// Components clipped by the quantiser so far.
    pub fn clipped(&self) -> u64 {
        self.clipped
    }

    /// Hand over the geometry of the epoch at `t_s` (`links[a * n_tx + tx]`, `None` when
    /// not visible). The blocks between the previous epoch and this one are rendered and
    /// appended, per antenna, to `out[a]`.
    pub fn push_epoch(&mut self, t_s: f64, links: Vec<Option<LinkEnd>>, out: &mut [Vec<u8>]) {
        if let Some((t_prev, prev)) = self.previous.take() {
            self.render_interval(t_prev, &prev, t_s, &links, out);
        }
        self.previous = Some((t_s, links));
    }

    fn render_interval(
        &mut self,
        t0: f64,
        start: &[Option<LinkEnd>],
        t1: f64,
        end: &[Option<LinkEnd>],
        out: &mut [Vec<u8>],
    ) {
        let n_tx = self.transmitters.len();
        let segments: Vec<Vec<Segment>> = (0..self.n_antennas)
            .map(|a| {
                (0..n_tx)
                    .filter_map(|tx| {
                        let (s, e) = (start[a * n_tx + tx]?, end[a * n_tx + tx]?);
                        Some(Segment {
                            tx,
                            range: QuinticHermite::new(
                                t0,
                                t1,
                                [s.range_m, s.range_rate_mps, s.range_accel_mps2],
                                [e.range_m, e.range_rate_mps, e.range_accel_mps2],
                            ),
                            clock_t0_s: t0 - s.range_m / C_MPS,
                            clock_s: s.sat_clock_s,
                            drift: s.sat_clock_drift,
                            iono_m: s.iono_m,
                            iono_rate_mps: (e.iono_m - s.iono_m) / (t1 - t0),
                        })
                    })
                    .collect()
            })
            .collect();
        let (b0, b1) = ((t0 / BLOCK_S).round() as u64, (t1 / BLOCK_S).round() as u64);
        if self.truth_every > 0 {
            for b in (b0..b1).filter(|b| b % self.truth_every == 0) {
                let t = b as f64 * BLOCK_S;
                for (a, segs) in segments.iter().enumerate() {
                    for seg in segs {
                        let fc = self.transmitters[seg.tx].signal.carrier_hz();
                        let (tau, dt, iono) = seg.at(t);
                        let rate = seg.range.rate(t) - C_MPS * seg.drift;
                        self.truth.push(LinkTruth {
                            t_s: t,
                            antenna: a,
                            tx: seg.tx,
                            pseudorange_m: C_MPS * (tau - dt) + iono,
                            carrier_phase_cycles: fc * (tau - dt - iono / C_MPS),
                            doppler_hz: -rate * fc / C_MPS,
                            iono_m: iono,
                        });
                    }
                }
            }
        }
        for (a, sink) in out.iter_mut().enumerate().take(self.n_antennas) {
            let noise = &self.noise[a];
            let rendered: Vec<(Vec<u8>, u64)> = (b0..b1)
                .into_par_iter()
                .map_init(
                    || (Scratch::default(), noise.clone(), self.quantiser.clone()),
                    |(scratch, noise, quantiser), b| {
                        let before = quantiser.clipped();
                        let bytes = self.render_block(&segments[a], b, scratch, noise, quantiser);
                        (bytes, quantiser.clipped() - before)
                    },
                )
                .collect();
            for (bytes, clipped) in rendered {
                sink.extend_from_slice(&bytes);
                self.clipped += clipped;
            }
        }
    }

    fn render_block(
        &self,
        segments: &[Segment],
        b: u64,
        s: &mut Scratch,
        noise: &mut ThermalNoise,
        quantiser: &mut Quantiser,
    ) -> Vec<u8> {
        let n = self.n;
        s.i.clear();
        s.i.resize(n, 0.0);
        s.q.clear();
        s.q.resize(n, 0.0);
        let (t0, t1) = (b as f64 * BLOCK_S, (b + 1) as f64 * BLOCK_S);
        let if_cycles_per_block = self.cfg.if_hz * BLOCK_S;
        let if_phase0 = ((if_cycles_per_block - if_cycles_per_block.floor()) * b as f64).fract();
        for seg in segments {
            let tx = &self.transmitters[seg.tx];
            let fc = tx.signal.carrier_hz();
            let ((tau0, dt0, i0), (tau1, dt1, i1)) = (seg.at(t0), seg.at(t1));
            // The code is delayed by the ionosphere, the carrier advanced.
            let (tsv0, tsv1) = (t0 - tau0 - i0 / C_MPS + dt0, t1 - tau1 - i1 / C_MPS + dt1);
            let (k0, code_phase) = tx.chip_at(tsv0);
            let code_per_sample = tx.chip_rate_hz * (tsv1 - tsv0) / n as f64;
            let needed = ChannelBlock::chips_needed(code_phase, code_per_sample, n);
            s.chips.clear();
            tx.chip_signs(k0, needed, &mut s.chips);
            let phi0 = if_phase0 - fc * (tau0 - i0 / C_MPS - dt0);
            let phi1 = if_phase0 + if_cycles_per_block - fc * (tau1 - i1 / C_MPS - dt1);
            let ch = ChannelBlock {
                amplitude: self.amplitude,
                carrier_phase_cycles: phi0,
                carrier_cycles_per_sample: (phi1 - phi0) / n as f64,
                code_phase_chips: code_phase,
                code_chips_per_sample: code_per_sample,
                chip_signs: &s.chips,
            };
            mix_into(&mut s.i, &mut s.q, &ch, &mut s.mix);
        }
        noise.add(b * n as u64, &mut s.i, &mut s.q);
        let mut bytes = Vec::with_capacity(n * self.cfg.format.bytes_per_sample());
        quantiser.write(&s.i, &s.q, &mut bytes);
        bytes
    }

    /// The container format.
    pub fn format(&self) -> SampleFormat {
        self.cfg.format
    }
}
