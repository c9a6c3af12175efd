//! Almanac content (D1 subframes 4/5, D2 subframe 5), derived from the constellation's
//! broadcast ephemerides.
//!
//! Choices (documented; the ICD leaves almanac generation to the control segment):
//! - Reference time: toa = the encoder's toe rounded down to a multiple of 2^12 s, in the
//!   toe's week (WNa = that week mod 256).
//! - Elements at toa from each satellite's ephemeris (the one with toe nearest to toa):
//!   M0 + n (toa - toe), the node and inclination carried to toa, and a semi-major axis
//!   chosen so that the almanac's Keplerian mean motion equals the ephemeris' corrected
//!   one (sqrt(mu/A^3) + Delta n) so the along-track drift matches. Harmonic corrections
//!   are dropped. GEO ephemerides, given in the tilted GEO frame, are rotated into the
//!   Earth-fixed frame at toa (the almanac uses the standard algorithm for every
//!   satellite); their almanac Omega_dot is 0.
//! - Inclination reference (§5.2.4): i = 0.30 semicircles + delta_i for MEO/IGSO and
//!   delta_i alone for GEO, the satellite type taken from the PRN (GEO: 1-5, 59-63).
//! - Clock: a0 = af0 + af1 dt + af2 dt^2, a1 = af1 + 2 af2 dt with dt = toa - toc.
//! - Only PRNs 1-30 have almanac pages (subframe 4 pages 1-24 and subframe 5 pages 1-6 of
//!   D1; subframe 5 pages 37-60 and 95-100 of D2). The ICD's extended almanac of PRNs
//!   31-63 (AmEpID/AmID, §5.2.4) is not broadcast: AmEpID = AmID = 00, which receivers
//!   read as "no extended almanac". A PRN without ephemeris, or whose almanac does not
//!   fit the fields, gets an all-zero page (sqrt(A) = 0: no almanac) and health
//!   [`HEA_UNAVAILABLE`].

use super::BdsNavError;
use super::quant::{Quantiser, p2, wrap_pi};
use super::reexpress::{GEO_TILT_RAD, euler_313, orientation, rot_x, rot_z};
use hifitime::Epoch;
use skyforge_orbits::constants::{GM_BDS, OMEGA_E_BDS};
use skyforge_orbits::ephemeris::{BroadcastEphemeris, OrbitClass, System};
use skyforge_orbits::time::bdt_week_sow;
use std::f64::consts::PI;

/// PRNs with almanac pages.
pub(super) const ALMANAC_PRNS: u8 = 30;
/// Health word of a healthy satellite (9 bits, §5.2.4).
pub(super) const HEA_HEALTHY: i64 = 0;
/// Health word of an unhealthy or absent satellite: MSB set ("satellite clock
/// unavailable"). The meaning of the other bits could not be confirmed for this build;
/// only this bit is used.
pub(super) const HEA_UNAVAILABLE: i64 = 0x100;
/// Spacing of toa (s).
pub(super) const TOA_LSB_S: f64 = 4096.0;
/// Reference inclination of MEO/IGSO almanacs: 0.30 semicircles.
const I_REF_MEO_RAD: f64 = 0.30 * PI;

/// Widths and scale factors of the almanac fields (§5.2.4, almanac parameters).
pub(super) mod alm {
    use super::{PI, p2};
    pub const SQRT_A: (usize, i32) = (24, -11);
    pub const A1: (usize, i32) = (11, -38);
    pub const A0: (usize, i32) = (11, -20);
    pub const E: (usize, i32) = (17, -21);
    /// delta_i: 16 bits of 2^-19 semicircles.
    pub const DELTA_I: (usize, i32) = (16, -19);
    /// Omega dot: 17 bits of 2^-38 semicircles/s.
    pub const OMEGA_DOT: (usize, i32) = (17, -38);
    /// Omega0, omega, M0: 24 bits of 2^-23 semicircles.
    pub const ANGLE_BITS: usize = 24;
    pub fn semicircles(n: i32) -> f64 {
        PI * p2(n)
    }
}

/// One almanac page's orbit and clock fields (integers in LSB units).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct AlmanacFields {
    pub sqrt_a: i64,
    pub a1: i64,
    pub a0: i64,
    pub omega0: i64,
    pub e: i64,
    pub delta_i: i64,
    pub omega_dot: i64,
    pub omega: i64,
    pub m0: i64,
}

/// The almanac the encoder broadcasts.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(super) struct Almanac {
    /// WNa (week mod 256).
    pub wna: i64,
    /// toa in units of 2^12 s.
    pub toa: i64,
    /// Almanac of PRN k + 1, if any.
    pub sats: [Option<AlmanacFields>; ALMANAC_PRNS as usize],
    /// Hea_i, 9 bits, of PRN k + 1.
    pub health: [i64; ALMANAC_PRNS as usize],
}

/// Whether a PRN is a GEO one (the PRN decides the D1/D2 format and the almanac
/// inclination reference).
pub(super) fn is_geo_prn(prn: u8) -> bool {
    prn <= 5 || prn >= 59
}

impl Almanac {
    /// The almanac at toa = `toe` rounded down to 2^12 s, from `set` (other systems and
    /// PRNs above 30 ignored).
    pub(super) fn build(set: &[BroadcastEphemeris], toe: Epoch) -> Self {
        let (week, toe_sow) = bdt_week_sow(toe);
        let toa_sow = TOA_LSB_S * (toe_sow / TOA_LSB_S).floor();
        let toa = toe + hifitime::Duration::from_seconds(toa_sow - toe_sow);
        let mut out = Self {
            wna: i64::from(week % 256),
            toa: (toa_sow / TOA_LSB_S) as i64,
            sats: [None; ALMANAC_PRNS as usize],
            health: [HEA_UNAVAILABLE; ALMANAC_PRNS as usize],
        };
        for prn in 1..=ALMANAC_PRNS {
            let nearest = set
                .iter()
                .filter(|e| e.sat.system == System::Beidou && e.sat.prn == prn)
                .min_by(|a, b| {
                    let da = (a.toe - toa).to_seconds().abs();
                    let db = (b.toe - toa).to_seconds().abs();
                    da.total_cmp(&db)
                });
            let k = usize::from(prn - 1);
            if let Some(fields) = nearest.and_then(|e| fields_at(e, toa, toa_sow).ok()) {
                out.sats[k] = Some(fields);
                if nearest.is_some_and(|e| e.health == 0) {
                    out.health[k] = HEA_HEALTHY;
                }
            }
        }
        out
    }
}

/// Almanac fields of `eph` at `toa` (see the module notes).
fn fields_at(
    eph: &BroadcastEphemeris,
    toa: Epoch,
    toa_sow: f64,
) -> Result<AlmanacFields, BdsNavError> {
    let dt = (toa - eph.toe).to_seconds();
    let toe_sow = bdt_week_sow(eph.toe).1;
    let n_rad_s = eph.orbit.mean_motion_rad_s(GM_BDS);
    let sqrt_a_alm = (GM_BDS / (n_rad_s * n_rad_s)).cbrt().sqrt();
    let (node_ecef, incl, argp, omega_dot) = match eph.class {
        OrbitClass::Standard => (
            eph.orbit.omega0 + (eph.orbit.omega_dot - OMEGA_E_BDS) * dt - OMEGA_E_BDS * toe_sow,
            eph.orbit.i0 + eph.orbit.idot * dt,
            eph.orbit.omega,
            eph.orbit.omega_dot,
        ),
        OrbitClass::BeidouGeo => {
            let r_geo = orientation(
                eph.orbit.omega0 - OMEGA_E_BDS * toe_sow + eph.orbit.omega_dot * dt,
                eph.orbit.i0 + eph.orbit.idot * dt,
                eph.orbit.omega,
            );
            let q = rot_z(-OMEGA_E_BDS * dt) * rot_x(GEO_TILT_RAD);
            let (node, incl, argp) = euler_313(&(q * r_geo));
            (node, incl, argp, 0.0)
        }
    };
    let i_ref = if is_geo_prn(eph.sat.prn) {
        0.0
    } else {
        I_REF_MEO_RAD
    };
    let dtc = (toa - eph.toc).to_seconds();
    let sat = eph.sat.to_string();
    let q = Quantiser { sat: &sat };
    let fixed =
        |field, value, (bits, exp): (usize, i32), signed| q.q(field, value, p2(exp), bits, signed);
    let semicircles = |field, value, (bits, exp): (usize, i32)| {
        q.q(field, value, alm::semicircles(exp), bits, true)
    };
    Ok(AlmanacFields {
        sqrt_a: fixed("almanac sqrt(A)", sqrt_a_alm, alm::SQRT_A, false)?,
        a1: fixed(
            "almanac a1",
            eph.clock.af1 + 2.0 * eph.clock.af2 * dtc,
            alm::A1,
            true,
        )?,
        a0: fixed(
            "almanac a0",
            eph.clock.af0 + (eph.clock.af1 + eph.clock.af2 * dtc) * dtc,
            alm::A0,
            true,
        )?,
        omega0: q.angle(
            "almanac Omega0",
            node_ecef + OMEGA_E_BDS * toa_sow,
            alm::ANGLE_BITS,
        )?,
        e: fixed("almanac e", eph.orbit.e, alm::E, false)?,
        delta_i: semicircles("almanac delta_i", wrap_pi(incl - i_ref), alm::DELTA_I)?,
        omega_dot: semicircles("almanac Omega dot", omega_dot, alm::OMEGA_DOT)?,
        omega: q.angle("almanac omega", argp, alm::ANGLE_BITS)?,
        m0: q.angle("almanac M0", eph.orbit.m0 + n_rad_s * dt, alm::ANGLE_BITS)?,
    })
}
