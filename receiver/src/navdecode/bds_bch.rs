//! BeiDou D1/D2 error correction: BCH(15,11,1) with g(x) = x^4 + x + 1 and the bit
//! interleaving of words 2-10 (BDS-SIS-ICD-B1I-3.0 §5.1.3).
//!
//! Word 1 sends its first 15 bits (preamble, Rev) uncoded and then one codeword; words
//! 2-10 interleave two codewords bit by bit (first codeword on the first-sent bit). A
//! codeword is 11 information bits then 4 parity bits, highest degree first. The code is
//! a cyclic Hamming code: every single error has its own syndrome x^j mod g(x), so one
//! error per codeword is corrected; two errors are miscorrected (not detectable).

/// Information bits of a subframe: 26 in word 1, 22 in each of words 2-10.
pub(crate) const INFO_BITS: usize = 26 + 9 * 22;

/// g(x) = x^4 + x + 1.
const G: u32 = 0b1_0011;

/// Remainder of a 15-bit word (bit 14 = x^14) divided by g(x).
const fn syndrome(cw: u32) -> u32 {
    let mut r = cw & 0x7FFF;
    let mut deg = 14;
    while deg >= 4 {
        if (r >> deg) & 1 == 1 {
            r ^= G << (deg - 4);
        }
        deg -= 1;
    }
    r
}

/// Error pattern of each syndrome (index = syndrome): the single bit x^j with
/// x^j mod g(x) = syndrome; 0 for syndrome 0.
const ERROR_OF_SYNDROME: [u32; 16] = {
    let mut t = [0u32; 16];
    let mut j = 0;
    while j < 15 {
        t[syndrome(1 << j) as usize] = 1 << j;
        j += 1;
    }
    t
};

/// The 11 information bits of a received codeword after correcting at most one error,
/// and whether a bit was corrected.
fn correct(cw: u32) -> (u32, bool) {
    let s = syndrome(cw) as usize;
    let fixed = (cw ^ ERROR_OF_SYNDROME[s]) & 0x7FFF;
    (fixed >> 4, s != 0)
}

/// Value of `bits` (0/1, first most significant).
fn pack(bits: impl Iterator<Item = u8>) -> u32 {
    bits.fold(0u32, |a, b| (a << 1) | u32::from(b & 1))
}

/// Append the `len` low bits of `v`, most significant first.
fn unpack(v: u32, len: usize, out: &mut Vec<u8>) {
    out.extend((0..len).rev().map(|k| ((v >> k) & 1) as u8));
}

/// The information bits of a 300-bit subframe (true polarity) in the ICD's order, and the
/// number of corrected bits.
pub(crate) fn decode_subframe(bits: &[u8]) -> (Vec<u8>, u32) {
    let bit = |k: usize| bits.get(k).copied().unwrap_or(0);
    let mut info = Vec::with_capacity(INFO_BITS);
    info.extend((0..15).map(bit));
    let (w1, c) = correct(pack((15..30).map(bit)));
    let mut corrected = u32::from(c);
    unpack(w1, 11, &mut info);
    for word in 1..10 {
        let start = 30 * word;
        let first = pack((0..15).map(|k| bit(start + 2 * k)));
        let second = pack((0..15).map(|k| bit(start + 2 * k + 1)));
        for cw in [first, second] {
            let (v, c) = correct(cw);
            corrected += u32::from(c);
            unpack(v, 11, &mut info);
        }
    }
    (info, corrected)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn syndromes_of_single_errors_are_distinct_and_nonzero() {
        let mut seen = [false; 16];
        for j in 0..15 {
            let s = syndrome(1 << j) as usize;
            assert!(s != 0 && !seen[s], "x^{j}");
            seen[s] = true;
        }
        // Hand computation: x^4 = x + 1, so x^12 = (x + 1)^3 = x^3 + x^2 + x + 1 and
        // x^13 = x^3 + x^2 + 1; m(x) = x^9 + x^8 gives m x^4 mod g = x (parity 0010).
        assert_eq!(syndrome(1 << 12), 0b1111);
        assert_eq!(syndrome(1 << 13), 0b1101);
        assert_eq!(syndrome(0b011_0000_0000 << 4), 0b0010);
        assert_eq!(syndrome((0b011_0000_0000 << 4) | 0b0010), 0);
        // All ones is a codeword: g(x) divides x^15 + 1 = (x + 1)(x^14 + ... + 1) and
        // g(1) = 1, so g(x) divides the all-ones polynomial.
        assert_eq!(syndrome(0x7FFF), 0);
    }

    #[test]
    fn one_error_per_codeword_is_corrected() {
        let cw = (0b101_1100_0110 << 4) | syndrome(0b101_1100_0110 << 4);
        assert_eq!(syndrome(cw), 0);
        for j in 0..15 {
            assert_eq!(correct(cw ^ (1 << j)), (0b101_1100_0110, true));
        }
        assert_eq!(correct(cw), (0b101_1100_0110, false));
    }

    #[test]
    fn words_are_deinterleaved_first_codeword_first() {
        // Word 2 carries codeword A = all ones (info 0x7FF) on the first-sent bits and
        // codeword B = 0 on the others: 1010...10.
        let mut bits = vec![0u8; 300];
        for k in 0..15 {
            bits[30 + 2 * k] = 1;
        }
        let (info, corrected) = decode_subframe(&bits);
        assert_eq!(corrected, 0);
        assert_eq!(info.len(), INFO_BITS);
        assert!(info[26..37].iter().all(|&b| b == 1));
        assert!(info[37..48].iter().all(|&b| b == 0));
    }
}
