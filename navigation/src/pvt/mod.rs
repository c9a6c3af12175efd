//! Single-point positioning: least-squares position, velocity and time from pseudoranges
//! (and Doppler) of GPS L1 C/A, BeiDou B1I or both, with broadcast ephemerides.
//!
//! Per satellite: transmit time from the pseudorange, satellite clock with the relativistic
//! term and the group delay of the signal (GPS TGD for L1 C/A, BeiDou TGD1 for B1I;
//! IS-GPS-200 20.3.3.3.3.2, BDS-SIS-ICD-B1I 5.2.4.10), the Earth's rotation during the
//! signal's flight (Sagnac), the broadcast Klobuchar ionosphere and the standard
//! troposphere for a receiver inside the atmosphere, elevation weighting, and a receiver
//! clock per system (the BeiDou one as GPS clock + inter-system bias when both fly).
//! After the fix a residual test ([`raim`]) detects a fault and excludes the satellite with
//! the largest normalised residual ([`exclusion`]), and the fix carries its protection
//! levels and integrity verdict ([`protection`], [`Protection`]).

pub(crate) mod exclusion;
mod geometry;
pub(crate) mod nmea;
pub(crate) mod protection;
pub(crate) mod raim;
mod ranging;
mod smoothing;
pub(crate) mod solve;
#[cfg(test)]
mod test_geometry;
mod velocity;

pub use nmea::{gga, gsa, rmc};

pub(crate) use geometry::local_frame;
pub use geometry::{FromEphemeris, NearAntenna, Recorded, SatView, Satellites, Transmitted};
pub use raim::{chi2_survival, detection_parameters};
pub use ranging::IonosphereCorrection;
pub(crate) use ranging::{Ranging, per_satellite};
pub use smoothing::{CarrierSmoother, CodeAndCarrier, JUMP_SIGMAS, SmoothingConfig};
pub(crate) use solve::ranging_delay_beyond_tgd_s;
pub use solve::{CodeResidual, code_residuals, solve, solve_with};
pub use velocity::{records_velocity, solve_velocity};

use skyforge_gnss::signal::Signal;
use skyforge_orbits::Vec3;
use skyforge_orbits::ephemeris::KlobucharCoeffs;
use skyforge_orbits::ephemeris::SatId;

/// The satellite of `eph` for a receiver at `r_rx_m` at time `t_s` (s since the ephemeris
/// origin), before any measurement: the flight time from the geometry alone (a typical
/// pseudorange of the range itself).
pub fn predicted_view(
    eph: &skyforge_orbits::ephemeris::BoundEphemeris,
    t_s: f64,
    r_rx_m: &Vec3,
) -> SatView {
    ViewPoint::new(*r_rx_m).predict(eph, t_s).view
}

/// A receiver place from which several satellites are predicted: its local frame (for
/// azimuth and elevation) is computed once, not per satellite.
#[derive(Debug, Clone, Copy)]
pub struct ViewPoint {
    r_rx_m: Vec3,
    frame: Option<skyforge_orbits::Mat3>,
}

/// A predicted satellite: its state at transmit time and the view from the receiver.
#[derive(Debug, Clone, Copy)]
pub struct Predicted {
    pub transmitted: Transmitted,
    pub view: SatView,
}

impl ViewPoint {
    /// The place `r_rx_m` (ECEF, m), with its local frame when it is a position.
    pub fn new(r_rx_m: Vec3) -> Self {
        Self {
            r_rx_m,
            frame: geometry::local_frame(&r_rx_m),
        }
    }

    /// The place `r_rx_m` without angles (views carry no azimuth and elevation).
    pub fn without_angles(r_rx_m: Vec3) -> Self {
        Self {
            r_rx_m,
            frame: None,
        }
    }

    /// The satellite of `eph` at time `t_s`, before any measurement. Two passes: the first
    /// gives the range, the second the view at that flight time.
    pub fn predict(&self, eph: &skyforge_orbits::ephemeris::BoundEphemeris, t_s: f64) -> Predicted {
        let first = Transmitted::of(eph, t_s, 2.0e7).seen_from(&self.r_rx_m, None);
        let transmitted = Transmitted::of(eph, t_s, first.range_m);
        Predicted {
            transmitted,
            view: self.see(&transmitted),
        }
    }

    /// The view of a satellite already at its transmit time.
    pub fn see(&self, transmitted: &Transmitted) -> SatView {
        transmitted.seen_from(&self.r_rx_m, self.frame.as_ref())
    }
}

/// One pseudorange (and optionally Doppler) of one satellite on one signal at the receive
/// epoch; a satellite may have one per signal ([`IonosphereCorrection`] says how the solver
/// uses them).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Measurement {
    pub sat: SatId,
    /// Pseudorange (m).
    pub pseudorange_m: f64,
    /// Doppler (Hz, RINEX sign: positive when approaching), if measured.
    pub doppler_hz: Option<f64>,
    /// The signal measured: its carrier for the Doppler and the ionosphere, its broadcast
    /// group delay for the satellite clock.
    pub signal: Signal,
}

impl Measurement {
    /// The measurement of a record that has a pseudorange.
    pub fn of_record(r: &skyforge_gnss::observation::ObsRecord) -> Option<Self> {
        Some(Self {
            sat: r.sat,
            pseudorange_m: r.pseudorange_m?,
            doppler_hz: r.doppler_hz,
            signal: r.signal,
        })
    }

    /// The measurements of every record of `records` that has a pseudorange.
    pub fn of_records(records: &[skyforge_gnss::observation::ObsRecord]) -> Vec<Self> {
        records.iter().filter_map(Self::of_record).collect()
    }
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
    /// The broadcast model on one signal per satellite, or the ionosphere-free combination
    /// of two.
    pub ionosphere: IonosphereCorrection,
    /// Apply the standard troposphere (for receivers inside it).
    pub troposphere: bool,
    /// Elevation weighting sigma^2 = a^2 + b^2 / sin^2(el) (m): a, b.
    pub sigma_a_m: f64,
    pub sigma_b_m: f64,
    /// Probability of false alarm of the residual test (0 disables it and the protection
    /// levels).
    pub raim_pfa: f64,
    /// Probability of missed detection the protection levels are computed for (0 disables
    /// them): Yuan 2000 table 5-1's minimum detection probability 0.999 gives 1e-3.
    pub raim_pmd: f64,
    /// Horizontal alarm limit (m): RAIM is available for a fix whose HPL does not exceed
    /// it. Default: Yuan 2000 table 5-1's non-precision approach, 555.96 m (0.3 NM).
    pub raim_hal_m: f64,
    /// Vertical alarm limit (m), if the phase of flight has one (table 5-1 has none).
    pub raim_val_m: Option<f64>,
    /// Carrier-smoothed code before the fix ([`CarrierSmoother`], the book's eqs.
    /// 5-60..5-64), applied by the receiver's PVT stage; `None`: raw code.
    pub carrier_smoothing: Option<SmoothingConfig>,
}

impl Default for PvtConfig {
    /// 10 deg mask, no ionosphere coefficients, troposphere on, a = b = 0.3 m (the common
    /// elevation-dependent code-noise model, also RTKLIB's default), residual test at 1e-3,
    /// protection levels at P_md = 1e-3 against the 555.96 m non-precision-approach limit.
    fn default() -> Self {
        Self {
            elevation_mask_rad: 10f64.to_radians(),
            iono_gps: None,
            iono_bds: None,
            ionosphere: IonosphereCorrection::Broadcast,
            troposphere: true,
            sigma_a_m: 0.3,
            sigma_b_m: 0.3,
            raim_pfa: 1e-3,
            raim_pmd: 1e-3,
            raim_hal_m: 555.96,
            raim_val_m: None,
            carrier_smoothing: None,
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
    /// c x receiver clock offset against GPST (m); for a fix without GPS, against the
    /// first system's time (BDT+14 s, GST) on the GPST-aligned scale the ephemerides use.
    pub clock_bias_m: f64,
    /// c x (BeiDou clock - GPS clock) (m) when GPS and BeiDou alone are in the fix (a
    /// Galileo clock is estimated, not reported yet).
    pub inter_system_bias_m: Option<f64>,
    pub dop: Dop,
    /// Satellites in the fix, with their post-fit residuals (m) and elevations (rad).
    pub used: Vec<(SatId, f64, f64)>,
    /// Satellites the residual test excluded.
    pub excluded: Vec<SatId>,
    /// Sum of squared weighted residuals and its degrees of freedom.
    pub chi2: f64,
    pub dof: usize,
    /// Protection levels and the integrity verdict of the residual test; `None` when the
    /// test is off (`raim_pfa` or `raim_pmd` 0) or has fewer than two degrees of freedom
    /// (RAIM unavailable).
    pub protection: Option<Protection>,
}

/// What the residual test says of one fix.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum IntegrityStatus {
    /// The test passed and HPL (and VPL, with a vertical limit) is within the alarm limit.
    Available,
    /// The test passed but the protection level exceeds the alarm limit: RAIM cannot
    /// protect this geometry.
    Unavailable,
    /// The test fired on all satellites and the fix without the excluded one (the largest
    /// normalised residual, [`exclusion`]) passes it (fault detection and exclusion).
    Excluded,
    /// The test fired and no exclusion made the fix consistent: do not use.
    Alarm,
}

/// Protection levels of a fix (of the satellites finally used) and the test's verdict.
#[derive(Debug, Clone, PartialEq)]
pub struct Protection {
    /// Horizontal and vertical protection levels (m): Yuan 2000 eqs. 5-10, 5-12 by the
    /// slope method ([`protection`]).
    pub hpl_m: f64,
    pub vpl_m: f64,
    /// Threshold of the test (chi-square (1 - pfa) quantile, eq. 5-9 inverted) and the
    /// noncentrality detected with probability 1 - P_md at it (eq. 5-11).
    pub threshold: f64,
    pub lambda_det: f64,
    /// Horizontal and vertical slope (m) of every used satellite, in [`Fix::used`] order.
    pub slopes: Vec<protection::Slope>,
    /// The test fired on the fix with every satellite (a detection).
    pub alarm: bool,
    /// Statistic and position of the fix with every satellite (equal to [`Fix::chi2`] and
    /// [`Fix::r_ecef_m`] without exclusion).
    pub chi2_all: f64,
    pub r_all_ecef_m: Vec3,
    pub status: IntegrityStatus,
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
