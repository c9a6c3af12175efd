//! The CNAV decoder on encoder symbols with noise, from mid-message: timing of every
//! message, the ephemeris, inversion, a lost symbol, a polarity flip, restart, noise.

use super::super::symbol_test_support::{
    self, UNEVEN, ephemerides, feed, noise, noisy, starts, subframes, sync_counts,
};
use super::super::{NavDecoder, NavEvent, SubframeInfo};
use super::CnavDecoder;
use hifitime::{Epoch, TimeScale};
use skyforge_gnss::navmsg::gps_cnav::{CnavEncoder, CnavParams};
use skyforge_orbits::ephemeris::{SatId, nominal};

const PRN: u8 = 7;
/// GPS week of the stream.
const WEEK: u32 = 2253;
/// Symbols per message.
const M: u64 = 600;
/// The first symbol fed: 317 symbols into message 6000 of the week (10:00:00 GPST on
/// Sunday, the toe), so the first message starts at stream symbol 283.
const K0: u64 = 6000 * M + 317;
/// Es/N0 (dB) of the test streams: Eb/N0 5.5 dB before decoding.
const ES_N0_DB: f64 = 2.5;
/// Symbols from a message's start to the end of its lead-out: when it is reported.
const REPORT_AFTER: u64 = 670;

fn encoder() -> CnavEncoder {
    let toe = Epoch::from_gregorian_hms(2023, 3, 12, 10, 0, 0, TimeScale::GPST);
    let eph = nominal::gps(toe)
        .into_iter()
        .find(|e| e.sat.prn == PRN)
        .unwrap();
    CnavEncoder::new(&eph, &CnavParams::default(), WEEK).unwrap()
}

fn decoder() -> CnavDecoder {
    CnavDecoder::new(SatId::gps(PRN)).unwrap()
}

/// Each subframe starts on a message boundary of the encoder's stream, stream symbol 0
/// being encoder symbol `k0`, with the message's type and time and polarity `inverted`.
fn check(enc: &CnavEncoder, subs: &[(u64, SubframeInfo)], k0: u64, inverted: bool) {
    for (_, s) in subs {
        let k = k0 + s.start_bit;
        assert_eq!(k % M, 0, "{s:?}");
        let (week, tow) = enc.message_time(k / M);
        assert_eq!(s.tow_s, f64::from(tow), "{s:?}");
        assert!(s.week.is_none_or(|w| w == week), "{s:?}");
        assert_eq!(s.id, enc.message_type(k / M), "{s:?}");
        assert_eq!(s.inverted, inverted, "{s:?}");
        assert_eq!((s.page, s.corrected_bits), (None, 0));
    }
}

/// Stream starts of the messages that begin at or after stream symbol `from` and whose
/// lead-out ends within `len` symbols, stream symbol 0 being encoder symbol `k0`.
fn expected_starts(k0: u64, from: u64, len: u64) -> Vec<u64> {
    symbol_test_support::expected_starts(k0, from, len, M, REPORT_AFTER)
}

#[test]
fn noisy_stream_from_mid_message_round_trips() {
    let enc = encoder();
    let len = 10 * M;
    let soft = noisy(&enc.symbols(K0, len as usize), ES_N0_DB, false, 1);
    let mut dec = decoder();
    let events = feed(&mut dec, &soft, &UNEVEN);
    let subs = subframes(&events);
    assert_eq!(starts(&subs), expected_starts(K0, 0, len));
    check(&enc, &subs, K0, false);
    // The week comes with the first type 10 and stays.
    let first10 = subs.iter().position(|(_, s)| s.id == 10).unwrap();
    assert!(subs[..first10].iter().all(|(_, s)| s.week.is_none()));
    assert!(subs[first10..].iter().all(|(_, s)| s.week == Some(WEEK)));
    // Locked, a message comes out as soon as its lead-out is in (chunks up to 97).
    assert!(subs[1..].iter().all(|(at, s)| at - s.start_bit < 700 + 97));
    let ephs = ephemerides(&events);
    assert_eq!(ephs.len(), 1);
    assert_eq!(ephs[0].eph, enc.broadcast_ephemeris());
    assert_eq!(ephs[0].tgd2_s, None);
    assert_eq!(sync_counts(&events), (1, 0));
    let stats = dec.stats();
    assert_eq!(stats.bits, len);
    assert_eq!(stats.subframes, subs.len() as u64);
    assert_eq!((stats.dropped_subframes, stats.sync_losses), (0, 0));
    assert!(dec.is_synchronised());
}

#[test]
fn inverted_stream_fed_symbol_by_symbol_decodes_with_inverted_set() {
    let enc = encoder();
    let len = 10 * M;
    let soft = noisy(&enc.symbols(K0, len as usize), ES_N0_DB, true, 2);
    let mut dec = decoder();
    let events = feed(&mut dec, &soft, &[1]);
    let subs = subframes(&events);
    assert_eq!(starts(&subs), expected_starts(K0, 0, len));
    check(&enc, &subs, K0, true);
    assert!(
        subs[1..]
            .iter()
            .all(|(at, s)| at - s.start_bit == REPORT_AFTER)
    );
    assert!(matches!(
        events[0].1,
        NavEvent::SyncAcquired {
            start_bit: 283,
            inverted: true
        }
    ));
    assert_eq!(ephemerides(&events)[0].eph, enc.broadcast_ephemeris());
}

#[test]
fn a_lost_symbol_loses_and_regains_sync() {
    let enc = encoder();
    let len = 16 * M;
    let gap = 2500;
    let mut symbols = enc.symbols(K0, len as usize + 1);
    symbols.remove(gap as usize);
    let soft = noisy(&symbols, ES_N0_DB, false, 3);
    let mut dec = decoder();
    let events = feed(&mut dec, &soft, &UNEVEN);
    let subs = subframes(&events);
    let (before, after): (Vec<_>, Vec<_>) = subs.iter().partition(|(_, s)| s.start_bit < gap);
    // From the gap on, stream symbol i is encoder symbol K0 + i + 1.
    check(&enc, &before, K0, false);
    check(&enc, &after, K0 + 1, false);
    assert_eq!(starts(&before), [283, 883, 1483]);
    // Three failures (2083, 2683, 3283 - 1 being a message again), then the search
    // from 8 symbols before the third finds the shifted message.
    let lost = events.iter().find_map(|(_, e)| match e {
        NavEvent::SyncLost { at_bit } => Some(*at_bit),
        _ => None,
    });
    assert_eq!(lost, Some(3283));
    assert_eq!(starts(&after), expected_starts(K0 + 1, 3200, len));
    assert_eq!(sync_counts(&events), (2, 1));
    let stats = dec.stats();
    assert_eq!((stats.dropped_subframes, stats.sync_losses), (3, 1));
    assert_eq!(stats.subframes, subs.len() as u64);
}

#[test]
fn a_half_cycle_slip_flips_the_polarity_without_losing_sync() {
    let enc = encoder();
    let len = 10 * M;
    let mut soft = noisy(&enc.symbols(K0, len as usize), ES_N0_DB, false, 4);
    soft[3000..].iter_mut().for_each(|x| *x = -*x);
    let mut dec = decoder();
    let events = feed(&mut dec, &soft, &UNEVEN);
    let subs = subframes(&events);
    let (before, after): (Vec<_>, Vec<_>) = subs.iter().partition(|(_, s)| s.start_bit < 3000);
    check(&enc, &before, K0, false);
    check(&enc, &after, K0, true);
    // Only the message holding the flip (2683) is lost.
    let all = expected_starts(K0, 0, len);
    assert_eq!(
        starts(&subs),
        all.iter()
            .copied()
            .filter(|&s| s != 2683)
            .collect::<Vec<_>>()
    );
    assert_eq!(sync_counts(&events), (1, 0));
    assert_eq!(dec.stats().dropped_subframes, 1);
}

#[test]
fn restart_keeps_counting_symbols() {
    let enc = encoder();
    let len = 10 * M;
    let soft = noisy(&enc.symbols(K0, len as usize), ES_N0_DB, false, 5);
    let mut dec = decoder();
    let mut events = feed(&mut dec, &soft[..2000], &UNEVEN);
    dec.restart();
    assert!(!dec.is_synchronised());
    events.extend(feed(&mut dec, &soft[2000..], &UNEVEN));
    let subs = subframes(&events);
    check(&enc, &subs, K0, false);
    let later: Vec<_> = subs
        .iter()
        .filter(|(_, s)| s.start_bit >= 2000)
        .copied()
        .collect();
    assert_eq!(starts(&later), expected_starts(K0, 2000, len));
    assert_eq!(sync_counts(&events), (2, 0));
    assert_eq!(dec.stats().bits, len);
}

#[test]
fn pure_noise_gives_no_message() {
    let mut dec = decoder();
    let events = feed(&mut dec, &noise(30_000, 6), &UNEVEN);
    assert!(events.is_empty(), "{events:?}");
    let stats = dec.stats();
    assert_eq!((stats.bits, stats.subframes), (30_000, 0));
}

#[test]
fn non_gps_satellites_are_refused() {
    assert!(CnavDecoder::new(SatId::galileo(PRN)).is_err());
    assert!(CnavDecoder::new(SatId::gps(33)).is_err());
}
