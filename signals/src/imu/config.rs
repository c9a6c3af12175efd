//! `[imu]`: the IMU a platform carries, its sampling rate and its sensor errors.
//!
//! The errors come from a grade ([`ImuGrade`], the presets of [`super::grades`]) or, with
//! `grade = "custom"`, from `[imu.gyro]` and `[imu.accel]` written out in the units data
//! sheets use. Internally every error is SI ([`TriadErrors`]).

use serde::Deserialize;
use skyforge_orbits::check::{Allowed, Invalid, check_table};

/// Degrees per hour in rad/s.
pub const DEG_PER_H: f64 = std::f64::consts::PI / 180.0 / 3600.0;
/// Degrees per root hour (angle random walk) in rad/sqrt(s).
pub const DEG_PER_ROOT_H: f64 = std::f64::consts::PI / 180.0 / 60.0;
/// Metres per second per root hour (velocity random walk) in m/s/sqrt(s).
pub const MPS_PER_ROOT_H: f64 = 1.0 / 60.0;
/// A micro-g in m/s^2 (standard gravity, 9.80665 m/s^2).
pub const MICRO_G: f64 = 9.806_65e-6;

/// `[imu]`.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ImuConfig {
    /// Output rate (Hz): one increment every `1 / rate_hz` seconds.
    pub rate_hz: f64,
    /// The sensors' error grade.
    pub grade: ImuGrade,
    /// `[imu.gyro]`: the gyros of `grade = "custom"`.
    #[serde(default)]
    pub gyro: Option<GyroSpec>,
    /// `[imu.accel]`: the accelerometers of `grade = "custom"`.
    #[serde(default)]
    pub accel: Option<AccelSpec>,
    /// `[imu.vibration]`: a sinusoidal vibration the sensors feel and the platform's truth
    /// does not hold (an engine's or a hull's), off when absent.
    #[serde(default)]
    pub vibration: Option<VibrationConfig>,
}

/// The error grades (sources in [`super::grades`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum ImuGrade {
    /// No errors: the increments are the truth's (quantisation and vibration off too).
    Ideal,
    /// A ring-laser navigation-grade IMU (paper 001's).
    Navigation,
    /// A tactical-grade IMU (fibre-optic or good MEMS).
    Tactical,
    /// A consumer MEMS IMU (phones, drones, automotive).
    Consumer,
    /// The book's Table 3-1 SINS (the cascaded GPS/INS simulation).
    #[serde(rename = "book-table-3-1")]
    BookTable31,
    /// The errors of `[imu.gyro]` and `[imu.accel]`.
    Custom,
}

/// `[imu.gyro]`: a gyro triad's errors, per axis, in data-sheet units.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GyroSpec {
    /// Turn-on bias, 1 sigma (deg/h): drawn once per run.
    pub bias_deg_h: f64,
    /// Bias instability, 1 sigma of a first-order Gauss-Markov process (deg/h).
    pub instability_deg_h: f64,
    /// Its correlation time (s).
    pub instability_tau_s: f64,
    /// Angle random walk (deg/sqrt(h)).
    pub arw_deg_rth: f64,
    /// Scale-factor error, 1 sigma (ppm).
    pub scale_factor_ppm: f64,
    /// Misalignment and non-orthogonality, 1 sigma of each off-diagonal term (mrad).
    pub misalignment_mrad: f64,
    /// One count of the angle output (micro-rad); 0: not quantised.
    pub quantum_urad: f64,
}

/// `[imu.accel]`: an accelerometer triad's errors, per axis, in data-sheet units.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AccelSpec {
    /// Turn-on bias, 1 sigma (micro-g): drawn once per run.
    pub bias_ug: f64,
    /// Bias instability, 1 sigma of a first-order Gauss-Markov process (micro-g).
    pub instability_ug: f64,
    /// Its correlation time (s).
    pub instability_tau_s: f64,
    /// Velocity random walk (m/s/sqrt(h)).
    pub vrw_mps_rth: f64,
    /// Scale-factor error, 1 sigma (ppm).
    pub scale_factor_ppm: f64,
    /// Misalignment and non-orthogonality, 1 sigma of each off-diagonal term (mrad).
    pub misalignment_mrad: f64,
    /// One count of the velocity output (micro-m/s); 0: not quantised.
    pub quantum_umps: f64,
}

/// `[imu.vibration]`: per body axis a sinusoid of the given amplitude at one frequency,
/// each axis with its own drawn phase.
#[derive(Debug, Clone, Copy, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct VibrationConfig {
    /// Frequency (Hz).
    pub frequency_hz: f64,
    /// Specific-force amplitude (m/s^2).
    pub accel_mps2: f64,
    /// Angular-rate amplitude (deg/s).
    pub gyro_dps: f64,
}

/// One sensor triad's errors in SI units (rad/s and rad for gyros, m/s^2 and m/s for
/// accelerometers), per axis, 1 sigma.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TriadErrors {
    /// Turn-on bias (rate units).
    pub bias: f64,
    /// Gauss-Markov bias instability (rate units) and its correlation time (s).
    pub instability: f64,
    pub instability_tau_s: f64,
    /// White rate noise density (rate units times sqrt(s)): the increment noise over
    /// `dt` is `density * sqrt(dt)`.
    pub density: f64,
    /// Scale-factor error (dimensionless).
    pub scale_factor: f64,
    /// Off-diagonal misalignment terms (rad).
    pub misalignment_rad: f64,
    /// One output count (increment units); 0: not quantised.
    pub quantum: f64,
}

impl TriadErrors {
    /// No errors.
    pub const NONE: Self = Self {
        bias: 0.0,
        instability: 0.0,
        instability_tau_s: 1.0,
        density: 0.0,
        scale_factor: 0.0,
        misalignment_rad: 0.0,
        quantum: 0.0,
    };
}

impl From<GyroSpec> for TriadErrors {
    fn from(g: GyroSpec) -> Self {
        Self {
            bias: g.bias_deg_h * DEG_PER_H,
            instability: g.instability_deg_h * DEG_PER_H,
            instability_tau_s: g.instability_tau_s,
            density: g.arw_deg_rth * DEG_PER_ROOT_H,
            scale_factor: g.scale_factor_ppm * 1e-6,
            misalignment_rad: g.misalignment_mrad * 1e-3,
            quantum: g.quantum_urad * 1e-6,
        }
    }
}

impl From<AccelSpec> for TriadErrors {
    fn from(a: AccelSpec) -> Self {
        Self {
            bias: a.bias_ug * MICRO_G,
            instability: a.instability_ug * MICRO_G,
            instability_tau_s: a.instability_tau_s,
            density: a.vrw_mps_rth * MPS_PER_ROOT_H,
            scale_factor: a.scale_factor_ppm * 1e-6,
            misalignment_rad: a.misalignment_mrad * 1e-3,
            quantum: a.quantum_umps * 1e-6,
        }
    }
}

/// IMU output rates: 1 Hz to 10 kHz.
pub const RATE_HZ: Allowed = Allowed::closed(1.0, 10_000.0, "Hz");
const NONNEG_DEG_H: Allowed = Allowed::closed(0.0, 36_000.0, "deg/h");
const TAU_S: Allowed = Allowed::above(0.0, 3.2e7, "s");
const ARW: Allowed = Allowed::closed(0.0, 100.0, "deg/sqrt(h)");
const BIAS_UG: Allowed = Allowed::closed(0.0, 1e6, "micro-g");
const VRW: Allowed = Allowed::closed(0.0, 100.0, "m/s/sqrt(h)");
const PPM: Allowed = Allowed::closed(0.0, 1e5, "ppm");
const MRAD: Allowed = Allowed::closed(0.0, 100.0, "mrad");
const QUANTUM: Allowed = Allowed::closed(0.0, 1e5, "micro-units");
const VIBRATION_HZ: Allowed = Allowed::above(0.0, 5_000.0, "Hz");
const VIBRATION_MPS2: Allowed = Allowed::closed(0.0, 1_000.0, "m/s^2");
const VIBRATION_DPS: Allowed = Allowed::closed(0.0, 1_000.0, "deg/s");

impl GyroSpec {
    fn check(&self) -> Result<(), Invalid> {
        check_table(&[
            ("bias_deg_h", self.bias_deg_h, NONNEG_DEG_H),
            ("instability_deg_h", self.instability_deg_h, NONNEG_DEG_H),
            ("instability_tau_s", self.instability_tau_s, TAU_S),
            ("arw_deg_rth", self.arw_deg_rth, ARW),
            ("scale_factor_ppm", self.scale_factor_ppm, PPM),
            ("misalignment_mrad", self.misalignment_mrad, MRAD),
            ("quantum_urad", self.quantum_urad, QUANTUM),
        ])
    }
}

impl AccelSpec {
    fn check(&self) -> Result<(), Invalid> {
        check_table(&[
            ("bias_ug", self.bias_ug, BIAS_UG),
            ("instability_ug", self.instability_ug, BIAS_UG),
            ("instability_tau_s", self.instability_tau_s, TAU_S),
            ("vrw_mps_rth", self.vrw_mps_rth, VRW),
            ("scale_factor_ppm", self.scale_factor_ppm, PPM),
            ("misalignment_mrad", self.misalignment_mrad, MRAD),
            ("quantum_umps", self.quantum_umps, QUANTUM),
        ])
    }
}

impl ImuConfig {
    /// An IMU of `grade` at `rate_hz`, without vibration.
    pub fn of_grade(grade: ImuGrade, rate_hz: f64) -> Self {
        Self {
            rate_hz,
            grade,
            gyro: None,
            accel: None,
            vibration: None,
        }
    }

    /// The rate inside [`RATE_HZ`]; `[imu.gyro]` and `[imu.accel]` given exactly for
    /// `grade = "custom"` and inside their bounds; the vibration inside its bounds and
    /// below the Nyquist frequency of the output rate.
    pub fn check(&self) -> Result<(), Invalid> {
        RATE_HZ.check("rate_hz", self.rate_hz)?;
        let custom = self.grade == ImuGrade::Custom;
        for (key, given) in [
            ("gyro", self.gyro.is_some()),
            ("accel", self.accel.is_some()),
        ] {
            if custom && !given {
                return Err(Invalid::new(
                    key,
                    "(missing)",
                    format!("grade = \"custom\" needs an [imu.{key}] table"),
                ));
            }
            if !custom && given {
                return Err(Invalid::new(
                    key,
                    "(a table)",
                    "only grade = \"custom\" takes sensor tables; the grades bring their own",
                ));
            }
        }
        if let Some(g) = &self.gyro {
            g.check().map_err(|e| e.within("gyro"))?;
        }
        if let Some(a) = &self.accel {
            a.check().map_err(|e| e.within("accel"))?;
        }
        if let Some(v) = &self.vibration {
            self.check_vibration(v).map_err(|e| e.within("vibration"))?;
        }
        Ok(())
    }

    fn check_vibration(&self, v: &VibrationConfig) -> Result<(), Invalid> {
        check_table(&[
            ("frequency_hz", v.frequency_hz, VIBRATION_HZ),
            ("accel_mps2", v.accel_mps2, VIBRATION_MPS2),
            ("gyro_dps", v.gyro_dps, VIBRATION_DPS),
        ])?;
        if v.frequency_hz >= self.rate_hz / 2.0 {
            return Err(Invalid::new(
                "frequency_hz",
                v.frequency_hz,
                format!(
                    "must lie below half the output rate ({} Hz): the increments would alias it",
                    self.rate_hz / 2.0
                ),
            ));
        }
        Ok(())
    }
}
