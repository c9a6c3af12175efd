//! The B-CNAV2 decoder on encoder symbols with noise, from mid-frame: timing of every
//! frame, the ephemeris, inversion, restart, noise.

use super::super::symbol_test_support::{
    self, UNEVEN, ephemerides, feed, noise, noisy, starts, subframes, sync_counts,
};
use super::super::{NavDecoder, SubframeInfo};
use super::BdsCnav2Decoder;
use hifitime::{Epoch, TimeScale};
use skyforge_gnss::navmsg::BdsCnavParams;
use skyforge_gnss::navmsg::bds_cnav2::BdsCnav2Encoder;
use skyforge_orbits::ephemeris::{BeidouSet, SatId, nominal};
use skyforge_orbits::time::bdt_week_sow;

const PRN: u8 = 23;
/// Symbols per frame.
const M: u64 = 600;
/// The first symbol fed: 217 symbols into frame 12000 of the week (10:00:00 BDT on
/// Sunday, the toe), so the first frame starts at stream symbol 383.
const K0: u64 = 12_000 * M + 217;
/// Es/N0 (dB) of the test streams.
const ES_N0_DB: f64 = 2.5;

fn encoder() -> BdsCnav2Encoder {
    let toe = Epoch::from_gregorian_hms(2023, 3, 12, 10, 0, 0, TimeScale::BDT);
    let eph = nominal::beidou(BeidouSet::Bds3, toe)
        .into_iter()
        .find(|e| e.sat.prn == PRN)
        .unwrap();
    BdsCnav2Encoder::new(&eph, &BdsCnavParams::default(), bdt_week_sow(toe).0).unwrap()
}

fn decoder() -> BdsCnav2Decoder {
    BdsCnav2Decoder::new(SatId::beidou(PRN)).unwrap()
}

/// Each subframe starts on a frame boundary of the encoder's stream, stream symbol 0
/// being encoder symbol `k0`, with the frame's type, time and polarity `inverted`.
fn check(enc: &BdsCnav2Encoder, subs: &[(u64, SubframeInfo)], k0: u64, inverted: bool) {
    for (_, s) in subs {
        let k = k0 + s.start_bit;
        assert_eq!(k % M, 0, "{s:?}");
        let (week, sow) = enc.frame_time(k / M);
        assert_eq!(s.tow_s, f64::from(sow), "{s:?}");
        assert!(s.week.is_none_or(|w| w == week), "{s:?}");
        assert_eq!(s.id, enc.message_type(k / M), "{s:?}");
        assert_eq!(s.inverted, inverted, "{s:?}");
    }
}

fn expected_starts(k0: u64, from: u64, len: u64) -> Vec<u64> {
    symbol_test_support::expected_starts(k0, from, len, M, M)
}

#[test]
fn noisy_stream_from_mid_frame_round_trips() {
    let enc = encoder();
    let len = 10 * M;
    let soft = noisy(&enc.symbols(K0, len as usize), ES_N0_DB, false, 1);
    let mut dec = decoder();
    let events = feed(&mut dec, &soft, &UNEVEN);
    let subs = subframes(&events);
    assert_eq!(starts(&subs), expected_starts(K0, 0, len));
    check(&enc, &subs, K0, false);
    let ephs = ephemerides(&events);
    assert_eq!(ephs.len(), 1);
    assert_eq!(ephs[0].eph, enc.broadcast_ephemeris());
    assert_eq!(sync_counts(&events), (1, 0));
    let stats = dec.stats();
    assert_eq!((stats.bits, stats.subframes), (len, subs.len() as u64));
    assert_eq!((stats.dropped_subframes, stats.sync_losses), (0, 0));
    assert!(dec.is_synchronised());
}

#[test]
fn inverted_stream_decodes_with_inverted_set() {
    let enc = encoder();
    let len = 8 * M;
    let soft = noisy(&enc.symbols(K0, len as usize), ES_N0_DB, true, 2);
    let mut dec = decoder();
    let events = feed(&mut dec, &soft, &[1]);
    let subs = subframes(&events);
    assert_eq!(starts(&subs), expected_starts(K0, 0, len));
    check(&enc, &subs, K0, true);
    assert_eq!(ephemerides(&events)[0].eph, enc.broadcast_ephemeris());
}

#[test]
fn restart_keeps_counting_symbols() {
    let enc = encoder();
    let len = 8 * M;
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
}

#[test]
fn pure_noise_gives_no_frame() {
    let mut dec = decoder();
    let events = feed(&mut dec, &noise(30_000, 6), &UNEVEN);
    assert!(events.is_empty(), "{events:?}");
    assert_eq!(dec.stats().subframes, 0);
}

#[test]
fn non_beidou_satellites_are_refused() {
    assert!(BdsCnav2Decoder::new(SatId::gps(PRN)).is_err());
    assert!(BdsCnav2Decoder::new(SatId::beidou(64)).is_err());
}
