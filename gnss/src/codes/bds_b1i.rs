//! BeiDou B1I ranging code (BDS-SIS-ICD-B1I-3.0, 2019-02, §4.3 "Ranging Code
//! Characteristics").
//!
//! The B1I code of PRN i is a balanced 2047-chip Gold code truncated by its last chip to
//! 2046 chips (1 ms at 2.046 Mcps). Two 11-stage registers,
//! G1 = 1 + x + x^7 + x^8 + x^9 + x^10 + x^11 and
//! G2 = 1 + x + x^2 + x^3 + x^4 + x^5 + x^8 + x^9 + x^11, both loaded with the initial phase
//! 01010101010 (stage 1 to stage 11) at the start of every period, i.e. reset after 2046
//! chips. G1 puts out its stage 11; the G2 output is the modulo-2 sum of the G2 stages of
//! the PRN's phase assignment (two stages for PRN 1-37, three for PRN 38-63); the code is
//! their modulo-2 sum.

use super::{level_from_logic, shift_register_step, stage};

/// B1I chip rate, chips per second (BDS-SIS-ICD-B1I-3.0 §4.3).
pub const BDS_B1I_CHIP_RATE_HZ: f64 = 2.046e6;
/// B1I code length in chips: the 2047-chip Gold code less its last chip (§4.3).
pub const BDS_B1I_CODE_LENGTH: usize = 2046;
/// Highest PRN with a B1I phase assignment in BDS-SIS-ICD-B1I-3.0.
pub const BDS_B1I_PRN_MAX: u8 = 63;

const STAGES: u32 = 11;
/// G1 = 1 + x + x^7 + x^8 + x^9 + x^10 + x^11.
const G1_FEEDBACK: u16 = stage(1) | stage(7) | stage(8) | stage(9) | stage(10) | stage(11);
/// G2 = 1 + x + x^2 + x^3 + x^4 + x^5 + x^8 + x^9 + x^11.
const G2_FEEDBACK: u16 =
    stage(1) | stage(2) | stage(3) | stage(4) | stage(5) | stage(8) | stage(9) | stage(11);
/// Initial phase 01010101010 of both registers, stage 1 first (the pattern reads the same
/// from stage 11, so the stage order cannot be confused).
const INITIAL_PHASE: u16 = stage(2) | stage(4) | stage(6) | stage(8) | stage(10);

/// G2 stages whose modulo-2 sum forms the G2 output, for PRN 1..=63 (index PRN - 1).
///
/// BDS-SIS-ICD-B1I-3.0 §4.3, table "Phase assignment of G2 sequence" (PRN 1-37 as in
/// BDS-SIS-ICD-2.0 Table 4-2; PRN 38-63, three stages each, from the 3.0 table as quoted
/// identically by two independent public B1I generators, see the tests, and by the
/// 63-entry table of GNSS-SDR's current source; the Debian GNSS-SDR 0.0.17 binary
/// generates PRN 1-33 only).
#[rustfmt::skip]
const G2_PHASE_ASSIGNMENT: [&[u32]; BDS_B1I_PRN_MAX as usize] = [
    // PRN 1-10
    &[1, 3], &[1, 4], &[1, 5], &[1, 6], &[1, 8], &[1, 9], &[1, 10], &[1, 11], &[2, 7], &[3, 4],
    // PRN 11-20
    &[3, 5], &[3, 6], &[3, 8], &[3, 9], &[3, 10], &[3, 11], &[4, 5], &[4, 6], &[4, 8], &[4, 9],
    // PRN 21-30
    &[4, 10], &[4, 11], &[5, 6], &[5, 8], &[5, 9], &[5, 10], &[5, 11], &[6, 8], &[6, 9], &[6, 10],
    // PRN 31-37
    &[6, 11], &[8, 9], &[8, 10], &[8, 11], &[9, 10], &[9, 11], &[10, 11],
    // PRN 38-45
    &[1, 2, 7], &[1, 3, 4], &[1, 3, 6], &[1, 3, 8], &[1, 3, 10], &[1, 3, 11], &[1, 4, 5],
    &[1, 4, 9],
    // PRN 46-53
    &[1, 5, 6], &[1, 5, 8], &[1, 5, 10], &[1, 5, 11], &[1, 6, 9], &[1, 8, 9], &[1, 9, 10],
    &[1, 9, 11],
    // PRN 54-63
    &[2, 3, 7], &[2, 5, 7], &[2, 7, 9], &[3, 4, 5], &[3, 4, 9], &[3, 5, 6], &[3, 5, 8],
    &[3, 5, 10], &[3, 5, 11], &[3, 6, 9],
];

/// Mask of the G2 stages of `prn`'s phase assignment, `None` outside 1..=63.
fn g2_output_mask(prn: u8) -> Option<u16> {
    let index = usize::from(prn).checked_sub(1)?;
    let stages = G2_PHASE_ASSIGNMENT.get(index)?;
    Some(stages.iter().fold(0, |mask, &k| mask | stage(k)))
}

/// The first `length` chips of `prn`'s Gold sequence from the initial phase (logic 0/1).
/// `length` = 2046 is the B1I code; 2047 is the full, untruncated Gold period.
fn gold_chips(prn: u8, length: usize) -> Option<Vec<u8>> {
    let g2_mask = g2_output_mask(prn)?;
    let mut g1 = INITIAL_PHASE;
    let mut g2 = INITIAL_PHASE;
    let mut chips = Vec::with_capacity(length);
    for _ in 0..length {
        let (g1_out, g1_next) = shift_register_step(g1, G1_FEEDBACK, STAGES);
        let g2_out = ((g2 & g2_mask).count_ones() & 1) as u8;
        chips.push(g1_out ^ g2_out);
        g1 = g1_next;
        g2 = shift_register_step(g2, G2_FEEDBACK, STAGES).1;
    }
    Some(chips)
}

/// One period (2046 chips) of the B1I code of `prn` as logic chips (0/1), chip 0 first.
/// `None` for a PRN outside 1..=63.
pub fn bds_b1i_logic(prn: u8) -> Option<Vec<u8>> {
    gold_chips(prn, BDS_B1I_CODE_LENGTH)
}

/// One period (2046 chips) of the B1I code of `prn` as signal levels (logic 0 -> +1,
/// logic 1 -> -1), chip 0 first. `None` for a PRN outside 1..=63.
pub fn bds_b1i(prn: u8) -> Option<Vec<i8>> {
    Some(
        bds_b1i_logic(prn)?
            .into_iter()
            .map(level_from_logic)
            .collect(),
    )
}

#[cfg(test)]
mod tests {
    use super::super::bit_correlation::PackedCode;
    use super::*;

    /// Chips of the B1I code published by two independent third-party generators, in octal
    /// (first chip is the most significant bit of 24): symlPigeon/bds-Sim
    /// `bdsTx/coding/ranging_code/b1i/prn-*.json` (all 2046 chips, first and last 24 used
    /// here) and the self-test values of a GNU Radio B1I transmitter (`bds_b1i_tx.py`,
    /// first 24 chips of PRN 1, 2, 6, 38, 63). The ICD itself prints no chip values.
    /// (PRN, first 24 chips, last 24 chips or `None` where only the first are published.)
    const PUBLISHED_CHIPS_OCTAL: [(u8, u32, Option<u32>); 5] = [
        (1, 0o31333315, Some(0o05072065)),
        (2, 0o44461070, None),
        (6, 0o32442011, None),
        (38, 0o67733254, Some(0o66354450)),
        (63, 0o74366441, Some(0o46747602)),
    ];

    /// Gold values for a degree-11 preferred pair: -1, -t, t - 2 with
    /// t = 2^((n+1)/2) + 1 = 65 (n = 11, odd).
    const GOLD_VALUES: [i64; 3] = [-65, -1, 63];

    fn octal_24(chips: &[u8]) -> u32 {
        chips
            .iter()
            .fold(0u32, |acc, &chip| (acc << 1) | u32::from(chip))
    }

    fn all_codes(length: usize) -> Vec<PackedCode> {
        (1..=BDS_B1I_PRN_MAX)
            .map(|prn| PackedCode::new(&gold_chips(prn, length).expect("PRN in range")))
            .collect()
    }

    #[test]
    fn chips_match_published_values() {
        for (prn, first, last) in PUBLISHED_CHIPS_OCTAL {
            let code = bds_b1i_logic(prn).expect("PRN in range");
            assert_eq!(code.len(), BDS_B1I_CODE_LENGTH);
            assert_eq!(octal_24(&code[..24]), first, "PRN {prn} first 24 chips");
            if let Some(last) = last {
                let tail = &code[BDS_B1I_CODE_LENGTH - 24..];
                assert_eq!(octal_24(tail), last, "PRN {prn} last 24 chips");
            }
        }
    }

    #[test]
    fn g1_and_g2_are_maximal_length_with_period_2047() {
        for feedback in [G1_FEEDBACK, G2_FEEDBACK] {
            let mut state = INITIAL_PHASE;
            let mut period = 0;
            loop {
                state = shift_register_step(state, feedback, STAGES).1;
                period += 1;
                if state == INITIAL_PHASE {
                    break;
                }
                assert!(period < 5000, "no return to the initial phase");
            }
            assert_eq!(period, 2047);
        }
    }

    #[test]
    fn code_is_the_gold_sequence_without_its_last_chip() {
        for prn in [1u8, 37, 38, 63] {
            let full = gold_chips(prn, 2047).expect("PRN in range");
            let code = bds_b1i_logic(prn).expect("PRN in range");
            assert_eq!(code[..], full[..BDS_B1I_CODE_LENGTH]);
            // The next period restarts from the initial phase: the 2047-chip run is periodic
            // with 2047, not 2046, so truncation really removes a chip.
            let two = gold_chips(prn, 2 * 2047).expect("PRN in range");
            assert_eq!(two[..2047], two[2047..]);
        }
    }

    /// The ICD calls the 2047-chip code "balanced": 1024 ones and 1023 zeros, chip sum -1.
    #[test]
    fn every_full_gold_code_is_balanced() {
        for prn in 1..=BDS_B1I_PRN_MAX {
            let full = gold_chips(prn, 2047).expect("PRN in range");
            let ones = full.iter().filter(|&&c| c == 1).count();
            assert_eq!(ones, 1024, "PRN {prn}");
            let sum: i64 = bds_b1i(prn)
                .expect("PRN in range")
                .iter()
                .map(|&c| i64::from(c))
                .sum();
            let last_level = i64::from(level_from_logic(full[2046]));
            assert_eq!(sum, -1 - last_level, "PRN {prn}");
        }
    }

    #[test]
    fn prn_outside_1_to_63_has_no_code() {
        for prn in [0u8, 64, 255] {
            assert!(bds_b1i(prn).is_none());
            assert!(bds_b1i_logic(prn).is_none());
        }
    }

    #[test]
    fn codes_are_distinct() {
        let codes: Vec<_> = (1..=BDS_B1I_PRN_MAX)
            .map(|prn| bds_b1i_logic(prn).expect("PRN in range"))
            .collect();
        for a in 0..codes.len() {
            for b in a + 1..codes.len() {
                assert_ne!(codes[a], codes[b], "PRN {} vs {}", a + 1, b + 1);
            }
        }
    }

    #[test]
    fn levels_follow_logic_0_plus_1_and_logic_1_minus_1() {
        let logic = bds_b1i_logic(7).expect("PRN 7");
        let levels = bds_b1i(7).expect("PRN 7");
        for (l, v) in logic.iter().zip(levels) {
            assert_eq!(v, if *l == 0 { 1 } else { -1 });
        }
    }

    /// Before truncation the 63 codes form part of a Gold family: every periodic
    /// correlation (2047 shifts, all pairs, auto side lobes) is -65, -1 or 63.
    #[test]
    fn untruncated_codes_are_three_valued_gold_codes() {
        let codes = all_codes(2047);
        for a in 0..codes.len() {
            for b in a..codes.len() {
                for (shift, r) in codes[a].all_correlations(&codes[b]).into_iter().enumerate() {
                    if a == b && shift == 0 {
                        assert_eq!(r, 2047);
                    } else {
                        assert!(GOLD_VALUES.contains(&r), "PRN {} vs {}: {r}", a + 1, b + 1);
                    }
                }
            }
        }
    }

    /// The transmitted 2046-chip codes repeat every 2046 chips, so their periodic
    /// correlation is a sum of two partial-period Gold correlations and is no longer
    /// three-valued. Measured over all 1953 pairs and all 2046 shifts: largest
    /// |cross-correlation| 210 (PRN 12 vs 35, 0.103 of 2046, -19.8 dB) and largest |auto
    /// side lobe| 182 (0.089). Bound tested: |R| <= 0.11 * 2046 = 225 (-19.2 dB).
    #[test]
    fn truncated_code_correlations_stay_within_eleven_percent() {
        let codes = all_codes(BDS_B1I_CODE_LENGTH);
        let bound = (0.11 * BDS_B1I_CODE_LENGTH as f64) as i64;
        for a in 0..codes.len() {
            assert_eq!(codes[a].len(), BDS_B1I_CODE_LENGTH);
            for b in a..codes.len() {
                for (shift, r) in codes[a].all_correlations(&codes[b]).into_iter().enumerate() {
                    if a == b && shift == 0 {
                        assert_eq!(r, BDS_B1I_CODE_LENGTH as i64);
                    } else {
                        assert!(
                            r.abs() <= bound,
                            "PRN {} vs {} shift {shift}: {r}",
                            a + 1,
                            b + 1
                        );
                    }
                }
            }
        }
    }
}
