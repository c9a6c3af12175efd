//! Broadcast ephemeris parameters and the user algorithms: GPS LNAV (IS-GPS-200 table
//! 20-IV, relativistic clock correction, TGD) and BeiDou D1/D2 (BDS-SIS-ICD, MEO/IGSO and
//! the GEO transformation, BDT).

use super::sat_id::SatId;
use crate::Vec3;
use crate::time::TimeOrigin;
use hifitime::Epoch;

/// How the orbit is evaluated.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum OrbitClass {
    /// GPS, and BeiDou MEO/IGSO: the standard Keplerian user algorithm.
    Standard,
    /// BeiDou GEO: computed in an inertial-like frame, then rotated by -5 deg about X and
    /// by the Earth rotation since toe about Z (BDS-SIS-ICD 5.2.4.12).
    BeidouGeo,
}

/// One set of broadcast ephemeris and clock parameters, as the navigation message carries
/// them (SI units: m, rad, s, rad/s).
#[derive(Debug, Clone, PartialEq)]
pub struct BroadcastEphemeris {
    pub sat: SatId,
    pub class: OrbitClass,
    /// Reference time of ephemeris (in the system's own time scale).
    pub toe: Epoch,
    /// Reference time of clock.
    pub toc: Epoch,
    pub sqrt_a: f64,
    pub e: f64,
    pub i0: f64,
    pub omega0: f64,
    pub omega: f64,
    pub m0: f64,
    pub delta_n: f64,
    pub idot: f64,
    pub omega_dot: f64,
    pub cuc: f64,
    pub cus: f64,
    pub crc: f64,
    pub crs: f64,
    pub cic: f64,
    pub cis: f64,
    pub af0: f64,
    pub af1: f64,
    pub af2: f64,
    /// Group delay for the signal SkyForge uses (GPS TGD for L1 C/A; BeiDou TGD1 for B1I).
    pub tgd_s: f64,
    /// Issue of data (IODE for GPS, AODE for BeiDou).
    pub iode: u32,
    /// Issue of data, clock (IODC for GPS, AODC for BeiDou).
    pub iodc: u32,
    /// 0 = healthy.
    pub health: u32,
    /// Fit interval (s) around toe within which the set may be used.
    pub fit_interval_s: f64,
}

/// An ephemeris bound to a scenario time origin: evaluates at `t_s` seconds since the start.
#[derive(Debug, Clone, PartialEq)]
pub struct BoundEphemeris {
    pub eph: BroadcastEphemeris,
    /// toe, seconds since the scenario start.
    pub toe_s: f64,
    /// toc, seconds since the scenario start.
    pub toc_s: f64,
}

impl BroadcastEphemeris {
    /// Bind to a scenario origin.
    pub fn bind(&self, origin: &TimeOrigin) -> BoundEphemeris {
        todo!("{origin:?}")
    }
}

impl BoundEphemeris {
    /// Antenna phase-centre position (ECEF at the same instant, m) at `t_s`.
    pub fn position_ecef(&self, t_s: f64) -> Vec3 {
        todo!("{t_s}")
    }
    /// Position and velocity (ECEF, m and m/s) at `t_s`.
    pub fn state_ecef(&self, t_s: f64) -> (Vec3, Vec3) {
        todo!("{t_s}")
    }
    /// Satellite clock offset (s) at `t_s`: polynomial plus relativistic correction, without TGD.
    pub fn clock_offset_s(&self, t_s: f64) -> f64 {
        todo!("{t_s}")
    }
    /// Satellite clock drift (s/s) at `t_s`, including the relativistic term's derivative.
    pub fn clock_drift(&self, t_s: f64) -> f64 {
        todo!("{t_s}")
    }
}
