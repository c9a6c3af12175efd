//! The B-CNAV1 decoder on encoder symbols with noise: aligned on a frame start (as the
//! tracking channel hands them on), and searching from mid-frame, inverted.

use super::super::symbol_test_support::{
    UNEVEN, ephemerides, expected_starts, feed, noisy, starts, subframes, sync_counts,
};
use super::super::{NavDecoder, SubframeInfo};
use super::BdsCnav1Decoder;
use hifitime::{Epoch, TimeScale};
use skyforge_gnss::navmsg::BdsCnavParams;
use skyforge_gnss::navmsg::bds_cnav1::BdsCnav1Encoder;
use skyforge_orbits::ephemeris::{BeidouSet, SatId, nominal};
use skyforge_orbits::time::bdt_week_sow;

const PRN: u8 = 30;
/// Symbols per frame.
const M: u64 = 1800;
/// Frame 2000 of the week: 10:00:00 BDT on Sunday, the toe.
const FRAME: u64 = 2000;
/// Es/N0 (dB) of the test streams (the gnss crate's frame test's).
const ES_N0_DB: f64 = 2.5;

fn encoder() -> BdsCnav1Encoder {
    let toe = Epoch::from_gregorian_hms(2023, 3, 12, 10, 0, 0, TimeScale::BDT);
    let eph = nominal::beidou(BeidouSet::Bds3, toe)
        .into_iter()
        .find(|e| e.sat.prn == PRN)
        .unwrap();
    BdsCnav1Encoder::new(&eph, &BdsCnavParams::default(), bdt_week_sow(toe).0).unwrap()
}

/// Each subframe starts on a frame boundary of the encoder's stream (stream symbol 0
/// being encoder symbol `k0`) with that frame's time and polarity `inverted`.
fn check(enc: &BdsCnav1Encoder, subs: &[(u64, SubframeInfo)], k0: u64, inverted: bool) {
    for (_, s) in subs {
        let k = k0 + s.start_bit;
        assert_eq!(k % M, 0, "{s:?}");
        let (week, sow) = enc.frame_time(k / M);
        assert_eq!((s.week, s.tow_s), (Some(week), f64::from(sow)), "{s:?}");
        assert_eq!((s.id, s.inverted), (1, inverted), "{s:?}");
    }
}

/// From a frame start, as the channel feeds it: every frame decoded at its start, locked
/// from symbol 0 (no search, no sync event), one ephemeris, the encoder's.
#[test]
fn an_aligned_stream_decodes_every_frame() {
    let enc = encoder();
    let k0 = FRAME * M;
    let soft = noisy(&enc.symbols(k0, 4 * M as usize), ES_N0_DB, false, 11);
    let mut dec = BdsCnav1Decoder::aligned(SatId::beidou(PRN)).unwrap();
    assert!(dec.is_synchronised());
    let events = feed(&mut dec, &soft, &UNEVEN);
    let subs = subframes(&events);
    assert_eq!(starts(&subs), [0, M, 2 * M, 3 * M]);
    check(&enc, &subs, k0, false);
    assert_eq!(sync_counts(&events), (0, 0));
    let ephs = ephemerides(&events);
    assert_eq!(ephs.len(), 1);
    assert_eq!(ephs[0].eph, enc.broadcast_ephemeris());
    assert_eq!(dec.stats().subframes, 4);
}

/// From 217 symbols into a frame, inverted, on a decoder that does not know the
/// alignment: it finds the frames by the PRN word and reports each once decoded.
#[test]
fn a_search_from_mid_frame_finds_the_inverted_frames() {
    let enc = encoder();
    let k0 = FRAME * M + 217;
    let len = 5 * M;
    let soft = noisy(&enc.symbols(k0, len as usize), ES_N0_DB, true, 12);
    let mut dec = BdsCnav1Decoder::new(SatId::beidou(PRN)).unwrap();
    let events = feed(&mut dec, &soft, &UNEVEN);
    let subs = subframes(&events);
    assert_eq!(starts(&subs), expected_starts(k0, 0, len, M, M));
    check(&enc, &subs, k0, true);
    assert_eq!(sync_counts(&events), (1, 0));
    assert!(dec.is_synchronised());
    assert!(BdsCnav1Decoder::new(SatId::gps(3)).is_err());
}
