//! B-CNAV2 frames: structure (preamble, CRC, LDPC codeword), timing, the schedule, field
//! values, noiseless decoding and the assembly of the ephemeris, and the refusals.

use super::*;
use crate::navmsg::A_REF_MEO_M;
use crate::navmsg::field::read_fields;
use hifitime::TimeScale;
use skyforge_orbits::ephemeris::BeidouSet;
use skyforge_orbits::ephemeris::nominal;
use skyforge_orbits::time::bdt_week_sow;
use std::f64::consts::PI;

/// A BDS-3 MEO (19) or IGSO (38) nominal ephemeris with toe = toc at 10:00 BDT.
fn eph(prn: u8) -> BroadcastEphemeris {
    let toe = Epoch::from_gregorian_hms(2023, 3, 12, 10, 0, 0, TimeScale::BDT);
    let mut e = nominal::beidou(BeidouSet::Bds3, toe)
        .into_iter()
        .find(|e| e.sat.prn == prn)
        .unwrap();
    e.iode = 37;
    e.clock.af0 = 1.5e-4;
    e.clock.af1 = -2.0e-11;
    e
}

fn encoder(prn: u8) -> BdsCnav2Encoder {
    let e = eph(prn);
    let week = bdt_week_sow(e.toe).0;
    let params = BdsCnavParams {
        tgd_b2ap_s: -3.1e-9,
        isc_b2ad_s: 0.4e-9,
        ..Default::default()
    };
    BdsCnav2Encoder::new(&e, &params, week).unwrap()
}

/// Soft symbols of 0/1 symbols (0 -> +1), without noise.
fn soft(symbols: &[u8]) -> Vec<f32> {
    symbols.iter().map(|&s| 1.0 - 2.0 * f32::from(s)).collect()
}

#[test]
fn a_frame_is_preamble_then_an_ldpc_codeword_of_bits_with_a_crc() {
    let enc = encoder(19);
    for n in 0..4 {
        let bits = enc.frame_bits(n);
        assert_eq!(bits.len(), 288);
        assert_eq!(crc24q_bits(&bits), 0);
        let symbols = enc.frame_symbols(n);
        assert_eq!(symbols.len(), CNAV2_FRAME_SYMBOLS);
        let pre = symbols[..24]
            .iter()
            .fold(0u32, |a, &b| (a << 1) | u32::from(b));
        assert_eq!(pre, 0xE2_4DE8);
        assert!(B2A_FRAME.is_codeword(&symbols[24..]));
        assert_eq!(symbols[24..24 + 288], bits[..]);
    }
    assert_eq!(enc.symbols(590, 20), enc.symbols(0, 1200)[590..610]);
    for k in [0, 23, 599, 600, 1234] {
        assert_eq!(enc.symbol(k), enc.symbols(k, 1)[0], "symbol {k}");
    }
    // Symbol 0 at the start of the encoder's BDT week.
    assert_eq!(
        enc.week_start(),
        skyforge_orbits::time::epoch_from_bdt(enc.week(), 0.0)
    );
    assert_eq!(bdt_week_sow(enc.week_start()), (enc.week(), 0.0));
}

#[test]
fn header_carries_prn_type_and_sow_of_the_schedule() {
    let enc = encoder(19);
    let n = 1201; // 3603 s into the week: a type 11.
    let bits = enc.frame_bits(n);
    let h = read_fields(&bits, &layout::HEADER);
    assert_eq!(h, [19, 11, 1201]);
    assert_eq!(enc.frame_time(n), (enc.week(), 3603));
    assert_eq!(
        (0..8).map(|n| enc.message_type(n)).collect::<Vec<_>>(),
        [10, 11, 30, 34, 10, 11, 30, 34]
    );
    assert_eq!(enc.frame_time(201_600), (enc.week() + 1, 0));
}

#[test]
fn type_10_fields_are_the_quantised_ephemeris() {
    let enc = encoder(19);
    let e = eph(19);
    let msg = decode_frame(&soft(&enc.frame_symbols(0))).unwrap();
    assert_eq!((msg.prn, msg.mes_type, msg.sow_s), (19, 10, 0));
    assert_eq!(msg.field("WN"), Some(i64::from(enc.week() % 8192)));
    assert_eq!(msg.field("IODE"), Some(37));
    assert_eq!(msg.field("toe"), Some(36_000 / 300));
    assert_eq!(msg.field("SatType"), Some(3));
    let a = e.orbit.sqrt_a * e.orbit.sqrt_a;
    let delta_a = ((a - A_REF_MEO_M) * 512.0).round() as i64;
    assert_eq!(msg.field("Delta A"), Some(delta_a));
    let e_raw = (e.orbit.e * 2f64.powi(34)).round() as i64;
    assert_eq!(msg.field("e"), Some(e_raw));
    assert_eq!(
        (msg.field("A dot"), msg.field("Delta n0 dot")),
        (Some(0), Some(0))
    );
    let m0 = (e.orbit.m0 / PI * 2f64.powi(32)).round() as i64;
    assert_eq!(msg.field("M0"), Some(m0));
    assert_eq!(msg.field("a0"), None);
}

#[test]
fn decoded_types_10_11_30_give_the_broadcast_ephemeris() {
    for prn in [19, 38] {
        let enc = encoder(prn);
        let mut asm = Cnav2Assembler::new(SatId::beidou(prn));
        let mut got = None;
        // From a type 30 on: the first 10/11 pair completes the set at frame 6.
        for n in 2..7 {
            let msg = decode_frame(&soft(&enc.frame_symbols(n))).unwrap();
            got = asm.push(&msg).or(got);
            assert_eq!(got.is_some(), n >= 5, "frame {n}");
        }
        let b = enc.broadcast_ephemeris();
        assert_eq!(got.unwrap(), b);
        assert_eq!(asm.week(), Some(enc.week()));
        assert_eq!((b.iode, b.iodc), (37, 37));
        assert!((b.clock.tgd_s + 3.1e-9).abs() < 2f64.powi(-35));
        let e = eph(prn);
        assert!((b.orbit.sqrt_a - e.orbit.sqrt_a).abs() < 1e-6);
        assert!((b.orbit.omega_dot - e.orbit.omega_dot).abs() < PI * 2f64.powi(-44));
    }
}

#[test]
fn inverted_or_corrupt_frames_are_refused() {
    let enc = encoder(19);
    let good = soft(&enc.frame_symbols(0));
    let inverted: Vec<f32> = good.iter().map(|x| -x).collect();
    assert_eq!(
        decode_frame(&inverted),
        Err(Cnav2DecodeError::Preamble { inverted: true })
    );
    assert_eq!(decode_frame(&good[1..]), Err(Cnav2DecodeError::Length(599)));
    // A valid codeword of other bits: the CRC catches it.
    let mut bits = enc.frame_bits(0);
    bits[40] ^= 1;
    let mut symbols = enc.frame_symbols(0)[..24].to_vec();
    symbols.extend(B2A_FRAME.encode_bits(&bits));
    assert_eq!(decode_frame(&soft(&symbols)), Err(Cnav2DecodeError::Crc));
}

#[test]
fn geo_and_non_beidou_sets_are_refused() {
    let toe = Epoch::from_gregorian_hms(2023, 3, 12, 10, 0, 0, TimeScale::BDT);
    let geo = nominal::beidou(BeidouSet::Bds3, toe)
        .into_iter()
        .find(|e| e.sat.prn == 59)
        .unwrap();
    assert!(matches!(
        BdsCnav2Encoder::new(&geo, &BdsCnavParams::default(), 0),
        Err(BdsCnavError::NotMeoIgso { .. })
    ));
    let mut off = eph(19);
    off.toe += hifitime::Duration::from_seconds(1.0);
    assert!(matches!(
        BdsCnav2Encoder::new(&off, &BdsCnavParams::default(), 0),
        Err(BdsCnavError::OffGrid { field: "toe", .. })
    ));
}
