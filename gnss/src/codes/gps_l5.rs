//! GPS L5 ranging codes I5 and Q5 and their Neumann-Hoffman codes (IS-GPS-705J §3.2.1 and
//! §3.3.2).
//!
//! Each 10230-chip (1 ms) code is XA(t) XOR XBi(t): two 13-stage registers,
//! XA = 1 + x^9 + x^10 + x^12 + x^13 and
//! XB = 1 + x + x^3 + x^4 + x^6 + x^7 + x^8 + x^12 + x^13, each putting out its stage 13.
//! XA starts from all ones and is short-cycled: it restarts from all ones after 8190 chips,
//! one chip before the end of its 8191-chip m-sequence. XB runs through its m-sequence from
//! the PRN's initial XB state (Tables 3-Ia/3-Ib), the all-ones state advanced by the PRN's
//! "XB code advance". Both restart at every 1 ms code epoch. I5 and Q5 differ only in the
//! initial XB state. On top, each I5 code period carries one chip of the 10-chip NH code
//! (1 kHz, a 10 ms cycle aligned with the 100 symbol/s CNAV symbols) and each Q5 period
//! one chip of the 20-chip NH code (a 20 ms cycle).

use std::sync::OnceLock;

use super::neumann_hoffman::NH20;
use super::table::numeric_rows;
use super::{
    Register, levels, levels_from_logic, stage, state_from_stage_1_first, two_register_code,
};

/// L5 chip rate, chips per second (IS-GPS-705 §3.3.2).
pub const GPS_L5_CHIP_RATE_HZ: f64 = 10.23e6;
/// L5 code length in chips: one period is 1 ms (IS-GPS-705 §3.3.2).
pub const GPS_L5_CODE_LENGTH: usize = 10230;
/// Highest PRN with an L5 code phase assignment in IS-GPS-705 Tables 3-Ia and 3-Ib.
pub const GPS_L5_PRN_MAX: u8 = 63;

/// The 10-chip Neumann-Hoffman code on I5, logic chips, first chip first: 0000110101
/// (IS-GPS-705 §3.3.2).
pub const GPS_L5_I_NH10_LOGIC: [u8; 10] = [0, 0, 0, 0, 1, 1, 0, 1, 0, 1];
/// The I5 NH code as signal levels, one chip per 1 ms code period.
pub const GPS_L5_I_NH10: [i8; 10] = levels_from_logic(GPS_L5_I_NH10_LOGIC);
/// The 20-chip Neumann-Hoffman code on Q5 as signal levels, one chip per 1 ms code period:
/// 00000100110101001110 (IS-GPS-705 §3.3.2), the same sequence as the
/// BeiDou D1 NH code ([`NH20`]).
pub const GPS_L5_Q_NH20: [i8; 20] = NH20;

const STAGES: u32 = 13;
/// XA = 1 + x^9 + x^10 + x^12 + x^13.
const XA_FEEDBACK: u16 = stage(9) | stage(10) | stage(12) | stage(13);
/// XB = 1 + x + x^3 + x^4 + x^6 + x^7 + x^8 + x^12 + x^13.
const XB_FEEDBACK: u16 =
    stage(1) | stage(3) | stage(4) | stage(6) | stage(7) | stage(8) | stage(12) | stage(13);
const ALL_ONES: u16 = (1 << STAGES) - 1;
/// XA restarts after 8190 chips (IS-GPS-705 §3.3.2).
const XA_SHORT_CYCLE: usize = 8190;

/// The XA register: all ones at every code epoch.
const XA: Register = Register {
    stages: STAGES,
    feedback: XA_FEEDBACK,
    start: ALL_ONES,
};

/// IS-GPS-705J Tables 3-Ia/3-Ib; see the file's header for the columns and the source.
const TABLE: &str = include_str!("data/gps_l5.txt");

/// The columns of `TABLE`: XB advances (I5, Q5) and initial XB states (I5, Q5).
fn table() -> &'static [Vec<u32>] {
    static ROWS: OnceLock<Vec<Vec<u32>>> = OnceLock::new();
    ROWS.get_or_init(|| numeric_rows("data/gps_l5.txt", TABLE, &[10, 10, 2, 2]))
}

/// Which of the two L5 codes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Component {
    I5,
    Q5,
}

/// The XB register of `prn`'s `component` at the code epoch, `None` outside 1..=63.
fn xb(prn: u8, component: Component) -> Option<Register> {
    let row = table().get(usize::from(prn).checked_sub(1)?)?;
    let printed = row[if component == Component::I5 { 2 } else { 3 }];
    Some(Register {
        stages: STAGES,
        feedback: XB_FEEDBACK,
        start: state_from_stage_1_first(printed, STAGES),
    })
}

fn code(prn: u8, component: Component) -> Option<Vec<u8>> {
    let xb = xb(prn, component)?;
    Some(two_register_code(
        XA,
        XA_SHORT_CYCLE,
        xb,
        GPS_L5_CODE_LENGTH,
    ))
}

/// One period (10230 chips) of the I5 code of `prn` as logic chips (0/1), chip 0 first.
/// `None` for a PRN outside 1..=63.
pub fn gps_l5_i_logic(prn: u8) -> Option<Vec<u8>> {
    code(prn, Component::I5)
}

/// One period (10230 chips) of the Q5 code of `prn` as logic chips (0/1), chip 0 first.
/// `None` for a PRN outside 1..=63.
pub fn gps_l5_q_logic(prn: u8) -> Option<Vec<u8>> {
    code(prn, Component::Q5)
}

/// One period of the I5 code of `prn` as signal levels (logic 0 -> +1, logic 1 -> -1).
/// `None` for a PRN outside 1..=63.
pub fn gps_l5_i(prn: u8) -> Option<Vec<i8>> {
    gps_l5_i_logic(prn).map(levels)
}

/// One period of the Q5 code of `prn` as signal levels (logic 0 -> +1, logic 1 -> -1).
/// `None` for a PRN outside 1..=63.
pub fn gps_l5_q(prn: u8) -> Option<Vec<i8>> {
    gps_l5_q_logic(prn).map(levels)
}

#[cfg(test)]
mod tests {
    use super::super::{assert_distinct, chips_word as word, register_period};
    use super::*;

    /// The two columns the ICD prints for each PRN must describe the same register: the
    /// all-ones XB state clocked "XB code advance" times is the printed initial XB state.
    /// This checks every transcribed row of Tables 3-Ia/3-Ib, I5 and Q5.
    #[test]
    fn printed_initial_states_are_the_printed_advances_of_all_ones() {
        let all_ones = Register {
            stages: STAGES,
            feedback: XB_FEEDBACK,
            start: ALL_ONES,
        };
        assert_eq!(table().len(), usize::from(GPS_L5_PRN_MAX));
        for prn in 1..=GPS_L5_PRN_MAX {
            let row = &table()[usize::from(prn) - 1];
            for (component, advance) in [(Component::I5, row[0]), (Component::Q5, row[1])] {
                let advanced = all_ones.state_after(advance as usize);
                let printed = xb(prn, component).expect("PRN in range").start;
                assert_eq!(
                    advanced, printed,
                    "PRN {prn} {component:?}: advance {advance} gives {advanced:013b}"
                );
            }
        }
    }

    /// The first 13 chips: XA puts out 13 ones, XB its printed initial state from stage 13
    /// (the rightmost printed digit) back to stage 1 (the leftmost).
    #[test]
    fn first_13_chips_are_ones_xor_the_printed_xb_state_read_from_stage_13() {
        for prn in 1..=GPS_L5_PRN_MAX {
            let row = &table()[usize::from(prn) - 1];
            for (logic, printed) in [(gps_l5_i_logic(prn), row[2]), (gps_l5_q_logic(prn), row[3])] {
                let logic = logic.expect("PRN in range");
                let reversed = printed.reverse_bits() >> (32 - STAGES);
                assert_eq!(word(&logic[..13]), !reversed & 0x1FFF, "PRN {prn}");
            }
        }
    }

    /// An independent generator written from IS-GPS-705 §3.3.2 with one bit per array
    /// element: XA restarts from all ones at chip 8190, XB never restarts within a period.
    #[test]
    fn codes_equal_a_direct_array_implementation() {
        for prn in [1u8, 2, 37, 38, 63] {
            let row = &table()[usize::from(prn) - 1];
            for (code, printed) in [(gps_l5_i_logic(prn), row[2]), (gps_l5_q_logic(prn), row[3])] {
                let mut xa = [1u8; 13];
                let mut xb = [0u8; 13];
                for (k, cell) in xb.iter_mut().enumerate() {
                    *cell = ((printed >> (12 - k)) & 1) as u8;
                }
                let mut expected = Vec::with_capacity(GPS_L5_CODE_LENGTH);
                for chip in 0..GPS_L5_CODE_LENGTH {
                    expected.push(xa[12] ^ xb[12]);
                    let fa = xa[8] ^ xa[9] ^ xa[11] ^ xa[12];
                    let fb = xb[0] ^ xb[2] ^ xb[3] ^ xb[5] ^ xb[6] ^ xb[7] ^ xb[11] ^ xb[12];
                    xa.rotate_right(1);
                    xb.rotate_right(1);
                    xa[0] = fa;
                    xb[0] = fb;
                    if chip + 1 == 8190 {
                        xa = [1; 13];
                    }
                }
                assert_eq!(code, Some(expected), "PRN {prn}");
            }
        }
    }

    #[test]
    fn xa_and_xb_are_maximal_length_with_period_8191() {
        for feedback in [XA_FEEDBACK, XB_FEEDBACK] {
            assert_eq!(register_period(feedback, STAGES), 8191);
        }
    }

    #[test]
    fn all_126_codes_are_distinct() {
        let codes: Vec<_> = (1..=GPS_L5_PRN_MAX)
            .flat_map(|prn| [gps_l5_i_logic(prn), gps_l5_q_logic(prn)])
            .map(|code| code.expect("PRN in range"))
            .collect();
        assert!(codes.iter().all(|c| c.len() == GPS_L5_CODE_LENGTH));
        assert_distinct("L5 I5 and Q5", &codes);
    }

    #[test]
    fn prn_outside_1_to_63_has_no_code() {
        for prn in [0u8, 64, 255] {
            assert!(gps_l5_i(prn).is_none());
            assert!(gps_l5_q(prn).is_none());
        }
        let levels = gps_l5_q(5).expect("PRN 5");
        let logic = gps_l5_q_logic(5).expect("PRN 5");
        assert!(
            levels
                .iter()
                .zip(&logic)
                .all(|(&v, &l)| v == 1 - 2 * l as i8)
        );
    }

    /// IS-GPS-705 §3.3.2 prints the NH codes as 0000110101 and 00000100110101001110.
    #[test]
    fn neumann_hoffman_codes_match_the_icd() {
        assert_eq!(word(&GPS_L5_I_NH10_LOGIC), 0b0000110101);
        let nh20: Vec<u8> = GPS_L5_Q_NH20.iter().map(|&v| u8::from(v < 0)).collect();
        assert_eq!(word(&nh20), 0b00000100110101001110);
        // 4 ones and 6 zeros: level sum 6 - 4 = 2.
        assert_eq!(GPS_L5_I_NH10.iter().map(|&v| i32::from(v)).sum::<i32>(), 2);
    }
}
