//! CRC-24Q, the 24-bit cyclic redundancy check of the Galileo I/NAV and F/NAV pages
//! (Galileo OS SIS ICD, "Checksum": §5.1.9.4 in Issue 1), also used by GPS CNAV and
//! BeiDou B-CNAV.
//!
//! Generator polynomial g(X) = X^24 + X^23 + X^18 + X^17 + X^14 + X^11 + X^10 + X^7 +
//! X^6 + X^5 + X^4 + X^3 + X + 1 (0x1864CFB); the register starts at zero, bits are fed
//! most significant first, and there is no reflection or final inversion. Appending the
//! 24 parity bits to the message makes the whole sequence divisible by g(X).

/// The generator polynomial with its X^24 term (0x1864CFB).
pub const CRC24Q_POLY: u32 = 0x0186_4CFB;

const MASK_24: u32 = 0x00FF_FFFF;

/// The byte-at-a-time table of g(X), built at compile time.
const TABLE: [u32; 256] = build_table();

const fn build_table() -> [u32; 256] {
    let mut table = [0u32; 256];
    let mut byte = 0;
    while byte < 256 {
        let mut reg = (byte as u32) << 16;
        let mut i = 0;
        while i < 8 {
            reg <<= 1;
            if reg & 0x0100_0000 != 0 {
                reg ^= CRC24Q_POLY;
            }
            i += 1;
        }
        table[byte] = reg & MASK_24;
        byte += 1;
    }
    table
}

/// CRC-24Q of whole bytes, continuing from register `init` (0 for a fresh message).
pub fn crc24q_update(init: u32, bytes: &[u8]) -> u32 {
    bytes.iter().fold(init & MASK_24, |reg, &b| {
        let index = ((reg >> 16) as u8 ^ b) as usize;
        ((reg << 8) ^ TABLE[index]) & MASK_24
    })
}

/// CRC-24Q of whole bytes from a zero register.
pub fn crc24q(bytes: &[u8]) -> u32 {
    crc24q_update(0, bytes)
}

/// CRC-24Q of a bit sequence (one bit, 0 or 1, per element; the first element is the
/// first bit sent), from a zero register. Any non-zero element counts as 1.
pub fn crc24q_bits(bits: &[u8]) -> u32 {
    bits.iter().fold(0u32, |reg, &bit| {
        let feedback = ((reg >> 23) & 1) ^ u32::from(bit != 0);
        let shifted = (reg << 1) & MASK_24;
        if feedback == 1 {
            shifted ^ (CRC24Q_POLY & MASK_24)
        } else {
            shifted
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// Polynomial long division of message(X) * X^24 by g(X), one bit at a time: the
    /// textbook definition, independent of both implementations above.
    fn naive(bits: &[u8]) -> u32 {
        let mut dividend: Vec<u8> = bits.to_vec();
        dividend.extend([0u8; 24]);
        let g: Vec<u8> = (0..25)
            .rev()
            .map(|k| ((CRC24Q_POLY >> k) & 1) as u8)
            .collect();
        for i in 0..bits.len() {
            if dividend[i] == 1 {
                for (d, gk) in dividend[i..i + 25].iter_mut().zip(&g) {
                    *d ^= gk;
                }
            }
        }
        dividend[bits.len()..]
            .iter()
            .fold(0, |acc, &b| (acc << 1) | u32::from(b))
    }

    fn to_bits(bytes: &[u8]) -> Vec<u8> {
        bytes
            .iter()
            .flat_map(|b| (0..8).rev().map(move |k| (b >> k) & 1))
            .collect()
    }

    /// An RTCM 3 frame (preamble 0xD3, length 19, message 1005) and its CRC-24Q, the
    /// example of the swiftnav crate's `edc::compute_crc24q` documentation (docs.rs).
    const RTCM_FRAME: [u8; 22] = [
        0xD3, 0x00, 0x13, 0x3E, 0xD7, 0xD3, 0x02, 0x02, 0x98, 0x0E, 0xDE, 0xEF, 0x34, 0xB4, 0xBD,
        0x62, 0xAC, 0x09, 0x41, 0x98, 0x6F, 0x33,
    ];

    #[test]
    fn published_rtcm_frame_vector() {
        assert_eq!(crc24q(&RTCM_FRAME), 0x36_0B98);
        assert_eq!(crc24q_bits(&to_bits(&RTCM_FRAME)), 0x36_0B98);
        assert_eq!(naive(&to_bits(&RTCM_FRAME)), 0x36_0B98);
    }

    #[test]
    fn published_openpgp_check_value() {
        // CRC-24/OPENPGP is the same polynomial started from 0xB704CE; its catalogued check
        // value over the ASCII string "123456789" is 0x21CF02 (RFC 4880 §6.1 algorithm).
        assert_eq!(crc24q_update(0xB7_04CE, b"123456789"), 0x21_CF02);
    }

    #[test]
    fn a_message_followed_by_its_crc_leaves_no_remainder() {
        let crc = crc24q(&RTCM_FRAME);
        let mut framed = RTCM_FRAME.to_vec();
        framed.extend([(crc >> 16) as u8, (crc >> 8) as u8, crc as u8]);
        assert_eq!(crc24q(&framed), 0);
        framed[5] ^= 0x10;
        assert_ne!(crc24q(&framed), 0);
    }

    #[test]
    fn empty_message_is_zero() {
        assert_eq!(crc24q(&[]), 0);
        assert_eq!(crc24q_bits(&[]), 0);
    }

    proptest! {
        #[test]
        fn table_and_bitwise_agree_with_long_division(
            bytes in proptest::collection::vec(any::<u8>(), 0..64),
            extra in proptest::collection::vec(0u8..2, 0..8),
        ) {
            let mut bits = to_bits(&bytes);
            prop_assert_eq!(crc24q(&bytes), naive(&bits));
            bits.extend(&extra);
            prop_assert_eq!(crc24q_bits(&bits), naive(&bits));
        }

        #[test]
        fn split_updates_chain(bytes in proptest::collection::vec(any::<u8>(), 0..64), at in 0usize..64) {
            let at = at.min(bytes.len());
            prop_assert_eq!(crc24q_update(crc24q(&bytes[..at]), &bytes[at..]), crc24q(&bytes));
        }
    }
}
