//! Subframes 1-3: the clock and ephemeris of the transmitting satellite, quantised per
//! IS-GPS-200 tables 20-I and 20-III, re-expressed at a toe/toc on the 16-s grid.

use super::scale::{self, Scale};
use super::words::DataWords;
use super::{GPS_PI, LnavError, NS_PER_S, epoch_from_gps_ns, gps_ns, week_and_sow};
use skyforge_orbits::constants::{GM_GPS, OMEGA_E_GPS};
use skyforge_orbits::ephemeris::{
    BroadcastEphemeris, ClockParams, HarmonicCorrections, KeplerElements, OrbitClass, SatId, System,
};

/// Grid of toe and toc (s): their LSB (IS-GPS-200 table 20-III).
const TIME_GRID_S: i64 = 16;
/// Fit intervals longer than this set the fit interval flag (IS-GPS-200 20.3.3.4.3.1: 0 = 4 h).
const FIT_4H_S: f64 = 4.0 * 3600.0;

/// The subframe 1-3 content as broadcast: ICD integers (tables 20-I, 20-III).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct RawEphemeris {
    pub health: u32,
    pub tgd: i64,
    pub iodc: u32,
    pub af2: i64,
    pub af1: i64,
    pub af0: i64,
    /// toc, whole GPS seconds since the GPS epoch (a multiple of 16).
    pub toc_gps_s: i64,
    pub iode: u32,
    pub crs: i64,
    pub delta_n: i64,
    pub m0: i64,
    pub cuc: i64,
    pub e: i64,
    pub cus: i64,
    pub sqrt_a: i64,
    /// toe, whole GPS seconds since the GPS epoch (a multiple of 16).
    pub toe_gps_s: i64,
    pub fit_flag: bool,
    pub cic: i64,
    pub omega0: i64,
    pub cis: i64,
    pub i0: i64,
    pub crc: i64,
    pub omega: i64,
    pub omega_dot: i64,
    pub idot: i64,
}

/// The multiple of `grid` whole seconds nearest to `ns` nanoseconds (ties up).
fn round_to_grid_s(ns: i128, grid: i64) -> i64 {
    let g = i128::from(grid) * NS_PER_S;
    ((ns + g / 2).div_euclid(g) * i128::from(grid)) as i64
}

/// Move the reference epochs of `eph` to `toe_gps_s` and `toc_gps_s` (whole GPS seconds)
/// without changing the orbit or clock it describes.
///
/// The user algorithm of IS-GPS-200 table 20-IV is exactly invariant under this change:
/// tk enters only through M = M0 + n tk, i = i0 + IDOT tk and
/// OMEGA = OMEGA0 + (OMEGADOT - OMEGA_E) tk - OMEGA_E toe_sow, so with d = toe' - toe:
/// M0' = M0 + n d, i0' = i0 + IDOT d and
/// OMEGA0' = OMEGA0 + (OMEGADOT - OMEGA_E) d + OMEGA_E (toe_sow' - toe_sow) (= OMEGA0 +
/// OMEGADOT d within a week). The clock polynomial of 20.3.3.3.3.1 moves with
/// af0' = af0 + af1 dc + af2 dc^2, af1' = af1 + 2 af2 dc (dc = toc' - toc); the
/// relativistic term depends on E only and is unchanged.
pub(crate) fn reexpress(
    eph: &BroadcastEphemeris,
    toe_gps_s: i64,
    toc_gps_s: i64,
) -> BroadcastEphemeris {
    let toe_old_ns = gps_ns(eph.toe);
    let toc_old_ns = gps_ns(eph.toc);
    let d = (i128::from(toe_gps_s) * NS_PER_S - toe_old_ns) as f64 * 1e-9;
    let dc = (i128::from(toc_gps_s) * NS_PER_S - toc_old_ns) as f64 * 1e-9;
    let sow_old = toe_old_ns.rem_euclid(i128::from(super::WEEK_S) * NS_PER_S) as f64 * 1e-9;
    let sow_new = week_and_sow(toe_gps_s).1 as f64;
    let n = eph.orbit.mean_motion_rad_s(GM_GPS);
    let mut out = eph.clone();
    out.toe = epoch_from_gps_ns(i128::from(toe_gps_s) * NS_PER_S);
    out.toc = epoch_from_gps_ns(i128::from(toc_gps_s) * NS_PER_S);
    out.orbit.m0 = eph.orbit.m0 + n * d;
    out.orbit.i0 = eph.orbit.i0 + eph.orbit.idot * d;
    out.orbit.omega0 = eph.orbit.omega0
        + (eph.orbit.omega_dot - OMEGA_E_GPS) * d
        + OMEGA_E_GPS * (sow_new - sow_old);
    out.clock.af0 = eph.clock.af0 + dc * (eph.clock.af1 + dc * eph.clock.af2);
    out.clock.af1 = eph.clock.af1 + 2.0 * dc * eph.clock.af2;
    out
}

/// Check that `eph` is a GPS satellite LNAV can carry; returns its name for messages.
pub(crate) fn check_gps(sat: SatId) -> Result<String, LnavError> {
    if sat.system == System::Gps && (1..=32).contains(&sat.prn) {
        Ok(sat.to_string())
    } else {
        Err(LnavError::NotGps {
            sat: sat.to_string(),
        })
    }
}

/// Check an integer field against its allowed maximum.
fn check_int(what: String, value: u32, max: u32, allowed: &'static str) -> Result<u32, LnavError> {
    if value <= max {
        Ok(value)
    } else {
        Err(LnavError::BadValue {
            what,
            value: i64::from(value),
            allowed,
        })
    }
}

impl RawEphemeris {
    /// Quantise `eph` after moving toe and toc to the nearest 16-s grid point.
    pub fn new(eph: &BroadcastEphemeris) -> Result<Self, LnavError> {
        let name = check_gps(eph.sat)?;
        let toe_s = round_to_grid_s(gps_ns(eph.toe), TIME_GRID_S);
        let toc_s = round_to_grid_s(gps_ns(eph.toc), TIME_GRID_S);
        if toe_s < 0 || toc_s < 0 {
            return Err(LnavError::BeforeGpsEpoch {
                epoch: eph.toe.min(eph.toc).to_string(),
            });
        }
        let p = &reexpress(eph, toe_s, toc_s);
        let q = |s: &Scale, v: f64| s.quantise(v, &name);
        let qa = |s: &Scale, v_rad: f64| s.quantise_angle(v_rad / GPS_PI, &name);
        let iodc = check_int(format!("{name} IODC"), eph.iodc, 1023, "0-1023")?;
        let iode = check_int(format!("{name} IODE"), eph.iode, 255, "0-255")?;
        if iode != iodc & 0xFF {
            // IS-GPS-200 20.3.4.4: IODE equals the 8 LSBs of IODC of the same data set.
            return Err(LnavError::BadValue {
                what: format!("{name} IODE {iode} with IODC"),
                value: i64::from(iodc),
                allowed: "IODE = 8 LSBs of IODC (IS-GPS-200 20.3.4.4)",
            });
        }
        Ok(Self {
            health: check_int(
                format!("{name} health"),
                eph.health,
                63,
                "6-bit SV health 0-63",
            )?,
            tgd: q(&scale::TGD, eph.clock.tgd_s)?,
            iodc,
            af2: q(&scale::AF2, p.clock.af2)?,
            af1: q(&scale::AF1, p.clock.af1)?,
            af0: q(&scale::AF0, p.clock.af0)?,
            toc_gps_s: toc_s,
            iode,
            crs: q(&scale::CRS, p.harmonics.crs)?,
            delta_n: q(&scale::DELTA_N, p.orbit.delta_n / GPS_PI)?,
            m0: qa(&scale::M0, p.orbit.m0)?,
            cuc: q(&scale::CUC, p.harmonics.cuc)?,
            e: q(&scale::ECC, p.orbit.e)?,
            cus: q(&scale::CUS, p.harmonics.cus)?,
            sqrt_a: q(&scale::SQRT_A, p.orbit.sqrt_a)?,
            toe_gps_s: toe_s,
            fit_flag: eph.fit_interval_s > FIT_4H_S,
            cic: q(&scale::CIC, p.harmonics.cic)?,
            omega0: qa(&scale::OMEGA0, p.orbit.omega0)?,
            cis: q(&scale::CIS, p.harmonics.cis)?,
            i0: qa(&scale::I0, p.orbit.i0)?,
            crc: q(&scale::CRC, p.harmonics.crc)?,
            omega: qa(&scale::OMEGA, p.orbit.omega)?,
            omega_dot: q(&scale::OMEGA_DOT, p.orbit.omega_dot / GPS_PI)?,
            idot: q(&scale::IDOT, p.orbit.idot / GPS_PI)?,
        })
    }

    /// The quantised parameters back in SI units (radians, not semicircles): the orbit
    /// and clock a receiver decodes. `input` supplies what the message does not carry
    /// (satellite, fit interval).
    pub fn si_ephemeris(&self, input: &BroadcastEphemeris) -> BroadcastEphemeris {
        let v = |s: &Scale, n: i64| s.value(n);
        let rad = |s: &Scale, n: i64| s.value(n) * GPS_PI;
        let orbit = KeplerElements {
            sqrt_a: v(&scale::SQRT_A, self.sqrt_a),
            e: v(&scale::ECC, self.e),
            i0: rad(&scale::I0, self.i0),
            omega0: rad(&scale::OMEGA0, self.omega0),
            omega: rad(&scale::OMEGA, self.omega),
            m0: rad(&scale::M0, self.m0),
            delta_n: rad(&scale::DELTA_N, self.delta_n),
            idot: rad(&scale::IDOT, self.idot),
            omega_dot: rad(&scale::OMEGA_DOT, self.omega_dot),
        };
        let harmonics = HarmonicCorrections {
            cuc: v(&scale::CUC, self.cuc),
            cus: v(&scale::CUS, self.cus),
            crc: v(&scale::CRC, self.crc),
            crs: v(&scale::CRS, self.crs),
            cic: v(&scale::CIC, self.cic),
            cis: v(&scale::CIS, self.cis),
        };
        let clock = ClockParams {
            af0: v(&scale::AF0, self.af0),
            af1: v(&scale::AF1, self.af1),
            af2: v(&scale::AF2, self.af2),
            tgd_s: v(&scale::TGD, self.tgd),
            tgd2_s: 0.0,
        };
        BroadcastEphemeris {
            toc: epoch_from_gps_ns(i128::from(self.toc_gps_s) * NS_PER_S),
            iode: self.iode,
            iodc: self.iodc,
            health: self.health,
            ..BroadcastEphemeris::from_elements(
                input.sat,
                OrbitClass::Standard,
                epoch_from_gps_ns(i128::from(self.toe_gps_s) * NS_PER_S),
                orbit,
                harmonics,
                clock,
                input.fit_interval_s,
            )
        }
    }

    /// Words 3-10 of subframe 1 (table 20-I); the week number (word 3 bits 1-10) is
    /// written by the encoder per subframe. L2 code flags 01 (P code on), L2 P data flag 0,
    /// reserved bits alternating ones and zeros.
    pub fn subframe1(&self, ura_index: u32) -> DataWords {
        let mut d = DataWords::default();
        d.put(3, 11, 2, 0b01);
        d.put(3, 13, 4, ura_index);
        d.put(3, 17, 6, self.health);
        d.put(3, 23, 2, self.iodc >> 8);
        d.put(4, 1, 1, 0);
        d.put_alternating(4, 2, 23);
        d.put_alternating(5, 1, 24);
        d.put_alternating(6, 1, 24);
        d.put_alternating(7, 1, 16);
        d.put_field(7, 17, &scale::TGD, self.tgd);
        d.put(8, 1, 8, self.iodc & 0xFF);
        d.put_field(
            8,
            9,
            &scale::TOC,
            week_and_sow(self.toc_gps_s).1 / TIME_GRID_S,
        );
        d.put_field(9, 1, &scale::AF2, self.af2);
        d.put_field(9, 9, &scale::AF1, self.af1);
        d.put_field(10, 1, &scale::AF0, self.af0);
        d
    }

    /// Words 3-10 of subframe 2 (table 20-II); AODO = 0.
    pub fn subframe2(&self) -> DataWords {
        let mut d = DataWords::default();
        d.put(3, 1, 8, self.iode);
        d.put_field(3, 9, &scale::CRS, self.crs);
        d.put_field(4, 1, &scale::DELTA_N, self.delta_n);
        d.put_split32(4, &scale::M0, self.m0);
        d.put_field(6, 1, &scale::CUC, self.cuc);
        d.put_split32(6, &scale::ECC, self.e);
        d.put_field(8, 1, &scale::CUS, self.cus);
        d.put_split32(8, &scale::SQRT_A, self.sqrt_a);
        d.put_field(
            10,
            1,
            &scale::TOE,
            week_and_sow(self.toe_gps_s).1 / TIME_GRID_S,
        );
        d.put(10, 17, 1, u32::from(self.fit_flag));
        d.put(10, 18, 5, 0);
        d
    }

    /// Words 3-10 of subframe 3 (table 20-II).
    pub fn subframe3(&self) -> DataWords {
        let mut d = DataWords::default();
        d.put_field(3, 1, &scale::CIC, self.cic);
        d.put_split32(3, &scale::OMEGA0, self.omega0);
        d.put_field(5, 1, &scale::CIS, self.cis);
        d.put_split32(5, &scale::I0, self.i0);
        d.put_field(7, 1, &scale::CRC, self.crc);
        d.put_split32(7, &scale::OMEGA, self.omega);
        d.put_field(9, 1, &scale::OMEGA_DOT, self.omega_dot);
        d.put(10, 1, 8, self.iode);
        d.put_field(10, 9, &scale::IDOT, self.idot);
        d
    }
}
