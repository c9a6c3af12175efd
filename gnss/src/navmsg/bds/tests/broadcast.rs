//! External oracle: subframes broadcast by C06 (D1) and C01 (D2) and the values GNSSTk
//! decodes from them. The test decoder is checked against those values, and the encoder
//! must reproduce the broadcast bits from the decoded parameters.

// The expected values are quoted with the digits they were published with.
#![allow(clippy::excessive_precision)]

use super::super::almanac::{Almanac, AlmanacFields, HEA_HEALTHY};
use super::super::bch::codeword;
use super::super::info::InfoBits;
use super::super::pages::{self, UtcFields};
use super::super::real_words::*;
use super::super::test_decoder::*;
use super::{assert_close, from_decoded, logical};
use crate::navmsg::bds::BdsNavEncoder;
use skyforge_orbits::ephemeris::{OrbitClass, SatId};

const WEEK: u32 = 810;

fn checked(words: &[u32; 10]) -> [u8; 300] {
    assert_eq!(
        parity_errors(words),
        Vec::<usize>::new(),
        "broadcast parity"
    );
    logical_from_words(words)
}

/// The encoder's codewords equal the broadcast ones: same BCH convention and bit order.
#[test]
fn encoder_parity_matches_every_broadcast_codeword() {
    let all = [
        C06_SF1,
        C06_SF2,
        C06_SF3,
        C06_SF5_P1,
        C06_SF5_P7,
        C06_SF5_P8,
        C06_SF5_P10,
    ];
    for words in all.iter().chain(C01_SF1.iter()).chain([&C01_SF5_P11]) {
        let w1 = words[0] & 0x7FFF;
        assert_eq!(codeword(w1 >> 4), w1, "word 1");
        for &w in &words[1..] {
            let (c1, c2) = logical_codewords(w);
            assert_eq!(codeword(c1 >> 4), c1, "{w:#010x}");
            assert_eq!(codeword(c2 >> 4), c2, "{w:#010x}");
        }
    }
}

/// The test decoder against GNSSTk's decoded values (PNBBDSD1NavDataFactory_T).
#[test]
fn c06_ephemeris_decodes_to_the_published_values() {
    let d = decode_d1(&checked(&C06_SF1), &checked(&C06_SF2), &checked(&C06_SF3));
    assert_eq!(
        (d.sow, d.wn, d.sat_h1, d.aodc, d.aode, d.urai),
        (345_600, 810, 0, 0, 1, 0)
    );
    assert_eq!((d.toc_s, d.toe_s), (345_600.0, 345_600.0));
    assert_eq!(header(&checked(&C06_SF2)).3, 345_606);
    assert_eq!(header(&checked(&C06_SF3)).3, 345_612);
    assert_close("TGD1", d.tgd1_s, 8.2e-9, 1e-20);
    assert_close("TGD2", d.tgd2_s, -1.9e-9, 1e-20);
    let alpha = [
        6.519258e-9,
        2.98023223876953125e-8,
        -2.98023223876953125e-7,
        4.17232513427734375e-7,
    ];
    let beta = [112_640.0, 180_224.0, -524_288.0, 458_752.0];
    for n in 0..4 {
        assert_close("alpha", d.alpha[n], alpha[n], 1e-15);
        assert_eq!(d.beta[n], beta[n]);
    }
    let rel = |what, a: f64, b: f64| assert_close(what, a, b, 1e-8 * b.abs());
    rel("Cus", d.cus, 2.102460712194442749e-05);
    rel("Cuc", d.cuc, -4.5062042772769927979e-06);
    rel("Crc", d.crc, -404.640625);
    rel("Crs", d.crs, -143.203125);
    rel("Cic", d.cic, 7.91624188e-08);
    rel("Cis", d.cis, -3.39932740e-08);
    rel("M0", d.m0, -8.5672685685526606125e-02);
    rel("Delta n", d.delta_n, 1.20183578e-09);
    rel("e", d.e, 1.1284291860647499561e-02);
    rel("A", d.sqrt_a * d.sqrt_a, 4.2170134522822760046e+07);
    rel("Omega0", d.omega0, -1.9160860634641034839);
    rel("i0", d.i0, 9.450732988963341796e-01);
    rel("omega", d.omega, -2.1772769963262814663);
    rel("Omega dot", d.omega_dot, -1.78078846e-09);
    rel("IDOT", d.idot, 4.37518224e-10);
    rel("a0", d.a0, 6.2543887179344892502e-04);
    rel("a1", d.a1, 4.82804907e-11);
    assert_eq!(d.a2, 0.0);
}

/// From the decoded parameters the encoder rebuilds C06's subframes 1-3 bit for bit
/// (information and parity; the one reserved bit of subframe 3 is 0 in both).
#[test]
fn encoder_reproduces_c06_subframes_1_to_3() {
    let d = decode_d1(&checked(&C06_SF1), &checked(&C06_SF2), &checked(&C06_SF3));
    let (eph, iono, extra) = from_decoded(&d, SatId::beidou(6), OrbitClass::Standard, WEEK);
    let enc = BdsNavEncoder::with_extra_fields(&eph, &iono, &[], WEEK, &extra)
        .expect("broadcast values fit");
    let first = 345_600 / 6;
    for (k, real) in [C06_SF1, C06_SF2, C06_SF3].iter().enumerate() {
        let ours = logical_words(&enc.subframe(first + k as u64));
        assert_eq!(
            ours.map(|w| format!("{w:08X}")),
            real.map(|w| format!("{w:08X}")),
            "subframe {}",
            k + 1
        );
    }
    // Broadcast values lie on the message's grid: quantisation returns them.
    let q = enc.broadcast_ephemeris();
    assert_eq!(q.toe, eph.toe);
    for (name, a, b) in [
        ("sqrt_a", q.orbit.sqrt_a, eph.orbit.sqrt_a),
        ("M0", q.orbit.m0, eph.orbit.m0),
        ("Omega0", q.orbit.omega0, eph.orbit.omega0),
        ("af0", q.clock.af0, eph.clock.af0),
        ("TGD", q.clock.tgd_s, eph.clock.tgd_s),
    ] {
        assert_close(name, a, b, 1e-15 * b.abs().max(1e-9));
    }
}

#[test]
fn c06_almanac_page_decodes_and_is_reproduced() {
    let b = checked(&C06_SF5_P1);
    assert_eq!(header(&b), (0b111_0001_0010, 0, 5, 345_624));
    let a = decode_almanac(&b);
    assert_eq!(a.pnum, 1);
    // GNSSTk values (angles in semicircles), PNBBDSD1NavDataFactory_T processSF5Pg8Test.
    assert_eq!(a.sqrt_a, 5282.56201171875);
    assert_eq!(a.e, 0.0003604888916015625);
    assert_eq!(a.delta_i_sc, 0.0025119781494140625);
    assert_close("Omega0", a.omega0_sc, -0.25995099544525146484, 1e-15);
    assert_close("omega", a.omega_sc, 0.017611861228942871094, 1e-15);
    assert_close("M0", a.m0_sc, -0.60474646091461181641, 1e-15);
    assert_close("Omega dot", a.omega_dot_sc, -2.25554686039686203e-09, 1e-20);
    assert_eq!(a.a0, -0.0008869171142578125);
    assert_close("a1", a.a1, 7.2759576141834259033e-12, 1e-25);
    assert_eq!(a.toa_s, 81_920.0);
    // The page body written from those integers matches the broadcast bits (except
    // AmEpID, the last two information bits, which SkyForge sets to 00).
    let n = |v: f64, e: i32| (v / 2f64.powi(e)).round() as i64;
    let fields = AlmanacFields {
        sqrt_a: n(a.sqrt_a, -11),
        a1: n(a.a1, -38),
        a0: n(a.a0, -20),
        omega0: n(a.omega0_sc, -23),
        e: n(a.e, -21),
        delta_i: n(a.delta_i_sc, -19),
        omega_dot: n(a.omega_dot_sc, -38),
        omega: n(a.omega_sc, -23),
        m0: n(a.m0_sc, -23),
    };
    let alm = Almanac {
        wna: 42,
        toa: 20,
        sats: [None; 30],
        health: [HEA_HEALTHY; 30],
    };
    let mut s = InfoBits::with_header(5, 345_624);
    pages::almanac(&mut s, 1, Some(&fields), &alm);
    let ours = logical_words(&s.encode());
    assert_eq!(ours[..9], C06_SF5_P1[..9]);
    assert_eq!(ours[9] >> 10, C06_SF5_P1[9] >> 10);
}

#[test]
fn c06_health_and_utc_pages_decode_and_are_reproduced() {
    let (hea1, none) = decode_health(&checked(&C06_SF5_P7), true);
    assert!(none.is_none());
    // GNSSTk processSF5Pg7Test: PRN 7, 17: 256; 15, 18: 510; 19: 88; others 0.
    let expected: Vec<u64> = (1..=19)
        .map(|p| match p {
            7 | 17 => 256,
            15 | 18 => 510,
            19 => 88,
            _ => 0,
        })
        .collect();
    assert_eq!(hea1, expected);
    let (hea2, wna_toa) = decode_health(&checked(&C06_SF5_P8), false);
    assert_eq!(hea2, vec![88; 11]);
    assert_eq!(wna_toa, Some((810 % 256, 81_920.0)));
    let (dt_ls, dt_lsf, wn_lsf, a0, a1, dn) = decode_utc(&checked(&C06_SF5_P10));
    assert_eq!((dt_ls, dt_lsf, wn_lsf, dn), (4, 4, 829 % 256, 6));
    assert_close("A0UTC", a0, -6.519258e-9, 1e-15);
    assert_eq!(a1, 0.0);

    let mut health = [0i64; 30];
    for (h, &v) in health.iter_mut().zip(hea1.iter().chain(&hea2)) {
        *h = v as i64;
    }
    let alm = Almanac {
        wna: 42,
        toa: 20,
        sats: [None; 30],
        health,
    };
    let mut s7 = InfoBits::with_header(5, 345_804);
    pages::health1(&mut s7, 7, &alm);
    assert_eq!(
        decode_health(&logical_bits(&s7.encode()).expect("parity"), true).0,
        hea1
    );
    let mut s8 = InfoBits::with_header(5, 345_834);
    pages::health2(&mut s8, 8, &alm);
    let ours = decode_health(&logical_bits(&s8.encode()).expect("parity"), false);
    assert_eq!(ours, (hea2, wna_toa));
    let mut s10 = InfoBits::with_header(5, 345_894);
    let utc = UtcFields {
        dt_ls: 4,
        dt_lsf: 4,
        wn_lsf: 61,
        dn: 6,
    };
    pages::utc(&mut s10, 10, &utc);
    let ours = decode_utc(&logical_bits(&s10.encode()).expect("parity"));
    assert_eq!((ours.0, ours.1, ours.2, ours.5), (4, 4, 61, 6));
}

/// From C01's decoded ephemeris the encoder rebuilds its 10 subframe 1 pages: every
/// defined bit equal (reserved bits are zero in SkyForge's pages, patterned in C01's).
#[test]
fn encoder_reproduces_c01_subframe1_pages() {
    let real: Vec<[u8; 300]> = C01_SF1.iter().map(checked).collect();
    let pages: [[u8; 300]; 10] = std::array::from_fn(|k| real[k]);
    let d = decode_d2(&pages);
    assert_eq!((d.sow, d.wn), (345_600, 810));
    assert!((6493.0..6494.0).contains(&d.sqrt_a), "GEO radius");
    let (eph, iono, extra) = from_decoded(&d, SatId::beidou(1), OrbitClass::BeidouGeo, WEEK);
    let enc = BdsNavEncoder::with_extra_fields(&eph, &iono, &[], WEEK, &extra)
        .expect("broadcast values fit");
    let header: &[(usize, usize)] = &[(1, 11), (12, 4), (16, 3), (19, 8), (31, 12), (43, 4)];
    for (k, real_page) in real.iter().enumerate() {
        let frame = 345_600 / 3 + k as u64;
        let ours = logical(&enc, frame * 5);
        for &(pos, len) in header.iter().chain(D2_PAGE_FIELDS[k]) {
            assert_eq!(
                &ours[pos - 1..pos - 1 + len],
                &real_page[pos - 1..pos - 1 + len],
                "page {} bits {pos}..{}",
                k + 1,
                pos + len - 1
            );
        }
    }
    let ours: [[u8; 300]; 10] = std::array::from_fn(|k| logical(&enc, (115_200 + k as u64) * 5));
    assert_eq!(decode_d2(&ours), d);
}

#[test]
fn encoder_reproduces_an_empty_c01_grid_page() {
    let d = decode_d2(&std::array::from_fn(|k| checked(&C01_SF1[k])));
    let (eph, iono, extra) = from_decoded(&d, SatId::beidou(1), OrbitClass::BeidouGeo, WEEK);
    let enc = BdsNavEncoder::with_extra_fields(&eph, &iono, &[], WEEK, &extra)
        .expect("broadcast values fit");
    let index = 345_630 / 3 * 5 + 4;
    assert_eq!(logical_words(&enc.subframe(index)), C01_SF5_P11);
}
