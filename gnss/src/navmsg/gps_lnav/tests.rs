//! Tests of the whole message against an independent parity checker and field decoder
//! written here from IS-GPS-200 (table 20-XIV, figure 20-1, tables 20-I, 20-III, 20-V,
//! 20-VI, 20-X), sharing no code with the encoder.

use super::fixtures::{header_iono, real_prn1, utc_week_2190};
use super::*;
use hifitime::TimeScale;
use proptest::prelude::*;
use skyforge_orbits::ephemeris::{
    BroadcastEphemeris, ClockParams, HarmonicCorrections, KeplerElements, SatId, nominal,
};
use skyforge_orbits::time::TimeOrigin;

// ---------------------------------------------------------------------------------------
// Independent parity checker (IS-GPS-200 table 20-XIV, one explicit XOR per term).

/// Bit D_k (k = 1..30) of a transmitted word.
fn bit(word: u32, k: u32) -> u32 {
    (word >> (30 - k)) & 1
}

/// Whether `word` satisfies the parity equations given the previous word.
fn parity_ok(word: u32, previous: u32) -> bool {
    let s29 = bit(previous, 29);
    let s30 = bit(previous, 30);
    let d = |i: u32| bit(word, i) ^ s30;
    let p25 = s29
        ^ d(1)
        ^ d(2)
        ^ d(3)
        ^ d(5)
        ^ d(6)
        ^ d(10)
        ^ d(11)
        ^ d(12)
        ^ d(13)
        ^ d(14)
        ^ d(17)
        ^ d(18)
        ^ d(20)
        ^ d(23);
    let p26 = s30
        ^ d(2)
        ^ d(3)
        ^ d(4)
        ^ d(6)
        ^ d(7)
        ^ d(11)
        ^ d(12)
        ^ d(13)
        ^ d(14)
        ^ d(15)
        ^ d(18)
        ^ d(19)
        ^ d(21)
        ^ d(24);
    let p27 = s29
        ^ d(1)
        ^ d(3)
        ^ d(4)
        ^ d(5)
        ^ d(7)
        ^ d(8)
        ^ d(12)
        ^ d(13)
        ^ d(14)
        ^ d(15)
        ^ d(16)
        ^ d(19)
        ^ d(20)
        ^ d(22);
    let p28 = s30
        ^ d(2)
        ^ d(4)
        ^ d(5)
        ^ d(6)
        ^ d(8)
        ^ d(9)
        ^ d(13)
        ^ d(14)
        ^ d(15)
        ^ d(16)
        ^ d(17)
        ^ d(20)
        ^ d(21)
        ^ d(23);
    let p29 = s30
        ^ d(1)
        ^ d(3)
        ^ d(5)
        ^ d(6)
        ^ d(7)
        ^ d(9)
        ^ d(10)
        ^ d(14)
        ^ d(15)
        ^ d(16)
        ^ d(17)
        ^ d(18)
        ^ d(21)
        ^ d(22)
        ^ d(24);
    let p30 = s29
        ^ d(3)
        ^ d(5)
        ^ d(6)
        ^ d(8)
        ^ d(9)
        ^ d(10)
        ^ d(11)
        ^ d(13)
        ^ d(15)
        ^ d(19)
        ^ d(22)
        ^ d(23)
        ^ d(24);
    [p25, p26, p27, p28, p29, p30]
        .iter()
        .zip(25..=30)
        .all(|(&p, k)| p == bit(word, k))
}

// ---------------------------------------------------------------------------------------
// Independent field decoder.

/// Source data bits d1..d24 of the ten words (D30* complement undone), d1 at bit 23.
fn source_words(words: &[u32; 10], previous: u32) -> [u32; 10] {
    let mut prev = previous;
    std::array::from_fn(|k| {
        let w = words[k];
        let data = (w >> 6) & 0xFF_FFFF;
        let out = if prev & 1 == 1 {
            !data & 0xFF_FFFF
        } else {
            data
        };
        prev = w;
        out
    })
}

/// Unsigned field at ICD word `w` (1-10), bits `first..first+len-1`.
fn field(src: &[u32; 10], w: usize, first: u32, len: u32) -> u64 {
    u64::from((src[w - 1] >> (24 - (first - 1 + len))) & ((1u32 << len) - 1))
}

/// Two's complement of an unsigned `len`-bit value.
fn signed(v: u64, len: u32) -> i64 {
    if v >> (len - 1) == 1 {
        v as i64 - (1i64 << len)
    } else {
        v as i64
    }
}

/// 32-bit field: 8 MSBs at bits 17-24 of word `w`, 24 LSBs in word `w + 1`.
fn split32(src: &[u32; 10], w: usize) -> u64 {
    (field(src, w, 17, 8) << 24) | field(src, w + 1, 1, 24)
}

/// A decoded subframe-1-3 ephemeris (ICD units: semicircles for angles).
#[derive(Debug, Default)]
struct Decoded {
    wn: u64,
    ura: u64,
    health: u64,
    iodc: u64,
    tgd: f64,
    toc: f64,
    af2: f64,
    af1: f64,
    af0: f64,
    iode2: u64,
    crs: f64,
    delta_n: f64,
    m0: f64,
    cuc: f64,
    e: f64,
    cus: f64,
    sqrt_a: f64,
    toe: f64,
    fit: u64,
    cic: f64,
    omega0: f64,
    cis: f64,
    i0: f64,
    crc: f64,
    omega: f64,
    omega_dot: f64,
    iode3: u64,
    idot: f64,
}

fn p2(n: i32) -> f64 {
    2f64.powi(n)
}

/// Decode subframes 1, 2, 3 (figure 20-1 sheets 1-3, tables 20-I and 20-III).
fn decode_ephemeris(sf1: &[u32; 10], sf2: &[u32; 10], sf3: &[u32; 10]) -> Decoded {
    let s1 = source_words(sf1, 0);
    let s2 = source_words(sf2, sf1[9]);
    let s3 = source_words(sf3, sf2[9]);
    Decoded {
        wn: field(&s1, 3, 1, 10),
        ura: field(&s1, 3, 13, 4),
        health: field(&s1, 3, 17, 6),
        iodc: (field(&s1, 3, 23, 2) << 8) | field(&s1, 8, 1, 8),
        tgd: signed(field(&s1, 7, 17, 8), 8) as f64 * p2(-31),
        toc: field(&s1, 8, 9, 16) as f64 * 16.0,
        af2: signed(field(&s1, 9, 1, 8), 8) as f64 * p2(-55),
        af1: signed(field(&s1, 9, 9, 16), 16) as f64 * p2(-43),
        af0: signed(field(&s1, 10, 1, 22), 22) as f64 * p2(-31),
        iode2: field(&s2, 3, 1, 8),
        crs: signed(field(&s2, 3, 9, 16), 16) as f64 * p2(-5),
        delta_n: signed(field(&s2, 4, 1, 16), 16) as f64 * p2(-43),
        m0: signed(split32(&s2, 4), 32) as f64 * p2(-31),
        cuc: signed(field(&s2, 6, 1, 16), 16) as f64 * p2(-29),
        e: split32(&s2, 6) as f64 * p2(-33),
        cus: signed(field(&s2, 8, 1, 16), 16) as f64 * p2(-29),
        sqrt_a: split32(&s2, 8) as f64 * p2(-19),
        toe: field(&s2, 10, 1, 16) as f64 * 16.0,
        fit: field(&s2, 10, 17, 1),
        cic: signed(field(&s3, 3, 1, 16), 16) as f64 * p2(-29),
        omega0: signed(split32(&s3, 3), 32) as f64 * p2(-31),
        cis: signed(field(&s3, 5, 1, 16), 16) as f64 * p2(-29),
        i0: signed(split32(&s3, 5), 32) as f64 * p2(-31),
        crc: signed(field(&s3, 7, 1, 16), 16) as f64 * p2(-5),
        omega: signed(split32(&s3, 7), 32) as f64 * p2(-31),
        omega_dot: signed(field(&s3, 9, 1, 24), 24) as f64 * p2(-43),
        iode3: field(&s3, 10, 1, 8),
        idot: signed(field(&s3, 10, 9, 14), 14) as f64 * p2(-43),
    }
}

// ---------------------------------------------------------------------------------------
// Fixtures.

fn ok<T>(r: Result<T, LnavError>) -> T {
    r.unwrap_or_else(|e| panic!("{e}"))
}

/// Nominal constellation at `epoch` (31 PRNs), its almanac and the PRN-1 encoder of the
/// real ephemeris.
fn encoder_with_nominal_almanac() -> (LnavEncoder, Almanac) {
    let eph = real_prn1();
    let almanac = ok(Almanac::from_ephemerides(&nominal::gps(eph.toe), eph.toe));
    let enc = ok(LnavEncoder::new(
        &eph,
        &almanac,
        &header_iono(),
        &utc_week_2190(),
        2,
    ));
    (enc, almanac)
}

/// Subframe index of the first subframe of the frame containing `epoch`.
fn frame_start(epoch: Epoch) -> u64 {
    let k = ok(subframe_index_at(epoch));
    k - k % 5
}

// ---------------------------------------------------------------------------------------
// (a) parity.

#[test]
fn every_word_of_a_master_frame_has_valid_parity_and_single_flips_are_caught() {
    let (enc, _) = encoder_with_nominal_almanac();
    let first = frame_start(real_prn1().toe);
    let mut previous = 0u32;
    for k in first..first + 125 {
        let words = enc.subframe(k);
        for (j, &w) in words.iter().enumerate() {
            assert!(w >> 30 == 0, "word wider than 30 bits");
            assert!(parity_ok(w, previous), "subframe {k} word {}", j + 1);
            for b in 0..30 {
                assert!(
                    !parity_ok(w ^ (1 << b), previous),
                    "flip of bit {b} not caught (subframe {k} word {})",
                    j + 1
                );
            }
            if j == 1 || j == 9 {
                assert_eq!(w & 0b11, 0, "t bits: D29 = D30 = 0 in word {}", j + 1);
            }
            previous = w;
        }
    }
}

proptest! {
    #[test]
    fn parity_of_arbitrary_data(source in 0u32..(1 << 24), prev in 0u32..(1 << 30)) {
        let w = super::parity::encode_word(source, prev);
        prop_assert!(parity_ok(w, prev));
        let flip = source % 30;
        prop_assert!(!parity_ok(w ^ (1 << flip), prev));
    }
}

// ---------------------------------------------------------------------------------------
// (b) field decoding.

/// Assert |decoded - input| <= LSB / 2 (plus f64 rounding).
fn within_half_lsb(name: &str, decoded: f64, input: f64, lsb: f64) {
    let err = (decoded - input).abs();
    assert!(
        err <= 0.5 * lsb * (1.0 + 1e-9) + 1e-15 * input.abs(),
        "{name}: decoded {decoded:e}, input {input:e}, |err| = {:.3} LSB",
        err / lsb
    );
}

#[test]
fn subframes_1_to_3_decode_to_the_input_within_half_an_lsb() {
    let (enc, _) = encoder_with_nominal_almanac();
    let eph = real_prn1();
    let first = frame_start(eph.toe);
    let d = decode_ephemeris(
        &enc.subframe(first),
        &enc.subframe(first + 1),
        &enc.subframe(first + 2),
    );
    assert_eq!(d.wn, 2190 % 1024);
    assert_eq!(
        (d.ura, d.health, d.iodc, d.iode2, d.iode3),
        (2, 0, 39, 39, 39)
    );
    assert_eq!(d.fit, 0);
    assert_eq!((d.toc, d.toe), (518_400.0, 518_400.0));
    // Each value within half an LSB of the input, and exactly what broadcast_ephemeris()
    // says was sent (`unit`: GPS_PI for the angles, which the message carries in
    // semicircles).
    let b = enc.broadcast_ephemeris();
    let (ei, eh, ec) = (&eph.orbit, &eph.harmonics, &eph.clock);
    let (bo, bh, bc) = (&b.orbit, &b.harmonics, &b.clock);
    for (name, decoded, input, sent, lsb, unit) in [
        ("TGD", d.tgd, ec.tgd_s, bc.tgd_s, p2(-31), 1.0),
        ("af2", d.af2, ec.af2, bc.af2, p2(-55), 1.0),
        ("af1", d.af1, ec.af1, bc.af1, p2(-43), 1.0),
        ("af0", d.af0, ec.af0, bc.af0, p2(-31), 1.0),
        ("Crs", d.crs, eh.crs, bh.crs, p2(-5), 1.0),
        ("dn", d.delta_n, ei.delta_n, bo.delta_n, p2(-43), GPS_PI),
        ("M0", d.m0, ei.m0, bo.m0, p2(-31), GPS_PI),
        ("Cuc", d.cuc, eh.cuc, bh.cuc, p2(-29), 1.0),
        ("e", d.e, ei.e, bo.e, p2(-33), 1.0),
        ("Cus", d.cus, eh.cus, bh.cus, p2(-29), 1.0),
        ("sqrtA", d.sqrt_a, ei.sqrt_a, bo.sqrt_a, p2(-19), 1.0),
        ("Cic", d.cic, eh.cic, bh.cic, p2(-29), 1.0),
        ("OMEGA0", d.omega0, ei.omega0, bo.omega0, p2(-31), GPS_PI),
        ("Cis", d.cis, eh.cis, bh.cis, p2(-29), 1.0),
        ("i0", d.i0, ei.i0, bo.i0, p2(-31), GPS_PI),
        ("Crc", d.crc, eh.crc, bh.crc, p2(-5), 1.0),
        ("omega", d.omega, ei.omega, bo.omega, p2(-31), GPS_PI),
        (
            "OMEGADOT",
            d.omega_dot,
            ei.omega_dot,
            bo.omega_dot,
            p2(-43),
            GPS_PI,
        ),
        ("IDOT", d.idot, ei.idot, bo.idot, p2(-43), GPS_PI),
    ] {
        within_half_lsb(name, decoded, input / unit, lsb);
        let x = decoded * unit;
        assert!(
            (x - sent).abs() <= 1e-15 * sent.abs(),
            "{name}: {x} vs {sent}"
        );
    }
    assert_eq!((b.toe, b.toc), (eph.toe, eph.toc));
}

/// A random ephemeris inside the LNAV ranges (angles anywhere on the circle).
fn arb_ephemeris() -> impl Strategy<Value = BroadcastEphemeris> {
    let angles = (-4.0f64..4.0, -4.0f64..4.0, 0.8f64..1.1, -4.0f64..4.0);
    let orbit = (
        0.0f64..0.03,
        5100.0f64..5200.0,
        -1e-8f64..1e-8,
        -9e-9f64..9e-9,
    );
    let harmonics = (-1e3f64..1e3, -1e3f64..1e3, -6e-5f64..6e-5, -6e-5f64..6e-5);
    let clock = (-9e-4f64..9e-4, -3e-9f64..3e-9, -3e-15f64..3e-15, 0u32..1024);
    (angles, orbit, harmonics, clock, 0u32..37_800).prop_map(
        |(
            (m0, om0, i0, w),
            (e, sqrt_a, dn, odot),
            (crs, crc, cuc, cis),
            (af0, af1, af2, iodc),
            toe16,
        )| {
            let toe = Epoch::from_gpst_seconds(2190.0 * 604_800.0 + f64::from(toe16) * 16.0);
            BroadcastEphemeris {
                orbit: KeplerElements {
                    m0,
                    omega0: om0,
                    i0,
                    omega: w,
                    e,
                    sqrt_a,
                    delta_n: dn,
                    omega_dot: odot,
                    idot: dn / 10.0,
                },
                harmonics: HarmonicCorrections {
                    crs,
                    crc,
                    cuc,
                    cus: -cuc,
                    cic: cis / 3.0,
                    cis,
                },
                clock: ClockParams {
                    af0,
                    af1,
                    af2,
                    tgd_s: af2 * 1e7,
                    tgd2_s: 0.0,
                },
                iodc,
                iode: iodc & 0xFF,
                toe,
                toc: toe,
                ..real_prn1()
            }
        },
    )
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]
    #[test]
    fn random_ephemerides_decode_within_half_an_lsb(eph in arb_ephemeris()) {
        let almanac = ok(Almanac::from_ephemerides(&[], eph.toe));
        let enc = ok(LnavEncoder::new(&eph, &almanac, &header_iono(), &utc_week_2190(), 0));
        let first = frame_start(eph.toe);
        let d = decode_ephemeris(&enc.subframe(first), &enc.subframe(first + 1), &enc.subframe(first + 2));
        let wrap = |x: f64| x - 2.0 * (x / 2.0).round();
        let angle = |name: &str, got: f64, rad: f64| {
            let err = wrap(got - rad / GPS_PI).abs();
            assert!(err <= 0.5 * p2(-31) * (1.0 + 1e-6), "{name}: {:.3} LSB", err / p2(-31));
        };
        angle("M0", d.m0, eph.orbit.m0);
        angle("OMEGA0", d.omega0, eph.orbit.omega0);
        angle("omega", d.omega, eph.orbit.omega);
        within_half_lsb("i0", d.i0, eph.orbit.i0 / GPS_PI, p2(-31));
        within_half_lsb("e", d.e, eph.orbit.e, p2(-33));
        within_half_lsb("sqrtA", d.sqrt_a, eph.orbit.sqrt_a, p2(-19));
        within_half_lsb("dn", d.delta_n, eph.orbit.delta_n / GPS_PI, p2(-43));
        within_half_lsb("OMEGADOT", d.omega_dot, eph.orbit.omega_dot / GPS_PI, p2(-43));
        within_half_lsb("IDOT", d.idot, eph.orbit.idot / GPS_PI, p2(-43));
        within_half_lsb("Crs", d.crs, eph.harmonics.crs, p2(-5));
        within_half_lsb("Crc", d.crc, eph.harmonics.crc, p2(-5));
        within_half_lsb("Cuc", d.cuc, eph.harmonics.cuc, p2(-29));
        within_half_lsb("Cus", d.cus, eph.harmonics.cus, p2(-29));
        within_half_lsb("Cic", d.cic, eph.harmonics.cic, p2(-29));
        within_half_lsb("Cis", d.cis, eph.harmonics.cis, p2(-29));
        within_half_lsb("af0", d.af0, eph.clock.af0, p2(-31));
        within_half_lsb("af1", d.af1, eph.clock.af1, p2(-43));
        within_half_lsb("af2", d.af2, eph.clock.af2, p2(-55));
        within_half_lsb("TGD", d.tgd, eph.clock.tgd_s, p2(-31));
        prop_assert_eq!(d.iodc, u64::from(eph.iodc));
        prop_assert_eq!(d.iode2, u64::from(eph.iode));
        prop_assert_eq!(d.iode3, u64::from(eph.iode));
        let (_, sow) = skyforge_orbits::time::gpst_week_sow(eph.toe);
        prop_assert_eq!(d.toe, sow);
        prop_assert_eq!(d.fit, 0);
    }
}

// ---------------------------------------------------------------------------------------
// (c) structure and timing.

#[test]
fn tlm_how_ids_and_tow_count_follow_the_icd() {
    let (enc, _) = encoder_with_nominal_almanac();
    // Around the end of GPS week 2190: the TOW count of the next subframe wraps to 0 and
    // the subframe cycle restarts with ID 1 at the week start (IS-GPS-200 20.3.4.1).
    let week_start = 2191 * SUBFRAMES_PER_WEEK;
    let mut last_tow = None;
    for k in week_start - 20..week_start + 20 {
        let w = enc.subframe(k);
        assert_eq!(w[0] >> 22, 0x8B, "preamble (D30* = 0 so not inverted)");
        assert_eq!(bit(w[0], 23), 0, "integrity status flag");
        let src = source_words(&w, 0);
        let tow = field(&src, 2, 1, 17);
        let id = field(&src, 2, 20, 3);
        let expected_tow = (k % SUBFRAMES_PER_WEEK + 1) % SUBFRAMES_PER_WEEK;
        assert_eq!(
            tow, expected_tow,
            "HOW TOW = start of the next subframe / 6 s"
        );
        assert_eq!(id, k % SUBFRAMES_PER_WEEK % 5 + 1);
        if let Some(prev) = last_tow {
            assert_eq!(tow, (prev + 1) % SUBFRAMES_PER_WEEK);
        }
        last_tow = Some(tow);
        if id == 1 {
            let wn = field(&src, 3, 1, 10);
            assert_eq!(wn, (k / SUBFRAMES_PER_WEEK) % 1024);
        }
    }
    // Subframe 1 of week 2191 says WN 2191 mod 1024 = 143.
    let src = source_words(&enc.subframe(week_start), 0);
    assert_eq!(field(&src, 3, 1, 10), 143);
}

#[test]
fn bits_and_bit_agree_with_subframe() {
    let (enc, _) = encoder_with_nominal_almanac();
    let first = frame_start(real_prn1().toe) + 3;
    let bits = enc.bits(first, 4);
    assert_eq!(bits.len(), 4 * BITS_PER_SUBFRAME);
    for (n, &b) in bits.iter().enumerate() {
        let k = first + (n / 300) as u64;
        let word = enc.subframe(k)[(n % 300) / 30];
        assert_eq!(u32::from(b), bit(word, (n % 30) as u32 + 1));
        assert_eq!(enc.bit(first * 300 + n as u64), b);
    }
    // The preamble is the first 8 bits of every subframe.
    assert_eq!(&bits[300..308], &[1, 0, 0, 0, 1, 0, 1, 1]);
}

#[test]
fn subframe_timing_helpers() {
    let e = Epoch::from_gregorian(2022, 1, 1, 0, 0, 7, 0, TimeScale::GPST);
    let k = ok(subframe_index_at(e));
    assert_eq!(k, (2190 * 604_800 + 518_400 + 6) / 6);
    assert_eq!(
        subframe_start(k),
        Epoch::from_gregorian(2022, 1, 1, 0, 0, 6, 0, TimeScale::GPST)
    );
    let before = Epoch::from_gregorian(1980, 1, 5, 0, 0, 0, 0, TimeScale::GPST);
    assert!(subframe_index_at(before).is_err());
}

// ---------------------------------------------------------------------------------------
// (d) subframes 4 and 5.

/// Data ID, SV ID of the page in subframe `k` and its source words.
fn page_of(enc: &LnavEncoder, k: u64) -> (u64, u64, [u32; 10]) {
    let src = source_words(&enc.subframe(k), 0);
    (field(&src, 3, 1, 2), field(&src, 3, 3, 6), src)
}

#[test]
fn pages_carry_the_table_20_v_sv_ids_and_page_25_health() {
    let (enc, almanac) = encoder_with_nominal_almanac();
    // IS-GPS-200 table 20-V, subframe 4 pages 1..25.
    let sf4 = [
        57, 25, 26, 27, 28, 57, 29, 30, 31, 32, 57, 62, 52, 53, 54, 57, 55, 56, 58, 59, 57, 60, 61,
        62, 63,
    ];
    let week_start = 2190 * SUBFRAMES_PER_WEEK;
    for page in 0..25u64 {
        let frame = week_start + 5 * page;
        let (id4, sv4, _) = page_of(&enc, frame + 3);
        let (id5, sv5, src5) = page_of(&enc, frame + 4);
        assert_eq!((id4, id5), (1, 1), "data ID 01");
        // The nominal constellation has PRN 1-31: PRN 32 (subframe 4 page 10) is a dummy.
        let expect4 = if sf4[page as usize] == 32 {
            0
        } else {
            sf4[page as usize]
        };
        assert_eq!(sv4, expect4, "subframe 4 page {}", page + 1);
        let expect5 = if page < 24 { page + 1 } else { 51 };
        assert_eq!(sv5, expect5, "subframe 5 page {}", page + 1);
        if page < 24 {
            // toa of the almanac page.
            assert_eq!(field(&src5, 4, 1, 8) * 4096, u64::from(almanac.toa_s()));
        }
    }
    // The cycle repeats every 25 frames (12.5 min).
    assert_eq!(
        enc.subframe(week_start + 3)[2..],
        enc.subframe(week_start + 128)[2..]
    );

    // Subframe 5 page 25: toa, WNa, health of PRN 1-24 (all 0).
    let (_, _, s) = page_of(&enc, week_start + 5 * 24 + 4);
    assert_eq!(field(&s, 3, 9, 8) * 4096, u64::from(almanac.toa_s()));
    assert_eq!(field(&s, 3, 17, 8), u64::from(almanac.week() % 256));
    for prn in 0..24 {
        assert_eq!(field(&s, 4 + prn / 4, 1 + 6 * (prn as u32 % 4), 6), 0);
    }
    // Subframe 4 page 25: configurations (1001 for PRN 1-31, 0000 for 32), health of
    // PRN 25-31 = 0 and 111111 ("not available") for PRN 32.
    let (_, _, s) = page_of(&enc, week_start + 5 * 24 + 3);
    let mut configs = Vec::new();
    for w in 3..=8 {
        let (first, count) = match w {
            3 => (9, 4),
            8 => (1, 4),
            _ => (1, 6),
        };
        for j in 0..count {
            configs.push(field(&s, w, first + 4 * j, 4));
        }
    }
    assert_eq!(configs.len(), 32);
    assert!(configs[..31].iter().all(|&c| c == 0b1001));
    assert_eq!(configs[31], 0);
    let health: Vec<u64> = [
        (8, 19),
        (9, 1),
        (9, 7),
        (9, 13),
        (9, 19),
        (10, 1),
        (10, 7),
        (10, 13),
    ]
    .iter()
    .map(|&(w, b)| field(&s, w, b, 6))
    .collect();
    assert_eq!(health, vec![0, 0, 0, 0, 0, 0, 0, 0b11_1111]);

    // The dummy almanac page of PRN 32: alternating ones and zeros after the SV ID.
    let (_, sv, s) = page_of(&enc, week_start + 5 * 9 + 3);
    assert_eq!(sv, 0);
    assert_eq!(field(&s, 3, 9, 16), 0xAAAA);
    assert_eq!(field(&s, 6, 1, 24), 0xAA_AAAA);
}

#[test]
fn page_18_decodes_to_the_quantised_iono_and_utc() {
    let (enc, _) = encoder_with_nominal_almanac();
    let (id, sv, s) = page_of(&enc, 2190 * SUBFRAMES_PER_WEEK + 5 * 17 + 3);
    assert_eq!((id, sv), (1, 56));
    let i8f = |w, b| signed(field(&s, w, b, 8), 8) as f64;
    let alpha = [
        i8f(3, 9) * p2(-30),
        i8f(3, 17) * p2(-27),
        i8f(4, 1) * p2(-24),
        i8f(4, 9) * p2(-24),
    ];
    let beta = [
        i8f(4, 17) * p2(11),
        i8f(5, 1) * p2(14),
        i8f(5, 9) * p2(16),
        i8f(5, 17) * p2(16),
    ];
    let want = header_iono();
    for (got, w) in alpha
        .iter()
        .chain(&beta)
        .zip(want.alpha.iter().chain(&want.beta))
    {
        assert!((got - w).abs() <= 1e-4 * w.abs(), "{got} vs {w}");
    }
    assert_eq!(enc.iono().alpha, alpha);
    let a1 = signed(field(&s, 6, 1, 24), 24) as f64 * p2(-50);
    let a0 = signed((field(&s, 7, 1, 24) << 8) | field(&s, 8, 1, 8), 32) as f64 * p2(-30);
    assert!((a0 - 9.313_225_746_2e-10).abs() < 1e-19 && (a1 - 2.664_535_259e-15).abs() < 1e-24);
    assert_eq!(field(&s, 8, 9, 8) * 4096, 589_824);
    assert_eq!(field(&s, 8, 17, 8), 2190 % 256);
    assert_eq!(signed(field(&s, 9, 1, 8), 8), 18);
    assert_eq!(field(&s, 9, 9, 8), 1929 % 256);
    assert_eq!(field(&s, 9, 17, 8), 7);
    assert_eq!(signed(field(&s, 10, 1, 8), 8), 18);
}

#[test]
fn almanac_pages_decode_to_the_almanac_orbit() {
    let (enc, almanac) = encoder_with_nominal_almanac();
    let week_start = 2190 * SUBFRAMES_PER_WEEK;
    for prn in 1u8..=24 {
        let (_, sv, s) = page_of(&enc, week_start + 5 * (u64::from(prn) - 1) + 4);
        assert_eq!(sv, u64::from(prn));
        let a = almanac
            .ephemeris(prn)
            .unwrap_or_else(|| panic!("PRN {prn}"));
        let e = field(&s, 3, 9, 16) as f64 * p2(-21);
        let di = signed(field(&s, 4, 9, 16), 16) as f64 * p2(-19);
        let odot = signed(field(&s, 5, 1, 16), 16) as f64 * p2(-38);
        let sqrt_a = field(&s, 6, 1, 24) as f64 * p2(-11);
        let om0 = signed(field(&s, 7, 1, 24), 24) as f64 * p2(-23);
        let w = signed(field(&s, 8, 1, 24), 24) as f64 * p2(-23);
        let m0 = signed(field(&s, 9, 1, 24), 24) as f64 * p2(-23);
        let af0 = signed((field(&s, 10, 1, 8) << 3) | field(&s, 10, 20, 3), 11) as f64 * p2(-20);
        let af1 = signed(field(&s, 10, 9, 11), 11) as f64 * p2(-38);
        assert_eq!(field(&s, 5, 17, 8), 0, "health");
        let close =
            |x: f64, y: f64| assert!((x - y).abs() <= 1e-15 * y.abs().max(1e-30), "{x} vs {y}");
        close(e, a.orbit.e);
        close((0.30 + di) * GPS_PI, a.orbit.i0);
        close(odot * GPS_PI, a.orbit.omega_dot);
        close(sqrt_a, a.orbit.sqrt_a);
        close(om0 * GPS_PI, a.orbit.omega0);
        close(w * GPS_PI, a.orbit.omega);
        close(m0 * GPS_PI, a.orbit.m0);
        close(af0, a.clock.af0);
        close(af1, a.clock.af1);
    }
}

#[test]
fn almanac_orbit_follows_the_nominal_ephemerides() {
    // Nominal orbits have no harmonics and delta n = 0, so the almanac differs only by its
    // coarser quantisation (table 20-VI), half an LSB each: delta i 2^-20 semicircle is
    // 80 m cross-track at GPS radius, the other angles 2^-24 semicircle 5 m, sqrt A
    // 2^-12 m^1/2 2.5 m radially (then drifting along-track through the mean motion).
    let epoch = Epoch::from_gregorian(2023, 3, 15, 7, 13, 27, 0, TimeScale::UTC);
    let ephs = nominal::gps(epoch);
    let almanac = ok(Almanac::from_ephemerides(&ephs, epoch));
    assert_eq!(almanac.prns(), (1..=31).collect::<Vec<u8>>());
    let origin = TimeOrigin::new(epoch);
    let mut worst_at_toa = 0.0f64;
    let mut worst_day = 0.0f64;
    for eph in &ephs {
        let a = almanac
            .ephemeris(eph.sat.prn)
            .unwrap_or_else(|| panic!("{}", eph.sat));
        let (be, ba) = (eph.bind(&origin), a.bind(&origin));
        let toa_s = origin.seconds_since_start(almanac.toa());
        worst_at_toa = worst_at_toa.max((be.position_ecef(toa_s) - ba.position_ecef(toa_s)).norm());
        for dt in [-43_200.0, 43_200.0] {
            let t = toa_s + dt;
            worst_day = worst_day.max((be.position_ecef(t) - ba.position_ecef(t)).norm());
        }
    }
    println!(
        "almanac vs nominal ephemeris: {worst_at_toa:.2} m at toa, {worst_day:.1} m at +-12 h"
    );
    assert!(worst_at_toa < 95.0, "{worst_at_toa}");
    assert!(worst_day < 150.0, "{worst_day}");
    // toa is the 4096-s step nearest the epoch (2023-03-15 07:13:45 GPST is 285225 s into
    // week 2253: 70 x 4096 = 286720 s is nearest).
    assert_eq!((almanac.week(), almanac.toa_s()), (2253, 286_720));
}

// ---------------------------------------------------------------------------------------
// Quantisation residuals of the orbit the signal follows.

#[test]
fn residuals_nominal_constellation() {
    // Off the 16-s grid on purpose: toe/toc are re-expressed at the nearest grid point.
    let epoch = Epoch::from_gregorian(2023, 3, 15, 7, 13, 27, 0, TimeScale::UTC);
    let ephs = nominal::gps(epoch);
    let almanac = ok(Almanac::from_ephemerides(&ephs, epoch));
    let origin = TimeOrigin::new(epoch);
    let mut worst = 0.0f64;
    let mut worst_clock = 0.0f64;
    for eph in &ephs {
        let enc = ok(LnavEncoder::new(
            eph,
            &almanac,
            &header_iono(),
            &utc_week_2190(),
            0,
        ));
        let q = enc.broadcast_ephemeris();
        let (_, toe_sow) = skyforge_orbits::time::gpst_week_sow(q.toe);
        assert_eq!(toe_sow % 16.0, 0.0);
        let (b0, b1) = (eph.bind(&origin), q.bind(&origin));
        for step in 0..=240 {
            let t = 60.0 * f64::from(step);
            worst = worst.max((b0.position_ecef(t) - b1.position_ecef(t)).norm());
            worst_clock = worst_clock.max((b0.clock_offset_s(t) - b1.clock_offset_s(t)).abs());
        }
    }
    println!("nominal constellation, 4 h from toe: max 3D {worst:.4} m, clock {worst_clock:e} s");
    assert!(worst < 0.08, "{worst}");
    assert_eq!(worst_clock, 0.0);
}

#[test]
fn reexpression_at_a_shifted_toe_is_exact() {
    // Move a real ephemeris (with harmonics, delta n, IDOT, clock drift) by 7 s and back
    // to a different week: positions and clocks must agree to f64 rounding.
    let eph = real_prn1();
    let origin = TimeOrigin::new(eph.toe);
    let toe_s = (gps_ns(eph.toe) / NS_PER_S) as i64;
    for shift in [7, -8, 302_400] {
        let moved = super::ephemeris::reexpress(&eph, toe_s + shift, toe_s + shift);
        let (b0, b1) = (eph.bind(&origin), moved.bind(&origin));
        for t in [-7200.0, -1.0, 0.0, 3600.0, 7200.0] {
            let dr = (b0.position_ecef(t) - b1.position_ecef(t)).norm();
            let dc = (b0.clock_offset_s(t) - b1.clock_offset_s(t)).abs();
            assert!(
                dr < 1e-5 && dc < 1e-15,
                "shift {shift}: {dr} m, {dc} s at {t}"
            );
        }
    }
}

// ---------------------------------------------------------------------------------------
// Errors.

#[test]
fn bad_inputs_are_errors() {
    let eph = real_prn1();
    let almanac = ok(Almanac::from_ephemerides(
        std::slice::from_ref(&eph),
        eph.toe,
    ));
    let make = |e: &BroadcastEphemeris, ura| {
        LnavEncoder::new(e, &almanac, &header_iono(), &utc_week_2190(), ura)
    };
    assert!(matches!(make(&eph, 16), Err(LnavError::BadValue { .. })));
    let bds = BroadcastEphemeris {
        sat: SatId::beidou(19),
        ..eph.clone()
    };
    assert!(matches!(make(&bds, 0), Err(LnavError::NotGps { .. })));
    let big_clock = BroadcastEphemeris {
        clock: ClockParams {
            af0: 2e-3,
            ..eph.clock
        },
        ..eph.clone()
    };
    match make(&big_clock, 0) {
        Err(LnavError::OutOfRange { what, .. }) => assert_eq!(what, "G01 af0"),
        other => panic!("{other:?}"),
    }
    let iod = BroadcastEphemeris {
        iode: 40,
        ..eph.clone()
    };
    assert!(matches!(make(&iod, 0), Err(LnavError::BadValue { .. })));
    let bad_iono = IonoParams {
        alpha: [1.0, 0.0, 0.0, 0.0],
        ..header_iono()
    };
    assert!(LnavEncoder::new(&eph, &almanac, &bad_iono, &utc_week_2190(), 0).is_err());
}
