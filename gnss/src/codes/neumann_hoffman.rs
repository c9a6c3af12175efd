//! The 20-chip Neumann-Hoffman secondary code of the BeiDou D1 message
//! (BDS-SIS-ICD-B1I-3.0 §5.2.1 "Secondary Code Modulated on D1").
//!
//! On MEO/IGSO D1 signals each 50 bit/s navigation bit (20 ms) is spread by the NH code
//! (0,0,0,0,0,1,0,0,1,1,0,1,0,1,0,0,1,1,1,0), one NH chip per 1 ms ranging-code period,
//! the first NH chip starting together with the navigation bit.

use super::levels_from_logic;

/// NH code length in chips (one navigation bit).
pub const NH20_LENGTH: usize = 20;
/// Duration of one NH chip, seconds: one B1I code period.
pub const NH20_CHIP_DURATION_S: f64 = 1e-3;

/// The NH code as logic chips, first chip first (BDS-SIS-ICD-B1I-3.0 §5.2.1).
pub const NH20_LOGIC: [u8; NH20_LENGTH] =
    [0, 0, 0, 0, 0, 1, 0, 0, 1, 1, 0, 1, 0, 1, 0, 0, 1, 1, 1, 0];

/// The NH code as signal levels (logic 0 -> +1, logic 1 -> -1), first chip first.
pub const NH20: [i8; NH20_LENGTH] = levels_from_logic(NH20_LOGIC);

/// NH level of the `code_period_index`-th 1 ms code period counted from the start of a
/// navigation bit (wraps every 20 periods).
pub const fn nh20_level(code_period_index: u64) -> i8 {
    NH20[(code_period_index % NH20_LENGTH as u64) as usize]
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The same 20 chips written as one 20-bit word, first chip most significant:
    /// 0000 0100 1101 0100 1110 = 0x04D4E. IS-GPS-705 §3.3.2.3 uses this same 20-bit
    /// Neumann-Hoffman code on the L5 Q5 channel.
    const ICD_NH20_WORD: u32 = 0x04D4E;

    #[test]
    fn chips_match_the_icd_sequence() {
        let word = NH20_LOGIC
            .iter()
            .fold(0u32, |acc, &chip| (acc << 1) | u32::from(chip));
        assert_eq!(word, ICD_NH20_WORD);
    }

    #[test]
    fn levels_map_logic_0_to_plus_1() {
        for (logic, level) in NH20_LOGIC.iter().zip(NH20) {
            assert_eq!(level, if *logic == 0 { 1 } else { -1 });
        }
        // 8 ones and 12 zeros: level sum 12 - 8 = 4.
        assert_eq!(NH20.iter().map(|&c| i32::from(c)).sum::<i32>(), 4);
    }

    #[test]
    fn level_wraps_every_twenty_code_periods() {
        for k in 0..100u64 {
            assert_eq!(nh20_level(k), NH20[(k % 20) as usize]);
        }
        assert_eq!(nh20_level(5), -1);
        assert_eq!(nh20_level(20), 1);
        assert_eq!(nh20_level(u64::MAX), NH20[(u64::MAX % 20) as usize]);
    }
}
