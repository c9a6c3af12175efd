//! The clock, ephemeris and word type 3-6 parameters as raw field values, and the
//! ephemeris they describe in SI units (Galileo OS SIS ICD Issue 2.1 §5.1).

use super::quant::{self as q, Field};
use super::{InavError, InavParams};
use crate::navmsg::field::Fields;
use crate::navmsg::galileo_fnav::eph::{T_REF_GRID_S, to_ephemeris as fnav_ephemeris};
use crate::navmsg::galileo_fnav::time::{GstTime, gst_time};
use hifitime::Epoch;
use skyforge_orbits::ephemeris::{BroadcastEphemeris, ClockParams, NavMessage, SatId};

/// E1-B and E5b health bits in [`BroadcastEphemeris::health`], the RINEX 3 Galileo SV
/// health layout: E1-B DVS bit 0, E1-B HS bits 1-2, E5b DVS bit 6, E5b HS bits 7-8.
pub(super) fn health_bits(e1b_hs: i64, e1b_dvs: i64, e5b_hs: i64, e5b_dvs: i64) -> u32 {
    let b = |v: i64, mask: u32, at: u32| (v as u32 & mask) << at;
    b(e1b_dvs, 1, 0) | b(e1b_hs, 3, 1) | b(e5b_dvs, 1, 6) | b(e5b_hs, 3, 7)
}

/// BGD(E1,E5a) and BGD(E1,E5b) of a set: an I/NAV set's tgd2_s and tgd_s; an F/NAV set
/// has only the first (its tgd_s), the second is then sent as 0.
fn bgds(eph: &BroadcastEphemeris) -> (f64, f64) {
    match eph.message {
        NavMessage::GalileoFnav => (eph.clock.tgd_s, 0.0),
        _ => (eph.clock.tgd2_s, eph.clock.tgd_s),
    }
}

/// A reference time on the 60 s grid: its GST week and seconds of week, or the error.
fn on_grid(sat: &str, field: &Field, t: Epoch) -> Result<GstTime, InavError> {
    let g = gst_time(t);
    if g.ns_of_week.is_multiple_of(T_REF_GRID_S * 1_000_000_000) {
        Ok(g)
    } else {
        Err(InavError::OffGrid {
            sat: sat.to_string(),
            field: field.name,
            sow_s: g.sow_s(),
            grid_s: T_REF_GRID_S as f64,
        })
    }
}

/// Quantise the clock, ephemeris, health and the word type 3-6 and 10 parameters.
pub(super) fn quantise(
    eph: &BroadcastEphemeris,
    params: &InavParams,
    sat: &str,
) -> Result<Fields, InavError> {
    let (o, h, c) = (&eph.orbit, &eph.harmonics, &eph.clock);
    let toe = on_grid(sat, &q::TOE, eph.toe)?;
    let toc = on_grid(sat, &q::TOC, eph.toc)?;
    let (bgd_a, bgd_b) = bgds(eph);
    let bits = |at: u32, mask: u32| f64::from((eph.health >> at) & mask);
    let plain: [(&Field, f64); 25] = [
        (&q::SVID, f64::from(eph.sat.prn)),
        (&q::IODNAV, f64::from(eph.iode)),
        (&q::TOC, toc.sow_s()),
        (&q::AF0, c.af0),
        (&q::AF1, c.af1),
        (&q::AF2, c.af2),
        (&q::BGD_E1_E5A, bgd_a),
        (&q::BGD_E1_E5B, bgd_b),
        (&q::E1B_DVS, bits(0, 1)),
        (&q::E1B_HS, bits(1, 3)),
        (&q::E5B_DVS, bits(6, 1)),
        (&q::E5B_HS, bits(7, 3)),
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
    let mut f = Fields::default();
    let range = |e| InavError::out_of_range(sat, e);
    for (field, v) in plain.into_iter().chain(params.values(&q::SISA)) {
        f.set(field, field.quantise(v).map_err(range)?);
    }
    for (field, v) in [(&q::M0, o.m0), (&q::OMEGA0, o.omega0), (&q::OMEGA, o.omega)] {
        f.set(field, field.quantise_angle(v).map_err(range)?);
    }
    f.set(&q::TIME, q::TIME_VALID);
    Ok(f)
}

/// The ephemeris the raw fields describe, with toe and toc at the given epochs (on the
/// grid, in the weeks the caller resolved): F/NAV's conversion of the orbit and clock,
/// with I/NAV's message, group delays and health.
pub(super) fn to_ephemeris(f: &Fields, sat: SatId, toe: Epoch, toc: Epoch) -> BroadcastEphemeris {
    let base = fnav_ephemeris(f, sat, toe, toc);
    let si = |field: &Field| field.si_value(f.get(field));
    BroadcastEphemeris {
        message: NavMessage::GalileoInav,
        health: health_bits(
            f.get(&q::E1B_HS),
            f.get(&q::E1B_DVS),
            f.get(&q::E5B_HS),
            f.get(&q::E5B_DVS),
        ),
        clock: ClockParams {
            tgd_s: si(&q::BGD_E1_E5B),
            tgd2_s: si(&q::BGD_E1_E5A),
            ..base.clock
        },
        ..base
    }
}
