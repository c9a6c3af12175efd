//! Carrier-smoothed code: the growing-memory Kalman filter of the book (Yuan 2000,
//! section 5.6, eqs. 5-60..5-64) on each satellite's signal, before the fix.
//!
//! The book's filter has the state `X = [rho, N]` with `phi_obv = N - rho + e_phi` and
//! `rho_obv = rho + e_rho` (eq. 5-60), and runs (eqs. 5-61..5-64)
//!
//! ```text
//! rho_k = (N_{k-1} - phi_k) + k1 e_k,   N_k = N_{k-1} + k2 e_k,
//! e_k = rho_obv,k - (N_{k-1} - phi_k),
//! k1 = (s_rho^2 / (k + 1) + s_phi^2) / (s_rho^2 + s_phi^2),   k2 = 1 / (k + 1),
//! X_0 = [rho_obv,0, rho_obv,0 + phi_obv,0].
//! ```
//!
//! RINEX carrier phase runs with the range (`L lambda = rho + N' lambda`), the opposite
//! sign of the book's `phi`: here `phi = -L lambda` and `N = -N' lambda`, so the
//! prediction is `L_k lambda - A_{k-1}` with `A = L lambda - rho` and `A_k = A_{k-1} -
//! k2 e_k` (a unit test runs both forms side by side). A filter restarts (`k = 0`) at a
//! loss of lock, after a missing epoch, and when the code departs from the carrier's
//! prediction by more than [`JUMP_SIGMAS`] code sigmas (a slip the tracker did not flag).
//! Optionally the memory stops growing at `max_epochs` (k2 no smaller than
//! `1 / max_epochs`): on one frequency the ionosphere moves code and carrier apart at
//! twice its rate, which a growing memory turns into a bias.

use skyforge_gnss::observation::{LLI_LOSS_OF_LOCK, ObsRecord};
use skyforge_gnss::signal::Signal;
use skyforge_orbits::constants::C_MPS;
use skyforge_orbits::ephemeris::SatId;

/// Code departure from the carrier's prediction (in code sigmas) that restarts a filter.
/// # assumed: five sigmas, a false restart per 1.7 million epochs of Gaussian code noise.
pub const JUMP_SIGMAS: f64 = 5.0;

/// `[pvt.carrier_smoothing]`: the filter's noise figures and memory.
#[derive(Debug, Clone, Copy, PartialEq, serde::Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct SmoothingConfig {
    /// Code noise sigma (m): the book's "typically 1-5 m".
    pub code_sigma_m: f64,
    /// Carrier noise sigma (m): the book's "a few mm".
    pub phase_sigma_m: f64,
    /// Largest memory (epochs); `None`: the book's growing memory.
    pub max_epochs: Option<u32>,
    /// Epoch interval (s) beyond which a signal's filter restarts. # assumed: 1.5 s, one
    /// missed epoch at the default 1 Hz.
    pub max_gap_s: f64,
}

impl Default for SmoothingConfig {
    /// # assumed: 1 m code (the low end of the book's range, a 45 dB-Hz receiver's code
    /// is below it) and 5 mm carrier (the book's "carrier noise 5-10 mm"); growing memory.
    fn default() -> Self {
        Self {
            code_sigma_m: 1.0,
            phase_sigma_m: 0.005,
            max_epochs: None,
            max_gap_s: 1.5,
        }
    }
}

/// One signal's filter.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Track {
    /// Epochs since the (re)start: the book's `k`.
    k: u32,
    /// `A = L lambda - rho` (m).
    offset_m: f64,
    t_s: f64,
}

/// One antenna's filters, one per satellite and signal.
#[derive(Debug, Clone, Default)]
pub struct CarrierSmoother {
    config: SmoothingConfig,
    tracks: Vec<((SatId, Signal), Track)>,
    restarts: usize,
}

/// One epoch's code and carrier of a satellite's signal.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CodeAndCarrier {
    pub sat: SatId,
    pub signal: Signal,
    pub t_s: f64,
    pub pseudorange_m: f64,
    /// RINEX-signed carrier phase (cycles).
    pub carrier_phase_cycles: f64,
    /// The tracker lost lock since the previous epoch (RINEX LLI bit 0).
    pub loss_of_lock: bool,
}

impl CarrierSmoother {
    pub fn new(config: SmoothingConfig) -> Self {
        Self {
            config,
            ..Self::default()
        }
    }

    /// Restarts so far other than the first epoch of a signal (a loss of lock, a gap, a
    /// code jump).
    pub fn restarts(&self) -> usize {
        self.restarts
    }

    /// The smoothed pseudorange of `m` (eqs. 5-61..5-64), its filter advanced; the raw
    /// pseudorange when the carrier is not finite.
    pub fn smooth(&mut self, m: &CodeAndCarrier) -> f64 {
        let lambda_m = C_MPS / m.signal.carrier_hz();
        let phase_m = m.carrier_phase_cycles * lambda_m;
        if !phase_m.is_finite() {
            self.tracks.retain(|(key, _)| *key != (m.sat, m.signal));
            return m.pseudorange_m;
        }
        let cfg = self.config;
        let fresh = Track {
            k: 0,
            offset_m: phase_m - m.pseudorange_m,
            t_s: m.t_s,
        };
        let Some(i) = self
            .tracks
            .iter()
            .position(|(key, _)| *key == (m.sat, m.signal))
        else {
            self.tracks.push(((m.sat, m.signal), fresh));
            return m.pseudorange_m;
        };
        let track = &mut self.tracks[i].1;
        let predicted = phase_m - track.offset_m;
        let innovation = m.pseudorange_m - predicted;
        let gap = m.t_s - track.t_s;
        if m.loss_of_lock
            || !(gap > 0.0 && gap <= cfg.max_gap_s)
            || innovation.abs() > JUMP_SIGMAS * cfg.code_sigma_m
        {
            *track = fresh;
            self.restarts += 1;
            return m.pseudorange_m;
        }
        let k = match cfg.max_epochs {
            Some(max) => (track.k + 1).min(max.max(1) - 1),
            None => track.k + 1,
        };
        let (s_rho2, s_phi2) = (cfg.code_sigma_m.powi(2), cfg.phase_sigma_m.powi(2));
        let n = f64::from(k) + 1.0;
        let k1 = (s_rho2 / n + s_phi2) / (s_rho2 + s_phi2);
        let k2 = 1.0 / n;
        track.k = k;
        track.offset_m -= k2 * innovation;
        track.t_s = m.t_s;
        predicted + k1 * innovation
    }

    /// The smoothed pseudorange of an observation record at `t_s` ([`Self::smooth`]): its
    /// raw pseudorange without a carrier, `None` without a pseudorange.
    pub fn smooth_record(&mut self, r: &ObsRecord, t_s: f64) -> Option<f64> {
        let pseudorange_m = r.pseudorange_m?;
        Some(match r.carrier_phase_cycles {
            Some(carrier_phase_cycles) => self.smooth(&CodeAndCarrier {
                sat: r.sat,
                signal: r.signal,
                t_s,
                pseudorange_m,
                carrier_phase_cycles,
                loss_of_lock: r.phase_lli & LLI_LOSS_OF_LOCK != 0,
            }),
            None => pseudorange_m,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;
    use rand_distr::{Distribution, Normal};
    use skyforge_orbits::ephemeris::System;

    const SAT: SatId = SatId {
        system: System::Gps,
        prn: 7,
    };

    fn epoch(
        k: usize,
        rho: f64,
        code_noise: f64,
        phase_noise: f64,
        n_cycles: f64,
    ) -> CodeAndCarrier {
        let lambda = C_MPS / Signal::GpsL1Ca.carrier_hz();
        CodeAndCarrier {
            sat: SAT,
            signal: Signal::GpsL1Ca,
            t_s: k as f64,
            pseudorange_m: rho + code_noise,
            carrier_phase_cycles: (rho + phase_noise) / lambda + n_cycles,
            loss_of_lock: false,
        }
    }

    /// The book's equations in its own sign convention (`phi = N - rho`), step by step.
    struct Book {
        n: f64,
        k: u32,
    }

    impl Book {
        fn step(&mut self, rho_obv: f64, phi_obv: f64, cfg: &SmoothingConfig) -> f64 {
            let (s_rho2, s_phi2) = (cfg.code_sigma_m.powi(2), cfg.phase_sigma_m.powi(2));
            self.k += 1;
            let kk = f64::from(self.k) + 1.0;
            let k1 = (s_rho2 / kk + s_phi2) / (s_rho2 + s_phi2);
            let k2 = 1.0 / kk;
            let e = rho_obv - (self.n - phi_obv);
            self.n += k2 * e;
            (self.n - k2 * e - phi_obv) + k1 * e
        }
    }

    /// Oracle: the RINEX-signed filter gives the book's eqs. 5-61..5-64 evaluated in the
    /// book's sign convention, epoch by epoch.
    #[test]
    fn rinex_signed_filter_is_the_books_filter() {
        let cfg = SmoothingConfig::default();
        let mut smoother = CarrierSmoother::new(cfg);
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(5);
        let code = Normal::new(0.0, 1.0).unwrap();
        let phase = Normal::new(0.0, 0.005).unwrap();
        let lambda = C_MPS / Signal::GpsL1Ca.carrier_hz();
        let mut book: Option<Book> = None;
        for k in 0..200 {
            let rho = 2.2e7 + 800.0 * k as f64 + 0.3 * (k * k) as f64;
            let m = epoch(
                k,
                rho,
                code.sample(&mut rng),
                phase.sample(&mut rng),
                12345.0,
            );
            let ours = smoother.smooth(&m);
            let phi_obv = -m.carrier_phase_cycles * lambda;
            let theirs = match &mut book {
                None => {
                    book = Some(Book {
                        n: m.pseudorange_m + phi_obv,
                        k: 0,
                    });
                    m.pseudorange_m
                }
                Some(b) => b.step(m.pseudorange_m, phi_obv, &cfg),
            };
            assert!(
                (ours - theirs).abs() < 1e-6,
                "epoch {k}: {ours} vs {theirs}"
            );
        }
    }

    /// With white code noise and a clean carrier the smoothed error after `k` epochs is
    /// about `sigma / sqrt(k + 1)` (the growing memory averages the code): measured over
    /// 400 independent filters at epochs 24 and 99.
    #[test]
    fn the_smoothed_code_noise_falls_with_the_square_root_of_the_memory() {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(9);
        let code = Normal::new(0.0, 1.0).unwrap();
        let (mut sq24, mut sq99) = (0.0, 0.0);
        let trials = 400;
        for _ in 0..trials {
            let mut smoother = CarrierSmoother::new(SmoothingConfig::default());
            for k in 0..100 {
                let rho = 2.1e7 + 500.0 * k as f64;
                let err = smoother.smooth(&epoch(k, rho, code.sample(&mut rng), 0.0, 7.0)) - rho;
                match k {
                    24 => sq24 += err * err,
                    99 => sq99 += err * err,
                    _ => {}
                }
            }
        }
        let (rms24, rms99) = ((sq24 / trials as f64).sqrt(), (sq99 / trials as f64).sqrt());
        // Expected 0.2 and 0.1 m; 400 trials estimate an rms to about 3.5 %.
        assert!((rms24 / 0.2 - 1.0).abs() < 0.12, "{rms24}");
        assert!((rms99 / 0.1 - 1.0).abs() < 0.12, "{rms99}");
    }

    /// A loss of lock, a missed epoch and a carrier slip the tracker did not flag each
    /// restart the filter (its output is the raw code again); a capped memory stops
    /// narrowing.
    #[test]
    fn slips_gaps_and_losses_of_lock_restart_the_filter() {
        let mut s = CarrierSmoother::new(SmoothingConfig::default());
        let rho = |k: usize| 2.0e7 + 100.0 * k as f64;
        for k in 0..10 {
            s.smooth(&epoch(k, rho(k), 0.0, 0.0, 0.0));
        }
        // A 50-cycle slip (9.5 m): the code departs from the carrier's prediction by 8.6 m.
        let slipped = epoch(10, rho(10), 0.9, 0.0, 50.0);
        assert_eq!(s.smooth(&slipped), slipped.pseudorange_m);
        let mut lost = epoch(11, rho(11), 0.9, 0.0, 50.0);
        lost.loss_of_lock = true;
        assert_eq!(s.smooth(&lost), lost.pseudorange_m);
        let late = epoch(14, rho(14), 0.9, 0.0, 50.0);
        assert_eq!(s.smooth(&late), late.pseudorange_m);
        assert_eq!(s.restarts(), 3);
        // Smoothing resumes: a 0.9 m code error shrinks at the next epoch.
        let next = s.smooth(&epoch(15, rho(15), 0.0, 0.0, 50.0));
        assert!((next - rho(15)).abs() < 0.5, "{next}");

        let capped = SmoothingConfig {
            max_epochs: Some(10),
            ..SmoothingConfig::default()
        };
        let mut s = CarrierSmoother::new(capped);
        let mut last = 0.0;
        for k in 0..60 {
            let err = if k == 59 { 1.0 } else { 0.0 };
            last = s.smooth(&epoch(k, rho(k), err, 0.0, 0.0)) - rho(k);
        }
        // With k held at 9 a code step enters with weight k1 ~ 1/10.
        assert!((last - 0.1).abs() < 0.01, "{last}");
    }
}
