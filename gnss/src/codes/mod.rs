//! Ranging codes: GPS L1 C/A and L5, Galileo E5a (and E1 from the user's tables), BeiDou
//! B1I, B1C and B2a, with their secondary codes.
//!
//! Chips are given in two forms:
//! - logic level, `u8` in {0, 1}, as printed in the ICD tables;
//! - signal level, `i8` in {+1, -1}, ready to multiply a carrier.
//!
//! The mapping is logic 0 -> +1 and logic 1 -> -1 ([`level_from_logic`]), the usual
//! BPSK convention (IS-GPS-200 §3.3.1.1 and BDS-SIS-ICD-B1I §4.2.2 both modulate by
//! modulo-2 addition, which this mapping turns into a product).

pub(crate) mod bds_b1c;
pub(crate) mod bds_b1i;
pub(crate) mod bds_b2a;
pub(crate) mod galileo_e1;
pub(crate) mod galileo_e5a;
pub(crate) mod gps_ca;
pub(crate) mod gps_l5;
pub mod neumann_hoffman;
mod table;
mod weil;

#[cfg(test)]
mod bit_correlation;

pub use bds_b1c::{
    BDS_B1C_CHIP_RATE_HZ, BDS_B1C_CODE_LENGTH, BDS_B1C_PRN_MAX, BDS_B1C_SECONDARY_LENGTH,
    bds_b1c_data, bds_b1c_pilot, bds_b1c_pilot_secondary,
};
pub use bds_b1i::{BDS_B1I_CHIP_RATE_HZ, bds_b1i};
pub use bds_b2a::{
    BDS_B2A_CHIP_RATE_HZ, BDS_B2A_CODE_LENGTH, BDS_B2A_DATA_SECONDARY,
    BDS_B2A_PILOT_SECONDARY_LENGTH, BDS_B2A_PRN_MAX, bds_b2a_data, bds_b2a_pilot,
    bds_b2a_pilot_secondary,
};
pub use galileo_e1::{
    E1_CODES_CHECK_ENV, E1_CODES_ENV, E1Codes, E1CodesError, GALILEO_E1_C_SECONDARY,
    GALILEO_E1_CHIP_RATE_HZ, GALILEO_E1_CODE_LENGTH, GALILEO_E1_PRN_MAX, e1_codes, galileo_e1b,
    galileo_e1c,
};
pub use galileo_e5a::{
    GALILEO_E5A_CHIP_RATE_HZ, GALILEO_E5A_CODE_LENGTH, GALILEO_E5A_I_SECONDARY,
    GALILEO_E5A_PRN_MAX, GALILEO_E5A_Q_SECONDARY_LENGTH, galileo_e5a_i, galileo_e5a_q,
    galileo_e5a_q_secondary,
};
pub use gps_ca::{GPS_CA_CHIP_RATE_HZ, GPS_CA_CODE_LENGTH, gps_ca};
pub use gps_l5::{
    GPS_L5_CHIP_RATE_HZ, GPS_L5_CODE_LENGTH, GPS_L5_I_NH10, GPS_L5_PRN_MAX, GPS_L5_Q_NH20,
    gps_l5_i, gps_l5_q,
};

/// Signal level of a logic chip: logic 0 -> +1, logic 1 -> -1 (only the lowest bit is used).
pub const fn level_from_logic(bit: u8) -> i8 {
    1 - 2 * (bit & 1) as i8
}

/// Signal levels of a whole sequence of logic chips ([`level_from_logic`] chip by chip).
pub const fn levels_from_logic<const N: usize>(logic: [u8; N]) -> [i8; N] {
    let mut levels = [0i8; N];
    let mut i = 0;
    while i < N {
        levels[i] = level_from_logic(logic[i]);
        i += 1;
    }
    levels
}

/// Signal levels of a vector of logic chips.
fn levels(logic: Vec<u8>) -> Vec<i8> {
    logic.into_iter().map(level_from_logic).collect()
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

/// A register state printed as a binary number whose leftmost digit is stage 1 (as
/// IS-GPS-705 Tables 3-Ia/3-Ib and BDS-SIS-ICD-B2a Tables 5-2/5-3 print them), in the
/// stage-k-in-bit-(k-1) form of [`shift_register_step`].
const fn state_from_stage_1_first(printed: u32, stages: u32) -> u16 {
    (printed.reverse_bits() >> (32 - stages)) as u16
}

/// A Fibonacci shift register as [`shift_register_step`] clocks it: its number of stages,
/// its feedback stages and the state it starts from (stage k in bit k-1).
#[derive(Clone, Copy, Debug)]
struct Register {
    stages: u32,
    feedback: u16,
    start: u16,
}

impl Register {
    /// The register's state after `clocks` clocks from its start state.
    #[cfg(test)]
    fn state_after(self, clocks: usize) -> u16 {
        (0..clocks).fold(self.start, |state, _| {
            shift_register_step(state, self.feedback, self.stages).1
        })
    }
}

/// The first `length` chips of the modulo-2 sum of two registers' outputs, register 1
/// restarting from its start state every `restart_1` chips (the "short cycle" of IS-GPS-705
/// §3.3.2 and BDS-SIS-ICD-B2a §5.2.1; a `restart_1` of `length` or more never restarts).
///
/// This is the code generator of IS-GPS-705 §3.3.2, the Galileo OS SIS ICD's E5 codes and
/// BDS-SIS-ICD-B2a §5.2.1: one register starts from all ones, the other from a PRN's state.
fn two_register_code(r1: Register, restart_1: usize, r2: Register, length: usize) -> Vec<u8> {
    let (mut s1, mut s2) = (r1.start, r2.start);
    let mut chips = Vec::with_capacity(length);
    for i in 1..=length {
        let (out1, next1) = shift_register_step(s1, r1.feedback, r1.stages);
        let (out2, next2) = shift_register_step(s2, r2.feedback, r2.stages);
        chips.push(out1 ^ out2);
        s1 = if i % restart_1 == 0 { r1.start } else { next1 };
        s2 = next2;
    }
    chips
}

/// Test support: chips packed into a word, first chip in the most significant bit (the way
/// the ICDs print first and last chips in octal or hexadecimal).
#[cfg(test)]
fn chips_word(chips: &[u8]) -> u32 {
    chips.iter().fold(0, |acc, &c| (acc << 1) | u32::from(c))
}

/// Test support: the period of the register with `feedback` started from all ones (2^n - 1
/// for a maximal-length register; gives up past 2^n).
#[cfg(test)]
fn register_period(feedback: u16, stages: u32) -> usize {
    let all_ones = (1u16 << stages) - 1;
    let mut state = all_ones;
    for period in 1..=1usize << stages {
        state = shift_register_step(state, feedback, stages).1;
        if state == all_ones {
            return period;
        }
    }
    usize::MAX
}

/// Test support: asserts that no two of `codes` are equal (`what` names them in the message).
#[cfg(test)]
fn assert_distinct(what: &str, codes: &[Vec<u8>]) {
    for (a, code) in codes.iter().enumerate() {
        if let Some(b) = codes[a + 1..].iter().position(|other| other == code) {
            panic!("{what}: codes {a} and {} are equal", a + 1 + b);
        }
    }
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
