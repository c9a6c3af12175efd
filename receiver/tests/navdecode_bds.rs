//! BeiDou D1/D2 decoding round trip: SkyForge's encoder (skyforge-signals BdsNavEncoder)
//! makes the message of a known ephemeris; the receiver's decoder, fed from the middle of
//! a subframe in either polarity, must return every field within half an LSB of the
//! input and equal to the encoder's quantised values, the SOW of every subframe, and the
//! Klobuchar coefficients; one bit error in every word must be corrected by BCH.

mod navdecode_support;

use navdecode_support::{
    Field, assert_same_toe_toc, assert_within_lsb, ephemerides, soft, subframes,
};
use proptest::prelude::*;
use rand::{Rng, SeedableRng};
use skyforge_gnss::navmsg::{BdsExtraFields, BdsNavEncoder, BdsNavFormat, Klobuchar};
use skyforge_orbits::ephemeris::{
    BroadcastEphemeris, ClockParams, HarmonicCorrections, KeplerElements, OrbitClass, SatId,
};
use skyforge_orbits::time::epoch_from_bdt;
use skyforge_receiver::navdecode::{BdsDecoder, NavDecoder, NavEvent};
use std::f64::consts::PI;

const WEEK: u32 = 900;
const TOE_SOW: f64 = 345_600.0;

fn iono() -> Klobuchar {
    Klobuchar {
        alpha: [1.21e-8, 2.98e-8, -1.79e-7, 2.38e-7],
        beta: [1.24e5, -6.55e4, 1.97e5, -1.31e5],
    }
}

fn extra() -> BdsExtraFields {
    BdsExtraFields {
        urai: 3,
        tgd2_s: -4.5e-9,
    }
}

/// A MEO (D1) or GEO (D2) ephemeris with every field non-zero.
fn ephemeris(prn: u8) -> BroadcastEphemeris {
    let geo = BdsNavFormat::for_prn(prn) == BdsNavFormat::D2;
    let toe = epoch_from_bdt(WEEK, TOE_SOW);
    let class = if geo {
        OrbitClass::BeidouGeo
    } else {
        OrbitClass::Standard
    };
    let orbit = KeplerElements {
        sqrt_a: if geo { 6493.41 } else { 5282.62 },
        e: if geo { 2.1e-4 } else { 6.3e-4 },
        i0: if geo { 0.031 } else { 0.962 },
        omega0: -2.13,
        omega: -0.71,
        m0: 1.93,
        delta_n: 3.9e-9,
        idot: -2.5e-10,
        omega_dot: -6.7e-9,
    };
    let harmonics = HarmonicCorrections {
        cuc: -1.1e-6,
        cus: 9.3e-6,
        crc: 170.4,
        crs: -20.1,
        cic: 3.2e-8,
        cis: -5.4e-8,
    };
    let clock = ClockParams {
        af0: -4.1e-4,
        af1: 7.2e-12,
        af2: -1.1e-19,
        tgd_s: 1.23e-8,
        tgd2_s: 0.0,
    };
    BroadcastEphemeris {
        toc: epoch_from_bdt(WEEK, TOE_SOW - 3600.0),
        iode: 7,
        iodc: 12,
        ..BroadcastEphemeris::from_elements(
            SatId::beidou(prn),
            class,
            toe,
            orbit,
            harmonics,
            clock,
            6.0 * 3600.0,
        )
    }
}

fn encoder(eph: &BroadcastEphemeris) -> BdsNavEncoder {
    BdsNavEncoder::with_extra_fields(eph, &iono(), std::slice::from_ref(eph), WEEK, &extra())
        .unwrap_or_else(|e| panic!("{e}"))
}

/// Angle difference wrapped to [-pi, pi).
fn angle_diff(a: f64, b: f64) -> f64 {
    (a - b + PI).rem_euclid(2.0 * PI) - PI
}

/// |decoded - reference| <= tol_lsb x lsb for every broadcast field (BDS-SIS-ICD-B1I-3.0
/// §5.2.4 scale factors, written out here).
fn compare(decoded: &BroadcastEphemeris, reference: &BroadcastEphemeris, tol_lsb: f64) {
    let p2 = |n: i32| 2f64.powi(n);
    let sc = PI;
    let fields: [Field; 15] = [
        ("sqrt_a", |e| e.orbit.sqrt_a, p2(-19)),
        ("e", |e| e.orbit.e, p2(-33)),
        ("delta_n", |e| e.orbit.delta_n, sc * p2(-43)),
        ("idot", |e| e.orbit.idot, sc * p2(-43)),
        ("omega_dot", |e| e.orbit.omega_dot, sc * p2(-43)),
        ("cuc", |e| e.harmonics.cuc, p2(-31)),
        ("cus", |e| e.harmonics.cus, p2(-31)),
        ("cic", |e| e.harmonics.cic, p2(-31)),
        ("cis", |e| e.harmonics.cis, p2(-31)),
        ("crc", |e| e.harmonics.crc, p2(-6)),
        ("crs", |e| e.harmonics.crs, p2(-6)),
        ("af0", |e| e.clock.af0, p2(-33)),
        ("af1", |e| e.clock.af1, p2(-50)),
        ("af2", |e| e.clock.af2, p2(-66)),
        ("tgd1", |e| e.clock.tgd_s, 0.1e-9),
    ];
    assert_within_lsb(decoded, reference, &fields, tol_lsb);
    for (name, a, b) in [
        ("i0", decoded.orbit.i0, reference.orbit.i0),
        ("omega0", decoded.orbit.omega0, reference.orbit.omega0),
        ("omega", decoded.orbit.omega, reference.orbit.omega),
        ("m0", decoded.orbit.m0, reference.orbit.m0),
    ] {
        let d = angle_diff(a, b).abs() / (sc * p2(-31));
        assert!(d <= tol_lsb, "{} {name}: {d:.3e} LSB", reference.sat);
    }
    assert_same_toe_toc(decoded, reference);
    assert_eq!(decoded.class, reference.class);
}

/// Feed `bits` (stream bit 0 = message bit `first_bit`) and check the subframe times.
fn decode(prn: u8, bits: &[u8], first_bit: u64, invert: bool) -> (Vec<NavEvent>, BdsDecoder) {
    let mut dec = BdsDecoder::new(SatId::beidou(prn)).unwrap_or_else(|e| panic!("{e}"));
    let mut events = Vec::new();
    for c in soft(bits, invert).chunks(173) {
        events.extend(dec.feed(c));
    }
    let bit_s = dec.format().bit_period_s();
    for s in subframes(&events) {
        let abs = first_bit + s.start_bit;
        assert_eq!(abs % 300, 0, "subframe start on the grid");
        let k = abs / 300;
        let t = abs as f64 * bit_s;
        assert!((s.tow_s - t).abs() < 1e-6, "tow {} vs {t}", s.tow_s);
        assert_eq!(u64::from(s.id), k % 5 + 1);
        assert_eq!(s.inverted, invert);
        if let Some(week) = s.week {
            assert_eq!(week, WEEK);
        }
    }
    (events, dec)
}

/// Message bits around toe: `n_subframes` subframes from 3 subframes before the one
/// holding toe, starting `skip` bits into the first.
fn message(enc: &BdsNavEncoder, n_subframes: u64, skip: u64) -> (Vec<u8>, u64) {
    let period = enc.format().subframe_period_s();
    let k = (TOE_SOW / period).round() as u64 - 3;
    let first_bit = k * 300 + skip;
    (
        enc.bits(first_bit, (n_subframes * 300 - skip) as usize),
        first_bit,
    )
}

/// Subframes to feed: D1 four 30-s frames, D2 two 30-s cycles of subframe-1 pages.
fn span(format: BdsNavFormat) -> u64 {
    match format {
        BdsNavFormat::D1 => 20,
        BdsNavFormat::D2 => 100,
    }
}

#[test]
fn d1_and_d2_round_trip_from_mid_subframe_in_both_polarities() {
    for prn in [19, 3] {
        let eph = ephemeris(prn);
        let enc = encoder(&eph);
        let quantised = enc.broadcast_ephemeris();
        for invert in [false, true] {
            let (bits, first_bit) = message(&enc, span(enc.format()), 77);
            let (events, dec) = decode(prn, &bits, first_bit, invert);
            assert!(matches!(
                events.first(),
                Some(NavEvent::SyncAcquired { start_bit: 223, inverted }) if *inverted == invert
            ));
            let ephs = ephemerides(&events);
            assert_eq!(ephs.len(), 1, "C{prn}: one ephemeris, emitted once");
            let d = ephs[0];
            compare(&d.eph, &eph, 0.5 + 1e-6);
            compare(&d.eph, &quantised, 1e-6);
            assert_eq!(
                (d.eph.iode, d.eph.iodc, d.eph.health),
                (quantised.iode, quantised.iodc, 0)
            );
            assert_eq!(d.ura_index, extra().urai);
            let tgd2 = d.tgd2_s.unwrap_or(f64::NAN);
            assert!((tgd2 - extra().tgd2_s).abs() <= 0.05e-9, "TGD2 {tgd2:e}");
            let ionos: Vec<_> = events
                .iter()
                .filter_map(|e| match e {
                    NavEvent::BdsIono(k) => Some(*k),
                    _ => None,
                })
                .collect();
            assert_eq!(ionos.len(), 1);
            let exps = ([-30, -27, -24, -24], [11, 14, 16, 16]);
            for n in 0..4 {
                let (a, b) = (ionos[0].alpha[n], iono().alpha[n]);
                assert!((a - b).abs() <= 0.5 * 2f64.powi(exps.0[n]), "alpha{n}");
                let (a, b) = (ionos[0].beta[n], iono().beta[n]);
                assert!((a - b).abs() <= 0.5 * 2f64.powi(exps.1[n]), "beta{n}");
            }
            let stats = dec.stats();
            assert_eq!(
                (stats.dropped_subframes, stats.corrected_bits),
                (0, 0),
                "C{prn}"
            );
            assert_eq!(stats.subframes, span(enc.format()) - 1);
            assert_eq!(dec.week(), Some(WEEK));
            if enc.format() == BdsNavFormat::D2 {
                let pages: Vec<_> = subframes(&events)
                    .iter()
                    .filter(|s| s.id == 1)
                    .filter_map(|s| s.page)
                    .collect();
                assert!(pages.len() >= 19 && pages.iter().all(|p| (1..=10).contains(p)));
            }
        }
    }
}

/// Flip one random bit in every 30-bit word; returns per subframe the number of flips
/// the BCH decoder must correct (word 1's first 15 bits are not coded).
fn corrupt(bits: &mut [u8], first_bit: u64, seed: u64) -> Vec<(u64, u32)> {
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    let mut expected = Vec::new();
    let first_word = first_bit.div_ceil(30) * 30;
    let mut w = first_word;
    while w + 30 <= first_bit + bits.len() as u64 {
        let pos: u64 = rng.random_range(0..30);
        bits[(w + pos - first_bit) as usize] ^= 1;
        let word_in_subframe = (w / 30) % 10;
        let counted = u32::from(word_in_subframe != 0 || pos >= 15);
        let sf = w / 300;
        match expected.last_mut() {
            Some((k, n)) if *k == sf => *n += counted,
            _ => expected.push((sf, counted)),
        }
        w += 30;
    }
    expected
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(12))]

    #[test]
    fn one_error_per_word_is_corrected(seed in any::<u64>(), invert in any::<bool>(), d2 in any::<bool>()) {
        let prn = if d2 { 2 } else { 27 };
        let eph = ephemeris(prn);
        let enc = encoder(&eph);
        let (mut bits, first_bit) = message(&enc, span(enc.format()) + 10, 131);
        let expected = corrupt(&mut bits, first_bit, seed);
        let (events, dec) = decode(prn, &bits, first_bit, invert);
        let decoded = subframes(&events);
        prop_assert!(decoded.len() as u64 >= span(enc.format()) - 3, "{} subframes", decoded.len());
        for s in &decoded {
            let k = (first_bit + s.start_bit) / 300;
            let want = expected.iter().find(|e| e.0 == k).map_or(0, |e| e.1);
            prop_assert_eq!(s.corrected_bits, want, "subframe {}", k);
        }
        let got = ephemerides(&events).first().map(|d| d.eph.clone());
        prop_assert!(got.is_some(), "no ephemeris");
        if let Some(got) = got {
            compare(&got, &enc.broadcast_ephemeris(), 1e-6);
        }
        prop_assert_eq!(dec.stats().dropped_subframes, 0);
        prop_assert!(dec.stats().corrected_bits >= 9 * decoded.len() as u64);
    }
}

#[test]
fn noise_alone_never_yields_a_subframe() {
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(11);
    let bits: Vec<u8> = (0..30_000).map(|_| rng.random_range(0..2u8)).collect();
    for prn in [19, 1] {
        let mut dec = BdsDecoder::new(SatId::beidou(prn)).unwrap_or_else(|e| panic!("{e}"));
        let events = dec.feed(&soft(&bits, false));
        assert!(subframes(&events).is_empty(), "{events:?}");
    }
}

#[test]
fn wrong_satellites_are_refused() {
    assert!(BdsDecoder::new(SatId::gps(19)).is_err());
    assert!(BdsDecoder::new(SatId::beidou(64)).is_err());
    let d2 = BdsDecoder::new(SatId::beidou(60)).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(d2.format(), BdsNavFormat::D2);
}
