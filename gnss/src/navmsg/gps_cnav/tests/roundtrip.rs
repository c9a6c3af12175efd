//! Ephemeris -> symbols -> decoder -> ephemeris, and what quantisation costs.

use super::super::eph::{A_REF_M, OMEGA_DOT_REF_SC};
use super::super::quant::{self as q, Field};
use super::{PER_WEEK, WEEK, assemble, decode_messages, encoder, epoch, realistic};
use hifitime::Unit;
use skyforge_orbits::ephemeris::{BroadcastEphemeris, NavMessage, nominal};
use skyforge_orbits::time::TimeOrigin;
use std::f64::consts::PI;

/// The first message of the schedule cycle that holds `eph`'s toe.
fn cycle_at_toe(eph: &BroadcastEphemeris) -> u64 {
    let s = (eph.toe - encoder(eph).week_start()).to_seconds();
    (s as u64 / 24) * 4
}

/// The ephemeris decoded from two schedule cycles of `eph`'s message from message
/// `first`, and the encoder's.
fn round_trip(eph: &BroadcastEphemeris, first: u64) -> (BroadcastEphemeris, BroadcastEphemeris) {
    let enc = encoder(eph);
    let decoded = assemble(&decode_messages(&enc, first, 8));
    assert_eq!(decoded.len(), 1, "one complete set, yielded once");
    (decoded[0].eph.clone(), enc.broadcast_ephemeris())
}

/// |a - b| within half a step of `f` (angles compared modulo 2 pi).
fn within_half_lsb(f: &Field, a: f64, b: f64) {
    let d = a - b;
    let d = d - 2.0 * PI * (d / (2.0 * PI)).round();
    let tol = 0.5 * f.lsb_si() * (1.0 + 1e-9) + 1e-15 * a.abs();
    assert!(
        d.abs() <= tol,
        "{}: {a} vs {b} (step {})",
        f.name,
        f.lsb_si()
    );
}

fn check_quantisation(input: &BroadcastEphemeris, b: &BroadcastEphemeris) {
    let (o, p) = (&input.orbit, &b.orbit);
    let (h, g) = (&input.harmonics, &b.harmonics);
    let a = |x: f64| x * x - A_REF_M;
    let pairs: [(&Field, f64, f64); 19] = [
        (&q::DELTA_A, a(o.sqrt_a), a(p.sqrt_a)),
        (&q::E, o.e, p.e),
        (&q::I0, o.i0, p.i0),
        (&q::OMEGA0, o.omega0, p.omega0),
        (&q::OMEGA, o.omega, p.omega),
        (&q::M0, o.m0, p.m0),
        (&q::DELTA_N0, o.delta_n, p.delta_n),
        (&q::IDOT, o.idot, p.idot),
        (&q::DELTA_OMEGA_DOT, o.omega_dot, p.omega_dot),
        (&q::CUC, h.cuc, g.cuc),
        (&q::CUS, h.cus, g.cus),
        (&q::CRC, h.crc, g.crc),
        (&q::CRS, h.crs, g.crs),
        (&q::CIC, h.cic, g.cic),
        (&q::CIS, h.cis, g.cis),
        (&q::AF0, input.clock.af0, b.clock.af0),
        (&q::AF1, input.clock.af1, b.clock.af1),
        (&q::AF2, input.clock.af2, b.clock.af2),
        (&q::TGD, input.clock.tgd_s, b.clock.tgd_s),
    ];
    for (f, x, y) in pairs {
        within_half_lsb(f, x, y);
    }
    assert_eq!((b.toe, b.toc), (input.toe, input.toc));
    assert_eq!((b.iode, b.iodc, b.clock.tgd2_s), (0, 0, 0.0));
    assert_eq!(b.health, if input.health == 0 { 0 } else { 7 });
    assert_eq!(b.message, NavMessage::GpsLnav);
}

/// Largest position (m) and clock (s) differences over toe +- 2 h, every 5 min.
fn gaps(a: &BroadcastEphemeris, b: &BroadcastEphemeris) -> (f64, f64) {
    let origin = TimeOrigin::new(a.toe);
    let (ba, bb) = (a.bind(&origin), b.bind(&origin));
    (-24..=24)
        .map(|k| f64::from(k) * 300.0)
        .map(|t| {
            let dr = (ba.position_ecef(t) - bb.position_ecef(t)).norm();
            (dr, (ba.clock_offset_s(t) - bb.clock_offset_s(t)).abs())
        })
        .fold((0.0, 0.0), |(r, c), (dr, dc)| (r.max(dr), c.max(dc)))
}

fn check(input: &BroadcastEphemeris) {
    let (decoded, broadcast) = round_trip(input, cycle_at_toe(input));
    assert_eq!(decoded, broadcast, "{}: decoded == broadcast", input.sat);
    check_quantisation(input, &broadcast);
    // Half an LSB of each term, linearly summed at 26 560 km over 2 h, bounds the
    // quantisation: M0, OMEGA0, omega, i0 (pi 2^-33 rad: 9.7 mm each); Delta n0,
    // Delta OMEGAdot, IDOT (pi 2^-45 rad/s x 7200 s: 17 mm each); the four angular
    // harmonics (2^-31 rad: 12 mm each); Crs, Crc, e, Delta A (under 8 mm together).
    let (dr, dt) = gaps(input, &broadcast);
    println!(
        "{}: quantisation {dr:.3e} m, {dt:.3e} s over toe +- 2 h",
        input.sat
    );
    assert!(dr < 0.16, "{}: input vs quantised {dr} m", input.sat);
    // Half LSBs of af0, af1 x 7800 s, af2 x (7800 s)^2 (toc is up to 10 min from toe):
    // 1.46e-11 + 1.39e-11 + 2.64e-11 s.
    assert!(dt < 5.5e-11, "{}: input vs quantised {dt} s", input.sat);
}

#[test]
fn several_satellites_round_trip() {
    check(&realistic(1, epoch()));
    check(&realistic(17, epoch() + Unit::Hour * 3 + Unit::Minute * 5));
    // Extremes of signs, the node near +pi, an unhealthy set, a toe late in the week.
    let mut e = realistic(32, epoch() + Unit::Day * 6 + Unit::Hour * 22);
    e.orbit.m0 = -3.1;
    e.orbit.omega0 = PI - 1e-12;
    e.orbit.omega = -3.0;
    e.clock.af0 = 9.7e-4;
    e.clock.af1 = 1.8e-9;
    e.clock.tgd_s = 1.1e-7;
    e.health = 0b10_0000;
    check(&e);
    for eph in nominal::gps(epoch()).iter().step_by(6) {
        check(eph);
    }
}

#[test]
fn a_set_decodes_across_the_week_boundary() {
    // toe at the last 5 min of the week; messages 100796..100803 straddle the boundary.
    let toe = encoder(&realistic(3, epoch())).week_start() + Unit::Second * (604_800 - 300);
    let e = realistic(3, toe);
    let (decoded, broadcast) = round_trip(&e, PER_WEEK - 4);
    assert_eq!(decoded, broadcast);
    // A receiver that starts in the next week resolves toe into the week before.
    let enc = encoder(&e);
    let next_week = assemble(&decode_messages(&enc, PER_WEEK, 4));
    assert_eq!(next_week.len(), 1);
    assert_eq!(next_week[0].eph, broadcast);
    assert_eq!((next_week[0].week, next_week[0].tow), (WEEK + 1, 18));
    assert_eq!(broadcast.toe, toe);
}

/// A set whose every value is a multiple of its CNAV step (relative to A_REF and
/// OMEGA_DOT_REF where CNAV sends a difference).
fn multiples(toe: hifitime::Epoch) -> BroadcastEphemeris {
    let mut e = realistic(11, toe);
    let semi = |k: f64, n: i32| k * PI * 2f64.powi(n);
    let p2 = |k: f64, n: i32| k * 2f64.powi(n);
    e.orbit.sqrt_a = (A_REF_M + p2(-1_234_567.0, -9)).sqrt();
    e.orbit.e = p2(123_456_789.0, -34);
    e.orbit.i0 = semi(1_312_345_678.0, -32);
    e.orbit.omega0 = semi(-2_987_654_321.0, -32);
    e.orbit.omega = semi(1_987_654_321.0, -32);
    e.orbit.m0 = semi(-123_456_789.0, -32);
    e.orbit.delta_n = semi(12_345.0, -44);
    e.orbit.idot = semi(-1_234.0, -44);
    e.orbit.omega_dot = (OMEGA_DOT_REF_SC + p2(-9_876.0, -44)) * PI;
    e.harmonics.cuc = p2(-1_234.0, -30);
    e.harmonics.cus = p2(9_876.0, -30);
    e.harmonics.crc = p2(54_321.0, -8);
    e.harmonics.crs = p2(-6_789.0, -8);
    e.harmonics.cic = p2(37.0, -30);
    e.harmonics.cis = p2(-61.0, -30);
    e.clock.af0 = p2(-4_567_891.0, -35);
    e.clock.af1 = p2(-2_345.0, -48);
    e.clock.af2 = p2(3.0, -60);
    e.clock.tgd_s = p2(-321.0, -35);
    e
}

#[test]
fn a_set_of_scale_factor_multiples_comes_back_within_a_millimetre() {
    let e = multiples(epoch() + Unit::Hour * 5);
    let (decoded, broadcast) = round_trip(&e, cycle_at_toe(&e));
    assert_eq!(decoded, broadcast);
    let (dr, dt) = gaps(&e, &broadcast);
    println!("multiples of the CNAV steps: {dr:e} m, {dt:e} s over toe +- 2 h");
    assert!(dr < 1e-3, "{dr} m");
    assert!(dt < 1e-15, "{dt} s");
    // Only Delta OMEGAdot is computed differently (reference added after scaling).
    assert_eq!(broadcast.harmonics, e.harmonics);
    assert_eq!(broadcast.clock, e.clock);
    assert_eq!(broadcast.orbit.m0, e.orbit.m0);
    assert_eq!(broadcast.orbit.sqrt_a, e.orbit.sqrt_a);
}

#[test]
fn type_30_and_33_parameters_come_back_from_the_messages() {
    let mut params = super::CnavParams::with_leap_seconds(18);
    params.ura_ed_index = -3;
    params.ura_ned0_index = -16;
    params.ura_ned1_index = 7;
    params.ura_ned2_index = 5;
    params.isc_l1ca_s = Some(-3.1e-9);
    params.isc_l5i5_s = Some(1.2e-8);
    params.isc_l5q5_s = None;
    params.iono.alpha = [1.3e-8, -7.45e-9, -5.96e-8, 1.19e-7];
    params.iono.beta = [96_256.0, -32_768.0, -131_072.0, 393_216.0];
    params.utc.a0 = -9.3e-10;
    params.utc.a1 = 8.9e-16;
    params.utc_a2 = 1.7e-19;
    params.utc.tot = 405_504;
    params.utc.wnt = WEEK;
    params.utc.wn_lsf = 1929;
    params.utc.dn = 7;
    let e = realistic(12, epoch());
    let enc = super::CnavEncoder::new(&e, &params, WEEK).unwrap();
    let messages = decode_messages(&enc, cycle_at_toe(&e), 4);
    let get = |name: &str| messages.iter().find_map(|m| m.field(name)).unwrap();
    for (f, v) in params.values() {
        within_half_lsb(f, v, f.si_value(get(f.name)));
    }
    assert_eq!(get("ISC_L5Q5"), -4096, "not available");
    assert_eq!(get("ISC_L2C"), 0);
    within_half_lsb(&q::ISC_L5I5, 1.2e-8, q::ISC_L5I5.si_value(get("ISC_L5I5")));
    assert_eq!(get("WNop"), i64::from(WEEK % 256));
    assert_eq!((get("WNot"), get("WNLSF")), (i64::from(WEEK), 1929));
    assert_eq!((get("Delta tLS"), get("Delta tLSF")), (18, 18));
    assert_eq!(get("toe"), get("top"));
    // iono() is what type 30 carries: the decoded coefficients exactly.
    let sent = enc.iono();
    for (k, (a, b)) in q::ALPHA.iter().zip(&q::BETA).enumerate() {
        assert_eq!(sent.alpha[k], a.si_value(get(a.name)), "{}", a.name);
        assert_eq!(sent.beta[k], b.si_value(get(b.name)), "{}", b.name);
    }
}
