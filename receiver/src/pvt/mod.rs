//! Single-point positioning: least-squares position, velocity and time from pseudoranges
//! (and Doppler) of GPS L1 C/A, BeiDou B1I or both, with broadcast ephemerides.
//!
//! Per satellite: transmit time from the pseudorange, satellite clock with the relativistic
//! term and the group delay of the signal (GPS TGD for L1 C/A, BeiDou TGD1 for B1I;
//! IS-GPS-200 20.3.3.3.3.2, BDS-SIS-ICD-B1I 5.2.4.10), the Earth's rotation during the
//! signal's flight (Sagnac), the broadcast Klobuchar ionosphere and the standard
//! troposphere for a receiver inside the atmosphere, elevation weighting, and a receiver
//! clock per system (the BeiDou one as GPS clock + inter-system bias when both fly).
//! After the fix a residual test ([`raim`]) excludes one faulty satellite.

mod geometry;
pub mod nmea;
pub mod raim;
pub(crate) mod solve;
mod velocity;

pub use geometry::SatView;
pub use solve::solve;
pub use velocity::solve_velocity;

use skyforge_orbits::Vec3;
use skyforge_orbits::ephemeris::SatId;
use skyforge_orbits::ephemeris::klobuchar::KlobucharCoeffs;

/// The satellite of `eph` for a receiver at `r_rx_m` at time `t_s` (s since the ephemeris
/// origin), before any measurement: the flight time from the geometry alone (a typical
/// pseudorange of the range itself).
pub fn predicted_view(
    eph: &skyforge_orbits::ephemeris::BoundEphemeris,
    t_s: f64,
    r_rx_m: &Vec3,
) -> SatView {
    // Two passes: the first gives the range, the second the view at that flight time.
    let first = geometry::sat_view(eph, t_s, 2.0e7, r_rx_m);
    geometry::sat_view(eph, t_s, first.range_m, r_rx_m)
}

/// One pseudorange (and optionally Doppler) of one satellite at the receive epoch.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Measurement {
    pub sat: SatId,
    /// Pseudorange (m).
    pub pseudorange_m: f64,
    /// Doppler (Hz, RINEX sign: positive when approaching), if measured.
    pub doppler_hz: Option<f64>,
    /// Carrier frequency of the signal (Hz), for the Doppler.
    pub carrier_hz: f64,
}

/// What the solver applies.
#[derive(Debug, Clone, PartialEq)]
pub struct PvtConfig {
    /// Satellites below this elevation are not used (rad); applied once a position exists.
    pub elevation_mask_rad: f64,
    /// Broadcast ionosphere coefficients (GPS, BeiDou); applied for receivers below
    /// [`IONOSPHERE_USER_CEILING_M`] when present. A BeiDou satellite without BeiDou
    /// coefficients uses the GPS model scaled to its frequency, and vice versa.
    pub iono_gps: Option<KlobucharCoeffs>,
    pub iono_bds: Option<KlobucharCoeffs>,
    /// Apply the standard troposphere (for receivers inside it).
    pub troposphere: bool,
    /// Elevation weighting sigma^2 = a^2 + b^2 / sin^2(el) (m): a, b.
    pub sigma_a_m: f64,
    pub sigma_b_m: f64,
    /// Probability of false alarm of the residual test (0 disables it).
    pub raim_pfa: f64,
}

impl Default for PvtConfig {
    /// 10 deg mask, no ionosphere coefficients, troposphere on, a = b = 0.3 m (the common
    /// elevation-dependent code-noise model, also RTKLIB's default), residual test at 1e-3.
    fn default() -> Self {
        Self {
            elevation_mask_rad: 10f64.to_radians(),
            iono_gps: None,
            iono_bds: None,
            troposphere: true,
            sigma_a_m: 0.3,
            sigma_b_m: 0.3,
            raim_pfa: 1e-3,
        }
    }
}

/// A receiver above this height is above most of the ionosphere: the ground model is not
/// applied (m). (Yuan 2000 section 5.4.1: 60 % of the delay lies below 350 km.)
pub const IONOSPHERE_USER_CEILING_M: f64 = 100e3;

/// Dilutions of precision (unweighted geometry; H and V in the local NED frame).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Dop {
    pub gdop: f64,
    pub pdop: f64,
    pub hdop: f64,
    pub vdop: f64,
    pub tdop: f64,
}

/// A position and time fix.
#[derive(Debug, Clone, PartialEq)]
pub struct Fix {
    /// Receive time the fix refers to (s since the ephemeris origin, GPST), corrected for
    /// the receiver clock: `t_rx - clock_bias_m / c`.
    pub t_s: f64,
    pub r_ecef_m: Vec3,
    /// c x receiver clock offset against GPST (m); for a BeiDou-only fix, against BDT+14 s
    /// i.e. the same GPST-aligned scale the ephemerides use.
    pub clock_bias_m: f64,
    /// c x (BeiDou clock - GPS clock) (m) when both systems are in the fix.
    pub inter_system_bias_m: Option<f64>,
    pub dop: Dop,
    /// Satellites in the fix, with their post-fit residuals (m) and elevations (rad).
    pub used: Vec<(SatId, f64, f64)>,
    /// Satellites the residual test excluded.
    pub excluded: Vec<SatId>,
    /// Sum of squared weighted residuals and its degrees of freedom.
    pub chi2: f64,
    pub dof: usize,
}

/// A velocity fix.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct VelocityFix {
    pub v_ecef_mps: Vec3,
    /// c x receiver clock drift (m/s).
    pub clock_drift_mps: f64,
}

/// Why no fix.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum PvtError {
    #[error("{have} usable satellites, {need} needed (unknowns: position and {clocks} clock(s))")]
    TooFewSatellites {
        have: usize,
        need: usize,
        clocks: usize,
    },
    #[error("no ephemeris for {0} at the receive time")]
    NoEphemeris(SatId),
    #[error("the least-squares iteration did not converge (last step {step_m:.3} m)")]
    NoConvergence { step_m: f64 },
    #[error("singular geometry")]
    Singular,
}
