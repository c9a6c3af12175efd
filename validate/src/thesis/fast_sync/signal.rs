//! The input of the synchronisation experiment, thesis eq. 3.3-56: a real IF signal
//! `s[n] = A D[n] c[n] cos(2 pi (f_IF n Ts + phi_d(n Ts)) + theta) + u[n]` with a Doppler
//! phase `phi_d(t) = f0 t + f1 t^2 / 2 + f2 t^3 / 6` (cycles), C/A code with the matching
//! code Doppler, 1 ms data symbols and white Gaussian noise at the stated C/N0.

use rand::Rng;
use skyforge_orbits::constants::F_GPS_L1_HZ;
use skyforge_receiver::acquisition::Complex32;
use skyforge_signals::errors::{Stream, stream_rng};
use skyforge_signals::synth::ThermalNoise;

/// The experiment's signal parameters.
#[derive(Debug, Clone, Copy)]
pub struct SignalSpec {
    pub sample_rate_hz: f64,
    pub if_hz: f64,
    pub chip_rate_hz: f64,
    /// Doppler at t = 0 (Hz), its rate (Hz/s) and second derivative (Hz/s^2).
    pub doppler: [f64; 3],
    /// Carrier phase at t = 0 (rad).
    pub phase_rad: f64,
    pub cn0_dbhz: f64,
    /// Data symbol length (s).
    pub symbol_s: f64,
}

impl SignalSpec {
    /// Doppler (Hz) at `t`.
    pub fn doppler_hz(&self, t: f64) -> f64 {
        let [f0, f1, f2] = self.doppler;
        f0 + f1 * t + f2 * t * t / 2.0
    }

    /// Doppler carrier phase (rad) at `t`, without the IF.
    pub fn doppler_phase_rad(&self, t: f64) -> f64 {
        let [f0, f1, f2] = self.doppler;
        self.phase_rad + std::f64::consts::TAU * (f0 * t + f1 * t * t / 2.0 + f2 * t.powi(3) / 6.0)
    }

    /// Code phase (chips) at `t`: the chip rate scaled by the carrier's Doppler.
    pub fn code_phase_chips(&self, t: f64) -> f64 {
        let [f0, f1, f2] = self.doppler;
        let cycles = f0 * t + f1 * t * t / 2.0 + f2 * t.powi(3) / 6.0;
        self.chip_rate_hz * t + cycles * self.chip_rate_hz / F_GPS_L1_HZ
    }

    /// Real-signal amplitude 1: noise standard deviation per sample for the C/N0
    /// (signal power 1/2 over a noise density sigma^2 / (fs / 2)).
    pub fn noise_sigma(&self) -> f64 {
        let cn0 = 10f64.powf(self.cn0_dbhz / 10.0);
        (self.sample_rate_hz / (4.0 * cn0)).sqrt()
    }
}

/// Streams the samples of `spec` for `code` (one period, +/-1) in blocks.
pub struct SignalSource<'a> {
    spec: SignalSpec,
    code: &'a [i8],
    next: u64,
    /// Data symbols: the project's seeded stream [`Stream::FastSyncData`].
    rng: rand_chacha::ChaCha20Rng,
    /// Thermal noise: the synthesiser's generator; its in-phase part is the real noise.
    noise: ThermalNoise,
    symbols: Vec<f64>,
    noise_i: Vec<f32>,
    noise_q: Vec<f32>,
}

impl<'a> SignalSource<'a> {
    pub fn new(spec: SignalSpec, code: &'a [i8], seed: u64) -> Self {
        Self {
            noise: ThermalNoise::new(seed, 0, spec.noise_sigma() as f32),
            spec,
            code,
            next: 0,
            rng: stream_rng(seed, Stream::FastSyncData, 0),
            symbols: Vec::new(),
            noise_i: Vec::new(),
            noise_q: Vec::new(),
        }
    }

    /// The data symbol (+/-1) in force at `t`.
    fn symbol(&mut self, t: f64) -> f64 {
        let k = (t / self.spec.symbol_s).floor().max(0.0) as usize;
        while self.symbols.len() <= k {
            let s = if self.rng.random::<bool>() { 1.0 } else { -1.0 };
            self.symbols.push(s);
        }
        self.symbols[k]
    }

    /// The next `n` samples, as complex samples with a zero imaginary part.
    pub fn block(&mut self, n: usize, out: &mut Vec<Complex32>) {
        out.clear();
        self.noise_i.clear();
        self.noise_i.resize(n, 0.0);
        self.noise_q.clear();
        self.noise_q.resize(n, 0.0);
        self.noise
            .add(self.next, &mut self.noise_i, &mut self.noise_q);
        let fs = self.spec.sample_rate_hz;
        for i in 0..n as u64 {
            let t = (self.next + i) as f64 / fs;
            let chip = self.spec.code_phase_chips(t).floor() as i64;
            let c = f64::from(self.code[chip.rem_euclid(self.code.len() as i64) as usize]);
            let d = self.symbol(t);
            let phase =
                std::f64::consts::TAU * self.spec.if_hz * t + self.spec.doppler_phase_rad(t);
            let x = d * c * phase.cos() + f64::from(self.noise_i[i as usize]);
            out.push(Complex32::new(x as f32, 0.0));
        }
        self.next += n as u64;
    }
}
