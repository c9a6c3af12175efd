//! GPS L1 C/A ranging code (IS-GPS-200N §3.2.1.3 and §3.3.2.3).
//!
//! The C/A code of PRN i is the 1023-chip Gold code G1(t) XOR G2(t - d_i * Tc): two
//! 10-stage maximal-length shift registers, G1 = 1 + x^3 + x^10 and
//! G2 = 1 + x^2 + x^3 + x^6 + x^8 + x^9 + x^10, both set to all ones at the start of every
//! code period (1 ms), each putting out its stage 10, and G2 delayed by the PRN's "G2 delay"
//! d_i in chips. The ICD gives PRN 1-37 as a pair of G2 taps (Table 3-Ia), which equals a
//! delay, and PRN 38-63 as a delay with the matching initial G2 state (Table 3-Ib); one
//! delay table covers all 63.

use super::{level_from_logic, shift_register_step, stage};

/// C/A chip rate, chips per second (IS-GPS-200 §3.3.2.3).
pub const GPS_CA_CHIP_RATE_HZ: f64 = 1.023e6;
/// C/A code length in chips: one period is 1 ms (IS-GPS-200 §3.3.2.3).
pub const GPS_CA_CODE_LENGTH: usize = 1023;
/// Highest PRN with a C/A code assignment in IS-GPS-200 Tables 3-Ia and 3-Ib.
pub const GPS_CA_PRN_MAX: u8 = 63;

const STAGES: u32 = 10;
/// G1 = 1 + x^3 + x^10.
const G1_FEEDBACK: u16 = stage(3) | stage(10);
/// G2 = 1 + x^2 + x^3 + x^6 + x^8 + x^9 + x^10.
const G2_FEEDBACK: u16 = stage(2) | stage(3) | stage(6) | stage(8) | stage(9) | stage(10);
/// Both registers start each period with every stage set to 1.
const ALL_ONES: u16 = (1 << STAGES) - 1;

/// G2 delay in chips for PRN 1..=63 (index PRN - 1).
///
/// IS-GPS-200N Table 3-Ia "Code Phase Assignments" (PRN 1-37, column "Code Delay Chips,
/// C/A") and Table 3-Ib "Expanded Code Phase Assignments" (PRN 38-63, column "G2 Delay").
/// PRN 34 and PRN 37 share delay 950: the ICD assigns them the same C/A code.
#[rustfmt::skip]
const G2_DELAY_CHIPS: [u16; GPS_CA_PRN_MAX as usize] = [
    // PRN 1-37, Table 3-Ia
      5,   6,   7,   8,  17,  18, 139, 140, 141, 251,
    252, 254, 255, 256, 257, 258, 469, 470, 471, 472,
    473, 474, 509, 512, 513, 514, 515, 516, 859, 860,
    861, 862, 863, 950, 947, 948, 950,
    // PRN 38-63, Table 3-Ib
                                         67, 103,  91,
     19, 679, 225, 625, 946, 638, 161, 1001, 554, 280,
    710, 709, 775, 864, 558, 220, 397,  55, 898, 759,
    367, 299, 1018,
];

/// One period of the m-sequence of a 10-stage register started from all ones.
fn m_sequence(feedback: u16) -> [u8; GPS_CA_CODE_LENGTH] {
    let mut sequence = [0u8; GPS_CA_CODE_LENGTH];
    let mut state = ALL_ONES;
    for chip in &mut sequence {
        let (output, next) = shift_register_step(state, feedback, STAGES);
        *chip = output;
        state = next;
    }
    sequence
}

/// G2 delay of `prn` in chips (IS-GPS-200 Tables 3-Ia/3-Ib), `None` outside 1..=63.
pub fn gps_ca_g2_delay_chips(prn: u8) -> Option<u16> {
    let index = usize::from(prn).checked_sub(1)?;
    G2_DELAY_CHIPS.get(index).copied()
}

/// One period of the C/A code of `prn` as logic chips (0/1), chip 0 first.
///
/// Chip i = G1(i) XOR G2(i - d) with d the PRN's G2 delay (IS-GPS-200 §3.3.2.3).
/// `None` for a PRN outside 1..=63.
pub fn gps_ca_logic(prn: u8) -> Option<[u8; GPS_CA_CODE_LENGTH]> {
    let delay = usize::from(gps_ca_g2_delay_chips(prn)?);
    let g1 = m_sequence(G1_FEEDBACK);
    let g2 = m_sequence(G2_FEEDBACK);
    let mut code = [0u8; GPS_CA_CODE_LENGTH];
    for (i, chip) in code.iter_mut().enumerate() {
        let delayed = (i + GPS_CA_CODE_LENGTH - delay) % GPS_CA_CODE_LENGTH;
        *chip = g1[i] ^ g2[delayed];
    }
    Some(code)
}

/// One period of the C/A code of `prn` as signal levels (logic 0 -> +1, logic 1 -> -1),
/// chip 0 first. `None` for a PRN outside 1..=63.
pub fn gps_ca(prn: u8) -> Option<[i8; GPS_CA_CODE_LENGTH]> {
    Some(gps_ca_logic(prn)?.map(level_from_logic))
}

#[cfg(test)]
mod tests {
    use super::super::bit_correlation::PackedCode;
    use super::*;

    /// Column "First 10 Chips Octal" (C/A) of IS-GPS-200 Table 3-Ia for PRN 1-37, typed
    /// from the table, and of Table 3-Ib for PRN 38-63, as quoted from IS-GPS-200L in
    /// going-digital/blipgps `gps_chip.py` (the ICD PDF was not reachable from here). The
    /// first octal digit is the first chip; the next three digits hold chips 2-10.
    #[rustfmt::skip]
    const ICD_FIRST_10_CHIPS_OCTAL: [u16; 63] = [
        0o1440, 0o1620, 0o1710, 0o1744, 0o1133, 0o1455, 0o1131, 0o1454, 0o1626, 0o1504,
        0o1642, 0o1750, 0o1764, 0o1772, 0o1775, 0o1776, 0o1156, 0o1467, 0o1633, 0o1715,
        0o1746, 0o1763, 0o1063, 0o1706, 0o1743, 0o1761, 0o1770, 0o1774, 0o1127, 0o1453,
        0o1625, 0o1712, 0o1745, 0o1713, 0o1134, 0o1456, 0o1713,
        0o1760, 0o1236, 0o0063, 0o0626, 0o0126, 0o1674, 0o1234, 0o0271, 0o0712, 0o0213,
        0o0412, 0o0236, 0o0450, 0o0061, 0o0142, 0o0775, 0o0762, 0o0111, 0o1600, 0o0424,
        0o1351, 0o1550, 0o1271, 0o1441, 0o0444, 0o0032,
    ];

    /// IS-GPS-200N Table 3-Ia, column "Code Phase Selection C/A (G2i)": the two G2 stages
    /// whose modulo-2 sum forms G2i for PRN 1-37 (the two-tap coder).
    #[rustfmt::skip]
    const ICD_G2_TAPS_PRN_1_TO_37: [(u32, u32); 37] = [
        (2, 6), (3, 7), (4, 8), (5, 9), (1, 9), (2, 10), (1, 8), (2, 9), (3, 10), (2, 3),
        (3, 4), (5, 6), (6, 7), (7, 8), (8, 9), (9, 10), (1, 4), (2, 5), (3, 6), (4, 7),
        (5, 8), (6, 9), (1, 3), (4, 6), (5, 7), (6, 8), (7, 9), (8, 10), (1, 6), (2, 7),
        (3, 8), (4, 9), (5, 10), (4, 10), (1, 7), (2, 8), (4, 10),
    ];

    /// The Gold bound for degree-10 preferred pairs: periodic correlations of the family
    /// take only the values -1, -t, t - 2 with t = 2^((n+2)/2) + 1 = 65 (n = 10, even).
    const GOLD_VALUES: [i64; 3] = [-65, -1, 63];

    fn first_10_octal(code: &[u8]) -> u16 {
        code[..10]
            .iter()
            .fold(0u16, |acc, &chip| (acc << 1) | u16::from(chip))
    }

    #[test]
    fn first_10_chips_match_icd_tables_for_every_prn() {
        for prn in 1..=GPS_CA_PRN_MAX {
            let code = gps_ca_logic(prn).expect("PRN in range");
            let expected = ICD_FIRST_10_CHIPS_OCTAL[usize::from(prn) - 1];
            assert_eq!(
                first_10_octal(&code),
                expected,
                "PRN {prn}: got {:04o}, ICD {expected:04o}",
                first_10_octal(&code)
            );
        }
    }

    /// The two-tap coder of IS-GPS-200 §3.3.2.3 / Table 3-Ia, written independently of
    /// the delay formulation, must give the same code for PRN 1-37.
    #[test]
    fn two_tap_coder_equals_g2_delay_for_prn_1_to_37() {
        for (index, &(tap_a, tap_b)) in ICD_G2_TAPS_PRN_1_TO_37.iter().enumerate() {
            let prn = u8::try_from(index + 1).expect("small");
            let mut g1 = [1u8; 10];
            let mut g2 = [1u8; 10];
            let mut code = [0u8; GPS_CA_CODE_LENGTH];
            for chip in &mut code {
                let g2i = g2[tap_a as usize - 1] ^ g2[tap_b as usize - 1];
                *chip = g1[9] ^ g2i;
                let f1 = g1[2] ^ g1[9];
                let f2 = g2[1] ^ g2[2] ^ g2[5] ^ g2[7] ^ g2[8] ^ g2[9];
                g1.rotate_right(1);
                g2.rotate_right(1);
                g1[0] = f1;
                g2[0] = f2;
            }
            assert_eq!(Some(code), gps_ca_logic(prn), "PRN {prn}");
        }
    }

    #[test]
    fn g1_and_g2_are_maximal_length_with_period_1023() {
        for feedback in [G1_FEEDBACK, G2_FEEDBACK] {
            let mut state = ALL_ONES;
            let mut period = 0;
            loop {
                state = shift_register_step(state, feedback, STAGES).1;
                period += 1;
                if state == ALL_ONES {
                    break;
                }
                assert!(period < 2000, "no return to the start state");
            }
            assert_eq!(period, GPS_CA_CODE_LENGTH);
        }
    }

    #[test]
    fn prn_outside_1_to_63_has_no_code() {
        for prn in [0u8, 64, 200, 255] {
            assert!(gps_ca(prn).is_none());
            assert!(gps_ca_logic(prn).is_none());
            assert!(gps_ca_g2_delay_chips(prn).is_none());
        }
    }

    #[test]
    fn levels_follow_logic_0_plus_1_and_logic_1_minus_1() {
        let logic = gps_ca_logic(1).expect("PRN 1");
        let levels = gps_ca(1).expect("PRN 1");
        for (l, v) in logic.iter().zip(levels) {
            assert_eq!(v, if *l == 0 { 1 } else { -1 });
        }
    }

    #[test]
    fn codes_are_distinct_except_prn_34_and_37_which_the_icd_makes_equal() {
        let codes: Vec<_> = (1..=GPS_CA_PRN_MAX)
            .map(|prn| gps_ca_logic(prn).expect("PRN in range"))
            .collect();
        for a in 0..codes.len() {
            for b in a + 1..codes.len() {
                let same = (a + 1, b + 1) == (34, 37);
                assert_eq!(codes[a] == codes[b], same, "PRN {} vs {}", a + 1, b + 1);
            }
        }
    }

    /// Balance: a code's chip sum is its correlation with the all-ones sequence, which for a
    /// Gold code is one of the three Gold values.
    #[test]
    fn chip_sums_are_gold_values() {
        for prn in 1..=GPS_CA_PRN_MAX {
            let sum: i64 = gps_ca(prn)
                .expect("PRN in range")
                .iter()
                .map(|&c| i64::from(c))
                .sum();
            assert!(GOLD_VALUES.contains(&sum), "PRN {prn}: sum {sum}");
        }
    }

    /// Every periodic auto-correlation side lobe and every cross-correlation value, over all
    /// 1023 shifts and all pairs of PRN 1-63, is one of -65, -1, 63 (the Gold bound
    /// |R| <= 65). PRN 34/37 are one code, so that pair is its auto-correlation.
    #[test]
    fn all_correlations_are_three_valued_within_the_gold_bound() {
        let packed: Vec<_> = (1..=GPS_CA_PRN_MAX)
            .map(|prn| PackedCode::new(&gps_ca_logic(prn).expect("PRN in range")))
            .collect();
        let mut worst = 0i64;
        for a in 0..packed.len() {
            for b in a..packed.len() {
                let identical = a == b || (a + 1, b + 1) == (34, 37);
                let values = packed[a].all_correlations(&packed[b]);
                for (shift, &r) in values.iter().enumerate() {
                    if identical && shift == 0 {
                        assert_eq!(r, GPS_CA_CODE_LENGTH as i64);
                        continue;
                    }
                    assert!(
                        GOLD_VALUES.contains(&r),
                        "PRN {} vs {} shift {shift}: R = {r}",
                        a + 1,
                        b + 1
                    );
                    worst = worst.max(r.abs());
                }
            }
        }
        assert_eq!(worst, 65, "the bound is reached by some pair");
    }
}
