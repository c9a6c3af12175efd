//! GPS LNAV decoding round trip: SkyForge's LNAV encoder (skyforge-signals) makes the bit
//! stream of a known ephemeris; the receiver's decoder, fed the bits from the middle of a
//! subframe and in either polarity, must return every field within the ICD quantisation
//! of the input, exactly the encoder's quantised values, the TOW of every subframe, and
//! the page-18 ionosphere and UTC parameters. A bit error must be caught by parity and
//! its subframe dropped.

mod navdecode_support;

use navdecode_support::{
    Field, assert_same_toe_toc, assert_within_lsb, ephemerides, soft, subframes,
};
use skyforge_gnss::navmsg::gps_lnav::fixtures::{header_iono, real_prn1, utc_week_2190};
use skyforge_gnss::navmsg::gps_lnav::{
    Almanac, GPS_PI, LnavEncoder, SUBFRAMES_PER_WEEK, UtcParams, subframe_index_at,
};
use skyforge_orbits::ephemeris::{BroadcastEphemeris, ClockParams, SatId};
use skyforge_receiver::navdecode::{GpsLnavDecoder, NavDecoder, NavEvent, SUBFRAME_BITS};

/// A realistic ephemeris: GPS PRN 1 of brdc0010.22n, 2022-01-01 ([`real_prn1`]), with a
/// non-zero af2, the signs of af0 and TGD flipped and the PRN/IODC changed to exercise
/// more bits.
fn ephemeris() -> BroadcastEphemeris {
    let real = real_prn1();
    BroadcastEphemeris {
        sat: SatId::gps(27),
        clock: ClockParams {
            af0: -0.469126738608e-3,
            af2: -2.0e-16,
            tgd_s: -0.512227416039e-8,
            tgd2_s: 0.0,
            ..real.clock
        },
        iodc: 256 + 39,
        ..real
    }
}

const URA_INDEX: u8 = 5;

fn encoder(eph: &BroadcastEphemeris) -> LnavEncoder {
    let almanac = Almanac::from_ephemerides(std::slice::from_ref(eph), eph.toe)
        .unwrap_or_else(|e| panic!("{e}"));
    LnavEncoder::new(eph, &almanac, &header_iono(), &utc_week_2190(), URA_INDEX)
        .unwrap_or_else(|e| panic!("{e}"))
}

/// First subframe index at or after `from` that is subframe 4 page 18 (SV ID 56: page
/// 18 of the 25-page cycle that restarts each week, IS-GPS-200 20.3.4.1).
fn page18_subframe(from: u64) -> u64 {
    (from..from + 5 * 25 * 2)
        .find(|k| {
            let in_week = k % SUBFRAMES_PER_WEEK;
            in_week % 5 == 3 && (in_week / 5) % 25 == 17
        })
        .unwrap_or_else(|| panic!("no page 18 after {from}"))
}

/// |decoded - reference| <= tol_lsb x lsb for every broadcast field.
fn compare(decoded: &BroadcastEphemeris, reference: &BroadcastEphemeris, tol_lsb: f64) {
    let p2 = |n: i32| 2f64.powi(n);
    let sc = GPS_PI;
    let fields: [Field; 19] = [
        ("sqrt_a", |e| e.orbit.sqrt_a, p2(-19)),
        ("e", |e| e.orbit.e, p2(-33)),
        ("i0", |e| e.orbit.i0, sc * p2(-31)),
        ("omega0", |e| e.orbit.omega0, sc * p2(-31)),
        ("omega", |e| e.orbit.omega, sc * p2(-31)),
        ("m0", |e| e.orbit.m0, sc * p2(-31)),
        ("delta_n", |e| e.orbit.delta_n, sc * p2(-43)),
        ("idot", |e| e.orbit.idot, sc * p2(-43)),
        ("omega_dot", |e| e.orbit.omega_dot, sc * p2(-43)),
        ("cuc", |e| e.harmonics.cuc, p2(-29)),
        ("cus", |e| e.harmonics.cus, p2(-29)),
        ("cic", |e| e.harmonics.cic, p2(-29)),
        ("cis", |e| e.harmonics.cis, p2(-29)),
        ("crc", |e| e.harmonics.crc, p2(-5)),
        ("crs", |e| e.harmonics.crs, p2(-5)),
        ("af0", |e| e.clock.af0, p2(-31)),
        ("af1", |e| e.clock.af1, p2(-43)),
        ("af2", |e| e.clock.af2, p2(-55)),
        ("tgd", |e| e.clock.tgd_s, p2(-31)),
    ];
    assert_within_lsb(decoded, reference, &fields, tol_lsb);
    assert_same_toe_toc(decoded, reference);
    assert_eq!(
        (
            decoded.sat,
            decoded.class,
            decoded.iode,
            decoded.iodc,
            decoded.health
        ),
        (
            reference.sat,
            reference.class,
            reference.iode,
            reference.iodc,
            reference.health
        )
    );
    assert_eq!(decoded.fit_interval_s, 4.0 * 3600.0, "fit flag 0 is 4 h");
}

/// The bits of subframes `first..first + n`, starting `skip` bits into the first.
fn stream(enc: &LnavEncoder, first: u64, n: usize, skip: usize) -> Vec<u8> {
    enc.bits(first, n)[skip..].to_vec()
}

/// Every subframe event's TOW and week must match the subframe index it came from.
fn check_times(events: &[NavEvent], first_bit: u64) {
    let subframes = subframes(events);
    assert!(!subframes.is_empty());
    for s in subframes {
        let abs = first_bit + s.start_bit;
        assert_eq!(abs % SUBFRAME_BITS as u64, 0, "subframe start on the grid");
        let k = abs / SUBFRAME_BITS as u64;
        assert_eq!(s.tow_s, ((k % SUBFRAMES_PER_WEEK) * 6) as f64, "tow of {k}");
        assert_eq!(u64::from(s.id), k % 5 + 1, "subframe ID");
        if let Some(week) = s.week {
            assert_eq!(u64::from(week), k / SUBFRAMES_PER_WEEK);
        }
    }
}

fn run(invert: bool, chunk: usize) -> (Vec<NavEvent>, GpsLnavDecoder, u64) {
    let eph = ephemeris();
    let enc = encoder(&eph);
    let k0 = subframe_index_at(eph.toe).unwrap_or_else(|e| panic!("{e}"));
    let k18 = page18_subframe(k0);
    let first = k18 - 11;
    let skip = 137;
    let bits = stream(&enc, first, 14, skip);
    let mut dec = GpsLnavDecoder::new(eph.sat).unwrap_or_else(|e| panic!("{e}"));
    let mut events = Vec::new();
    for c in soft(&bits, invert).chunks(chunk) {
        events.extend(dec.feed(c));
    }
    (events, dec, first * SUBFRAME_BITS as u64 + skip as u64)
}

#[test]
fn round_trip_from_mid_subframe_in_both_polarities() {
    let eph = ephemeris();
    let enc = encoder(&eph);
    let quantised = enc.broadcast_ephemeris();
    for invert in [false, true] {
        let (events, dec, first_bit) = run(invert, 300);
        let acquired: Vec<_> = events
            .iter()
            .filter_map(|e| match e {
                NavEvent::SyncAcquired {
                    start_bit,
                    inverted,
                } => Some((*start_bit, *inverted)),
                _ => None,
            })
            .collect();
        assert_eq!(
            acquired,
            [(300 - 137, invert)],
            "one sync at the first preamble"
        );
        check_times(&events, first_bit);
        let ephs = ephemerides(&events);
        assert_eq!(ephs.len(), 1, "one ephemeris, emitted once");
        let d = ephs[0];
        compare(&d.eph, &eph, 0.5 + 1e-9);
        compare(&d.eph, &quantised, 1e-6);
        assert_eq!((d.ura_index, d.tgd2_s), (URA_INDEX, None));
        let iono_utc: Vec<_> = events
            .iter()
            .filter_map(|e| match e {
                NavEvent::GpsIonoUtc { iono, utc } => Some((*iono, *utc)),
                _ => None,
            })
            .collect();
        assert_eq!(iono_utc.len(), 1);
        let (got_iono, got_utc) = iono_utc[0];
        assert_eq!(got_iono, enc.iono());
        // WN_LSF is broadcast on 8 bits: the 2016 event (week 1929) is 261 weeks before
        // week 2190, so only its value modulo 256 survives (IS-GPS-200 20.3.3.5.2.4
        // bounds the difference by 127 weeks only for a scheduled leap second).
        assert_eq!(got_utc.wn_lsf % 256, enc.utc().wn_lsf % 256);
        assert_eq!(
            UtcParams {
                wn_lsf: enc.utc().wn_lsf,
                ..got_utc
            },
            enc.utc()
        );
        // The header values of a real RINEX file lie on the ICD grid, so the quantised
        // broadcast values equal them to their printed digits.
        for (a, b) in enc.iono().alpha.iter().zip(header_iono().alpha) {
            assert!((a - b).abs() <= 1e-4 * b.abs(), "alpha {a} vs {b}");
        }
        assert_eq!(dec.stats().dropped_subframes, 0);
        assert_eq!(dec.stats().subframes, 13);
        assert_eq!(dec.week(), Some(2190));
        assert!(dec.is_synchronised());
    }
}

#[test]
fn toe_in_the_next_week_and_tow_wrap_at_the_week_end() {
    // A set transmitted at the end of week 2190 whose toe (2 h into week 2191) lies in the
    // next week; the HOW count wraps to 0 at the week end.
    let mut eph = ephemeris();
    eph.toe = skyforge_orbits::time::epoch_from_gpst(2191, 7200.0);
    eph.toc = eph.toe;
    let enc = encoder(&eph);
    let week_start = 2191 * SUBFRAMES_PER_WEEK;
    let first = week_start - 8;
    let bits = stream(&enc, first, 16, 29);
    let mut dec = GpsLnavDecoder::new(eph.sat).unwrap_or_else(|e| panic!("{e}"));
    let events = dec.feed(&soft(&bits, true));
    check_times(&events, first * SUBFRAME_BITS as u64 + 29);
    let d = ephemerides(&events)
        .first()
        .copied()
        .unwrap_or_else(|| panic!("no ephemeris: {events:?}"));
    compare(&d.eph, &enc.broadcast_ephemeris(), 1e-6);
    assert_eq!(dec.week(), Some(2191));
}

/// (start bit, TOW) of every decoded subframe.
fn subframe_times(events: &[NavEvent]) -> Vec<(u64, f64)> {
    subframes(events)
        .iter()
        .map(|s| (s.start_bit, s.tow_s))
        .collect()
}

#[test]
fn a_lost_bit_ends_the_lock_and_sync_is_found_again() {
    let eph = ephemeris();
    let enc = encoder(&eph);
    let k0 = subframe_index_at(eph.toe).unwrap_or_else(|e| panic!("{e}"));
    let mut bits = stream(&enc, k0, 20, 0);
    bits.remove(1234); // a bit slip in tracking
    let mut dec = GpsLnavDecoder::new(eph.sat).unwrap_or_else(|e| panic!("{e}"));
    let events = dec.feed(&soft(&bits, false));
    assert!(
        events
            .iter()
            .any(|e| matches!(e, NavEvent::SyncLost { .. }))
    );
    let syncs: Vec<u64> = events
        .iter()
        .filter_map(|e| match e {
            NavEvent::SyncAcquired { start_bit, .. } => Some(*start_bit),
            _ => None,
        })
        .collect();
    assert_eq!(syncs.len(), 2, "{events:?}");
    assert_eq!(syncs[1] % 300, 299, "one bit earlier after the slip");
    for (start, tow) in subframe_times(&events) {
        let abs = if start < 1234 { start } else { start + 1 };
        assert_eq!(tow, (((k0 + abs / 300) % SUBFRAMES_PER_WEEK) * 6) as f64);
    }
    assert!(dec.stats().subframes >= 15, "{:?}", dec.stats());
}

#[test]
fn restart_after_a_gap_resynchronises() {
    let eph = ephemeris();
    let enc = encoder(&eph);
    let k0 = subframe_index_at(eph.toe).unwrap_or_else(|e| panic!("{e}"));
    let bits = stream(&enc, k0, 20, 0);
    let mut dec = GpsLnavDecoder::new(eph.sat).unwrap_or_else(|e| panic!("{e}"));
    let mut events = dec.feed(&soft(&bits[..1000], false));
    dec.restart();
    assert!(!dec.is_synchronised());
    // 1000 bits are missing: the stream continues at message bit 2000.
    events.extend(dec.feed(&soft(&bits[2000..], false)));
    let times = subframe_times(&events);
    assert!(times.iter().any(|&(start, _)| start >= 1000));
    for (start, tow) in times {
        let abs = if start < 1000 { start } else { start + 1000 };
        assert_eq!(tow, (((k0 + abs / 300) % SUBFRAMES_PER_WEEK) * 6) as f64);
    }
    assert!(events.iter().any(|e| matches!(e, NavEvent::Ephemeris(_))));
}

#[test]
fn bit_by_bit_feeding_gives_the_same_events() {
    let (whole, _, _) = run(false, 4200);
    let (single, _, _) = run(false, 1);
    let (odd, _, _) = run(false, 7);
    assert_eq!(whole, single);
    assert_eq!(whole, odd);
}

#[test]
fn parity_errors_drop_the_subframe() {
    let eph = ephemeris();
    let enc = encoder(&eph);
    let k0 = subframe_index_at(eph.toe).unwrap_or_else(|e| panic!("{e}"));
    // Start at a frame start; corrupt word 4 of the first subframe 2 and word 10 of the
    // first subframe 3 (one bit each).
    let first = k0 / 5 * 5 + 5;
    let mut bits = stream(&enc, first, 10, 0);
    bits[300 + 3 * 30 + 11] ^= 1;
    bits[600 + 9 * 30 + 29] ^= 1;
    let mut dec = GpsLnavDecoder::new(eph.sat).unwrap_or_else(|e| panic!("{e}"));
    let events = dec.feed(&soft(&bits, false));
    let dropped: Vec<_> = events
        .iter()
        .filter_map(|e| match e {
            NavEvent::SubframeDropped { start_bit, words } => Some((*start_bit, *words)),
            _ => None,
        })
        .collect();
    // The D30 error of word 10 spoils only its own subframe: word 10 always ends with
    // D29 = D30 = 0 (IS-GPS-200 20.3.5.2), so the next TLM is checked with those values.
    assert_eq!(dropped, [(300, 1 << 3), (600, 1 << 9)]);
    let decoded_starts: Vec<u64> = subframes(&events).iter().map(|s| s.start_bit).collect();
    assert!(!decoded_starts.contains(&300) && !decoded_starts.contains(&600));
    // The second frame completes the ephemeris.
    let eph_at: Vec<_> = events
        .iter()
        .filter(|e| matches!(e, NavEvent::Ephemeris(_)))
        .collect();
    assert_eq!(eph_at.len(), 1);
    assert!(dec.stats().parity_failed_words >= 2);
    assert!(dec.is_synchronised(), "isolated errors keep the lock");
}

#[test]
fn noise_alone_never_yields_a_subframe() {
    use rand::{Rng, SeedableRng};
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(7);
    let bits: Vec<u8> = (0..30_000).map(|_| rng.random_range(0..2u8)).collect();
    let mut dec = GpsLnavDecoder::new(SatId::gps(3)).unwrap_or_else(|e| panic!("{e}"));
    let events = dec.feed(&soft(&bits, false));
    assert!(
        !events.iter().any(|e| matches!(e, NavEvent::Subframe(_))),
        "{events:?}"
    );
}

#[test]
fn wrong_satellites_are_refused() {
    assert!(GpsLnavDecoder::new(SatId::beidou(19)).is_err());
    assert!(GpsLnavDecoder::new(SatId::gps(33)).is_err());
}
