//! Galileo E5a ranging codes E5a-I (F/NAV data) and E5a-Q (pilot) with their secondary
//! codes (Galileo OS SIS ICD Issue 2.1, 2023-11: the E5 code generator parameters, the
//! E5a-I and E5a-Q start-value tables, Tables 16 and 17 in the numbering the transcription of
//! `data/galileo_e5a.txt` cites, and the secondary-code tables).
//!
//! Each 10230-chip (1 ms) primary code is the modulo-2 sum of two 14-stage registers, the
//! truncated sum of two m-sequences of period 16383. Both components use the same feedback:
//! register 1 taps 40503 and register 2 taps 50661 (octal, bit d standing for x^d, bit 0 the
//! constant term), each register putting out its stage 14. Register 1 starts from all ones,
//! register 2 from the code's start value (octal, stage k in bit k-1); both restart at every
//! code epoch. The secondary codes add one chip per primary period: CS20_1 (20 chips) on
//! E5a-I, CS100_n (100 chips) on E5a-Q code n.

use std::sync::OnceLock;

use super::table::{hex_chip_rows, numeric_rows};
use super::{Register, levels, levels_from_logic, two_register_code};

/// E5a chip rate, chips per second (Galileo OS SIS ICD).
pub const GALILEO_E5A_CHIP_RATE_HZ: f64 = 10.23e6;
/// E5a primary code length in chips: one period is 1 ms (Galileo OS SIS ICD).
pub const GALILEO_E5A_CODE_LENGTH: usize = 10230;
/// Highest E5a code number in the ICD's tables (code n is used by the satellite of SVID n).
pub const GALILEO_E5A_PRN_MAX: u8 = 50;

/// E5a-I secondary code CS20_1, logic chips, first chip first: hexadecimal 842E9 as the
/// ICD's secondary-code table prints it.
pub const GALILEO_E5A_I_CS20_LOGIC: [u8; 20] =
    [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 1, 1, 1, 0, 1, 0, 0, 1];
/// CS20_1 as signal levels, one chip per 1 ms primary period (20 ms, one F/NAV symbol).
pub const GALILEO_E5A_I_SECONDARY: [i8; 20] = levels_from_logic(GALILEO_E5A_I_CS20_LOGIC);
/// E5a-Q secondary code length in chips (100 ms).
pub const GALILEO_E5A_Q_SECONDARY_LENGTH: usize = 100;

const STAGES: u32 = 14;
/// Register 1 taps, octal 40503 (the ICD's table of E5 code generator parameters).
const R1_TAPS_OCTAL: u32 = 0o40503;
/// Register 2 taps, octal 50661 (same table).
const R2_TAPS_OCTAL: u32 = 0o50661;
/// Register 1 starts every code from all ones.
const ALL_ONES: u16 = (1 << STAGES) - 1;

/// Feedback mask of a register whose taps the ICD gives in octal: bit d (x^d) is stage d.
const fn feedback_from_octal_taps(taps: u32) -> u16 {
    (taps >> 1) as u16
}

/// Tables 16/17: register-2 start values and first chips; see the file's header.
const TABLE: &str = include_str!("data/galileo_e5a.txt");
/// The CS100 table, codes 1-50.
const CS100: &str = include_str!("data/galileo_cs100.txt");

/// Columns of `TABLE`: start value and first 24 chips, for E5a-I then E5a-Q.
fn table() -> &'static [Vec<u32>] {
    static ROWS: OnceLock<Vec<Vec<u32>>> = OnceLock::new();
    ROWS.get_or_init(|| numeric_rows("data/galileo_e5a.txt", TABLE, &[8, 16, 8, 16]))
}

fn cs100() -> &'static [Vec<u8>] {
    static ROWS: OnceLock<Vec<Vec<u8>>> = OnceLock::new();
    ROWS.get_or_init(|| {
        hex_chip_rows(
            "data/galileo_cs100.txt",
            CS100,
            GALILEO_E5A_Q_SECONDARY_LENGTH,
        )
    })
}

/// The primary code of code number `prn` whose register-2 start value is in `column`.
fn primary(prn: u8, column: usize) -> Option<Vec<u8>> {
    let row = table().get(usize::from(prn).checked_sub(1)?)?;
    let register_1 = Register {
        stages: STAGES,
        feedback: feedback_from_octal_taps(R1_TAPS_OCTAL),
        start: ALL_ONES,
    };
    let register_2 = Register {
        stages: STAGES,
        feedback: feedback_from_octal_taps(R2_TAPS_OCTAL),
        start: row[column] as u16,
    };
    Some(two_register_code(
        register_1,
        GALILEO_E5A_CODE_LENGTH,
        register_2,
        GALILEO_E5A_CODE_LENGTH,
    ))
}

/// One period (10230 chips) of the E5a-I primary code of code number `prn` (1..=50) as logic
/// chips, chip 0 first; `None` outside 1..=50.
pub fn galileo_e5a_i_logic(prn: u8) -> Option<Vec<u8>> {
    primary(prn, 0)
}

/// One period (10230 chips) of the E5a-Q primary code of code number `prn` (1..=50) as logic
/// chips, chip 0 first; `None` outside 1..=50.
pub fn galileo_e5a_q_logic(prn: u8) -> Option<Vec<u8>> {
    primary(prn, 2)
}

/// The E5a-I primary code of `prn` as signal levels (logic 0 -> +1, logic 1 -> -1).
pub fn galileo_e5a_i(prn: u8) -> Option<Vec<i8>> {
    galileo_e5a_i_logic(prn).map(levels)
}

/// The E5a-Q primary code of `prn` as signal levels (logic 0 -> +1, logic 1 -> -1).
pub fn galileo_e5a_q(prn: u8) -> Option<Vec<i8>> {
    galileo_e5a_q_logic(prn).map(levels)
}

/// The E5a-Q secondary code CS100_`prn` as signal levels, one chip per primary period, chip
/// 0 first; `None` outside 1..=50.
pub fn galileo_e5a_q_secondary(prn: u8) -> Option<Vec<i8>> {
    let chips = cs100().get(usize::from(prn).checked_sub(1)?)?;
    Some(levels(chips.clone()))
}

#[cfg(test)]
mod tests {
    use super::super::{assert_distinct, chips_word as word, register_period};
    use super::*;

    /// Every code's first 24 chips equal the hexadecimal value the ICD prints beside its
    /// start value, for E5a-I and E5a-Q codes 1-50.
    #[test]
    fn first_24_chips_match_the_icd_for_every_code() {
        assert_eq!(table().len(), usize::from(GALILEO_E5A_PRN_MAX));
        for prn in 1..=GALILEO_E5A_PRN_MAX {
            let row = &table()[usize::from(prn) - 1];
            let i = galileo_e5a_i_logic(prn).expect("code in range");
            let q = galileo_e5a_q_logic(prn).expect("code in range");
            assert_eq!(
                word(&i[..24]),
                row[1],
                "E5a-I {prn}: {:06X}",
                word(&i[..24])
            );
            assert_eq!(
                word(&q[..24]),
                row[3],
                "E5a-Q {prn}: {:06X}",
                word(&q[..24])
            );
            assert_eq!(i.len(), GALILEO_E5A_CODE_LENGTH);
        }
    }

    #[test]
    fn both_registers_are_maximal_length_with_period_16383() {
        for taps in [R1_TAPS_OCTAL, R2_TAPS_OCTAL] {
            let feedback = feedback_from_octal_taps(taps);
            assert_eq!(register_period(feedback, STAGES), 16383, "taps {taps:o}");
        }
    }

    #[test]
    fn all_100_primary_codes_are_distinct() {
        let codes: Vec<_> = (1..=GALILEO_E5A_PRN_MAX)
            .flat_map(|prn| [galileo_e5a_i_logic(prn), galileo_e5a_q_logic(prn)])
            .map(|code| code.expect("code in range"))
            .collect();
        assert_distinct("E5a-I and E5a-Q", &codes);
    }

    /// CS20_1 is 842E9; CS100_1 starts 83F6F69D8F6E and CS100_50 ends F749F56 as printed. The
    /// 50 CS100 codes are distinct and each has 100 chips.
    #[test]
    fn secondary_codes_match_the_icd() {
        assert_eq!(word(&GALILEO_E5A_I_CS20_LOGIC), 0x842E9);
        let first = galileo_e5a_q_secondary(1).expect("code 1");
        let first_logic: Vec<u8> = first.iter().map(|&v| u8::from(v < 0)).collect();
        assert_eq!(
            first_logic[..48]
                .iter()
                .fold(0u64, |a, &c| (a << 1) | u64::from(c)),
            0x83F6_F69D_8F6E
        );
        let last = galileo_e5a_q_secondary(50).expect("code 50");
        let last_logic: Vec<u8> = last.iter().map(|&v| u8::from(v < 0)).collect();
        assert_eq!(word(&last_logic[72..]), 0xF749F56);
        assert_eq!(cs100().len(), usize::from(GALILEO_E5A_PRN_MAX));
        assert!(
            cs100()
                .iter()
                .all(|c| c.len() == GALILEO_E5A_Q_SECONDARY_LENGTH)
        );
        assert_distinct("CS100", cs100());
        assert!(galileo_e5a_q_secondary(51).is_none());
    }

    #[test]
    fn code_outside_1_to_50_has_none() {
        for prn in [0u8, 51, 255] {
            assert!(galileo_e5a_i(prn).is_none());
            assert!(galileo_e5a_q(prn).is_none());
        }
        assert_eq!(GALILEO_E5A_I_SECONDARY[0], -1);
    }
}
