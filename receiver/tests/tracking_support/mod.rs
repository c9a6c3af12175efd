//! Test signals for the tracking tests: one satellite's complex baseband (or IF) signal
//! with a polynomial Doppler, data bits (and the data secondary code: BeiDou D1's NH, L5's
//! NH10, E5a-I's CS20), for GPS L5 and Galileo E5a the pilot in quadrature (+90 deg, half
//! the power, its secondary code), for Galileo E1 the CBOC(6,1,1/11) sum of E1-B and
//! E1-C in phase (codes from made-up tables), for BeiDou B1C the QMBOC(6,1,4/33) of data
//! and pilot (BDS-SIS-ICD-B1C-1.0 §4.2.2), optional phase jump and outage, in complex white
//! Gaussian noise; plus its exact truth. Code periods count from a bit edge that is also
//! a start of the pilot's secondary code.
//! Shared by several test binaries, each using part of it.
#![allow(dead_code)]

use num_complex::Complex;
use rand::SeedableRng;
use rand_distr::{Distribution, StandardNormal};
use skyforge_gnss::codes::E1Codes;
use skyforge_gnss::signal::{PilotCodes, Signal};
use skyforge_gnss::subcarrier::{CBOC_SUBCHIPS, b1c_qmboc, e1_cboc};
use skyforge_receiver::replica::SignalCodes;
use skyforge_receiver::tracking::Handover;

/// One satellite signal and its truth.
#[derive(Debug, Clone)]
pub struct TestSignal {
    pub signal: Signal,
    pub prn: u8,
    pub fs_hz: f64,
    pub if_hz: f64,
    pub cn0_dbhz: f64,
    /// Doppler at t = 0 (Hz), its rate (Hz/s) and acceleration (Hz/s^2).
    pub doppler_hz: f64,
    pub doppler_rate_hzps: f64,
    pub doppler_accel_hzps2: f64,
    /// Carrier phase at t = 0 (cycles).
    pub phase0_cycles: f64,
    /// Code phase at t = 0 (chips since an arbitrary bit edge).
    pub code0_chips: f64,
    /// Carrier phase jump: (first sample, cycles).
    pub phase_jump: Option<(u64, f64)>,
    /// No signal in [start, end) samples.
    pub outage: Option<(u64, u64)>,
    pub seed: u64,
    /// The PRN's codes when not the signal's own (Galileo E1's from made-up tables).
    pub codes: Option<SignalCodes>,
}

/// Made-up Galileo E1 tables (pseudo-random chips, not the ICD's) written to a temporary
/// directory and read back unchecked.
pub fn made_up_e1_codes() -> E1Codes {
    let dir = tempfile::tempdir().expect("a temporary directory");
    let mut x: u32 = 12345;
    for name in ["galileo_e1b.txt", "galileo_e1c.txt"] {
        let mut text = String::new();
        for n in 1..=50 {
            let digits: String = (0..1023)
                .map(|_| {
                    x = x.wrapping_mul(1_103_515_245).wrapping_add(12345);
                    char::from_digit((x >> 16) & 15, 16).expect("a hexadecimal digit")
                })
                .collect();
            text.push_str(&format!("{n} {digits}\n"));
        }
        std::fs::write(dir.path().join(name), text).expect("write a made-up E1 table");
    }
    E1Codes::from_dir(dir.path(), false).expect("made-up tables")
}

impl TestSignal {
    /// A GPS C/A signal of PRN 7 at 4.092 Msps, 45 dB-Hz, Doppler 1.5 kHz + 0.5 Hz/s.
    pub fn gps_static() -> Self {
        Self {
            signal: Signal::GpsL1Ca,
            prn: 7,
            fs_hz: 4.092e6,
            if_hz: 0.0,
            cn0_dbhz: 45.0,
            doppler_hz: 1500.0,
            doppler_rate_hzps: 0.5,
            doppler_accel_hzps2: 0.0,
            phase0_cycles: 0.3,
            code0_chips: 123_456.7,
            phase_jump: None,
            outage: None,
            seed: 1,
            codes: None,
        }
    }

    /// The data code and the pilot's codes (if any) of this signal's PRN.
    pub fn signal_codes(&self) -> (Vec<i8>, Option<PilotCodes>) {
        match &self.codes {
            Some(c) => (c.data.clone(), c.pilot.clone()),
            None => (
                self.signal.code(self.prn).expect("valid PRN"),
                self.signal.pilot(self.prn).ok(),
            ),
        }
    }

    /// Time of sample `s` (s).
    pub fn time(&self, s: u64) -> f64 {
        s as f64 / self.fs_hz
    }

    /// Doppler at sample `s` (Hz).
    pub fn doppler_at(&self, s: u64) -> f64 {
        let t = self.time(s);
        self.doppler_hz + self.doppler_rate_hzps * t + 0.5 * self.doppler_accel_hzps2 * t * t
    }

    /// Integral of the Doppler from 0 to sample `s` (cycles).
    pub fn doppler_phase(&self, s: u64) -> f64 {
        let t = self.time(s);
        self.doppler_hz * t
            + self.doppler_rate_hzps * t * t / 2.0
            + self.doppler_accel_hzps2 * t * t * t / 6.0
    }

    /// Carrier phase of the signal at sample `s` (cycles, without the IF).
    pub fn carrier_phase(&self, s: u64) -> f64 {
        let jump = match self.phase_jump {
            Some((at, cycles)) if s >= at => cycles,
            _ => 0.0,
        };
        self.phase0_cycles + self.doppler_phase(s) + jump
    }

    /// Code phase at sample `s` (chips since the reference bit edge).
    pub fn code_phase(&self, s: u64) -> f64 {
        self.code0_chips
            + self.signal.chip_rate_hz()
                * (self.time(s) + self.doppler_phase(s) / self.signal.carrier_hz())
    }

    /// Data bit (+1/-1) of bit number `b`.
    pub fn data_bit(&self, b: u64) -> f64 {
        let mut x = b.wrapping_mul(0x9E37_79B9_7F4A_7C15) ^ self.seed;
        x ^= x >> 29;
        x = x.wrapping_mul(0xBF58_476D_1CE4_E5B9);
        x ^= x >> 32;
        if x & 1 == 0 { 1.0 } else { -1.0 }
    }

    /// Periods per bit of this PRN.
    pub fn periods_per_bit(&self) -> u64 {
        u64::from(
            self.signal
                .data_modulation(self.prn)
                .expect("a synthesised signal")
                .periods_per_bit(),
        )
    }

    /// Number of the bit that sample `s` falls in.
    pub fn bit_index(&self, s: u64) -> u64 {
        let len = self.signal.code_length() as f64;
        (self.code_phase(s) / (len * self.periods_per_bit() as f64)).floor() as u64
    }

    /// Samples `[first, first + n)` of signal plus noise (noise sigma 1 per component).
    pub fn generate(&self, first: u64, n: usize) -> Vec<Complex<f32>> {
        let (code, pilot) = self.signal_codes();
        let code: Vec<f64> = code.iter().map(|&c| f64::from(c)).collect();
        let cboc = self.signal == Signal::GalE1;
        let qmboc = self.signal == Signal::BdsB1C;
        let len = code.len() as f64;
        let amplitude = (10f64.powf(self.cn0_dbhz / 10.0) * 2.0 / self.fs_hz).sqrt();
        let ppb = self.periods_per_bit();
        let data_secondary = self
            .signal
            .data_modulation(self.prn)
            .and_then(|m| m.data_secondary_code())
            .unwrap_or(&[1]);
        // With a pilot, each component carries half the power (E1's CBOC and B1C's QMBOC
        // levels carry theirs).
        let amplitude = if pilot.is_some() && !cboc && !qmboc {
            amplitude * std::f64::consts::FRAC_1_SQRT_2
        } else {
            amplitude
        };
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(self.seed ^ first.rotate_left(17));
        let mut out = Vec::with_capacity(n);
        const CHUNK: usize = 1024;
        let mut start = first;
        while start < first + n as u64 {
            let count = CHUNK.min((first + n as u64 - start) as usize);
            // Exact phases at the chunk start, rates at its middle (quadratic terms over
            // 1024 samples are below 1e-5 cycles and 1e-6 chips).
            let mid = start + count as u64 / 2;
            let f = (self.if_hz + self.doppler_at(mid)) / self.fs_hz;
            let dp = self.signal.chip_rate_hz()
                * (1.0 + self.doppler_at(mid) / self.signal.carrier_hz())
                / self.fs_hz;
            let p0 = self.code_phase(start);
            // The jump is applied in the loop at its sample.
            let jumped = match self.phase_jump {
                Some((at, cycles)) if at < start => cycles,
                _ => 0.0,
            };
            let phi0 = self.phase0_cycles
                + self.doppler_phase(start)
                + jumped
                + (start as f64 * self.if_hz / self.fs_hz).fract();
            let mut z = Complex::from_polar(1.0, std::f64::consts::TAU * phi0);
            let w = Complex::from_polar(1.0, std::f64::consts::TAU * f);
            for i in 0..count {
                let s = start + i as u64;
                let p = p0 + i as f64 * dp;
                let period = (p / len).floor();
                let chip_index = (p - period * len) as usize % code.len();
                let chip = code[chip_index];
                let period = period as u64;
                let sign = self.data_bit(period / ppb)
                    * chip
                    * f64::from(data_secondary[(period % data_secondary.len() as u64) as usize]);
                let baseband = match &pilot {
                    Some(pc) => {
                        let l = pc.secondary.len() as u64;
                        let q = f64::from(pc.primary[chip_index])
                            * f64::from(pc.secondary[(period % l) as usize]);
                        let sub =
                            ((p.fract() * CBOC_SUBCHIPS as f64) as usize).min(CBOC_SUBCHIPS - 1);
                        if cboc {
                            // E1-B and E1-C in phase on the CBOC sub-chip of the chip.
                            let level = e1_cboc(sign as i8, q as i8)[sub];
                            Complex::new(f64::from(level), 0.0)
                        } else if qmboc {
                            let (i, q) = b1c_qmboc(sign as i8, q as i8);
                            Complex::new(f64::from(i[sub]), f64::from(q[sub]))
                        } else {
                            Complex::new(sign, q)
                        }
                    }
                    None => Complex::new(sign, 0.0),
                };
                let jump = match self.phase_jump {
                    Some((at, cycles)) if s == at => {
                        Complex::from_polar(1.0, std::f64::consts::TAU * cycles)
                    }
                    _ => Complex::new(1.0, 0.0),
                };
                z *= jump;
                let on = !matches!(self.outage, Some((a, b)) if s >= a && s < b);
                let x = if on {
                    z * baseband * amplitude
                } else {
                    Complex::new(0.0, 0.0)
                };
                let nr: f64 = StandardNormal.sample(&mut rng);
                let ni: f64 = StandardNormal.sample(&mut rng);
                out.push(Complex::new((x.re + nr) as f32, (x.im + ni) as f32));
                z *= w;
            }
            start += count as u64;
        }
        out
    }

    /// The hand-over an acquisition would give at sample 0, off by `code_err_samples`
    /// and `doppler_err_hz`.
    pub fn handover(&self, code_err_samples: f64, doppler_err_hz: f64) -> Handover {
        let len = self.signal.code_length() as f64;
        let dp = self.signal.chip_rate_hz() * (1.0 + self.doppler_hz / self.signal.carrier_hz())
            / self.fs_hz;
        let to_epoch = (len - self.code0_chips.rem_euclid(len)).rem_euclid(len);
        Handover {
            signal: self.signal,
            prn: self.prn,
            sample_index: 0,
            code_phase_samples: to_epoch / dp + code_err_samples,
            doppler_hz: self.doppler_hz + doppler_err_hz,
            doppler_rate_hzps: 0.0,
        }
    }

    /// Code phase error (chips) of a receiver's prompt code phase at sample `s`, wrapped to
    /// half a code period.
    pub fn code_error(&self, s: u64, rx_code_phase_chips: f64) -> f64 {
        let len = self.signal.code_length() as f64;
        (rx_code_phase_chips - self.code_phase(s) + len / 2.0).rem_euclid(len) - len / 2.0
    }
}

/// Mean and standard deviation.
pub fn mean_std(x: &[f64]) -> (f64, f64) {
    let n = x.len() as f64;
    let mean = x.iter().sum::<f64>() / n;
    let var = x.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0);
    (mean, var.sqrt())
}

/// Carrier phase errors (cycles) of receiver phases against truth, with the constant
/// offset and the Costas half-cycle ambiguity removed (wrapped around the median).
pub fn phase_errors(diffs: &[f64]) -> Vec<f64> {
    let wrap = |d: f64| (d + 0.25).rem_euclid(0.5) - 0.25;
    let mut sorted: Vec<f64> = diffs.iter().map(|&d| wrap(d)).collect();
    sorted.sort_by(f64::total_cmp);
    let median = sorted[sorted.len() / 2];
    diffs.iter().map(|&d| wrap(d - median)).collect()
}
