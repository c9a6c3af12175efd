//! B-CNAV1 frames: structure (BCH words, CRCs, LDPC codewords through the interleaver),
//! timing, noisy decoding of subframes 2 and 3 and the ephemeris of subframe 2.

use super::*;
use crate::navmsg::ldpc_gf64::B1C_SUBFRAME2;
use hifitime::TimeScale;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal};
use skyforge_orbits::ephemeris::BeidouSet;
use skyforge_orbits::ephemeris::nominal;
use skyforge_orbits::time::{bdt_week_sow, epoch_from_bdt};

fn encoder(prn: u8) -> BdsCnav1Encoder {
    let toe = Epoch::from_gregorian_hms(2023, 3, 12, 10, 0, 0, TimeScale::BDT);
    let mut eph = nominal::beidou(BeidouSet::Bds3, toe)
        .into_iter()
        .find(|e| e.sat.prn == prn)
        .unwrap();
    eph.iode = 12;
    let params = BdsCnavParams {
        tgd_b1cp_s: 5.2e-9,
        isc_b1cd_s: -0.7e-9,
        ..Default::default()
    };
    BdsCnav1Encoder::new(&eph, &params, bdt_week_sow(toe).0).unwrap()
}

/// BPSK soft values (0 -> +1) with noise of variance 1 / (2 Es/N0).
fn noisy(symbols: &[u8], es_n0_db: f64, seed: u64) -> Vec<f32> {
    let sigma = (0.5 / 10f64.powf(es_n0_db / 10.0)).sqrt();
    let normal = Normal::new(0.0, sigma).unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    symbols
        .iter()
        .map(|&b| (1.0 - 2.0 * f64::from(b) + normal.sample(&mut rng)) as f32)
        .collect()
}

#[test]
fn a_frame_is_the_bch_words_and_the_interleaved_codewords() {
    let enc = encoder(30);
    let n = 2005; // SOW 36090: hour 10, SOH count 5.
    assert_eq!(enc.frame_time(n).1, 36_090);
    let symbols = enc.frame_symbols(n);
    assert_eq!(symbols.len(), CNAV1_FRAME_SYMBOLS);
    assert_eq!(symbols[..21], prn_word(30)[..]);
    assert_eq!(symbols[21..72], soh_word(5)[..]);
    let (sf2, sf3) = enc.subframe_bits(n);
    assert_eq!((sf2.len(), sf3.len()), (600, 264));
    assert_eq!((crc24q_bits(&sf2), crc24q_bits(&sf3)), (0, 0));
    let coded = interleave::deinterleave(&symbols[72..]);
    assert!(B1C_SUBFRAME2.is_codeword(&coded[..1200]));
    assert_eq!(coded[..600], sf2[..]);
    assert_eq!(coded[1200..1464], sf3[..]);
    assert_eq!(read_fields(&sf2[13..21], &[HOW]), [10]);
    assert_eq!(enc.symbols(1790, 20), enc.symbols(0, 3600)[1790..1810]);
    assert_eq!(enc.symbol(n * 1800 + 21), soh_word(5)[0]);
    assert_eq!(enc.week_start(), epoch_from_bdt(enc.week(), 0.0));
}

#[test]
fn a_noisy_frame_decodes_to_the_broadcast_ephemeris() {
    let enc = encoder(30);
    let n = 2005;
    let soft = noisy(&enc.frame_symbols(n), 2.5, 9);
    let frame = decode_frame(&soft, 30).unwrap();
    assert_eq!(frame.soh, 5);
    assert_eq!(frame.time(), Some(enc.frame_time(n)));
    assert_eq!(frame.page_id(), Some(1));
    let eph = frame.ephemeris(SatId::beidou(30)).unwrap();
    assert_eq!(eph, enc.broadcast_ephemeris());
    assert_eq!((eph.iode, eph.iodc), (12, 12));
    assert!((eph.clock.tgd_s - 5.2e-9).abs() < 2f64.powi(-35));
}

#[test]
fn wrong_prn_inverted_and_noise_are_refused() {
    let enc = encoder(30);
    let soft = noisy(&enc.frame_symbols(7), 20.0, 3);
    assert_eq!(decode_frame(&soft, 31), Err(Cnav1DecodeError::Prn));
    let inverted: Vec<f32> = soft.iter().map(|x| -x).collect();
    assert!(prn_correlation(&inverted[..21], 30) < -0.9);
    assert_eq!(decode_frame(&inverted, 30), Err(Cnav1DecodeError::Prn));
    assert_eq!(
        decode_frame(&soft[1..], 30),
        Err(Cnav1DecodeError::Length(1799))
    );
    // Noise with the PRN word in front: no subframe passes.
    let mut rng = ChaCha8Rng::seed_from_u64(4);
    let normal = Normal::new(0.0f32, 1.0).unwrap();
    let mut fake: Vec<f32> = soft[..21].to_vec();
    fake.extend((21..1800).map(|_| normal.sample(&mut rng)));
    assert_eq!(decode_frame(&fake, 30), Err(Cnav1DecodeError::Subframes));
}
