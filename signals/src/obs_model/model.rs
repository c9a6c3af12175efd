//! Observables of one antenna and link from its truth: the truth's pseudorange and carrier
//! phase, the multipath the reflected paths cause in the loops, tracking noise, and an
//! integer carrier ambiguity per continuous track.

use super::config::ObsNoise;
use crate::errors::seed::{Stream, stream_rng};
use crate::synth::link::LinkTruth;
use rand::Rng;
use rand_chacha::ChaCha20Rng;
use rand_distr::{Distribution, StandardNormal};
use skyforge_gnss::observation::{LLI_LOSS_OF_LOCK, ObsRecord};
use skyforge_gnss::signal::Signal;
use skyforge_orbits::ephemeris::SatId;
use std::collections::HashMap;

/// Largest magnitude of a drawn carrier ambiguity (cycles): a receiver's accumulated phase
/// starts at an arbitrary whole number of cycles.
const MAX_AMBIGUITY_CYCLES: i64 = 1 << 20;

/// One continuous track of a link.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Track {
    ambiguity_cycles: i64,
    last_t_s: f64,
    /// Unit-variance noise states (code, phase), first-order Gauss-Markov.
    code_state: f64,
    phase_state: f64,
}

/// Draws observables from link truth. Every antenna has its own noise stream, all
/// ambiguities one stream, so the draws depend only on the seed and the links.
#[derive(Debug, Clone)]
pub struct ObservationModel {
    noise: ObsNoise,
    noise_rngs: Vec<ChaCha20Rng>,
    ambiguity_rng: ChaCha20Rng,
    tracks: HashMap<(usize, SatId, Signal), Track>,
    /// The interval between epochs (s).
    step_s: f64,
    /// Epoch spacing (s) beyond which a track counts as lost.
    max_gap_s: f64,
    /// Per antenna, the Doppler noise stream (none: the Doppler is the truth's).
    doppler_rngs: Option<Vec<ChaCha20Rng>>,
}

/// A standard normal draw.
fn normal(rng: &mut ChaCha20Rng) -> f64 {
    StandardNormal.sample(rng)
}

/// First-order Gauss-Markov step of a unit-variance state over `dt_s` with correlation
/// time `tau_s` (white when `tau_s` is zero).
fn markov(state: f64, dt_s: f64, tau_s: f64, rng: &mut ChaCha20Rng) -> f64 {
    let phi = if tau_s > 0.0 {
        (-dt_s / tau_s).exp()
    } else {
        0.0
    };
    phi * state + (1.0 - phi * phi).sqrt() * normal(rng)
}

impl ObservationModel {
    /// A model for `antennas` antennas observed every `step_s` seconds.
    pub fn new(noise: ObsNoise, seed: u64, antennas: usize, step_s: f64) -> Self {
        Self {
            noise,
            noise_rngs: (0..antennas)
                .map(|a| stream_rng(seed, Stream::ObservationNoise, a as u32))
                .collect(),
            ambiguity_rng: stream_rng(seed, Stream::CarrierAmbiguity, 0),
            tracks: HashMap::new(),
            step_s,
            max_gap_s: 1.5 * step_s,
            doppler_rngs: None,
        }
    }

    /// The interval between the model's epochs (s).
    pub fn step_s(&self) -> f64 {
        self.step_s
    }

    /// The Doppler gets white noise, from streams of its own (the code and phase draws
    /// stay as they were): the calibrated model's `doppler_factor` times
    /// [`LoopNoise::doppler_sigma_hz`](super::LoopNoise::doppler_sigma_hz) at each link's
    /// C/N0, or the constant model's `doppler_mps`. Refused for the elevation model, a
    /// constant model without `doppler_mps` and a calibration without a Doppler factor.
    pub fn with_doppler_noise(self, seed: u64) -> Result<Self, String> {
        match &self.noise {
            ObsNoise::Calibrated(cal) => {
                if let Some(s) = cal.signals.iter().find(|s| s.doppler_factor.is_none()) {
                    return Err(format!(
                        "the calibration has no doppler_factor for {}: re-run skyforge calibrate",
                        s.signal
                    ));
                }
            }
            ObsNoise::Constant { doppler_mps, .. } if doppler_mps.is_some() => {}
            _ => {
                return Err(
                    "Doppler noise needs the calibrated noise model, or the constant \
                            model with doppler_mps"
                        .into(),
                );
            }
        }
        let n = self.noise_rngs.len();
        Ok(Self {
            doppler_rngs: Some(
                (0..n)
                    .map(|a| stream_rng(seed, Stream::DopplerNoise, a as u32))
                    .collect(),
            ),
            ..self
        })
    }

    /// The Doppler noise (Hz, 1 sigma) of `signal` at `cn0_dbhz`: zero without Doppler
    /// noise or a calibration of the signal.
    fn doppler_sigma_hz(&self, signal: Signal, cn0_dbhz: f64) -> f64 {
        match (&self.noise, &self.doppler_rngs) {
            (ObsNoise::Calibrated(cal), Some(_)) => cal.of(signal).map_or(0.0, |c| {
                c.doppler_factor.unwrap_or(0.0) * c.loops.doppler_sigma_hz(cn0_dbhz)
            }),
            (ObsNoise::Constant { doppler_mps, .. }, Some(_)) => {
                doppler_mps.unwrap_or(0.0) / signal.wavelength_m()
            }
            _ => 0.0,
        }
    }

    /// Whether the model has noise for `signal` (the calibrated model only for the signals
    /// its calibration run measured).
    pub fn has_noise_for(&self, signal: Signal) -> bool {
        match &self.noise {
            ObsNoise::Calibrated(cal) => cal.of(signal).is_some(),
            ObsNoise::Elevation { .. } | ObsNoise::Constant { .. } => true,
        }
    }

    /// Code and phase standard deviations (m) and their correlation times (s).
    fn sigmas(&self, signal: Signal, cn0_dbhz: f64, elevation_rad: f64) -> ([f64; 2], [f64; 2]) {
        match &self.noise {
            ObsNoise::Constant {
                phase_m, code_m, ..
            } => ([*code_m, *phase_m], [0.0, 0.0]),
            ObsNoise::Elevation { phase, code } => (
                [code.sigma_m(elevation_rad), phase.sigma_m(elevation_rad)],
                [0.0, 0.0],
            ),
            ObsNoise::Calibrated(cal) => match cal.of(signal) {
                Some(c) => (
                    [
                        c.code_factor * c.loops.code_sigma_m(signal, cn0_dbhz),
                        c.phase_factor * c.loops.phase_sigma_m(signal, cn0_dbhz),
                    ],
                    [c.loops.code_correlation_s(), c.loops.phase_correlation_s()],
                ),
                None => ([0.0, 0.0], [0.0, 0.0]),
            },
        }
    }

    /// Antenna `antenna`'s observation of `sat` on `signal` from its truth `truth` (at a
    /// link elevation of `elevation_rad`).
    pub fn observe(
        &mut self,
        antenna: usize,
        sat: SatId,
        signal: Signal,
        truth: &LinkTruth,
        elevation_rad: f64,
    ) -> ObsRecord {
        let (sigma, tau) = self.sigmas(signal, truth.cn0_dbhz, elevation_rad);
        let key = (antenna, sat, signal);
        let t = truth.t_s;
        let previous = self.tracks.get(&key).copied();
        let rng = &mut self.noise_rngs[antenna];
        let (track, relocked) = match previous {
            Some(p) if t - p.last_t_s <= self.max_gap_s => {
                let dt = t - p.last_t_s;
                let track = Track {
                    last_t_s: t,
                    code_state: markov(p.code_state, dt, tau[0], rng),
                    phase_state: markov(p.phase_state, dt, tau[1], rng),
                    ..p
                };
                (track, false)
            }
            _ => {
                let track = Track {
                    ambiguity_cycles: self
                        .ambiguity_rng
                        .random_range(-MAX_AMBIGUITY_CYCLES..=MAX_AMBIGUITY_CYCLES),
                    last_t_s: t,
                    code_state: normal(rng),
                    phase_state: normal(rng),
                };
                (track, previous.is_some())
            }
        };
        self.tracks.insert(key, track);
        let lambda = signal.wavelength_m();
        let code_m = truth.pseudorange_m + truth.multipath_code_m + sigma[0] * track.code_state;
        let phase_cycles = truth.carrier_phase_cycles
            + (truth.multipath_carrier_m + sigma[1] * track.phase_state) / lambda
            + track.ambiguity_cycles as f64;
        let doppler_sigma = self.doppler_sigma_hz(signal, truth.cn0_dbhz);
        let doppler_hz = match self.doppler_rngs.as_mut() {
            Some(rngs) => truth.doppler_hz + doppler_sigma * normal(&mut rngs[antenna]),
            None => truth.doppler_hz,
        };
        let mut record = ObsRecord::complete(
            sat,
            signal,
            code_m,
            phase_cycles,
            doppler_hz,
            truth.cn0_dbhz,
        );
        if relocked {
            record.phase_lli = LLI_LOSS_OF_LOCK;
        }
        record
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::obs_model::{Calibration, LoopNoise, SignalCalibration};

    fn truth(t_s: f64) -> LinkTruth {
        LinkTruth {
            signal: Signal::GpsL1Ca,
            t_s,
            antenna: 0,
            tx: 0,
            pseudorange_m: 2.2e7 + 800.0 * t_s,
            carrier_phase_cycles: (2.2e7 + 800.0 * t_s) / Signal::GpsL1Ca.wavelength_m(),
            doppler_hz: -4200.0,
            cn0_dbhz: 45.0,
            iono_m: 0.0,
            tropo_m: 0.0,
            antenna_m: 0.0,
            rx_clock_m: 0.0,
            sat_clock_m: 0.0,
            event_code_m: 0.0,
            event_carrier_cycles: 0.0,
            multipath_code_m: 0.0,
            multipath_carrier_m: 0.0,
        }
    }

    /// Errors (code m, phase m) of `n` epochs at 1 s of one link, and the ambiguities seen.
    fn run(
        model: &mut ObservationModel,
        times: impl Iterator<Item = f64>,
    ) -> Vec<(f64, f64, f64, u8)> {
        let lambda = Signal::GpsL1Ca.wavelength_m();
        times
            .map(|t| {
                let tr = truth(t);
                let r = model.observe(0, SatId::gps(7), Signal::GpsL1Ca, &tr, 0.5);
                let code = r.pseudorange_m.unwrap() - tr.pseudorange_m;
                let phase_cycles = r.carrier_phase_cycles.unwrap() - tr.carrier_phase_cycles;
                let ambiguity = phase_cycles.round();
                (
                    code,
                    (phase_cycles - ambiguity) * lambda,
                    ambiguity,
                    r.phase_lli,
                )
            })
            .collect()
    }

    /// The receiver's default loops after pull-in.
    const LOOPS: LoopNoise = LoopNoise {
        pll_bandwidth_hz: 15.0,
        dll_bandwidth_hz: 0.25,
        spacing_chips: 0.5,
        coherent_s: 1e-3,
    };

    /// A GPS L1 C/A calibration with [`LOOPS`] and these factors.
    fn calibration(code: f64, phase: f64, doppler: Option<f64>) -> Calibration {
        Calibration {
            scenario: "test".into(),
            seed: 0,
            duration_s: 1.0,
            signals: vec![SignalCalibration {
                signal: "gps-l1ca".into(),
                loops: LOOPS,
                code_factor: code,
                phase_factor: phase,
                doppler_factor: doppler,
                cn0_dbhz: [45.0, 45.0],
                samples: 1,
            }],
        }
    }

    fn std(v: &[f64]) -> f64 {
        let m = v.iter().sum::<f64>() / v.len() as f64;
        (v.iter().map(|x| (x - m).powi(2)).sum::<f64>() / (v.len() - 1) as f64).sqrt()
    }

    /// Constant noise: the drawn stds are the configured ones (N = 20000: a sample std's
    /// relative standard error is 0.5 %, the bound 3 % is six of them); one ambiguity for
    /// the whole track, no loss-of-lock flag.
    #[test]
    fn constant_noise_has_the_configured_stds_and_one_ambiguity() {
        let noise = ObsNoise::Constant {
            phase_m: 0.003,
            code_m: 0.5,
            doppler_mps: None,
        };
        let mut model = ObservationModel::new(noise, 3, 1, 1.0);
        let out = run(&mut model, (0..20_000).map(f64::from));
        let code: Vec<f64> = out.iter().map(|o| o.0).collect();
        let phase: Vec<f64> = out.iter().map(|o| o.1).collect();
        assert!((std(&code) / 0.5 - 1.0).abs() < 0.03, "{}", std(&code));
        assert!((std(&phase) / 0.003 - 1.0).abs() < 0.03, "{}", std(&phase));
        assert!(out.iter().all(|o| o.2 == out[0].2 && o.3 == 0));
    }

    /// Calibrated noise: the formula std times the factor, and code noise correlated over
    /// the DLL's 1/(4 Bn) = 1 s: lag-1 autocorrelation exp(-1) = 0.368 (standard error
    /// about 1/sqrt(N) = 0.007 at N = 20000; bound 0.04).
    #[test]
    fn calibrated_noise_follows_formula_factor_and_loop_correlation() {
        let loops = LOOPS;
        let calibration = calibration(1.5, 0.8, None);
        let mut model = ObservationModel::new(ObsNoise::Calibrated(calibration), 4, 1, 1.0);
        let out = run(&mut model, (0..20_000).map(f64::from));
        let code: Vec<f64> = out.iter().map(|o| o.0).collect();
        let phase: Vec<f64> = out.iter().map(|o| o.1).collect();
        let want_code = 1.5 * loops.code_sigma_m(Signal::GpsL1Ca, 45.0);
        let want_phase = 0.8 * loops.phase_sigma_m(Signal::GpsL1Ca, 45.0);
        // A correlated series has fewer independent samples: 5 % still covers it.
        assert!(
            (std(&code) / want_code - 1.0).abs() < 0.05,
            "{} vs {want_code}",
            std(&code)
        );
        assert!((std(&phase) / want_phase - 1.0).abs() < 0.03);
        let m = code.iter().sum::<f64>() / code.len() as f64;
        let c0: f64 = code.iter().map(|x| (x - m).powi(2)).sum();
        let c1: f64 = code.windows(2).map(|w| (w[0] - m) * (w[1] - m)).sum();
        assert!(
            (c1 / c0 - (-1.0f64).exp()).abs() < 0.04,
            "lag-1 {}",
            c1 / c0
        );
    }

    /// Doppler noise (opt-in): white, of the calibrated factor times the PLL's frequency
    /// jitter (N = 20000: 3 % is six standard errors of a std, and the lag-1
    /// autocorrelation within 0.03 of zero); the code and phase draws are those of the
    /// model without it; refused without a Doppler factor or for another noise model.
    #[test]
    fn doppler_noise_is_white_calibrated_and_leaves_code_and_phase_alone() {
        let loops = LOOPS;
        let noise = ObsNoise::Calibrated(calibration(1.0, 1.0, Some(17.0)));
        let mut with = ObservationModel::new(noise.clone(), 4, 1, 1.0)
            .with_doppler_noise(4)
            .unwrap();
        let mut without = ObservationModel::new(noise, 4, 1, 1.0);
        let (mut doppler, mut same) = (Vec::new(), true);
        for t in (0..20_000).map(f64::from) {
            let tr = truth(t);
            let a = with.observe(0, SatId::gps(7), Signal::GpsL1Ca, &tr, 0.5);
            let b = without.observe(0, SatId::gps(7), Signal::GpsL1Ca, &tr, 0.5);
            same &= a.pseudorange_m == b.pseudorange_m
                && a.carrier_phase_cycles == b.carrier_phase_cycles
                && b.doppler_hz == Some(tr.doppler_hz);
            doppler.push(a.doppler_hz.unwrap() - tr.doppler_hz);
        }
        assert!(same);
        let want = 17.0 * loops.doppler_sigma_hz(45.0);
        assert!(
            (std(&doppler) / want - 1.0).abs() < 0.03,
            "{} vs {want}",
            std(&doppler)
        );
        let m = doppler.iter().sum::<f64>() / doppler.len() as f64;
        let c0: f64 = doppler.iter().map(|x| (x - m).powi(2)).sum();
        let c1: f64 = doppler.windows(2).map(|w| (w[0] - m) * (w[1] - m)).sum();
        assert!((c1 / c0).abs() < 0.03, "lag-1 {}", c1 / c0);
        let old =
            ObservationModel::new(ObsNoise::Calibrated(calibration(1.0, 1.0, None)), 4, 1, 1.0);
        assert!(old.with_doppler_noise(4).is_err());
        let constant = ObsNoise::Constant {
            phase_m: 0.0,
            code_m: 0.0,
            doppler_mps: None,
        };
        assert!(
            ObservationModel::new(constant, 4, 1, 1.0)
                .with_doppler_noise(4)
                .is_err()
        );
    }

    /// The constant model's Doppler noise: white, `doppler_mps` as a range rate over the
    /// wavelength (N = 20000: 3 % is six standard errors of a std).
    #[test]
    fn constant_doppler_noise_has_the_configured_std() {
        let noise = ObsNoise::Constant {
            phase_m: 0.003,
            code_m: 0.5,
            doppler_mps: Some(0.1),
        };
        let mut model = ObservationModel::new(noise, 4, 1, 1.0)
            .with_doppler_noise(4)
            .unwrap();
        let rate: Vec<f64> = (0..20_000)
            .map(|t| {
                let tr = truth(f64::from(t));
                let a = model.observe(0, SatId::gps(7), Signal::GpsL1Ca, &tr, 0.5);
                (a.doppler_hz.unwrap() - tr.doppler_hz) * Signal::GpsL1Ca.wavelength_m()
            })
            .collect();
        assert!((std(&rate) / 0.1 - 1.0).abs() < 0.03, "{}", std(&rate));
    }

    /// A gap longer than the epoch step ends the track: a new ambiguity and the RINEX
    /// loss-of-lock flag at the first epoch after it; multipath adds to code and phase.
    #[test]
    fn a_gap_redraws_the_ambiguity_and_flags_loss_of_lock() {
        let noise = ObsNoise::Constant {
            phase_m: 0.0,
            code_m: 0.0,
            doppler_mps: None,
        };
        let mut model = ObservationModel::new(noise, 5, 1, 1.0);
        let times = [0.0, 1.0, 2.0, 6.0, 7.0];
        let out = run(&mut model, times.into_iter());
        assert_eq!(out[0].2, out[2].2);
        assert_ne!(out[2].2, out[3].2);
        assert_eq!(
            out.iter().map(|o| o.3).collect::<Vec<_>>(),
            [0, 0, 0, LLI_LOSS_OF_LOCK, 0]
        );
        let mut tr = truth(8.0);
        tr.multipath_code_m = 0.7;
        tr.multipath_carrier_m = 0.01;
        let r = model.observe(0, SatId::gps(7), Signal::GpsL1Ca, &tr, 0.5);
        assert!((r.pseudorange_m.unwrap() - tr.pseudorange_m - 0.7).abs() < 1e-6);
        let phase_m = (r.carrier_phase_cycles.unwrap() - tr.carrier_phase_cycles - out[4].2)
            * Signal::GpsL1Ca.wavelength_m();
        assert!((phase_m - 0.01).abs() < 1e-6);
    }
}
