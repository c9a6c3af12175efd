//! Frame structure: preamble, FraID, SOW, page schedules, error correction, the bit
//! stream and week roll-over; input errors.

use super::super::test_decoder::{bch_correct, deinterleave, header, read_u};
use super::logical;
use crate::navmsg::bds::{BdsNavEncoder, BdsNavError, BdsNavFormat, Klobuchar};
use proptest::prelude::*;
use skyforge_orbits::ephemeris::BeidouSet;
use skyforge_orbits::ephemeris::{BroadcastEphemeris, OrbitClass, SatId, nominal};
use skyforge_orbits::time::epoch_from_bdt;

const WEEK: u32 = 1000;

fn constellation() -> Vec<BroadcastEphemeris> {
    nominal::beidou(BeidouSet::Bds3, epoch_from_bdt(WEEK, 345_600.0))
}

fn encoder(prn: u8) -> BdsNavEncoder {
    let set = constellation();
    let eph = set
        .iter()
        .find(|e| e.sat.prn == prn)
        .expect("PRN in the set");
    BdsNavEncoder::new(eph, &Klobuchar::default(), &set, WEEK).expect("nominal set encodes")
}

#[test]
fn d1_header_fraid_sow_and_pages() {
    let enc = encoder(19);
    assert_eq!(enc.format(), BdsNavFormat::D1);
    // Two superframes, starting mid-week.
    let first = 50_000u64;
    for k in first..first + 2 * 24 * 5 {
        let b = logical(&enc, k);
        let (pre, rev, fra_id, sow) = header(&b);
        assert_eq!((pre, rev), (0b111_0001_0010, 0));
        assert_eq!(fra_id, k % 5 + 1);
        assert_eq!(sow, 6 * k, "+6 s per subframe");
        if fra_id >= 4 {
            assert_eq!(read_u(&b, &[(44, 7)]), (k / 5) % 24 + 1, "page number");
        }
        if fra_id == 1 {
            assert_eq!(read_u(&b, &[(61, 13)]), u64::from(WEEK));
        }
    }
}

#[test]
fn d2_header_sow_and_page_numbering() {
    let enc = encoder(59);
    assert_eq!(enc.format(), BdsNavFormat::D2);
    let first_frame = 100_000u64;
    for frame in first_frame..first_frame + 2 * 120 {
        for sub in 0..5u64 {
            let b = logical(&enc, frame * 5 + sub);
            let (pre, _, fra_id, sow) = header(&b);
            assert_eq!(pre, 0b111_0001_0010);
            assert_eq!(fra_id, sub + 1);
            assert_eq!(sow, 3 * frame, "SOW of the frame, +3 s per frame");
            match fra_id {
                1 => assert_eq!(read_u(&b, &[(43, 4)]), frame % 10 + 1, "pages 1-10"),
                2 => assert_eq!(read_u(&b, &[(44, 4)]), frame % 6 + 1),
                5 => assert_eq!(read_u(&b, &[(44, 7)]), frame % 120 + 1),
                _ => {}
            }
        }
    }
}

#[test]
fn week_roll_over_moves_wn_and_restarts_sow() {
    let enc = encoder(19);
    let per_week = 604_800 / 6;
    let b = logical(&enc, per_week);
    assert_eq!(header(&b).3, 0);
    assert_eq!(read_u(&b, &[(61, 13)]), u64::from(WEEK) + 1);
    let geo = encoder(60);
    let b = logical(&geo, 604_800 * 5 / 3);
    assert_eq!(header(&b).2, 1);
    assert_eq!(header(&b).3, 0);
    assert_eq!(read_u(&b, &[(65, 13)]), u64::from(WEEK) + 1);
}

#[test]
fn bit_stream_follows_the_subframes() {
    for prn in [19, 59] {
        let enc = encoder(prn);
        let first_bit = 3_000_000 * 300 + 250;
        let bits = enc.bits(first_bit, 400);
        let (a, b) = (enc.subframe(3_000_000), enc.subframe(3_000_001));
        let bit = |w: &[u32; 10], i: usize| ((w[i / 30] >> (29 - i % 30)) & 1) as u8;
        let expected: Vec<u8> = (250..300)
            .map(|i| bit(&a, i))
            .chain((0..300).map(|i| bit(&b, i)))
            .chain((0..50).map(|i| bit(&enc.subframe(3_000_002), i)))
            .collect();
        assert_eq!(bits, expected);
        let period_ns = (enc.format().bit_period_s() * 1e9).round() as i64;
        let t = enc.week_start()
            + hifitime::Duration::from_total_nanoseconds(i128::from(period_ns) * 1000 + 1);
        assert_eq!(enc.bit_index_at(t), Some(1000));
        assert_eq!(
            enc.bit_index_at(enc.week_start() - hifitime::Unit::Second * 1),
            None
        );
    }
    assert_eq!(BdsNavFormat::D1.bit_period_s(), 0.02);
    assert_eq!(BdsNavFormat::D2.bit_period_s(), 0.002);
}

proptest! {
    /// Any single error per codeword of an encoded subframe is corrected by the
    /// independent decoder.
    #[test]
    fn single_errors_per_codeword_are_corrected(
        index in 0u64..200_000,
        prn in prop::sample::select(vec![19u8, 59]),
        flips in prop::collection::vec((0usize..15, 0usize..15), 10),
    ) {
        let enc = encoder(prn);
        let words = enc.subframe(index);
        for (w, (&word, &(f1, f2))) in words.iter().zip(&flips).enumerate() {
            if w == 0 {
                let cw = word & 0x7FFF;
                prop_assert_eq!(bch_correct(cw ^ (1 << f1)), Some(cw));
            } else {
                let bad = word ^ (1 << (29 - 2 * (14 - f1))) ^ (1 << (28 - 2 * (14 - f2)));
                let (c1, c2) = deinterleave(word);
                let (b1, b2) = deinterleave(bad);
                prop_assert_eq!(bch_correct(b1), Some(c1));
                prop_assert_eq!(bch_correct(b2), Some(c2));
            }
        }
    }
}

#[test]
fn input_errors_are_reported() {
    let set = constellation();
    let iono = Klobuchar::default();
    let mut gps = set[0].clone();
    gps.sat = SatId::gps(5);
    assert!(matches!(
        BdsNavEncoder::new(&gps, &iono, &set, WEEK),
        Err(BdsNavError::NotBeidou { .. })
    ));
    let mut wrong_class = set[0].clone();
    wrong_class.class = OrbitClass::BeidouGeo;
    assert!(matches!(
        BdsNavEncoder::new(&wrong_class, &iono, &set, WEEK),
        Err(BdsNavError::ClassMismatch { .. })
    ));
    let mut big_clock = set[0].clone();
    big_clock.clock.af0 = 2e-3;
    match BdsNavEncoder::new(&big_clock, &iono, &set, WEEK) {
        Err(BdsNavError::FieldOutOfRange { field, .. }) => assert_eq!(field, "a0"),
        other => panic!("expected a0 out of range, got {other:?}"),
    }
    let mut old = set[0].clone();
    old.iode = 32;
    assert!(matches!(
        BdsNavEncoder::new(&old, &iono, &set, WEEK),
        Err(BdsNavError::FieldOutOfRange { field: "AODE", .. })
    ));
    let strong_iono = Klobuchar {
        alpha: [1e-6, 0.0, 0.0, 0.0],
        beta: [0.0; 4],
    };
    assert!(BdsNavEncoder::new(&set[0], &strong_iono, &set, WEEK).is_err());
}
