//! The clock, ephemeris and page type 1/4 parameters as raw field values, and the
//! ephemeris they describe in SI units (Galileo OS SIS ICD §5.1).

use super::quant::{self as q, Field};
use super::time::{GstTime, gst_time};
use super::{FnavError, FnavParams};
pub(super) use crate::navmsg::field::Fields;
use hifitime::Epoch;
use skyforge_orbits::ephemeris::{
    BroadcastEphemeris, ClockParams, HarmonicCorrections, KeplerElements, NavMessage, OrbitClass,
    SatId,
};

/// Fit interval given to decoded sets (s): SkyForge uses Galileo sets for 4 h from toe,
/// as for the sets it reads from RINEX.
const FIT_INTERVAL_S: f64 = 4.0 * 3600.0;
/// toe and toc grid (s): the LSB of t0e and t0c.
pub(crate) const T_REF_GRID_S: u64 = 60;

/// E5a health bits in [`BroadcastEphemeris::health`]: the RINEX 3 Galileo SV health
/// layout (E5a DVS bit 3, E5a HS bits 4-5).
pub(super) fn e5a_health_bits(hs: i64, dvs: i64) -> u32 {
    ((hs as u32 & 3) << 4) | ((dvs as u32 & 1) << 3)
}

/// BGD(E1,E5a) of a set: tgd_s of an F/NAV set, tgd2_s of an I/NAV one.
fn bgd_e1_e5a(eph: &BroadcastEphemeris) -> f64 {
    match eph.message {
        NavMessage::GalileoInav => eph.clock.tgd2_s,
        _ => eph.clock.tgd_s,
    }
}

/// A reference time on the 60 s grid: its GST week and seconds of week, or the error.
pub(super) fn on_grid(sat: &str, field: &Field, t: Epoch) -> Result<GstTime, FnavError> {
    let g = gst_time(t);
    if g.ns_of_week.is_multiple_of(T_REF_GRID_S * 1_000_000_000) {
        Ok(g)
    } else {
        Err(FnavError::OffGrid {
            sat: sat.to_string(),
            field: field.name,
            sow_s: g.ns_of_week as f64 * 1e-9,
            grid_s: T_REF_GRID_S as f64,
        })
    }
}

/// Quantise the clock, ephemeris, health and the page 1/4 parameters.
pub(super) fn quantise(
    eph: &BroadcastEphemeris,
    params: &FnavParams,
    sat: &str,
) -> Result<Fields, FnavError> {
    let mut f = Fields::default();
    let o = &eph.orbit;
    let h = &eph.harmonics;
    let c = &eph.clock;
    let toe = on_grid(sat, &q::TOE, eph.toe)?;
    let toc = on_grid(sat, &q::TOC, eph.toc)?;
    let plain: [(&Field, f64); 22] = [
        (&q::SVID, f64::from(eph.sat.prn)),
        (&q::IODNAV, f64::from(eph.iode)),
        (&q::TOC, toc.sow_s()),
        (&q::AF0, c.af0),
        (&q::AF1, c.af1),
        (&q::AF2, c.af2),
        (&q::BGD_E1_E5A, bgd_e1_e5a(eph)),
        (&q::E5A_HS, f64::from((eph.health >> 4) & 3)),
        (&q::E5A_DVS, f64::from((eph.health >> 3) & 1)),
        (&q::TOE, toe.sow_s()),
        (&q::E, o.e),
        (&q::SQRT_A, o.sqrt_a),
        (&q::I0, o.i0),
        (&q::DELTA_N, o.delta_n),
        (&q::IDOT, o.idot),
        (&q::OMEGA_DOT, o.omega_dot),
        (&q::CUC, h.cuc),
        (&q::CUS, h.cus),
        (&q::CRC, h.crc),
        (&q::CRS, h.crs),
        (&q::CIC, h.cic),
        (&q::CIS, h.cis),
    ];
    for (field, v) in plain {
        f.set(
            field,
            field
                .quantise(v)
                .map_err(|e| FnavError::out_of_range(sat, e))?,
        );
    }
    for (field, v) in [(&q::M0, o.m0), (&q::OMEGA0, o.omega0), (&q::OMEGA, o.omega)] {
        f.set(
            field,
            field
                .quantise_angle(v)
                .map_err(|e| FnavError::out_of_range(sat, e))?,
        );
    }
    for (field, v) in params.values(&q::SISA) {
        f.set(
            field,
            field
                .quantise(v)
                .map_err(|e| FnavError::out_of_range(sat, e))?,
        );
    }
    Ok(f)
}

/// The ephemeris the raw fields describe, with toe and toc at the given epochs (on the
/// grid, in the weeks the caller resolved).
pub(crate) fn to_ephemeris(f: &Fields, sat: SatId, toe: Epoch, toc: Epoch) -> BroadcastEphemeris {
    let si = |field: &Field| field.si_value(f.get(field));
    let orbit = KeplerElements {
        sqrt_a: si(&q::SQRT_A),
        e: si(&q::E),
        i0: si(&q::I0),
        omega0: si(&q::OMEGA0),
        omega: si(&q::OMEGA),
        m0: si(&q::M0),
        delta_n: si(&q::DELTA_N),
        idot: si(&q::IDOT),
        omega_dot: si(&q::OMEGA_DOT),
    };
    let harmonics = HarmonicCorrections {
        cuc: si(&q::CUC),
        cus: si(&q::CUS),
        crc: si(&q::CRC),
        crs: si(&q::CRS),
        cic: si(&q::CIC),
        cis: si(&q::CIS),
    };
    let clock = ClockParams {
        af0: si(&q::AF0),
        af1: si(&q::AF1),
        af2: si(&q::AF2),
        tgd_s: si(&q::BGD_E1_E5A),
        tgd2_s: 0.0,
    };
    let iod = f.get(&q::IODNAV) as u32;
    BroadcastEphemeris {
        message: NavMessage::GalileoFnav,
        toc,
        iode: iod,
        iodc: iod,
        health: e5a_health_bits(f.get(&q::E5A_HS), f.get(&q::E5A_DVS)),
        ..BroadcastEphemeris::from_elements(
            sat,
            OrbitClass::Standard,
            toe,
            orbit,
            harmonics,
            clock,
            FIT_INTERVAL_S,
        )
    }
}
