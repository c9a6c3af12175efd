//! Ephemeris -> symbols -> decoder -> ephemeris.

use super::super::quant::{self as q, Field};
use super::super::{FnavEncoder, FnavParams};
use super::{WEEK, assemble, decode_pages, encoder, epoch, frame_page_at, realistic};
use hifitime::{Epoch, Unit};
use skyforge_orbits::ephemeris::{BroadcastEphemeris, NavMessage, nominal};
use skyforge_orbits::time::TimeOrigin;
use std::f64::consts::PI;

/// The ephemeris decoded from one frame of `eph`'s message, and the encoder's.
fn round_trip(eph: &BroadcastEphemeris) -> (BroadcastEphemeris, BroadcastEphemeris) {
    let enc = encoder(eph);
    let first = frame_page_at(&enc, eph.toe);
    let decoded = assemble(&decode_pages(&enc, first, 60));
    assert_eq!(decoded.len(), 1, "one complete set per frame, yielded once");
    (decoded[0].eph.clone(), enc.broadcast_ephemeris())
}

/// |a - b| within half a step of `f` (angles compared modulo 2 pi).
fn within_half_lsb(f: &Field, a: f64, b: f64) {
    let d = a - b;
    let d = if d.abs() > PI {
        d - 2.0 * PI * (d / (2.0 * PI)).round()
    } else {
        d
    };
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
    let bgd_in = match input.message {
        NavMessage::GalileoInav => input.clock.tgd2_s,
        _ => input.clock.tgd_s,
    };
    let pairs: [(&Field, f64, f64); 21] = [
        (&q::SQRT_A, o.sqrt_a, p.sqrt_a),
        (&q::E, o.e, p.e),
        (&q::I0, o.i0, p.i0),
        (&q::OMEGA0, o.omega0, p.omega0),
        (&q::OMEGA, o.omega, p.omega),
        (&q::M0, o.m0, p.m0),
        (&q::DELTA_N, o.delta_n, p.delta_n),
        (&q::IDOT, o.idot, p.idot),
        (&q::OMEGA_DOT, o.omega_dot, p.omega_dot),
        (&q::CUC, h.cuc, g.cuc),
        (&q::CUS, h.cus, g.cus),
        (&q::CRC, h.crc, g.crc),
        (&q::CRS, h.crs, g.crs),
        (&q::CIC, h.cic, g.cic),
        (&q::CIS, h.cis, g.cis),
        (&q::AF0, input.clock.af0, b.clock.af0),
        (&q::AF1, input.clock.af1, b.clock.af1),
        (&q::AF2, input.clock.af2, b.clock.af2),
        (&q::BGD_E1_E5A, bgd_in, b.clock.tgd_s),
        (&q::TOE, 0.0, (b.toe - input.toe).to_seconds()),
        (&q::TOC, 0.0, (b.toc - input.toc).to_seconds()),
    ];
    for (f, a, b) in pairs {
        within_half_lsb(f, a, b);
    }
    assert_eq!((b.iode, b.iodc), (input.iode, input.iode));
    assert_eq!(b.health, input.health & 0b11_1000);
    assert_eq!(b.message, NavMessage::GalileoFnav);
    assert_eq!(b.clock.tgd2_s, 0.0);
}

/// Largest position difference (m) over 4 h from toe.
fn orbit_gap_m(a: &BroadcastEphemeris, b: &BroadcastEphemeris) -> f64 {
    let origin = TimeOrigin::new(a.toe);
    let (ba, bb) = (a.bind(&origin), b.bind(&origin));
    (0..=48)
        .map(|k| f64::from(k) * 300.0)
        .map(|t| (ba.position_ecef(t) - bb.position_ecef(t)).norm())
        .fold(0.0, f64::max)
}

fn check(input: &BroadcastEphemeris) {
    let (decoded, broadcast) = round_trip(input);
    assert_eq!(
        decoded, broadcast,
        "{}: decoded == broadcast_ephemeris()",
        input.sat
    );
    check_quantisation(input, &broadcast);
    assert_eq!(orbit_gap_m(&decoded, &broadcast), 0.0);
    // Quantisation alone moves the orbit by centimetres over 4 h: half an LSB of Delta n
    // or OMEGAdot (pi 2^-44 rad/s) is 2.6e-9 rad after 4 h, 7.6 cm along the orbit at
    // 29 600 km, and half an LSB of sqrt A changes A by 1 cm. Measured: 1-8 cm.
    let gap = orbit_gap_m(input, &broadcast);
    assert!(gap < 0.25, "{}: input vs quantised {gap} m", input.sat);
}

#[test]
fn nominal_constellation_round_trips() {
    let set = nominal::galileo(epoch());
    assert!(set.len() >= 20);
    for eph in set.iter().step_by(5) {
        check(eph);
    }
}

#[test]
fn realistic_sets_round_trip() {
    let t = epoch() + Unit::Hour * 3 + Unit::Minute * 7;
    check(&realistic(19, t));
    // Negative and positive extremes of the signs, an I/NAV set (its BGD(E1,E5a) is
    // tgd2_s), a toe late in the week.
    let mut e = realistic(4, epoch() + Unit::Day * 6 + Unit::Hour * 23);
    e.orbit.m0 = -3.1;
    e.orbit.omega0 = PI - 1e-12;
    e.orbit.omega = 3.0;
    e.clock.af0 = 0.06;
    e.clock.af1 = 5.9e-9;
    e.message = NavMessage::GalileoInav;
    e.clock.tgd_s = 1e-9;
    e.clock.tgd2_s = -3.3e-8;
    e.health = 0b1_1111_1111;
    check(&e);
}

#[test]
fn week_start_is_the_gst_week_and_gps_week_1024_starts_gst_week_0() {
    let enc = encoder(&realistic(3, epoch()));
    assert_eq!(enc.week(), WEEK);
    assert_eq!(
        enc.week_start(),
        Epoch::from_gregorian_hms(2023, 3, 12, 0, 0, 0, hifitime::TimeScale::GST)
    );
    let gst0 = Epoch::from_gregorian_hms(1999, 8, 22, 0, 0, 0, hifitime::TimeScale::GST);
    assert_eq!(super::super::time::gst_epoch(0, 0), gst0);
    assert_eq!(gst0, skyforge_orbits::time::epoch_from_gpst(1024, 0.0));
    assert_eq!(
        skyforge_orbits::time::gpst_week_sow(enc.week_start()),
        (WEEK + 1024, 0.0)
    );
}

#[test]
fn page_1_and_4_parameters_come_back_from_the_pages() {
    let params = FnavParams {
        sisa_index: 107,
        ai0: 85.25,
        ai1: -0.113_281_25,
        ai2: 0.004_5,
        a0_s: -2.1e-9,
        a1_s_s: 3.5e-15,
        dt_ls_s: 18,
        t0t_s: 345_600,
        wn0t: 1229 % 256,
        wn_lsf: 1229 % 256,
        dn: 7,
        dt_lsf_s: 19,
        a0g_s: 4.2e-9,
        a1g_s_s: -1.1e-14,
        t0g_s: 432_000,
        wn0g: 1229 % 64,
    };
    let e = realistic(12, epoch());
    let enc = FnavEncoder::new(&e, &[], &params, WEEK).unwrap();
    let pages = decode_pages(&enc, frame_page_at(&enc, e.toe), 5);
    let get = |name: &str| pages.iter().find_map(|p| p.field(name)).unwrap();
    for (f, v) in params.values(&super::super::quant::SISA) {
        within_half_lsb(f, v, f.si_value(get(f.name)));
    }
    assert_eq!(get("SISA(E1,E5a)"), 107);
    assert_eq!(get("Region 1-5 flags"), 0);
}
