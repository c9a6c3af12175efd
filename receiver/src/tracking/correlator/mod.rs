//! The correlator kernel: one block of complex `f32` samples, carrier removal by a local
//! carrier NCO, and three (early, prompt, late) or five (plus very early and very late)
//! code replicas accumulated in one pass.
//!
//! Carrier: the replica `exp(j 2 pi phi(i))`, `phi(i) = phi0 + i dphi` (cycles), is made by
//! `LANES` interleaved phasor recurrences `z[i + LANES] = z[i] w^LANES` started from exact
//! f64 values; each sample is multiplied by `conj(z)`. Over a 4092-sample block each lane
//! takes 256 f32 steps: the replica phase drifts by about 1e-5 rad (measured in this
//! module's tests), far below any loop's thermal jitter.
//!
//! Code: the replica of a tap with offset `delta` (chips) carries chip
//! `floor(p0 + delta + i dp) mod L` at sample `i`; the kernel walks the chips (integer
//! chip boundaries, one fixed-width store per chip) and fills a per-tap buffer, so the
//! per-sample loop is a plain multiply-accumulate the compiler vectorises. A positive offset is an
//! early replica (ahead of the prompt), a negative offset a late one. A BOC(1,1) replica
//! ([`Correlator::pilot_and_data_boc11`]) walks half-chips at twice the rate; phases,
//! rates and offsets stay in chips outside the kernel.
//!
//! Two kernels compute these sums, chosen at run time: with AVX-512 and at most one chip
//! per sample, [`v4`] spreads each tap's chips by a window permutation inside the
//! accumulation loop (no replica buffers); otherwise the portable kernel above runs with
//! the widest vector instructions the CPU has (AVX2 or SSE2, through `pulp`). Both use no
//! unsafe code. Within one machine the result depends only on the samples and the NCO
//! state, never on how the caller split its data into blocks around that call.

use num_complex::Complex;
use skyforge_gnss::nco::LanePhasors;
use skyforge_gnss::signal::Signal;
use skyforge_gnss::spread::LANES;

use super::TrackingError;
use crate::replica::replica_chips;

#[cfg(target_arch = "x86_64")]
mod v4;

/// Largest number of taps a [`Correlator`] computes.
pub const MAX_TAPS: usize = 5;

/// The replicas a correlator computes, as offsets from the prompt.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum TapSet {
    /// Early, prompt, late; early and late `early_late_spacing_chips` apart (early at
    /// `+d/2`, late at `-d/2`).
    Three { early_late_spacing_chips: f64 },
    /// Very early, early, prompt, late, very late: early/late `early_late_spacing_chips`
    /// apart, very early/very late `very_spacing_chips` apart.
    Five {
        early_late_spacing_chips: f64,
        very_spacing_chips: f64,
    },
    /// A signal with a pilot ([`Correlator::pilot_and_data`]): early, prompt and late of
    /// the pilot code, then the prompt of the data code.
    PilotAndData { early_late_spacing_chips: f64 },
}

impl TapSet {
    /// Number of taps.
    pub fn len(self) -> usize {
        match self {
            TapSet::Three { .. } => 3,
            TapSet::Five { .. } => 5,
            TapSet::PilotAndData { .. } => 4,
        }
    }

    /// Always false: a tap set holds three or five taps.
    pub fn is_empty(self) -> bool {
        false
    }

    /// Index of the prompt tap in the correlator output.
    pub fn prompt_index(self) -> usize {
        match self {
            TapSet::Three { .. } | TapSet::PilotAndData { .. } => 1,
            TapSet::Five { .. } => 2,
        }
    }

    /// Offsets (chips) of the taps in output order: very early, early, prompt, late, very
    /// late (the first and last only for [`TapSet::Five`]); early, prompt, late, data
    /// prompt for [`TapSet::PilotAndData`]. Positive is early.
    pub fn offsets_chips(self) -> [f64; MAX_TAPS] {
        match self {
            TapSet::Three {
                early_late_spacing_chips: d,
            }
            | TapSet::PilotAndData {
                early_late_spacing_chips: d,
            } => [d / 2.0, 0.0, -d / 2.0, 0.0, 0.0],
            TapSet::Five {
                early_late_spacing_chips: d,
                very_spacing_chips: v,
            } => [v / 2.0, d / 2.0, 0.0, -d / 2.0, -v / 2.0],
        }
    }

    /// Taps of the tracked code (the data prompt of [`TapSet::PilotAndData`] aside).
    fn tracked_len(self) -> usize {
        match self {
            TapSet::PilotAndData { .. } => 3,
            _ => self.len(),
        }
    }

    fn check(self) -> Result<Self, TrackingError> {
        let offsets = &self.offsets_chips()[..self.tracked_len()];
        let ok = offsets.iter().all(|o| o.is_finite() && o.abs() < 1.5) && offsets[0] > 0.0;
        let ordered = offsets.windows(2).all(|w| w[0] > w[1]);
        if ok && ordered {
            Ok(self)
        } else {
            Err(TrackingError::InvalidConfig(format!(
                "correlator spacings must be positive, below 3 chips and very early outside \
                 early: {self:?}"
            )))
        }
    }
}

/// The local carrier and code NCOs at the first sample of a block.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NcoState {
    /// Carrier replica phase at the first sample (cycles; only the fraction matters here).
    pub carrier_phase_cycles: f64,
    /// Carrier phase increment per sample (cycles): (IF + Doppler) / fs.
    pub carrier_cycles_per_sample: f64,
    /// Prompt code phase at the first sample (chips from the start of a code period).
    pub code_phase_chips: f64,
    /// Code phase increment per sample (chips): code rate / fs; must be positive.
    pub code_chips_per_sample: f64,
}

impl NcoState {
    /// The same NCOs `n` samples later (code phase not wrapped).
    pub fn advanced(&self, n: usize) -> Self {
        Self {
            carrier_phase_cycles: self.carrier_phase_cycles
                + n as f64 * self.carrier_cycles_per_sample,
            code_phase_chips: self.code_phase_chips + n as f64 * self.code_chips_per_sample,
            ..*self
        }
    }
}

/// A correlator for one ranging code (and the data code of a signal with a pilot): the
/// codes, the taps and reusable buffers.
#[derive(Debug, Clone)]
pub struct Correlator {
    /// One code period as signal levels (+1.0 / -1.0), then its first [`LANES`] chips
    /// again (the windows of [`v4`]).
    code: Vec<f32>,
    /// The data code of [`TapSet::PilotAndData`] likewise (empty otherwise).
    data_code: Vec<f32>,
    /// Replica chips per code period.
    len: usize,
    /// Replica chips per code chip: 2 for BOC(1,1) half-chips, else 1.
    subchips: f64,
    taps: TapSet,
    /// The portable kernel's per-tap replica buffers, `taps.len()` slices of the block
    /// length plus `RUN`.
    replicas: Vec<f32>,
    /// The carrier-wiped block of [`accumulate_wiped`] (real parts, then imaginary).
    wiped: Vec<f32>,
    out: [Complex<f64>; MAX_TAPS],
}

impl Correlator {
    /// A correlator for `code` (signal levels +1/-1, one period) with the given taps.
    /// [`TapSet::PilotAndData`] needs [`Self::pilot_and_data`].
    pub fn new(code: &[i8], taps: TapSet) -> Result<Self, TrackingError> {
        if matches!(taps, TapSet::PilotAndData { .. }) {
            return Err(TrackingError::InvalidConfig(
                "a pilot-and-data correlator needs both codes".into(),
            ));
        }
        Self::with_codes(code, &[], taps, 1)
    }

    /// A correlator for a signal with a pilot: early, prompt and late of `pilot` and the
    /// prompt of `data` (codes of one length, chips aligned).
    pub fn pilot_and_data(
        pilot: &[i8],
        data: &[i8],
        early_late_spacing_chips: f64,
    ) -> Result<Self, TrackingError> {
        same_length(pilot, data)?;
        Self::with_codes(
            pilot,
            data,
            TapSet::PilotAndData {
                early_late_spacing_chips,
            },
            1,
        )
    }

    /// [`Self::pilot_and_data`] with BOC(1,1) replicas (Galileo E1): each chip `c` of the
    /// codes as the half-chips `+c, -c`; the NCO's phase and rate and the spacing stay in
    /// chips.
    pub fn pilot_and_data_boc11(
        pilot: &[i8],
        data: &[i8],
        early_late_spacing_chips: f64,
    ) -> Result<Self, TrackingError> {
        same_length(pilot, data)?;
        let half_chips = |c: &[i8]| replica_chips(Signal::GalE1, c);
        Self::with_codes(
            &half_chips(pilot),
            &half_chips(data),
            TapSet::PilotAndData {
                early_late_spacing_chips,
            },
            2,
        )
    }

    fn with_codes(
        code: &[i8],
        data: &[i8],
        taps: TapSet,
        subchips: u8,
    ) -> Result<Self, TrackingError> {
        if code.is_empty() {
            return Err(TrackingError::InvalidConfig("empty ranging code".into()));
        }
        let table = |c: &[i8]| {
            let n = if c.is_empty() { 0 } else { c.len() + LANES };
            c.iter().cycle().take(n).map(|&c| f32::from(c)).collect()
        };
        Ok(Self {
            code: table(code),
            data_code: table(data),
            len: code.len(),
            subchips: f64::from(subchips),
            taps: taps.check()?,
            replicas: Vec::new(),
            wiped: Vec::new(),
            out: [Complex::new(0.0, 0.0); MAX_TAPS],
        })
    }

    /// The taps this correlator computes.
    pub fn taps(&self) -> TapSet {
        self.taps
    }

    /// Code length in chips.
    pub fn code_length(&self) -> usize {
        self.len / self.subchips as usize
    }

    /// Correlate `samples` with the replicas of `nco`: returns one complex sum per tap in
    /// [`TapSet::offsets_chips`] order, `sum_i x[i] conj(carrier(i)) code_tap(i)`.
    pub fn correlate(&mut self, samples: &[Complex<f32>], nco: &NcoState) -> &[Complex<f64>] {
        self.correlate_on(samples, nco, Kernels::Fastest)
    }

    fn correlate_on(
        &mut self,
        samples: &[Complex<f32>],
        nco: &NcoState,
        kernels: Kernels,
    ) -> &[Complex<f64>] {
        let n_taps = self.taps.len();
        // In replica chips (x 1.0, exact, for BPSK).
        let s = self.subchips;
        let (code, data) = (&self.code[..], &self.data_code[..]);
        let replica = Replica {
            code: &code[..self.len],
            data_code: &data[..self.len.min(data.len())],
            p0_chips: nco.code_phase_chips * s,
            dp: nco.code_chips_per_sample * s,
            offsets: self.taps.offsets_chips().map(|o| o * s),
        };
        let job = Job {
            samples,
            carrier: CarrierStart::new(nco),
            replica,
            kernels,
        };
        let (replicas, wiped) = (&mut self.replicas, &mut self.wiped);
        self.out = match self.taps {
            TapSet::Three { .. } => job.run::<3>([code; 3], replicas, wiped),
            TapSet::Five { .. } => job.run::<5>([code; 5], replicas, wiped),
            TapSet::PilotAndData { .. } => job.run::<4>([code, code, code, data], replicas, wiped),
        };
        &self.out[..n_taps]
    }
}

/// Which kernels [`Correlator::correlate_on`] may use.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Kernels {
    /// [`v4`] where it applies, else the portable kernel.
    Fastest,
    /// The portable kernel only (tests compare the two).
    #[cfg(test)]
    Portable,
}

/// One block to correlate.
struct Job<'a> {
    samples: &'a [Complex<f32>],
    carrier: CarrierStart,
    replica: Replica<'a>,
    kernels: Kernels,
}

impl Job<'_> {
    /// The `T` taps' sums; `tables` are the taps' codes for [`v4`].
    fn run<const T: usize>(
        self,
        tables: [&[f32]; T],
        replicas: &mut Vec<f32>,
        wiped: &mut Vec<f32>,
    ) -> [Complex<f64>; MAX_TAPS] {
        #[cfg(target_arch = "x86_64")]
        if self.kernels == Kernels::Fastest
            && let Some(out) = v4::correlate::<T>(self.samples, tables, &self.replica, self.carrier)
        {
            return out;
        }
        #[cfg(not(target_arch = "x86_64"))]
        let _ = tables;
        replicas.resize(T * (self.samples.len() + RUN), 0.0);
        dispatch::<T>(self.samples, replicas, wiped, self.replica, self.carrier)
    }
}

/// Longest chip run (samples) written with one fixed-width store; also the padding of each
/// replica buffer past the block.
const RUN: usize = 8;

/// Fill `buf[i]`, `i < n`, with the chip `floor(phase0 + i dp) mod L` of `code`, chip by
/// chip (for chips longer than `RUN - 1` samples). A non-positive or absurdly small rate
/// holds the first chip.
#[inline(always)]
fn fill_replica(buf: &mut [f32], n: usize, code: &[f32], phase0_chips: f64, dp: f64) {
    let len = code.len();
    let first = phase0_chips.floor();
    let mut chip = (first.rem_euclid(len as f64) as usize).min(len - 1);
    let samples_per_chip = 1.0 / dp;
    if !(dp > 0.0 && samples_per_chip * ONE < 2f64.powi(62)) {
        buf[..n].fill(code[chip]);
        return;
    }
    let step = (samples_per_chip * ONE) as u64;
    let mut boundary = ((first + 1.0 - phase0_chips) * samples_per_chip * ONE) as u64;
    let mut start = 0;
    while start < n {
        let end = (boundary.saturating_add(MASK) >> 32).min(n as u64) as usize;
        buf[start..end.max(start)].fill(code[chip]);
        start = end.max(start);
        boundary = boundary.saturating_add(step);
        chip += 1;
        if chip == len {
            chip = 0;
        }
    }
}

/// 1.0 in 32.32 fixed point.
const ONE: f64 = (1u64 << 32) as f64;
/// Adding it before the shift rounds a 32.32 value up.
const MASK: u64 = (1 << 32) - 1;

/// Fill one tap's replica `buf` (`n + RUN` values) with the chip
/// `floor(phase0 + i dp) mod L` at sample `i < n`, for chips of at most `RUN - 1` samples:
/// each run is written as one `RUN`-wide store that the next chip overwrites.
///
/// Chip boundaries are 32.32 fixed-point samples (integer arithmetic only): chip `k` of
/// the walk ends at `ceil(b0 + k step)`; over a 2046-chip block the accumulated boundary
/// error is below 5e-7 samples.
#[inline(always)]
fn fill_replica_short(buf: &mut [f32], n: usize, code: &[f32], phase0_chips: f64, dp: f64) {
    let len = code.len();
    let samples_per_chip = 1.0 / dp;
    let first = phase0_chips.floor();
    let mut chip = (first.rem_euclid(len as f64) as usize).min(len - 1);
    let step = (samples_per_chip * ONE) as u64;
    let mut boundary = ((first + 1.0 - phase0_chips) * samples_per_chip * ONE) as u64;
    let mut start = 0;
    // Chips ending at or before sample n - 1: no clamping.
    let limit = (n.saturating_sub(1) as u64) << 32;
    let mut fast = if boundary <= limit {
        ((limit - boundary) / step + 1) as usize
    } else {
        0
    };
    while fast > 0 {
        let run = fast.min(len - chip);
        for &value in &code[chip..chip + run] {
            buf[start..start + RUN].copy_from_slice(&[value; RUN]);
            start = ((boundary + MASK) >> 32) as usize;
            boundary += step;
        }
        fast -= run;
        chip = (chip + run) % len;
    }
    while start < n {
        buf[start..start + RUN].copy_from_slice(&[code[chip]; RUN]);
        start = (boundary.saturating_add(MASK) >> 32).min(n as u64) as usize;
        boundary = boundary.saturating_add(step);
        chip += 1;
        if chip == len {
            chip = 0;
        }
    }
}

/// Lane start phasors and the per-step rotation, from the f64 NCO state.
#[derive(Debug, Clone, Copy)]
struct CarrierStart {
    zr: [f32; LANES],
    zi: [f32; LANES],
    wr: f32,
    wi: f32,
}

impl CarrierStart {
    fn new(nco: &NcoState) -> Self {
        let z = LanePhasors::<LANES>::new(nco.carrier_phase_cycles, nco.carrier_cycles_per_sample);
        Self {
            zr: z.re,
            zi: z.im,
            wr: z.step_re,
            wi: z.step_im,
        }
    }
}

/// The code replica of one block: code, prompt phase and rate, tap offsets.
#[derive(Debug, Clone, Copy)]
struct Replica<'a> {
    code: &'a [f32],
    /// The data code: the fourth tap's (empty unless pilot and data).
    data_code: &'a [f32],
    p0_chips: f64,
    dp: f64,
    offsets: [f64; MAX_TAPS],
}

/// Run the `T`-tap kernel with the widest vector instructions the CPU has.
fn dispatch<const T: usize>(
    samples: &[Complex<f32>],
    replicas: &mut [f32],
    wiped: &mut Vec<f32>,
    replica: Replica<'_>,
    carrier: CarrierStart,
) -> [Complex<f64>; MAX_TAPS] {
    pulp::Arch::new().dispatch(Kernel::<T> {
        samples,
        replicas,
        wiped,
        replica,
        carrier,
    })
}

/// [`Correlator::correlate`]'s arguments, for the CPU-feature dispatch.
struct Kernel<'a, const T: usize> {
    samples: &'a [Complex<f32>],
    replicas: &'a mut [f32],
    wiped: &'a mut Vec<f32>,
    replica: Replica<'a>,
    carrier: CarrierStart,
}

impl<const T: usize> pulp::WithSimd for Kernel<'_, T> {
    type Output = [Complex<f64>; MAX_TAPS];
    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, _: S) -> Self::Output {
        let n = self.samples.len();
        let Replica {
            code,
            data_code,
            p0_chips,
            dp,
            offsets,
        } = self.replica;
        let short = dp > 0.0 && 1.0 / dp <= (RUN - 1) as f64;
        for (t, buf) in self.replicas.chunks_exact_mut(n + RUN).enumerate() {
            let code = if t == 3 && !data_code.is_empty() {
                data_code
            } else {
                code
            };
            if short {
                fill_replica_short(buf, n, code, p0_chips + offsets[t], dp);
            } else {
                fill_replica(buf, n, code, p0_chips + offsets[t], dp);
            }
        }
        if T > 3 {
            self.wiped.resize(2 * n, 0.0);
            accumulate_wiped::<T>(self.samples, self.replicas, self.carrier, self.wiped)
        } else {
            accumulate::<T>(self.samples, self.replicas, self.carrier)
        }
    }
}

/// [`accumulate`] in two passes, for more than three taps (whose single loop the compiler
/// keeps from vectorising well: a quarter of the three-tap speed, measured): the carrier
/// is wiped into `wiped` first, then each tap is one dot product. Every lane's sums take
/// the same products in the same order, so the result is [`accumulate`]'s, bit for bit.
#[inline(always)]
fn accumulate_wiped<const T: usize>(
    samples: &[Complex<f32>],
    replicas: &[f32],
    carrier: CarrierStart,
    wiped: &mut [f32],
) -> [Complex<f64>; MAX_TAPS] {
    let n = samples.len();
    let (re, im) = wiped.split_at_mut(n);
    let CarrierStart {
        mut zr,
        mut zi,
        wr,
        wi,
    } = carrier;
    let full = n / LANES * LANES;
    for ((x, br), bi) in samples[..full]
        .chunks_exact(LANES)
        .zip(re.chunks_exact_mut(LANES))
        .zip(im.chunks_exact_mut(LANES))
    {
        for l in 0..LANES {
            br[l] = x[l].re * zr[l] + x[l].im * zi[l];
            bi[l] = x[l].im * zr[l] - x[l].re * zi[l];
            let r = zr[l] * wr - zi[l] * wi;
            zi[l] = zr[l] * wi + zi[l] * wr;
            zr[l] = r;
        }
    }
    for l in 0..n - full {
        let x = samples[full + l];
        re[full + l] = x.re * zr[l] + x.im * zi[l];
        im[full + l] = x.im * zr[l] - x.re * zi[l];
    }
    let stride = n + RUN;
    let mut out = [Complex::new(0.0, 0.0); MAX_TAPS];
    for (t, o) in out.iter_mut().enumerate().take(T) {
        let code = &replicas[t * stride..t * stride + n];
        let mut acc_r = [0f32; LANES];
        let mut acc_i = [0f32; LANES];
        for ((c, br), bi) in code[..full]
            .chunks_exact(LANES)
            .zip(re.chunks_exact(LANES))
            .zip(im.chunks_exact(LANES))
        {
            for l in 0..LANES {
                acc_r[l] += c[l] * br[l];
                acc_i[l] += c[l] * bi[l];
            }
        }
        for l in 0..n - full {
            acc_r[l] += code[full + l] * re[full + l];
            acc_i[l] += code[full + l] * im[full + l];
        }
        *o = lane_sums(&acc_r, &acc_i);
    }
    out
}

/// The per-sample loop, compiled once per instruction set.
#[inline(always)]
fn accumulate<const T: usize>(
    samples: &[Complex<f32>],
    replicas: &[f32],
    carrier: CarrierStart,
) -> [Complex<f64>; MAX_TAPS] {
    let n = samples.len();
    let CarrierStart {
        mut zr,
        mut zi,
        wr,
        wi,
    } = carrier;
    let stride = n + RUN;
    let codes: [&[f32]; T] = std::array::from_fn(|t| &replicas[t * stride..t * stride + n]);
    let mut acc_r = [[0f32; LANES]; T];
    let mut acc_i = [[0f32; LANES]; T];
    let full = n / LANES * LANES;
    for (c, x) in samples[..full].chunks_exact(LANES).enumerate() {
        let base = c * LANES;
        // x conj(z), then the carrier rotation.
        let mut br = [0f32; LANES];
        let mut bi = [0f32; LANES];
        for l in 0..LANES {
            br[l] = x[l].re * zr[l] + x[l].im * zi[l];
            bi[l] = x[l].im * zr[l] - x[l].re * zi[l];
            let r = zr[l] * wr - zi[l] * wi;
            zi[l] = zr[l] * wi + zi[l] * wr;
            zr[l] = r;
        }
        for t in 0..T {
            let code = &codes[t][base..base + LANES];
            for l in 0..LANES {
                acc_r[t][l] += code[l] * br[l];
                acc_i[t][l] += code[l] * bi[l];
            }
        }
    }
    for l in 0..n - full {
        let x = samples[full + l];
        let br = x.re * zr[l] + x.im * zi[l];
        let bi = x.im * zr[l] - x.re * zi[l];
        for t in 0..T {
            acc_r[t][l] += codes[t][full + l] * br;
            acc_i[t][l] += codes[t][full + l] * bi;
        }
    }
    let mut out = [Complex::new(0.0, 0.0); MAX_TAPS];
    for t in 0..T {
        out[t] = lane_sums(&acc_r[t], &acc_i[t]);
    }
    out
}

/// The lanes' partial sums added up in f64.
#[inline(always)]
fn lane_sums(re: &[f32; LANES], im: &[f32; LANES]) -> Complex<f64> {
    Complex::new(
        re.iter().map(|&v| f64::from(v)).sum(),
        im.iter().map(|&v| f64::from(v)).sum(),
    )
}

/// Pilot and data codes must be of one length, their chips aligned.
fn same_length(pilot: &[i8], data: &[i8]) -> Result<(), TrackingError> {
    if pilot.len() != data.len() {
        return Err(TrackingError::InvalidConfig(format!(
            "pilot and data codes differ in length: {} and {}",
            pilot.len(),
            data.len()
        )));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A fixed pseudo-random +-1 sequence (LCG), independent of the code generators.
    fn signs(n: usize, seed: u32) -> Vec<i8> {
        let mut x = seed;
        (0..n)
            .map(|_| {
                x = x.wrapping_mul(1_103_515_245).wrapping_add(12345);
                if x >> 31 == 0 { 1 } else { -1 }
            })
            .collect()
    }

    /// `n` complex samples of +-1 components from [`signs`].
    fn noise(n: usize, seed: u32) -> Vec<Complex<f32>> {
        signs(2 * n, seed)
            .chunks_exact(2)
            .map(|c| Complex::new(f32::from(c[0]), f32::from(c[1])))
            .collect()
    }

    /// A tap's sum against the direct evaluation over `n` samples: f32 products of +-1
    /// values, so errors come from the phasor only (1e-5 relative).
    fn assert_matches(got: Complex<f64>, direct: Complex<f64>, n: usize, what: &str) {
        assert!(
            (got - direct).norm() < 1e-4 * n as f64,
            "{what}: {got} vs {direct}"
        );
    }

    /// Direct f64 evaluation of the correlation sum, sample by sample.
    fn reference(
        samples: &[Complex<f32>],
        code: &[i8],
        nco: &NcoState,
        offset: f64,
    ) -> Complex<f64> {
        let len = code.len() as f64;
        samples
            .iter()
            .enumerate()
            .map(|(i, x)| {
                let p = nco.code_phase_chips + offset + i as f64 * nco.code_chips_per_sample;
                let chip = code[(p.floor().rem_euclid(len)) as usize];
                let phi = std::f64::consts::TAU
                    * (nco.carrier_phase_cycles + i as f64 * nco.carrier_cycles_per_sample);
                let z = Complex::new(phi.cos(), -phi.sin());
                Complex::new(f64::from(x.re), f64::from(x.im)) * z * f64::from(chip)
            })
            .sum()
    }

    /// The sums of the fastest kernel this CPU has and of the portable one.
    fn both_kernels(
        corr: &mut Correlator,
        samples: &[Complex<f32>],
        nco: &NcoState,
    ) -> [Vec<Complex<f64>>; 2] {
        [Kernels::Fastest, Kernels::Portable].map(|k| corr.correlate_on(samples, nco, k).to_vec())
    }

    #[test]
    fn matches_direct_evaluation_for_three_and_five_taps() {
        let code = signs(1023, 7);
        let samples = noise(5000, 99);
        for (n, taps) in [
            (
                4092,
                TapSet::Three {
                    early_late_spacing_chips: 0.5,
                },
            ),
            (
                4999,
                TapSet::Five {
                    early_late_spacing_chips: 0.2,
                    very_spacing_chips: 1.0,
                },
            ),
            (
                7,
                TapSet::Three {
                    early_late_spacing_chips: 1.0,
                },
            ),
        ] {
            let nco = NcoState {
                carrier_phase_cycles: 1234.37,
                carrier_cycles_per_sample: 0.1234,
                code_phase_chips: 1022.3,
                code_chips_per_sample: 1.023e6 / 4.092e6 * (1.0 + 2e-6),
            };
            let mut corr = Correlator::new(&code, taps).unwrap();
            for out in both_kernels(&mut corr, &samples[..n], &nco) {
                let offsets = taps.offsets_chips();
                for t in 0..taps.len() {
                    let r = reference(&samples[..n], &code, &nco, offsets[t]);
                    assert_matches(out[t], r, n, &format!("tap {t}"));
                }
            }
        }
    }

    /// A code shorter than a vector's 16 chips (a window wraps more than once) and a
    /// sample rate below the chip rate (the window path does not apply).
    #[test]
    fn short_codes_and_coarse_sampling_match_direct_evaluation() {
        let samples = noise(333, 17);
        let taps = TapSet::Three {
            early_late_spacing_chips: 0.5,
        };
        // Phases off every chip edge (an edge sample may round either way).
        for (len, dp) in [(7, 0.931_7), (7, 1.301_3), (1023, 2.503_1)] {
            let code = signs(len, 23);
            let nco = NcoState {
                carrier_phase_cycles: 0.61,
                carrier_cycles_per_sample: -0.0173,
                code_phase_chips: 5.937,
                code_chips_per_sample: dp,
            };
            let mut corr = Correlator::new(&code, taps).unwrap();
            for out in both_kernels(&mut corr, &samples, &nco) {
                for (t, offset) in taps.offsets_chips()[..3].iter().enumerate() {
                    let r = reference(&samples, &code, &nco, *offset);
                    assert_matches(out[t], r, 333, &format!("{len} chips, {dp}: tap {t}"));
                }
            }
        }
    }

    /// The pilot-and-data taps against the direct evaluation: three taps of the pilot
    /// code, the fourth of the data code at the prompt, over short-chip (10.23 Mchip/s at
    /// 20.46 Msps) and long-chip blocks.
    #[test]
    fn pilot_and_data_taps_match_direct_evaluation() {
        let (pilot, data) = (signs(10_230, 11), signs(10_230, 12));
        let samples = noise(20_500, 5);
        for (n, dp) in [(20_460, 0.5 * (1.0 - 3e-6)), (20_001, 0.1)] {
            let nco = NcoState {
                carrier_phase_cycles: 0.37,
                carrier_cycles_per_sample: 0.0413,
                code_phase_chips: 10_229.6,
                code_chips_per_sample: dp,
            };
            let mut corr = Correlator::pilot_and_data(&pilot, &data, 0.5).unwrap();
            for out in both_kernels(&mut corr, &samples[..n], &nco) {
                assert_eq!(out.len(), 4);
                for (t, (code, offset)) in
                    [(&pilot, 0.25), (&pilot, 0.0), (&pilot, -0.25), (&data, 0.0)]
                        .into_iter()
                        .enumerate()
                {
                    let r = reference(&samples[..n], code, &nco, offset);
                    assert_matches(out[t], r, n, &format!("tap {t}"));
                }
            }
        }
        assert!(Correlator::pilot_and_data(&pilot, &data[1..], 0.5).is_err());
        let taps = TapSet::PilotAndData {
            early_late_spacing_chips: 0.5,
        };
        assert!(Correlator::new(&pilot, taps).is_err());
    }

    /// BOC(1,1) taps (Galileo E1) against the direct evaluation with the half-chip codes
    /// at twice the phase, rate and offsets, at 15 Msps (7.3 samples per half-chip) and
    /// 4.092 Msps (2).
    #[test]
    fn boc11_taps_match_direct_evaluation_on_half_chips() {
        let (pilot, data) = (signs(4092, 31), signs(4092, 32));
        let samples = noise(60_000, 6);
        let half = |c: &[i8]| c.iter().flat_map(|&c| [c, -c]).collect::<Vec<i8>>();
        let (hp, hd) = (half(&pilot), half(&data));
        for (n, fs) in [(60_000, 15e6), (16_368, 4.092e6)] {
            let nco = NcoState {
                carrier_phase_cycles: 0.12,
                carrier_cycles_per_sample: 0.0213,
                code_phase_chips: 4091.3,
                code_chips_per_sample: 1.023e6 * (1.0 + 1e-6) / fs,
            };
            let mut corr = Correlator::pilot_and_data_boc11(&pilot, &data, 0.15).unwrap();
            assert_eq!(corr.code_length(), 4092);
            let doubled = NcoState {
                code_phase_chips: 2.0 * nco.code_phase_chips,
                code_chips_per_sample: 2.0 * nco.code_chips_per_sample,
                ..nco
            };
            for out in both_kernels(&mut corr, &samples[..n], &nco) {
                for (t, (code, offset)) in [(&hp, 0.075), (&hp, 0.0), (&hp, -0.075), (&hd, 0.0)]
                    .into_iter()
                    .enumerate()
                {
                    let r = reference(&samples[..n], code, &doubled, 2.0 * offset);
                    assert_matches(out[t], r, n, &format!("tap {t} at {fs}"));
                }
            }
        }
    }

    /// The two-pass loop of four and five taps gives the single loop's sums bit for bit.
    #[test]
    fn the_two_pass_loop_equals_the_single_loop_exactly() {
        let noise = signs(2 * 5003, 21);
        let samples: Vec<Complex<f32>> = noise
            .chunks_exact(2)
            .map(|c| Complex::new(f32::from(c[0]) * 0.7, f32::from(c[1]) * 1.3))
            .collect();
        let n = samples.len();
        let replicas: Vec<f32> = signs(5 * (n + RUN), 22)
            .iter()
            .map(|&c| f32::from(c))
            .collect();
        let nco = NcoState {
            carrier_phase_cycles: 0.37,
            carrier_cycles_per_sample: 0.0413,
            code_phase_chips: 0.0,
            code_chips_per_sample: 0.5,
        };
        let mut wiped = vec![0f32; 2 * n];
        let carrier = CarrierStart::new(&nco);
        let one = accumulate::<4>(&samples, &replicas, carrier);
        let two = accumulate_wiped::<4>(&samples, &replicas, carrier, &mut wiped);
        assert_eq!(one, two);
        let one = accumulate::<5>(&samples, &replicas, carrier);
        let two = accumulate_wiped::<5>(&samples, &replicas, carrier, &mut wiped);
        assert_eq!(one, two);
    }

    #[test]
    fn a_matched_tone_gives_the_block_length_and_its_phase() {
        // Signal: the code at the prompt's phase on a carrier 0.1 cycle ahead of the NCO.
        let code = signs(1023, 3);
        let n = 4092;
        let nco = NcoState {
            carrier_phase_cycles: 0.25,
            carrier_cycles_per_sample: -0.0371,
            code_phase_chips: 0.0,
            code_chips_per_sample: 0.25,
        };
        let samples: Vec<Complex<f32>> = (0..n)
            .map(|i| {
                let chip = f64::from(code[i / 4]);
                let phi = std::f64::consts::TAU * (0.35 + i as f64 * -0.0371);
                Complex::new((chip * phi.cos()) as f32, (chip * phi.sin()) as f32)
            })
            .collect();
        let mut corr = Correlator::new(
            &code,
            TapSet::Three {
                early_late_spacing_chips: 0.5,
            },
        )
        .unwrap();
        let out = corr.correlate(&samples, &nco);
        let p = out[1];
        assert!((p.norm() - n as f64).abs() < 0.05, "{p}");
        assert!((p.arg() / std::f64::consts::TAU - 0.1).abs() < 1e-5, "{p}");
        // Early and late a quarter chip off the peak: the triangle gives 3/4 of it.
        // The fourth sample of each chip meets the neighbouring chip: +-0.25 / sqrt(1023)
        // of random sidelobe.
        assert!((out[0].norm() / n as f64 - 0.75).abs() < 0.035);
        assert!((out[2].norm() / n as f64 - 0.75).abs() < 0.035);
    }

    #[test]
    fn rejects_bad_spacings() {
        let code = [1i8, -1, 1];
        for taps in [
            TapSet::Three {
                early_late_spacing_chips: 0.0,
            },
            TapSet::Three {
                early_late_spacing_chips: f64::NAN,
            },
            TapSet::Five {
                early_late_spacing_chips: 1.0,
                very_spacing_chips: 0.5,
            },
        ] {
            assert!(Correlator::new(&code, taps).is_err());
        }
        assert!(
            Correlator::new(
                &[],
                TapSet::Three {
                    early_late_spacing_chips: 1.0
                }
            )
            .is_err()
        );
    }
}
