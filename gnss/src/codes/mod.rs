//! Ranging codes: GPS L1 C/A, BeiDou B1I, and the Neumann-Hoffman secondary code.
//!
//! Chips are given in two forms:
//! - logic level, `u8` in {0, 1}, as printed in the ICD tables;
//! - signal level, `i8` in {+1, -1}, ready to multiply a carrier.
//!
//! The mapping is logic 0 -> +1 and logic 1 -> -1 ([`level_from_logic`]), the usual
//! BPSK convention (IS-GPS-200 §3.3.1.1 and BDS-SIS-ICD-B1I §4.2.2 both modulate by
//! modulo-2 addition, which this mapping turns into a product).

pub(crate) mod bds_b1i;
pub(crate) mod gps_ca;
pub mod neumann_hoffman;

#[cfg(test)]
mod bit_correlation;

pub use bds_b1i::{BDS_B1I_CHIP_RATE_HZ, bds_b1i};
pub use gps_ca::{GPS_CA_CHIP_RATE_HZ, GPS_CA_CODE_LENGTH, gps_ca};

/// Signal level of a logic chip: logic 0 -> +1, logic 1 -> -1 (only the lowest bit is used).
pub const fn level_from_logic(bit: u8) -> i8 {
    1 - 2 * (bit & 1) as i8
}

/// Bit mask of shift-register stage `k` (1-based), stage k being bit k-1.
const fn stage(k: u32) -> u16 {
    1 << (k - 1)
}

/// One clock of a Fibonacci shift register of `stages` stages, stage k held in bit k-1.
///
/// Returns the output chip (the last stage, before the clock) and the next state: every
/// stage moves to the next one and stage 1 takes the modulo-2 sum of the stages in
/// `feedback`. This is the register of IS-GPS-200 §3.3.2.3 and BDS-SIS-ICD-B1I-3.0 §4.3
/// (a polynomial 1 + sum of x^k means stage k feeds back).
const fn shift_register_step(state: u16, feedback: u16, stages: u32) -> (u8, u16) {
    let output = ((state >> (stages - 1)) & 1) as u8;
    let input = ((state & feedback).count_ones() & 1) as u16;
    let mask = (1u16 << stages) - 1;
    (output, ((state << 1) | input) & mask)
}

#[cfg(test)]
mod tests {
    use super::level_from_logic;

    #[test]
    fn logic_zero_is_plus_one_and_logic_one_is_minus_one() {
        assert_eq!(level_from_logic(0), 1);
        assert_eq!(level_from_logic(1), -1);
    }

    #[test]
    fn product_of_levels_is_level_of_xor() {
        for a in 0..2u8 {
            for b in 0..2u8 {
                assert_eq!(
                    level_from_logic(a) * level_from_logic(b),
                    level_from_logic(a ^ b)
                );
            }
        }
    }
}
