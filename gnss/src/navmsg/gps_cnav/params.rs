//! What messages 10, 30 and 33 carry besides the orbit, clock and TGD (IS-GPS-705J
//! §20.3.3.1.1, §20.3.3.3.1, §20.3.3.6).

use super::quant::{self as q, Field};
use crate::navmsg::gps_lnav::{IonoParams, UtcParams};

/// What messages 10, 30 and 33 carry besides the orbit, clock and TGD, in SI units and
/// the integers the ICD defines. Default: accuracy indices 0, ISCs 0, Klobuchar zero, UTC
/// A0 = A1 = A2 = 0 with 18 leap seconds and no event ([`Self::with_leap_seconds`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CnavParams {
    /// URA_ED index (-16..15), type 10.
    pub ura_ed_index: i8,
    /// URA_NED0 (-16..15), URA_NED1 and URA_NED2 (0..7) indices, clock block.
    pub ura_ned0_index: i8,
    pub ura_ned1_index: u8,
    pub ura_ned2_index: u8,
    /// Inter-signal corrections (s), type 30; `None` sends "not available".
    pub isc_l1ca_s: Option<f64>,
    pub isc_l2c_s: Option<f64>,
    pub isc_l5i5_s: Option<f64>,
    pub isc_l5q5_s: Option<f64>,
    /// Klobuchar coefficients, type 30.
    pub iono: IonoParams,
    /// GPS-UTC parameters, type 33 (full weeks; their 13 LSBs are sent).
    pub utc: UtcParams,
    /// A2 (s/s^2) of type 33, which LNAV lacks.
    pub utc_a2: f64,
}

impl Default for CnavParams {
    fn default() -> Self {
        Self::with_leap_seconds(18)
    }
}

impl CnavParams {
    /// The defaults with GPS - UTC = `leap_s` before and after an event that is not
    /// scheduled (WNLSF = 0, DN = 1).
    pub fn with_leap_seconds(leap_s: i32) -> Self {
        Self {
            ura_ed_index: 0,
            ura_ned0_index: 0,
            ura_ned1_index: 0,
            ura_ned2_index: 0,
            isc_l1ca_s: Some(0.0),
            isc_l2c_s: Some(0.0),
            isc_l5i5_s: Some(0.0),
            isc_l5q5_s: Some(0.0),
            iono: IonoParams::default(),
            utc: UtcParams {
                a0: 0.0,
                a1: 0.0,
                tot: 0,
                wnt: 0,
                dt_ls: leap_s,
                wn_lsf: 0,
                dn: 1,
                dt_lsf: leap_s,
            },
            utc_a2: 0.0,
        }
    }

    /// Each field with its value in the field's SI unit (ISCs apart).
    pub(super) fn values(&self) -> [(&'static Field, f64); 21] {
        let (i, u) = (&self.iono, &self.utc);
        [
            (&q::URA_ED, f64::from(self.ura_ed_index)),
            (&q::URA_NED0, f64::from(self.ura_ned0_index)),
            (&q::URA_NED1, f64::from(self.ura_ned1_index)),
            (&q::URA_NED2, f64::from(self.ura_ned2_index)),
            (&q::ALPHA[0], i.alpha[0]),
            (&q::ALPHA[1], i.alpha[1]),
            (&q::ALPHA[2], i.alpha[2]),
            (&q::ALPHA[3], i.alpha[3]),
            (&q::BETA[0], i.beta[0]),
            (&q::BETA[1], i.beta[1]),
            (&q::BETA[2], i.beta[2]),
            (&q::BETA[3], i.beta[3]),
            (&q::A0, u.a0),
            (&q::A1, u.a1),
            (&q::A2, self.utc_a2),
            (&q::DT_LS, f64::from(u.dt_ls)),
            (&q::TOT, f64::from(u.tot)),
            (&q::WN_OT, f64::from(u.wnt % 8192)),
            (&q::WN_LSF, f64::from(u.wn_lsf % 8192)),
            (&q::DN, f64::from(u.dn)),
            (&q::DT_LSF, f64::from(u.dt_lsf)),
        ]
    }

    /// The four ISC fields and their values.
    pub(super) fn iscs(&self) -> [(&'static Field, Option<f64>); 4] {
        [
            (&q::ISC_L1CA, self.isc_l1ca_s),
            (&q::ISC_L2C, self.isc_l2c_s),
            (&q::ISC_L5I5, self.isc_l5i5_s),
            (&q::ISC_L5Q5, self.isc_l5q5_s),
        ]
    }
}
