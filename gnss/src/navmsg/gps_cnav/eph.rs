//! The ephemeris, clock and message type 30/33 parameters as raw field values, and the
//! ephemeris they describe in SI units (IS-GPS-705J §20.3.3.1, §20.3.3.2, §20.3.3.3).
//!
//! CNAV sends the orbit relative to references (Table 20-I): A = A_REF + Delta A,
//! OMEGAdot = OMEGA_DOT_REF + Delta OMEGAdot, and the user algorithm (Table 20-II) adds
//! Adot t_k to A and (Delta n0 + Delta n0 dot t_k / 2) to the mean motion. SkyForge's
//! [`BroadcastEphemeris`] follows the LNAV algorithm, so the encoder sends Adot = 0 and
//! Delta n0 dot = 0, with which the two algorithms coincide (sqrt A = sqrt(A_REF +
//! Delta A), Delta n = Delta n0).

use super::quant::{self as q, Field, OutOfRange};
use super::{CnavError, CnavParams};
pub(super) use crate::navmsg::field::Fields;
use hifitime::Epoch;
use skyforge_orbits::ephemeris::{
    BroadcastEphemeris, ClockParams, HarmonicCorrections, KeplerElements, NavMessage, OrbitClass,
    SatId,
};
use std::f64::consts::PI;

/// IS-GPS-705J Table 20-I: reference semi-major axis (m).
pub const A_REF_M: f64 = 26_559_710.0;
/// IS-GPS-705J Table 20-I: reference rate of right ascension (semicircles/s).
pub const OMEGA_DOT_REF_SC: f64 = -2.6e-9;
/// Grid of toe, toc and top (s): their LSB (Table 20-I, Table 20-III).
pub const T_REF_GRID_S: u64 = 300;
/// Fit interval given to decoded sets (s): the CNAV ephemeris curve fit of 3 h.
const FIT_INTERVAL_S: f64 = 3.0 * 3600.0;
/// Nanoseconds per second.
const NS: i128 = 1_000_000_000;

/// A reference time on the 300 s grid: its GPS week and seconds of week, or the error.
pub(super) fn on_grid(sat: &str, field: &Field, t: Epoch) -> Result<(u32, u64), CnavError> {
    let ns = t.to_gpst_duration().total_nanoseconds();
    let week_ns = 604_800 * NS;
    let (week, ns_of_week) = (ns.div_euclid(week_ns), ns.rem_euclid(week_ns));
    if ns_of_week % (T_REF_GRID_S as i128 * NS) == 0 && week >= 0 {
        Ok((week as u32, (ns_of_week / NS) as u64))
    } else {
        Err(CnavError::OffGrid {
            sat: sat.to_string(),
            field: field.name,
            sow_s: ns_of_week as f64 * 1e-9,
            grid_s: T_REF_GRID_S as f64,
        })
    }
}

fn range_error(sat: &str, e: OutOfRange) -> CnavError {
    CnavError::FieldOutOfRange {
        sat: sat.to_string(),
        field: e.field,
        value: e.value,
        min: e.min,
        max: e.max,
    }
}

/// The orbit and clock fields of `eph` in SI units (angles wrapped separately).
fn plain_values(eph: &BroadcastEphemeris) -> [(&'static Field, f64); 17] {
    let (o, h, c) = (&eph.orbit, &eph.harmonics, &eph.clock);
    [
        (&q::DELTA_A, o.sqrt_a * o.sqrt_a - A_REF_M),
        (&q::DELTA_N0, o.delta_n),
        (&q::E, o.e),
        (&q::I0, o.i0),
        (&q::DELTA_OMEGA_DOT, o.omega_dot - OMEGA_DOT_REF_SC * PI),
        (&q::IDOT, o.idot),
        (&q::CIS, h.cis),
        (&q::CIC, h.cic),
        (&q::CRS, h.crs),
        (&q::CRC, h.crc),
        (&q::CUS, h.cus),
        (&q::CUC, h.cuc),
        (&q::AF0, c.af0),
        (&q::AF1, c.af1),
        (&q::AF2, c.af2),
        (&q::TGD, c.tgd_s),
        (&q::HEALTH_L1, f64::from(u8::from(eph.health != 0))),
    ]
}

/// Quantise the orbit, clock, health and the type 30/33 parameters. toe, toc and top
/// (= toe: SkyForge has no separate orbit-determination epoch) must lie on the 300 s grid.
pub(super) fn quantise(
    eph: &BroadcastEphemeris,
    params: &CnavParams,
    sat: &str,
) -> Result<Fields, CnavError> {
    let mut f = Fields::default();
    let (toe_week, toe_sow) = on_grid(sat, &q::TOE, eph.toe)?;
    let (_, toc_sow) = on_grid(sat, &q::TOC, eph.toc)?;
    let err = |e| range_error(sat, e);
    for (field, v) in plain_values(eph) {
        f.set(field, field.quantise(v).map_err(err)?);
    }
    for (field, v) in [(&q::M0, eph.orbit.m0), (&q::OMEGA0, eph.orbit.omega0)] {
        f.set(field, field.quantise_angle(v).map_err(err)?);
    }
    f.set(
        &q::OMEGA,
        q::OMEGA.quantise_angle(eph.orbit.omega).map_err(err)?,
    );
    let health = f.get(&q::HEALTH_L1);
    f.set(&q::HEALTH_L2, health);
    f.set(&q::HEALTH_L5, health);
    f.set(&q::TOE, (toe_sow / T_REF_GRID_S) as i64);
    f.set(&q::TOP, (toe_sow / T_REF_GRID_S) as i64);
    f.set(&q::TOC, (toc_sow / T_REF_GRID_S) as i64);
    f.set(&q::WN_OP, i64::from(toe_week % 256));
    for (field, v) in params.values() {
        f.set(field, field.quantise(v).map_err(err)?);
    }
    for (field, isc) in params.iscs() {
        let raw = isc.map(|s| field.quantise(s)).transpose().map_err(err)?;
        f.set(field, raw.unwrap_or(q::GROUP_DELAY_NOT_AVAILABLE));
    }
    Ok(f)
}

/// Health bits of a decoded set: L1 << 2 | L2 << 1 | L5 (the encoder sends all three as
/// "unhealthy" for a set whose health is not 0).
fn health_bits(f: &Fields) -> u32 {
    [&q::HEALTH_L1, &q::HEALTH_L2, &q::HEALTH_L5]
        .iter()
        .fold(0, |acc, h| (acc << 1) | (f.get(h) as u32 & 1))
}

/// The ephemeris the raw fields describe, with toe and toc at the given epochs (on the
/// grid, in the weeks the caller resolved). Message: [`NavMessage::GpsLnav`], whose
/// clock reference (L1/L2 P(Y)) and TGD CNAV shares; CNAV has no IODE/IODC (0 here).
pub(super) fn to_ephemeris(f: &Fields, sat: SatId, toe: Epoch, toc: Epoch) -> BroadcastEphemeris {
    let si = |field: &Field| field.si_value(f.get(field));
    let orbit = KeplerElements {
        sqrt_a: (A_REF_M + si(&q::DELTA_A)).sqrt(),
        e: si(&q::E),
        i0: si(&q::I0),
        omega0: si(&q::OMEGA0),
        omega: si(&q::OMEGA),
        m0: si(&q::M0),
        delta_n: si(&q::DELTA_N0),
        idot: si(&q::IDOT),
        omega_dot: OMEGA_DOT_REF_SC * PI + si(&q::DELTA_OMEGA_DOT),
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
        tgd_s: si(&q::TGD),
        tgd2_s: 0.0,
    };
    BroadcastEphemeris {
        message: NavMessage::GpsLnav,
        toc,
        health: health_bits(f),
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
