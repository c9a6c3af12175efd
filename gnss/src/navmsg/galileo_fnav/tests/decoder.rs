//! The page decoder under noise, polarity errors and garbage.

use super::super::{FnavDecodeError, decode_page};
use super::{encoder, epoch, realistic, soft};
use proptest::prelude::*;

#[test]
fn scattered_symbol_errors_are_corrected() {
    let enc = encoder(&realistic(21, epoch()));
    for n in 100..106 {
        let clean = decode_page(&soft(&enc.page_symbols(n))).unwrap();
        let mut symbols = enc.page_symbols(n);
        // One error in 20 symbols, sync pattern included.
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
    for x in s.iter_mut().skip(12).step_by(5) {
        *x *= -0.3;
    }
    assert_eq!(decode_page(&s).unwrap(), clean);
}

#[test]
fn inverted_polarity_length_and_crc_are_reported() {
    let enc = encoder(&realistic(21, epoch()));
    let s = soft(&enc.page_symbols(3));
    let inverted: Vec<f32> = s.iter().map(|x| -x).collect();
    assert_eq!(decode_page(&inverted), Err(FnavDecodeError::Sync(12)));
    assert_eq!(decode_page(&s[..499]), Err(FnavDecodeError::Length(499)));
    // A burst the code cannot correct: 40 consecutive encoded bits' worth of symbols.
    let mut burst = s.clone();
    for j in 0..80 {
        let k = 12 + super::super::pages::interleaved_index(100 + j);
        burst[k] = -burst[k];
    }
    assert_eq!(decode_page(&burst), Err(FnavDecodeError::Crc));
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn random_soft_symbols_never_panic(
        v in proptest::collection::vec(-10.0f32..10.0, 0..600),
        sync in any::<bool>(),
    ) {
        let mut v = v;
        if sync && v.len() >= 12 {
            for (x, &b) in v.iter_mut().zip(&super::super::FNAV_SYNC) {
                *x = if b == 0 { 1.0 } else { -1.0 };
            }
        }
        let _ = decode_page(&v);
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
