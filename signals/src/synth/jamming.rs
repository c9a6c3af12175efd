//! The jammers of one recording: their waveforms added to an antenna's block before the
//! thermal noise, and the front end's automatic gain control after it.
//!
//! Jammer `j` at antenna `a` is received at baseband (the receiver's local oscillator at
//! the recording's carrier `f_b`, running on the receiver clock `dt`) with the phase
//! `phi(t) = IF t_rx + (f_j - f_b) t - f_j R(t) / c - f_b dt` (cycles), `R` the range,
//! interpolated linearly between geometry epochs as the satellites' delays are, and the
//! amplitude of its J/N0 in the renderer's noise units (thermal noise of 1 per component,
//! `N0 = 2 / fs`): a continuous wave `A e^{j 2 pi phi}` with `A^2 = J = (J/N0) 2 / fs`; a
//! noise jammer `w_k e^{j 2 pi phi}`, `w_k` complex Gaussian of `(J/N0) / fs` per
//! component, drawn from the jammer's own stream by absolute sample index, so every
//! antenna receives the same waveform, turned by its own carrier phase (the narrowband
//! array model: the delay across an array, nanoseconds, is a phase, not a shift of the
//! samples).
//!
//! Automatic gain control (an ideal one): with jammers on, the block is scaled by
//! `1 / sqrt(1 + sum_j J_j / (N0 fs))`, which keeps the total power where the quantiser
//! expects the thermal noise alone, as a real front end's AGC does; satellites and noise
//! are scaled alike, so signal-to-noise ratios do not change, and a jammer far stronger
//! than the noise leaves the signals below the quantiser's steps.

use super::noise::ThermalNoise;
use crate::errors::seed::Stream;
use crate::interference::{Jammer, JammerLink, JammerWaveform};
use skyforge_orbits::constants::C_MPS;
use std::f64::consts::TAU;

/// The jammers a recording on carrier `band_hz` sees, with their links at the two
/// geometry epochs around the samples being rendered.
#[derive(Debug, Clone)]
pub(crate) struct Jamming {
    jammers: Vec<Jammer>,
    /// Each seen jammer's index among the session's, and how many the session has.
    index: Vec<usize>,
    all: usize,
    band_hz: f64,
    sample_rate_hz: f64,
    /// Each jammer's noise stream (noise jammers; clones per rendering thread).
    pub noise: Vec<ThermalNoise>,
    /// `(t_s, links[a * n_seen + j])` at the previous and the next epoch.
    ends: Option<(EpochLinks, EpochLinks)>,
}

type EpochLinks = (f64, Vec<JammerLink>);

/// One block's span of `m` samples: the first sample's absolute index, true times at
/// its ends, the receiver clock there, and the IF phase at its ends (cycles).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Span {
    pub m: usize,
    pub first_sample: u64,
    pub t: (f64, f64),
    pub dt: (f64, f64),
    pub if_phase: (f64, f64),
}

impl Jamming {
    /// The session's `jammers` within half the sample rate of the recording's carrier
    /// `band_hz` (none: `None`), their noise drawn from `seed`'s jammer streams.
    pub fn new(jammers: &[Jammer], band_hz: f64, sample_rate_hz: f64, seed: u64) -> Option<Self> {
        let index: Vec<usize> = (0..jammers.len())
            .filter(|&j| jammers[j].config.in_band(band_hz, sample_rate_hz))
            .collect();
        let noise = (0..index.len())
            .map(|j| ThermalNoise::of_stream(seed, Stream::JammerNoise, j as u32, 1.0))
            .collect();
        (!index.is_empty()).then(|| Self {
            jammers: index.iter().map(|&j| jammers[j].clone()).collect(),
            index,
            all: jammers.len(),
            band_hz,
            sample_rate_hz,
            noise,
            ends: None,
        })
    }

    /// The links of every session jammer at the next geometry epoch `t_s`
    /// (`links[a * n_all + j]`), of which it keeps its own: the samples rendered up to it
    /// interpolate from the previous epoch's.
    pub fn set_links(&mut self, t_s: f64, links: &[JammerLink]) {
        let antennas = links.len() / self.all.max(1);
        let own: Vec<JammerLink> = (0..antennas)
            .flat_map(|a| self.index.iter().map(move |&j| (a, j)))
            .map(|(a, j)| links[a * self.all + j])
            .collect();
        let previous = match self.ends.take() {
            Some((_, next)) => next,
            None => (t_s, own.clone()),
        };
        self.ends = Some((previous, (t_s, own)));
    }

    /// Jammer `j`'s link at antenna `a` at true time `t`, interpolated (range, J/N0).
    fn at(&self, a: usize, j: usize, t: f64) -> Option<(f64, f64)> {
        let ((t0, l0), (t1, l1)) = self.ends.as_ref()?;
        let k = a * self.jammers.len() + j;
        let (p, q) = (l0.get(k)?, l1.get(k)?);
        let w = if t1 > t0 {
            ((t - t0) / (t1 - t0)).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let lerp = |x: f64, y: f64| x + (y - x) * w;
        Some((lerp(p.range_m, q.range_m), lerp(p.jn0_dbhz, q.jn0_dbhz)))
    }

    /// Adds the jammers on at the span's start to antenna `a`'s `i` and `q` (`noise`: this
    /// thread's clones of [`Self::noise`], `buffer`: scratch); returns the AGC's power
    /// factor `1 + sum J / (N0 fs)` (1 when none is on).
    pub fn add(
        &self,
        a: usize,
        span: &Span,
        (i, q): (&mut [f32], &mut [f32]),
        noise: &mut [ThermalNoise],
        buffer: &mut (Vec<f32>, Vec<f32>),
    ) -> f64 {
        let mut factor = 1.0;
        for (j, jammer) in self.jammers.iter().enumerate() {
            let cfg = &jammer.config;
            let (Some((r0, jn0)), Some((r1, _))) =
                (self.at(a, j, span.t.0), self.at(a, j, span.t.1))
            else {
                continue;
            };
            if !cfg.on_at(span.t.0) {
                continue;
            }
            let j_over_n0fs = 10f64.powf(jn0 / 10.0) / self.sample_rate_hz;
            factor += j_over_n0fs;
            let f_off = cfg.frequency_hz - self.band_hz;
            let phase = |t: f64, r: f64, dt: f64, if_phase: f64| {
                (if_phase + f_off * t - cfg.frequency_hz * r / C_MPS - self.band_hz * dt)
                    .rem_euclid(1.0)
            };
            let phi0 = phase(span.t.0, r0, span.dt.0, span.if_phase.0);
            // The phase's growth over the span, from the unwrapped difference.
            let growth = span.if_phase.1 - span.if_phase.0 + f_off * (span.t.1 - span.t.0)
                - cfg.frequency_hz * (r1 - r0) / C_MPS
                - self.band_hz * (span.dt.1 - span.dt.0);
            let step = growth / span.m as f64;
            match cfg.waveform {
                JammerWaveform::Cw => {
                    let amplitude = (2.0 * j_over_n0fs).sqrt();
                    rotate_into((i, q), None, amplitude, (phi0, step));
                }
                JammerWaveform::Noise => {
                    let (bi, bq) = buffer;
                    bi.clear();
                    bi.resize(span.m, 0.0);
                    bq.clear();
                    bq.resize(span.m, 0.0);
                    noise[j].add(span.first_sample, bi, bq);
                    let waveform = Some((&bi[..], &bq[..]));
                    rotate_into((i, q), waveform, j_over_n0fs.sqrt(), (phi0, step));
                }
            }
        }
        factor
    }
}

/// Adds `amplitude (w_k) e^{j 2 pi (phi0 + k step)}` to `i + j q` sample by sample, `w_k`
/// the waveform's samples (1 without one: a continuous wave); the phasor turned by a
/// constant step, exact enough over one block (its rounding grows by 1e-16 a sample).
fn rotate_into(
    (i, q): (&mut [f32], &mut [f32]),
    waveform: Option<(&[f32], &[f32])>,
    amplitude: f64,
    (phi0, step): (f64, f64),
) {
    let (mut c, mut s) = ((TAU * phi0).cos(), (TAU * phi0).sin());
    let (dc, ds) = ((TAU * step).cos(), (TAU * step).sin());
    for k in 0..i.len().min(q.len()) {
        let (wi, wq) = waveform.map_or((1.0, 0.0), |(wi, wq)| (f64::from(wi[k]), f64::from(wq[k])));
        i[k] += (amplitude * (wi * c - wq * s)) as f32;
        q[k] += (amplitude * (wi * s + wq * c)) as f32;
        (c, s) = (c * dc - s * ds, c * ds + s * dc);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::interference::JammerConfig;
    use skyforge_orbits::Vec3;

    const FS: f64 = 4.0e6;
    const L1: f64 = 1_575.42e6;

    /// A jammer at `offset_hz` from L1.
    fn jamming(waveform: JammerWaveform, offset_hz: f64, js_db: f64) -> Jamming {
        let config = JammerConfig {
            name: "j".into(),
            waveform,
            latitude_deg: 30.0,
            longitude_deg: 114.0,
            height_m: 0.0,
            js_db,
            frequency_hz: L1 + offset_hz,
            start_s: 0.0,
            stop_s: None,
        };
        // The links are set by hand: the reference point does not matter.
        let jammer = Jammer::new(&config, 45.0, &Vec3::zeros());
        Jamming::new(&[jammer], L1, FS, 7).unwrap()
    }

    /// A link at `range_m` with `jn0_dbhz`.
    fn link(range_m: f64, jn0_dbhz: f64) -> JammerLink {
        JammerLink {
            range_m,
            jn0_dbhz,
            azimuth_rad: 0.0,
            elevation_rad: 0.0,
        }
    }

    /// One 1-ms block of `m` samples at true time 0, no clock, no IF.
    fn span(m: usize) -> Span {
        Span {
            m,
            first_sample: 0,
            t: (0.0, m as f64 / FS),
            dt: (0.0, 0.0),
            if_phase: (0.0, 0.0),
        }
    }

    /// One antenna's in-phase and quadrature samples.
    type Iq = (Vec<f32>, Vec<f32>);

    /// Renders `j` at `antennas` antennas over one block: each antenna's samples and the
    /// AGC's factor.
    fn render(j: &Jamming, antennas: usize) -> (Vec<Iq>, f64) {
        let m = 4000;
        let mut noise = j.noise.clone();
        let mut buffer = (Vec::new(), Vec::new());
        let mut factor = 0.0;
        let out = (0..antennas)
            .map(|a| {
                let (mut i, mut q) = (vec![0.0; m], vec![0.0; m]);
                factor = j.add(a, &span(m), (&mut i, &mut q), &mut noise, &mut buffer);
                (i, q)
            })
            .collect();
        (out, factor)
    }

    /// A CW at 60 dB-Hz 1 kHz above the carrier: power `J = (J/N0) 2 / fs` in noise
    /// units, one cycle per millisecond, and the AGC's factor `1 + J / (N0 fs)`.
    #[test]
    fn a_cw_has_its_power_and_frequency() {
        let mut j = jamming(JammerWaveform::Cw, 1e3, 15.0);
        j.set_links(0.0, &[link(1000.0, 60.0)]);
        let (out, factor) = render(&j, 1);
        let (i, q) = &out[0];
        let power: f64 = (i.iter().zip(q))
            .map(|(a, b)| f64::from(a * a + b * b))
            .sum::<f64>()
            / i.len() as f64;
        let expected = 1e6 * 2.0 / FS;
        assert!(
            (power / expected - 1.0).abs() < 1e-4,
            "{power} against {expected}"
        );
        assert!((factor - (1.0 + 1e6 / FS)).abs() < 1e-12);
        // The phase turns once in the block (1 kHz over 1 ms): back where it began.
        let turn = |k: usize| f64::from(q[k]).atan2(f64::from(i[k]));
        let per_sample = 1e3 / FS * std::f64::consts::TAU;
        let wrapped = (turn(1) - turn(0) - per_sample + 3.0 * std::f64::consts::PI)
            .rem_euclid(std::f64::consts::TAU)
            - std::f64::consts::PI;
        assert!(wrapped.abs() < 1e-6, "{wrapped}");
    }

    /// A noise jammer at 70 dB-Hz adds `(J/N0) / fs` of variance per component, the same
    /// waveform at two antennas turned by their ranges' carrier phase (`f R / c`), and
    /// nothing while switched off.
    #[test]
    fn a_noise_jammer_is_one_waveform_turned_at_each_antenna() {
        let mut j = jamming(JammerWaveform::Noise, 0.0, 25.0);
        let quarter = C_MPS / L1 / 4.0;
        j.set_links(0.0, &[link(1000.0, 70.0), link(1000.0 + quarter, 70.0)]);
        let (out, _) = render(&j, 2);
        let variance = |x: &[f32]| x.iter().map(|v| f64::from(v * v)).sum::<f64>() / x.len() as f64;
        let expected = 1e7 / FS;
        for (i, q) in &out {
            for v in [variance(i), variance(q)] {
                assert!((v / expected - 1.0).abs() < 0.1, "{v} against {expected}");
            }
        }
        // A quarter wavelength further: the waveform a quarter cycle behind, `a1 = -j a0`.
        let (i0, q0) = &out[0];
        let (i1, q1) = &out[1];
        for k in 0..100 {
            assert!(
                (i1[k] - q0[k]).abs() < 1e-3 && (q1[k] + i0[k]).abs() < 1e-3,
                "{k}"
            );
        }
        j.jammers[0].config.start_s = 1.0;
        let (out, factor) = render(&j, 1);
        assert!(out[0].0.iter().all(|v| *v == 0.0) && factor == 1.0);
    }
}
