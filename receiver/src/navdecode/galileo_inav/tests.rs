//! The I/NAV decoder on encoder symbols with noise, from mid-page: lock time, timing of
//! every page, the ephemeris, inversion, a lost symbol, a polarity flip, pages without TOW,
//! noise.

use super::super::symbol_test_support::{
    self, UNEVEN, ephemerides, feed, noise, noisy, starts, subframes, sync_counts,
};
use super::super::{NavDecoder, NavEvent, SubframeInfo};
use super::InavDecoder;
use hifitime::{Epoch, TimeScale};
use skyforge_gnss::navmsg::galileo_inav::{InavEncoder, InavParams};
use skyforge_orbits::ephemeris::{SatId, nominal};

const SVID: u8 = 11;
/// GST week of the stream.
const WEEK: u32 = 1229;
/// Symbols per page and per page part.
const P: u64 = 500;
const HALF: u64 = 250;
/// The first symbol fed: 377 symbols before the page that starts at 10:00:05 GST on
/// Sunday (5 s after the toe; pages start at odd seconds), a word type 6, the third page
/// of its subframe. Page starts lie at encoder symbols 250 modulo 500.
const K0: u64 = 36_005 * 250 - 377;
/// Es/N0 (dB) of the test streams: Eb/N0 5.5 dB before decoding.
const ES_N0_DB: f64 = 2.5;
/// Symbols the search needs from its first candidate: a page period of candidates and a
/// page after the last.
const SEARCH_SPAN: u64 = 2 * P;

fn encoder() -> InavEncoder {
    let toe = Epoch::from_gregorian_hms(2023, 3, 12, 10, 0, 0, TimeScale::GST);
    let set = nominal::galileo(toe);
    let eph = set.iter().find(|e| e.sat.prn == SVID).unwrap();
    InavEncoder::new(eph, &set, &InavParams::default(), WEEK).unwrap()
}

fn decoder() -> InavDecoder {
    InavDecoder::new(SatId::galileo(SVID)).unwrap()
}

/// The encoder's page that starts at encoder symbol `k`.
fn page_at(k: u64) -> u64 {
    assert_eq!((k + HALF) % P, 0, "page start {k}");
    (k + HALF) / P
}

/// Each subframe starts on a page boundary of the encoder's stream, stream symbol 0
/// being encoder symbol `k0`, with the page's word type and time and polarity `inverted`;
/// the week is unknown only until a word type 0 or 5 gave it.
fn check(enc: &InavEncoder, subs: &[(u64, SubframeInfo)], k0: u64, inverted: bool) {
    let known = subs.iter().position(|(_, s)| s.week.is_some());
    for (i, (_, s)) in subs.iter().enumerate() {
        let n = page_at(k0 + s.start_bit);
        let (week, tow) = enc.page_time(n);
        let week = known.is_some_and(|k| i >= k).then_some(week);
        assert_eq!((s.week, s.tow_s), (week, f64::from(tow)), "{s:?}");
        assert_eq!(s.id, enc.word_type(n), "{s:?}");
        assert_eq!(s.inverted, inverted, "{s:?}");
        assert_eq!((s.page, s.corrected_bits), (None, 0));
    }
}

/// Stream starts of the pages that begin at or after stream symbol `from` and end within
/// `len` symbols, stream symbol 0 being encoder symbol `k0`.
fn expected_starts(k0: u64, from: u64, len: u64) -> Vec<u64> {
    symbol_test_support::expected_starts(k0 + HALF, from, len, P, P)
}

/// The stream symbol count at which synchronisation was acquired, and where.
fn acquired(events: &[(u64, NavEvent)]) -> (u64, u64, bool) {
    events
        .iter()
        .find_map(|(at, e)| match e {
            NavEvent::SyncAcquired {
                start_bit,
                inverted,
            } => Some((*at, *start_bit, *inverted)),
            _ => None,
        })
        .expect("synchronised")
}

#[test]
fn noisy_stream_from_mid_page_locks_within_two_pages_and_round_trips() {
    let enc = encoder();
    let len = 17 * P;
    let soft = noisy(&enc.symbols(K0, len as usize), ES_N0_DB, false, 11);
    let mut dec = decoder();
    let events = feed(&mut dec, &soft, &UNEVEN);
    // Locked as soon as the search window is in (plus the feeding's granularity).
    let (at, start, inverted) = acquired(&events);
    assert_eq!((start, inverted), (377, false));
    assert!(
        (SEARCH_SPAN..SEARCH_SPAN + 97).contains(&at),
        "locked at {at}"
    );
    let subs = subframes(&events);
    // Word types 6, 7, 8, 0 x 5, 1, 3, 5, 0, 0, 2, 4, 6: every page has a time.
    assert_eq!(starts(&subs), expected_starts(K0, 0, len));
    check(&enc, &subs, K0, false);
    assert!(subs[1..].iter().all(|(at, s)| at - s.start_bit < P + 97));
    // The first page's TOW is its own (word type 6): 10:00:05, an odd second. The week
    // comes with the fourth page, a word type 0.
    assert_eq!((subs[0].1.id, subs[0].1.tow_s), (6, 36_005.0));
    let weeks: Vec<_> = subs[..4].iter().map(|(_, s)| (s.id, s.week)).collect();
    assert_eq!(weeks, [(6, None), (7, None), (8, None), (0, Some(WEEK))]);
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
    let len = 17 * P;
    let soft = noisy(&enc.symbols(K0, len as usize), ES_N0_DB, true, 12);
    let mut dec = decoder();
    let events = feed(&mut dec, &soft, &[1]);
    assert_eq!(acquired(&events), (SEARCH_SPAN, 377, true));
    let subs = subframes(&events);
    assert_eq!(starts(&subs), expected_starts(K0, 0, len));
    check(&enc, &subs, K0, true);
    assert!(subs[1..].iter().all(|(at, s)| at - s.start_bit == P));
    assert_eq!(ephemerides(&events)[0].eph, enc.broadcast_ephemeris());
}

#[test]
fn a_lost_symbol_loses_and_regains_sync() {
    let enc = encoder();
    let len = 16 * P;
    let gap = 2600;
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
    // finds the shifted page at 3376, a word type 0 with its own TOW.
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
    // The word type 6 and 7 pages (to stream symbol 1377), then a restart: the next page,
    // a word type 8, carries no TOW and has none in its lock; the word type 0 after it
    // does.
    let mut events = feed(&mut dec, &soft[..1377], &UNEVEN);
    dec.restart();
    events.extend(feed(&mut dec, &soft[1377..], &UNEVEN));
    let subs = subframes(&events);
    check(&enc, &subs, K0, false);
    let types: Vec<u8> = [377, 877, 1377, 1877]
        .iter()
        .map(|&s| enc.word_type(page_at(K0 + s)))
        .collect();
    assert_eq!(types, [6, 7, 8, 0]);
    let reported: Vec<u64> = expected_starts(K0, 0, len)
        .into_iter()
        .filter(|&s| s != 1377)
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
    assert!(InavDecoder::new(SatId::gps(SVID)).is_err());
    assert!(InavDecoder::new(SatId::galileo(37)).is_err());
}
