//! The message decoder under noise, polarity errors, missing lead-in and garbage.

use super::super::{CNAV_LEAD_IN_SYMBOLS, CnavDecodeError, decode_message};
use super::{assemble, decode_messages, encoder, epoch, realistic, window};
use proptest::prelude::*;

#[test]
fn a_message_mid_week_decodes_from_the_stream() {
    let enc = encoder(&realistic(21, epoch()));
    // Thursday afternoon: the decoder knows nothing but the 740 symbols around it.
    let n = 4 * 14_400 + 9_001;
    let m = decode_message(&window(&enc, n)).unwrap();
    assert_eq!(m.msg_type, enc.message_type(n));
    assert_eq!(u64::from(m.tow_count), n + 1);
    // Without the symbols after the message, and with the lead-in erased.
    let mut w = window(&enc, n);
    w.truncate(CNAV_LEAD_IN_SYMBOLS + 600);
    w[..CNAV_LEAD_IN_SYMBOLS].fill(0.0);
    assert_eq!(decode_message(&w).unwrap(), m);
}

#[test]
fn scattered_symbol_errors_are_corrected() {
    let enc = encoder(&realistic(21, epoch()));
    for n in 100..106 {
        let clean = decode_message(&window(&enc, n)).unwrap();
        let mut w = window(&enc, n);
        // One error in 20 symbols, lead-in and lead-out included.
        for s in w.iter_mut().skip(n as usize % 20).step_by(20) {
            *s = -*s;
        }
        assert_eq!(decode_message(&w).unwrap(), clean, "message {n}");
    }
}

#[test]
fn weak_wrong_soft_symbols_are_outvoted() {
    let enc = encoder(&realistic(21, epoch()));
    let clean = decode_message(&window(&enc, 7)).unwrap();
    let mut w = window(&enc, 7);
    for x in w.iter_mut().step_by(4) {
        *x *= -0.3;
    }
    assert_eq!(decode_message(&w).unwrap(), clean);
}

#[test]
fn inverted_polarity_length_and_bursts_are_reported() {
    let enc = encoder(&realistic(21, epoch()));
    let w = window(&enc, 3);
    let inverted: Vec<f32> = w.iter().map(|x| -x).collect();
    assert_eq!(
        decode_message(&inverted),
        Err(CnavDecodeError::InvertedPolarity)
    );
    assert_eq!(
        decode_message(&w[..669]),
        Err(CnavDecodeError::Length {
            need: 670,
            got: 669
        })
    );
    // A burst the code cannot correct: 60 symbols of the payload inverted.
    let mut burst = w.clone();
    burst[300..360].iter_mut().for_each(|x| *x = -*x);
    assert_eq!(decode_message(&burst), Err(CnavDecodeError::Crc));
    // A burst over the preamble.
    let mut head = w.clone();
    head[70..90].iter_mut().for_each(|x| *x = -*x);
    assert_eq!(decode_message(&head), Err(CnavDecodeError::Preamble));
}

#[test]
fn a_message_of_the_wrong_satellite_restarts_the_assembly() {
    let a = encoder(&realistic(4, epoch()));
    let b = encoder(&realistic(6, epoch()));
    let (ma, mb) = (decode_messages(&a, 0, 4), decode_messages(&b, 0, 4));
    // 10 and 11 of PRN 4, then 30 of PRN 6: no set; PRN 6 needs its own 10 and 11.
    let mixed = [ma[0].clone(), ma[1].clone(), mb[2].clone()];
    assert!(assemble(&mixed).is_empty());
    assert_eq!(assemble(&mb[..3]).len(), 1);
}

#[test]
fn a_set_with_adot_or_delta_n_dot_is_not_returned() {
    let enc = encoder(&realistic(4, epoch()));
    let mut ms = decode_messages(&enc, 0, 3);
    let adot = ms[0].fields().position(|(n, _)| n == "Adot").unwrap();
    ms[0].values[adot] = 5;
    assert!(assemble(&ms).is_empty());
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    #[test]
    fn random_soft_symbols_never_panic(v in proptest::collection::vec(-10.0f32..10.0, 0..800)) {
        let _ = decode_message(&v);
    }

    #[test]
    fn non_finite_symbols_never_panic(at in 0usize..740, n in 1u64..40) {
        let enc = encoder(&realistic(2, epoch()));
        let mut w = window(&enc, n);
        w[at] = f32::NAN;
        w[(at + 370) % 740] = f32::INFINITY;
        let _ = decode_message(&w);
    }
}
