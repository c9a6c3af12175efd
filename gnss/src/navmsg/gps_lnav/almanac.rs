//! The almanac of subframes 4 and 5 (IS-GPS-200 20.3.3.5.1.2, table 20-VI), derived from
//! the broadcast ephemerides at a reference time toa.

use super::ephemeris::{check_gps, reexpress};
use super::scale::{self, Scale};
use super::words::DataWords;
use super::{GPS_PI, LnavError, NS_PER_S, WEEK_S, epoch_from_gps_ns, gps_ns, week_and_sow};
use hifitime::Epoch;
use skyforge_orbits::ephemeris::{
    BroadcastEphemeris, ClockParams, HarmonicCorrections, KeplerElements, OrbitClass, SatId, System,
};

/// Reference inclination of the almanac (semicircles): i = 0.30 + delta_i (table 20-VI).
const I_REF_SC: f64 = 0.30;
/// toa step (s): its LSB, 2^12 s.
const TOA_STEP_S: i64 = 4096;
/// Largest toa (s) in a week: 147 x 4096 = 602112 s (table 20-VI range).
const TOA_MAX_S: i64 = 602_112;
/// Validity given to the almanac when turned into an ephemeris: the six-day curve fits
/// of IS-GPS-200 20.3.3.5.1.2.
const ALMANAC_FIT_S: f64 = 6.0 * 86_400.0;
/// Six-bit page-25 health meaning "SV not available" (IS-GPS-200 20.3.3.5.1.3).
const HEALTH_NOT_AVAILABLE: u32 = 0b11_1111;

/// One almanac page: the ICD integers of table 20-VI.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Entry {
    e: i64,
    delta_i: i64,
    omega_dot: i64,
    sqrt_a: i64,
    omega0: i64,
    omega: i64,
    m0: i64,
    af0: i64,
    af1: i64,
    /// Six-bit health of subframe 1 / page 25.
    health6: u32,
}

impl Entry {
    /// Eight-bit almanac health: three NAV-data bits (table 20-VII: 000 all data OK, 111
    /// when the six-bit summary says some NAV data are bad) and the five signal bits.
    fn health8(&self) -> u32 {
        let nav = if self.health6 & 0b10_0000 != 0 {
            0b111
        } else {
            0
        };
        (nav << 5) | (self.health6 & 0b1_1111)
    }
}

/// The almanac every satellite broadcasts: PRN 1-32 at one reference time toa.
///
/// Each entry is the satellite's broadcast ephemeris whose toe is nearest toa,
/// re-expressed at toa (exactly, see `reexpress`) and quantised per table 20-VI. The
/// almanac model has no harmonic corrections, no delta n and no IDOT
/// (IS-GPS-200 20.3.3.5.2.1), so it departs from the ephemeris by the dropped harmonics
/// (up to a few hundred metres for real ephemerides) plus the delta n drift away from toa
/// (about 10 km per day for delta n = 4.5e-9 rad/s).
#[derive(Debug, Clone, PartialEq)]
pub struct Almanac {
    /// toa, whole GPS seconds since the GPS epoch.
    toa_gps_s: i64,
    entries: [Option<Entry>; 32],
}

impl Almanac {
    /// The almanac of the GPS satellites among `ephemerides` (other systems are
    /// skipped), at the toa on the 4096-s grid of the GPS week nearest `near`.
    pub fn from_ephemerides(
        ephemerides: &[BroadcastEphemeris],
        near: Epoch,
    ) -> Result<Self, LnavError> {
        let near_ns = gps_ns(near);
        if near_ns < 0 {
            return Err(LnavError::BeforeGpsEpoch {
                epoch: near.to_string(),
            });
        }
        let near_s = (near_ns / NS_PER_S) as i64;
        let (week, sow) = week_and_sow(near_s);
        let in_week = ((sow + TOA_STEP_S / 2) / TOA_STEP_S * TOA_STEP_S).min(TOA_MAX_S);
        let candidates = [week * WEEK_S + in_week, (week + 1) * WEEK_S];
        let toa_gps_s = if (candidates[0] - near_s).abs() <= (candidates[1] - near_s).abs() {
            candidates[0]
        } else {
            candidates[1]
        };
        let toa_ns = i128::from(toa_gps_s) * NS_PER_S;

        let mut nearest: [Option<&BroadcastEphemeris>; 32] = [None; 32];
        for eph in ephemerides {
            if eph.sat.system != System::Gps || !(1..=32).contains(&eph.sat.prn) {
                continue;
            }
            let slot = &mut nearest[usize::from(eph.sat.prn - 1)];
            let dist = |e: &BroadcastEphemeris| (gps_ns(e.toe) - toa_ns).abs();
            if slot.is_none_or(|best| dist(eph) < dist(best)) {
                *slot = Some(eph);
            }
        }
        let mut entries = [None; 32];
        for (entry, eph) in entries.iter_mut().zip(nearest) {
            if let Some(eph) = eph {
                *entry = Some(Self::entry(eph, toa_gps_s)?);
            }
        }
        Ok(Self { toa_gps_s, entries })
    }

    /// Quantise one satellite's ephemeris re-expressed at toa.
    fn entry(eph: &BroadcastEphemeris, toa_gps_s: i64) -> Result<Entry, LnavError> {
        let name = check_gps(eph.sat)?;
        let p = reexpress(eph, toa_gps_s, toa_gps_s);
        let q = |s: &Scale, v: f64| s.quantise(v, &name);
        let qa = |s: &Scale, v_rad: f64| s.quantise_angle(v_rad / GPS_PI, &name);
        if eph.health > 63 {
            return Err(LnavError::BadValue {
                what: format!("{name} health"),
                value: i64::from(eph.health),
                allowed: "6-bit SV health 0-63",
            });
        }
        Ok(Entry {
            e: q(&scale::ALM_E, p.orbit.e)?,
            delta_i: q(&scale::ALM_DELTA_I, p.orbit.i0 / GPS_PI - I_REF_SC)?,
            omega_dot: q(&scale::ALM_OMEGA_DOT, p.orbit.omega_dot / GPS_PI)?,
            sqrt_a: q(&scale::ALM_SQRT_A, p.orbit.sqrt_a)?,
            omega0: qa(&scale::ALM_OMEGA0, p.orbit.omega0)?,
            omega: qa(&scale::ALM_OMEGA, p.orbit.omega)?,
            m0: qa(&scale::ALM_M0, p.orbit.m0)?,
            af0: q(&scale::ALM_AF0, p.clock.af0)?,
            af1: q(&scale::ALM_AF1, p.clock.af1)?,
            health6: eph.health,
        })
    }

    /// Full GPS week of toa (WNa; its 8 LSBs are broadcast).
    pub fn week(&self) -> u32 {
        week_and_sow(self.toa_gps_s).0 as u32
    }

    /// toa, seconds of week [`Almanac::week`] (a multiple of 4096 s).
    pub fn toa_s(&self) -> u32 {
        week_and_sow(self.toa_gps_s).1 as u32
    }

    /// The toa epoch (GPST).
    pub fn toa(&self) -> Epoch {
        epoch_from_gps_ns(i128::from(self.toa_gps_s) * NS_PER_S)
    }

    /// PRNs that have an almanac page (the others get a dummy page and health 111111).
    pub fn prns(&self) -> Vec<u8> {
        (1u8..=32)
            .filter(|&p| self.entries[usize::from(p - 1)].is_some())
            .collect()
    }

    /// The almanac of `prn` as a receiver decodes it, written as an ephemeris (SI units,
    /// toe = toc = toa, no harmonics, delta n = IDOT = af2 = 0), so the user algorithm of
    /// the orbits crate evaluates it (IS-GPS-200 20.3.3.5.2.1).
    pub fn ephemeris(&self, prn: u8) -> Option<BroadcastEphemeris> {
        let entry = self
            .entries
            .get(usize::from(prn).checked_sub(1)?)?
            .as_ref()?;
        let toa = self.toa();
        let rad = |s: &Scale, n: i64| s.value(n) * GPS_PI;
        let orbit = KeplerElements {
            sqrt_a: scale::ALM_SQRT_A.value(entry.sqrt_a),
            e: scale::ALM_E.value(entry.e),
            i0: (I_REF_SC + scale::ALM_DELTA_I.value(entry.delta_i)) * GPS_PI,
            omega0: rad(&scale::ALM_OMEGA0, entry.omega0),
            omega: rad(&scale::ALM_OMEGA, entry.omega),
            m0: rad(&scale::ALM_M0, entry.m0),
            omega_dot: rad(&scale::ALM_OMEGA_DOT, entry.omega_dot),
            ..KeplerElements::default()
        };
        let clock = ClockParams {
            af0: scale::ALM_AF0.value(entry.af0),
            af1: scale::ALM_AF1.value(entry.af1),
            ..ClockParams::default()
        };
        Some(BroadcastEphemeris {
            health: entry.health6,
            ..BroadcastEphemeris::from_elements(
                SatId::gps(prn),
                OrbitClass::Standard,
                toa,
                orbit,
                HarmonicCorrections::default(),
                clock,
                ALMANAC_FIT_S,
            )
        })
    }

    /// Six-bit health of `prn` for page 25 (111111 when the PRN has no almanac).
    pub(crate) fn health6(&self, prn: u8) -> u32 {
        usize::from(prn)
            .checked_sub(1)
            .and_then(|k| self.entries.get(k).copied().flatten())
            .map_or(HEALTH_NOT_AVAILABLE, |e| e.health6)
    }

    /// Words 3-10 of the almanac page of `prn` after the data ID (figure 20-1 sheet 4,
    /// table 20-VI); returns the SV ID to write: `prn`, or 0 with alternating ones and
    /// zeros for a dummy SV (IS-GPS-200 20.3.3.5.1.2).
    pub(crate) fn write_page(&self, prn: u8, d: &mut DataWords) -> u32 {
        let Some(e) = usize::from(prn)
            .checked_sub(1)
            .and_then(|k| self.entries.get(k).copied().flatten())
        else {
            d.put_alternating(3, 9, 16);
            for w in 4..=9 {
                d.put_alternating(w, 1, 24);
            }
            d.put_alternating(10, 1, 22);
            return 0;
        };
        d.put_field(3, 9, &scale::ALM_E, e.e);
        d.put_field(4, 1, &scale::ALM_TOA, i64::from(self.toa_s()) / TOA_STEP_S);
        d.put_field(4, 9, &scale::ALM_DELTA_I, e.delta_i);
        d.put_field(5, 1, &scale::ALM_OMEGA_DOT, e.omega_dot);
        d.put(5, 17, 8, e.health8());
        d.put_field(6, 1, &scale::ALM_SQRT_A, e.sqrt_a);
        d.put_field(7, 1, &scale::ALM_OMEGA0, e.omega0);
        d.put_field(8, 1, &scale::ALM_OMEGA, e.omega);
        d.put_field(9, 1, &scale::ALM_M0, e.m0);
        let af0 = scale::ALM_AF0.bits_of(e.af0);
        d.put(10, 1, 8, af0 >> 3);
        d.put_field(10, 9, &scale::ALM_AF1, e.af1);
        d.put(10, 20, 3, af0 & 0b111);
        u32::from(prn)
    }

    /// Words 3-10 of subframe 5 page 25 after the data ID and SV ID (figure 20-1
    /// sheet 5): toa, WNa, six-bit health of PRN 1-24; word 10 bits 1-22 reserved.
    pub(crate) fn write_health_1_24(&self, d: &mut DataWords) {
        d.put_field(3, 9, &scale::ALM_TOA, i64::from(self.toa_s()) / TOA_STEP_S);
        d.put(3, 17, 8, self.week() & 0xFF);
        for prn in 1u8..=24 {
            let k = u32::from(prn - 1);
            d.put(4 + (k / 4) as usize, 1 + 6 * (k % 4), 6, self.health6(prn));
        }
        d.put_alternating(10, 1, 22);
    }
}
