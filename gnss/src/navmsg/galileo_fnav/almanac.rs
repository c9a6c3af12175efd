//! Almanac pages 5 and 6 (Galileo OS SIS ICD §4.2.4 page types 5/6, §5.1.10 almanac).
//!
//! The almanac refers to t0a, the encoder's toe rounded down to the 600 s grid, in GST
//! week WNa (2 bits). IODa (4 bits) is t0a / 600 modulo 16, so it changes with t0a.
//! The satellites are the Galileo sets of the constellation given, one per PRN (the set
//! whose toe is nearest t0a), in PRN order, three per page pair; a set whose almanac
//! values do not fit the almanac fields (e.g. an eccentricity above 0.031) is left out.
//! An empty slot has SVID 0 and all other fields 0 (an assumption: the ICD reserves no
//! value for it that could be checked here), as has the whole pair when no satellite is
//! left.
//!
//! Each set is moved to t0a: M0 advanced by the set's mean motion, OMEGA0 by OMEGAdot
//! (and re-referred to WNa's week), i by idot, the clock by its polynomial; Delta(A^1/2)
//! and delta i refer to the nominal 29 600 km and 56 deg.

use super::pages::ALMANAC_SAT;
use super::quant::{self as q, Field};
use super::time::{WEEK_S, gst_epoch, gst_time, nearest_week};
use hifitime::Epoch;
use skyforge_orbits::constants::{GM_GAL, OMEGA_E_GAL};
use skyforge_orbits::ephemeris::{
    BroadcastEphemeris, ClockParams, HarmonicCorrections, KeplerElements, NavMessage, OrbitClass,
    SatId, System,
};
use std::collections::BTreeMap;

/// t0a grid (s).
const T0A_GRID_S: u64 = 600;
/// How long a decoded almanac set is used around t0a (s): a week, a choice.
const ALMANAC_FIT_S: f64 = WEEK_S as f64;

/// The almanac reference of an encoder whose toe is `toe` (t0a is toe rounded down to the
/// 600 s grid): the raw IODa, WNa and t0a, and t0a as an epoch. Shared with I/NAV.
pub(crate) fn reference(toe: Epoch) -> ([i64; 3], Epoch) {
    let g = gst_time(toe);
    let sow = g.ns_of_week / 1_000_000_000;
    let t0a_s = sow - sow % T0A_GRID_S;
    let head = [
        (t0a_s / T0A_GRID_S % 16) as i64,
        i64::from(g.week % 4),
        (t0a_s / T0A_GRID_S) as i64,
    ];
    (head, gst_epoch(g.week, t0a_s))
}

/// The Galileo sets of `set`, one per PRN (the set whose toe is nearest `t0a`), in PRN
/// order, each with its raw almanac at `t0a` from SVID to af1 ([`ALMANAC_SAT`] order, the
/// health left to the message); sets whose values do not fit are left out. Shared with
/// I/NAV, whose almanac carries the same parameters (§5.1.10).
pub(crate) fn satellites(
    set: &[BroadcastEphemeris],
    t0a: Epoch,
) -> Vec<([i64; 10], &BroadcastEphemeris)> {
    let mut nearest: BTreeMap<u8, &BroadcastEphemeris> = BTreeMap::new();
    for e in set.iter().filter(|e| e.sat.system == System::Galileo) {
        let closer = |o: &&BroadcastEphemeris| (o.toe - t0a).abs() <= (e.toe - t0a).abs();
        if !nearest.get(&e.sat.prn).is_some_and(closer) {
            nearest.insert(e.sat.prn, e);
        }
    }
    nearest
        .into_values()
        .filter_map(|e| Some((satellite(e, t0a)?, e)))
        .collect()
}

/// The raw values of each page-5/6 pair, in the layouts' order; at least one pair.
pub(super) fn pages(set: &[BroadcastEphemeris], toe: Epoch) -> Vec<[Vec<i64>; 2]> {
    let (head, t0a) = reference(toe);
    let sats: Vec<[i64; 11]> = satellites(set, t0a)
        .into_iter()
        .map(|(raw, e)| {
            let mut sat = [0; 11];
            sat[..10].copy_from_slice(&raw);
            sat[10] = i64::from((e.health >> 4) & 3);
            sat
        })
        .collect();
    let mut triples: Vec<[[i64; 11]; 3]> = sats
        .chunks(3)
        .map(|c| std::array::from_fn(|i| c.get(i).copied().unwrap_or([0; 11])))
        .collect();
    if triples.is_empty() {
        triples.push([[0; 11]; 3]);
    }
    triples.iter().map(|t| pair(head, t)).collect()
}

/// Page 5 and page 6 values of one triple.
fn pair(head: [i64; 3], [s1, s2, s3]: &[[i64; 11]; 3]) -> [Vec<i64>; 2] {
    // SVID2's OMEGA0: 16-bit two's complement, 4 MSBs in page 5, 12 LSBs in page 6.
    let omega0 = s2[5] & 0xFFFF;
    let mut p5 = head.to_vec();
    p5.extend_from_slice(s1);
    p5.extend_from_slice(&s2[..5]);
    p5.push(omega0 >> 12);
    let mut p6 = vec![head[0], omega0 & 0xFFF];
    p6.extend_from_slice(&s2[6..]);
    p6.extend_from_slice(s3);
    p6.push(0);
    [p5, p6]
}

/// One satellite's raw almanac at `t0a` from SVID to af1, if every value fits.
fn satellite(e: &BroadcastEphemeris, t0a: Epoch) -> Option<[i64; 10]> {
    let o = &e.orbit;
    let dt = (t0a - e.toe).to_seconds();
    let dtc = (t0a - e.toc).to_seconds();
    let weeks = f64::from(gst_time(t0a).week) - f64::from(gst_time(e.toe).week);
    let a = o.sqrt_a * o.sqrt_a;
    let n = (GM_GAL / (a * a * a)).sqrt() + o.delta_n;
    let values: [f64; 10] = [
        f64::from(e.sat.prn),
        o.sqrt_a - q::ALM_A_NOMINAL_M.sqrt(),
        o.e,
        o.omega,
        o.i0 + o.idot * dt - q::ALM_I_NOMINAL_RAD,
        o.omega0 + o.omega_dot * dt - OMEGA_E_GAL * WEEK_S as f64 * weeks,
        o.omega_dot,
        o.m0 + n * dt,
        e.clock.af0 + dtc * (e.clock.af1 + dtc * e.clock.af2),
        e.clock.af1 + 2.0 * dtc * e.clock.af2,
    ];
    let mut raw = [0i64; 10];
    for ((slot, f), v) in raw.iter_mut().zip(&ALMANAC_SAT).zip(values) {
        *slot = quantise(f, v)?;
    }
    Some(raw)
}

/// Angles that span the circle wrap; everything else must fit.
fn quantise(f: &Field, v: f64) -> Option<i64> {
    let angle = [q::ALM_OMEGA.name, q::ALM_OMEGA0.name, q::ALM_M0.name].contains(&f.name);
    if angle {
        f.quantise_angle(v)
    } else {
        f.quantise(v)
    }
    .ok()
}

/// The almanac sets of a received page-5/6 pair (raw values in layout order) with one
/// IODa; `now` resolves WNa (2 bits) to the nearest week. Empty slots (SVID 0) and SVIDs
/// above 36 are skipped.
pub(super) fn decode(pt5: &[i64], pt6: &[i64], now: Epoch) -> Vec<BroadcastEphemeris> {
    if pt5.len() != 20 || pt6.len() != 19 || pt5[0] != pt6[0] {
        return Vec::new();
    }
    let t0a = t0a_epoch(pt5[1], pt5[2], now);
    let omega0_2 = ((pt5[19] << 12) | pt6[1]) as i16;
    let mut s2 = [0i64; 11];
    s2[..5].copy_from_slice(&pt5[14..19]);
    s2[5] = i64::from(omega0_2);
    s2[6..].copy_from_slice(&pt6[2..7]);
    [&pt5[3..14], &s2[..], &pt6[7..18]]
        .into_iter()
        .filter_map(|raw| {
            let health = super::eph::e5a_health_bits(raw[10], 0);
            to_ephemeris(&raw[..10], t0a, NavMessage::GalileoFnav, health)
        })
        .collect()
}

/// The epoch of a received almanac's raw WNa (2 bits) and t0a, the week resolved to the
/// one nearest `now`. Shared with I/NAV.
pub(crate) fn t0a_epoch(wna: i64, t0a: i64, now: Epoch) -> Epoch {
    let t0a_s = t0a as u64 * T0A_GRID_S;
    gst_epoch(nearest_week(now, t0a_s, wna as u32, 4), t0a_s)
}

/// One satellite's almanac (`raw`: SVID to af1 in [`ALMANAC_SAT`] order) as an ephemeris
/// of `message` with health bits `health` (no harmonics, no Delta n, toe = toc = t0a);
/// `None` for an empty slot (SVID 0) or an SVID above 36. Shared with I/NAV.
pub(crate) fn to_ephemeris(
    raw: &[i64],
    t0a: Epoch,
    message: NavMessage,
    health: u32,
) -> Option<BroadcastEphemeris> {
    let svid = u8::try_from(raw[0])
        .ok()
        .filter(|&p| p >= 1 && p <= System::Galileo.max_prn())?;
    let si = |i: usize| ALMANAC_SAT[i].si_value(raw[i]);
    let orbit = KeplerElements {
        sqrt_a: q::ALM_A_NOMINAL_M.sqrt() + si(1),
        e: si(2),
        omega: si(3),
        i0: q::ALM_I_NOMINAL_RAD + si(4),
        omega0: si(5),
        omega_dot: si(6),
        m0: si(7),
        delta_n: 0.0,
        idot: 0.0,
    };
    let clock = ClockParams {
        af0: si(8),
        af1: si(9),
        ..ClockParams::default()
    };
    Some(BroadcastEphemeris {
        message,
        health,
        ..BroadcastEphemeris::from_elements(
            SatId::galileo(svid),
            OrbitClass::Standard,
            t0a,
            orbit,
            HarmonicCorrections::default(),
            clock,
            ALMANAC_FIT_S,
        )
    })
}
