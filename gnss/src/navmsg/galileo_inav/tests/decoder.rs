//! The page decoder under noise, polarity errors, swapped parts and garbage.

use super::super::pages::{PART_SYMBOLS, interleaved_index};
use super::super::{INAV_SYNC, InavDecodeError, InavPage, decode_page, decode_page_part};
use super::{encoder, epoch, realistic, soft};
use proptest::prelude::*;

#[test]
fn scattered_symbol_errors_are_corrected() {
    let enc = encoder(&realistic(21, epoch()));
    for n in 100..106 {
        let clean = decode_page(&soft(&enc.page_symbols(n))).unwrap();
        let mut symbols = enc.page_symbols(n);
        // One error in 20 symbols, sync patterns included.
        for s in symbols.iter_mut().skip(n as usize % 20).step_by(20) {
            *s ^= 1;
        }
        assert_eq!(decode_page(&soft(&symbols)).unwrap(), clean, "page {n}");
    }
}

#[test]
fn weak_wrong_soft_symbols_are_outvoted() {
    let enc = encoder(&realistic(21, epoch()));
    let clean = decode_page(&soft(&enc.page_symbols(7))).unwrap();
    let mut s = soft(&enc.page_symbols(7));
    for x in s.iter_mut().skip(10).step_by(5) {
        *x *= -0.3;
    }
    assert_eq!(decode_page(&s).unwrap(), clean);
}

#[test]
fn parts_pair_only_as_even_then_odd_of_one_page() {
    let enc = encoder(&realistic(21, epoch()));
    let part = |n: u64, odd: usize| {
        let s = soft(&enc.page_symbols(n));
        decode_page_part(&s[odd * PART_SYMBOLS..(odd + 1) * PART_SYMBOLS]).unwrap()
    };
    // Pages 1 and 2: word types 2 and 4.
    let (even, odd) = (part(1, 0), part(1, 1));
    assert!(!even.is_odd() && odd.is_odd());
    assert_eq!(even.bits()[2..], enc.word_bits(1)[..112]);
    assert!(InavPage::from_parts(&even, &odd).is_ok());
    assert_eq!(
        InavPage::from_parts(&odd, &even),
        Err(InavDecodeError::EvenOdd)
    );
    // The odd part of the next page has the CRC of another word.
    assert_eq!(
        InavPage::from_parts(&even, &part(2, 1)),
        Err(InavDecodeError::Crc)
    );
}

#[test]
fn inverted_polarity_length_crc_and_alert_pages_are_reported() {
    let enc = encoder(&realistic(21, epoch()));
    let s = soft(&enc.page_symbols(3));
    let inverted: Vec<f32> = s.iter().map(|x| -x).collect();
    assert_eq!(decode_page(&inverted), Err(InavDecodeError::Sync(10)));
    assert_eq!(decode_page(&s[..499]), Err(InavDecodeError::Length(499)));
    assert_eq!(
        decode_page_part(&s[..251]),
        Err(InavDecodeError::Length(251))
    );
    // A burst the code cannot correct: 20 consecutive encoded bits' worth of symbols.
    let mut burst = s.clone();
    for j in 0..40 {
        let k = 10 + interleaved_index(60 + j);
        burst[k] = -burst[k];
    }
    assert_eq!(decode_page(&burst), Err(InavDecodeError::Crc));
    // Page type 1 in the even part: an alert page.
    let [mut even, odd] = enc.part_bits(3);
    even[1] = 1;
    let mut alert = super::super::pages::encode_part(&even).to_vec();
    alert.extend(super::super::pages::encode_part(&odd));
    assert_eq!(decode_page(&soft(&alert)), Err(InavDecodeError::Alert));
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn random_soft_symbols_never_panic(
        v in proptest::collection::vec(-10.0f32..10.0, 0..600),
        sync in any::<bool>(),
    ) {
        let mut v = v;
        if sync && v.len() >= 260 {
            for at in [0, 250] {
                for (x, &b) in v[at..].iter_mut().zip(&INAV_SYNC) {
                    *x = if b == 0 { 1.0 } else { -1.0 };
                }
            }
        }
        let _ = decode_page(&v);
        let _ = decode_page_part(&v);
    }

    #[test]
    fn non_finite_symbols_never_panic(nan_at in 0usize..500, page in 0u64..60) {
        let enc = encoder(&realistic(2, epoch()));
        let mut s = soft(&enc.page_symbols(page));
        s[nan_at] = f32::NAN;
        s[(nan_at + 250) % 500] = f32::INFINITY;
        let _ = decode_page(&s);
    }
}
