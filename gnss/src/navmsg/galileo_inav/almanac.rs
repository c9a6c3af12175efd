//! Almanac word types 7-10 (Galileo OS SIS ICD Issue 2.1 §4.3.5, §5.1.10).
//!
//! Words 7 to 10 carry the almanacs of three satellites (SVID1 in 7 and 8, SVID2 in 8 and
//! 9, SVID3 in 9 and 10), so the 24 subframes of a frame, 7 and 8 in one and 9 and 10 in
//! the next, carry 36. The reference (t0a, WNa, IODa), the choice of satellites, their
//! propagation to t0a and an empty slot's zeros are F/NAV's (`galileo_fnav::almanac`);
//! I/NAV adds each satellite's E5bHS and E1BHS.

use super::eph::health_bits;
use crate::navmsg::galileo_fnav::almanac::{reference, satellites, t0a_epoch, to_ephemeris};
use hifitime::Epoch;
use skyforge_orbits::ephemeris::{BroadcastEphemeris, NavMessage};

/// One satellite's raw almanac in `words::ALMANAC_SAT` order.
type Sat = [i64; 12];

/// The raw values of words 7, 8, 9 and 10 for each triple of satellites, one per layout
/// field (reserved and spare bits 0), word 10 closed by the raw GST-GPS parameters
/// `gst_gps`; at least one triple.
pub(super) fn words(set: &[BroadcastEphemeris], toe: Epoch, gst_gps: &[i64]) -> Vec<[Vec<i64>; 4]> {
    let (head, t0a) = reference(toe);
    let sats: Vec<Sat> = satellites(set, t0a)
        .into_iter()
        .map(|(raw, e)| {
            let mut sat = [0; 12];
            sat[..10].copy_from_slice(&raw);
            sat[10] = i64::from((e.health >> 7) & 3);
            sat[11] = i64::from((e.health >> 1) & 3);
            sat
        })
        .collect();
    let mut triples: Vec<[Sat; 3]> = sats
        .chunks(3)
        .map(|c| std::array::from_fn(|i| c.get(i).copied().unwrap_or([0; 12])))
        .collect();
    if triples.is_empty() {
        triples.push([[0; 12]; 3]);
    }
    triples
        .iter()
        .map(|[s1, s2, s3]| {
            let [ioda, wna, t0a] = head;
            [
                [&[ioda, wna, t0a], &s1[..8], &[0]].concat(),
                [&[ioda], &s1[8..], &s2[..7], &[0]].concat(),
                [&[ioda, wna, t0a], &s2[7..], &s3[..5]].concat(),
                [&[ioda], &s3[5..], gst_gps].concat(),
            ]
        })
        .collect()
}

/// The almanac sets of received words 7, 8, 9 and 10 (raw values in layout order) of one
/// IODa; `now` resolves WNa (2 bits) to the nearest week. Empty slots (SVID 0) and SVIDs
/// above 36 are skipped.
pub(super) fn decode(w: [&[i64]; 4], now: Epoch) -> Vec<BroadcastEphemeris> {
    let [w7, w8, w9, w10] = w;
    let lengths = [w7.len(), w8.len(), w9.len(), w10.len()];
    if lengths != [12, 13, 13, 12] || [w8[0], w9[0], w10[0]].iter().any(|&i| i != w7[0]) {
        return Vec::new();
    }
    let t0a = t0a_epoch(w7[1], w7[2], now);
    let s1 = [&w7[3..11], &w8[1..5]].concat();
    let s2 = [&w8[5..12], &w9[3..8]].concat();
    let s3 = [&w9[8..13], &w10[1..8]].concat();
    [s1, s2, s3]
        .iter()
        .filter_map(|raw| {
            let health = health_bits(raw[11], 0, raw[10], 0);
            to_ephemeris(&raw[..10], t0a, NavMessage::GalileoInav, health)
        })
        .collect()
}
