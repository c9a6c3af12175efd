//! The F/NAV decoder on encoder symbols with noise, from mid-page: timing of every page,
//! the ephemeris, inversion, a lost symbol, a polarity flip, pages without TOW, noise.

use super::super::symbol_test_support::{
    self, UNEVEN, ephemerides, feed, noise, noisy, starts, subframes, sync_counts,
};
use super::super::{NavDecoder, NavEvent, SubframeInfo};
use super::FnavDecoder;
use hifitime::{Epoch, TimeScale};
use skyforge_gnss::navmsg::galileo_fnav::{FnavEncoder, FnavParams};
use skyforge_orbits::ephemeris::{SatId, nominal};

const SVID: u8 = 11;
/// GST week of the stream.
const WEEK: u32 = 1229;
/// Symbols per page.
const P: u64 = 500;
/// The first symbol fed: 123 symbols into page 3600 of the week (10:00:00 GST on
/// Sunday, the toe, a page type 1), so the first page (type 2) starts at stream symbol 377.
const K0: u64 = 3600 * P + 123;
/// Es/N0 (dB) of the test streams: Eb/N0 5.5 dB before decoding.
const ES_N0_DB: f64 = 2.5;

fn encoder() -> FnavEncoder {
    let toe = Epoch::from_gregorian_hms(2023, 3, 12, 10, 0, 0, TimeScale::GST);
    let set = nominal::galileo(toe);
    let eph = set.iter().find(|e| e.sat.prn == SVID).unwrap();
    FnavEncoder::new(eph, &set, &FnavParams::default(), WEEK).unwrap()
}

fn decoder() -> FnavDecoder {
    FnavDecoder::new(SatId::galileo(SVID)).unwrap()
}

/// Each subframe starts on a page boundary of the encoder's stream, stream symbol 0
/// being encoder symbol `k0`, with the page's type and time and polarity `inverted`.
fn check(enc: &FnavEncoder, subs: &[(u64, SubframeInfo)], k0: u64, inverted: bool) {
    for (_, s) in subs {
        let k = k0 + s.start_bit;
        assert_eq!(k % P, 0, "{s:?}");
        let (week, tow) = enc.page_time(k / P);
        assert_eq!((s.week, s.tow_s), (Some(week), f64::from(tow)), "{s:?}");
        assert_eq!(s.id, enc.page_type(k / P), "{s:?}");
        assert_eq!(s.inverted, inverted, "{s:?}");
        assert_eq!((s.page, s.corrected_bits), (None, 0));
    }
}

/// Stream starts of the pages that begin at or after stream symbol `from` and end within
/// `len` symbols, stream symbol 0 being encoder symbol `k0`.
fn expected_starts(k0: u64, from: u64, len: u64) -> Vec<u64> {
    symbol_test_support::expected_starts(k0, from, len, P, P)
}

#[test]
fn noisy_stream_from_mid_page_round_trips() {
    let enc = encoder();
    let len = 14 * P;
    let soft = noisy(&enc.symbols(K0, len as usize), ES_N0_DB, false, 11);
    let mut dec = decoder();
    let events = feed(&mut dec, &soft, &UNEVEN);
    let subs = subframes(&events);
    // Types 2, 3, 4, 5, 1, 2, 3, 4, 6, 1, ...: 5 and 6 timed from the page before.
    assert_eq!(starts(&subs), expected_starts(K0, 0, len));
    assert!([5, 6].iter().all(|t| subs.iter().any(|(_, s)| s.id == *t)));
    check(&enc, &subs, K0, false);
    assert!(subs[1..].iter().all(|(at, s)| at - s.start_bit < P + 97));
    let ephs = ephemerides(&events);
    assert_eq!(ephs.len(), 1);
    assert_eq!(ephs[0].eph, enc.broadcast_ephemeris());
    assert_eq!((ephs[0].ura_index, ephs[0].tgd2_s), (0, None));
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
    let len = 14 * P;
    let soft = noisy(&enc.symbols(K0, len as usize), ES_N0_DB, true, 12);
    let mut dec = decoder();
    let events = feed(&mut dec, &soft, &[1]);
    let subs = subframes(&events);
    assert_eq!(starts(&subs), expected_starts(K0, 0, len));
    check(&enc, &subs, K0, true);
    assert!(subs[1..].iter().all(|(at, s)| at - s.start_bit == P));
    assert!(matches!(
        events[0].1,
        NavEvent::SyncAcquired {
            start_bit: 377,
            inverted: true
        }
    ));
    assert_eq!(ephemerides(&events)[0].eph, enc.broadcast_ephemeris());
}

#[test]
fn a_lost_symbol_loses_and_regains_sync() {
    let enc = encoder();
    let len = 16 * P;
    let gap = 2500;
    let mut symbols = enc.symbols(K0, len as usize + 1);
    symbols.remove(gap as usize);
    let soft = noisy(&symbols, ES_N0_DB, false, 13);
    let mut dec = decoder();
    let events = feed(&mut dec, &soft, &UNEVEN);
    let subs = subframes(&events);
    let (before, after): (Vec<_>, Vec<_>) = subs.iter().partition(|(_, s)| s.start_bit < gap);
    // From the gap on, stream symbol i is encoder symbol K0 + i + 1.
    check(&enc, &before, K0, false);
    check(&enc, &after, K0 + 1, false);
    assert_eq!(starts(&before), [377, 877, 1377, 1877]);
    // Three failures (2377, 2877, 3377), then the search from 8 symbols before the third
    // finds the shifted page at 3376.
    let lost = events.iter().find_map(|(_, e)| match e {
        NavEvent::SyncLost { at_bit } => Some(*at_bit),
        _ => None,
    });
    assert_eq!(lost, Some(3377));
    assert_eq!(starts(&after), expected_starts(K0 + 1, 3300, len));
    assert_eq!(sync_counts(&events), (2, 1));
    let stats = dec.stats();
    assert_eq!((stats.dropped_subframes, stats.sync_losses), (3, 1));
}

#[test]
fn a_half_cycle_slip_flips_the_polarity_without_losing_sync() {
    let enc = encoder();
    let len = 12 * P;
    let mut soft = noisy(&enc.symbols(K0, len as usize), ES_N0_DB, false, 14);
    soft[3000..].iter_mut().for_each(|x| *x = -*x);
    let mut dec = decoder();
    let events = feed(&mut dec, &soft, &UNEVEN);
    let subs = subframes(&events);
    let (before, after): (Vec<_>, Vec<_>) = subs.iter().partition(|(_, s)| s.start_bit < 3000);
    check(&enc, &before, K0, false);
    check(&enc, &after, K0, true);
    // Only the page holding the flip (2877) is lost.
    let all = expected_starts(K0, 0, len);
    let kept: Vec<u64> = all.into_iter().filter(|&s| s != 2877).collect();
    assert_eq!(starts(&subs), kept);
    assert_eq!(sync_counts(&events), (1, 0));
    assert_eq!(dec.stats().dropped_subframes, 1);
}

#[test]
fn a_page_without_tow_is_reported_only_after_a_timed_page_of_the_lock() {
    let enc = encoder();
    let len = 8 * P;
    let soft = noisy(&enc.symbols(K0, len as usize), ES_N0_DB, false, 15);
    let mut dec = decoder();
    // Pages 2, 3, 4 (to stream symbol 1877), then a restart: the next page, a type 5,
    // has no TOW of its own and none in its lock.
    let mut events = feed(&mut dec, &soft[..1877], &UNEVEN);
    dec.restart();
    events.extend(feed(&mut dec, &soft[1877..], &UNEVEN));
    let subs = subframes(&events);
    check(&enc, &subs, K0, false);
    assert_eq!(enc.page_type((K0 + 1877) / P), 5);
    let reported: Vec<u64> = expected_starts(K0, 0, len)
        .into_iter()
        .filter(|&s| s != 1877)
        .collect();
    assert_eq!(starts(&subs), reported);
    assert_eq!(dec.stats().subframes, subs.len() as u64 + 1);
    assert_eq!(sync_counts(&events), (2, 0));
}

#[test]
fn pure_noise_gives_no_page() {
    let mut dec = decoder();
    let events = feed(&mut dec, &noise(20_000, 16), &UNEVEN);
    assert!(events.is_empty(), "{events:?}");
    let stats = dec.stats();
    assert_eq!((stats.bits, stats.subframes), (20_000, 0));
}

#[test]
fn non_galileo_satellites_are_refused() {
    assert!(FnavDecoder::new(SatId::gps(SVID)).is_err());
    assert!(FnavDecoder::new(SatId::galileo(37)).is_err());
}
