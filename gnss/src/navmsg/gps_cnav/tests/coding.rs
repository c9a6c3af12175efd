//! The continuous FEC and the symbol timeline.

use super::{PER_WEEK, encoder, epoch, realistic};
use crate::navmsg::conv_k7::ConvK7;

#[test]
fn the_code_runs_on_across_messages() {
    let enc = encoder(&realistic(9, epoch()));
    // Encoding messages n - 1 and n as one stream from the zero state: its last 600
    // symbols must be message n's, whose encoder state the bits of n - 1 set.
    for n in [1u64, 2, 3, 1234, PER_WEEK - 1, PER_WEEK, PER_WEEK + 1] {
        let stream: Vec<u8> = (n - 1..=n).flat_map(|m| enc.message_bits(m)).collect();
        let symbols = ConvK7::GPS_L5.encode(&stream);
        assert_eq!(enc.message_symbols(n), symbols[600..], "message {n}");
    }
    // Message 0 continues the last message of the previous week (type 33, whose last
    // six bits are CRC bits), not the zero state.
    let cold = ConvK7::GPS_L5.encode(&enc.message_bits(0));
    assert_ne!(enc.message_symbols(0)[..12], cold[..12]);
}

#[test]
fn g1_comes_first_and_symbol_k_is_at_k_hundredths_of_a_second() {
    let enc = encoder(&realistic(9, epoch()));
    let n = 777u64;
    let bits = enc.message_bits(n);
    let previous = enc.message_bits(n - 1);
    // The first two symbols by hand from the generators (current bit first, taps
    // 1111001 and 1011011 over b_t .. b_t-6).
    let b = |j: usize| previous[300 - j];
    let g1 = (bits[0] + b(1) + b(2) + b(3) + b(6)) % 2;
    let g2 = (bits[0] + b(2) + b(3) + b(5) + b(6)) % 2;
    let k = n * 600;
    assert_eq!([enc.symbol(k), enc.symbol(k + 1)], [g1, g2]);
    // Message n starts at 6 n s, i.e. at symbol 100 * 6 n.
    let (week, tow) = enc.message_time(n);
    assert_eq!((week, u64::from(tow) * 100), (super::WEEK, k));
}

#[test]
fn symbols_and_symbol_agree_across_message_boundaries() {
    let enc = encoder(&realistic(9, epoch()));
    let first = 600 * 55 + 417;
    let run = enc.symbols(first, 1500);
    assert_eq!(run.len(), 1500);
    for (i, &s) in run.iter().enumerate() {
        assert_eq!(
            s,
            enc.symbol(first + i as u64),
            "symbol {}",
            first + i as u64
        );
    }
    // Jumping about (the cache must follow).
    for k in [5u64, 600 * 9 + 3, 7, 600 * PER_WEEK + 1, 5] {
        assert_eq!(enc.symbol(k), enc.symbols(k, 1)[0]);
    }
    // A clone encodes the same stream.
    let copy = enc.clone();
    assert_eq!(copy.symbols(first, 50), run[..50]);
}
