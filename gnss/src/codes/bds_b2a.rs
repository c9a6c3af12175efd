//! BeiDou B2a ranging codes: data and pilot primary codes and their secondary codes
//! (BDS-SIS-ICD-B2a-1.0, 2017-12, §5.2).
//!
//! Each 10230-chip (1 ms at 10.23 Mcps) primary code is the modulo-2 sum of two 13-stage
//! registers, each putting out its stage 13 (§5.2.1):
//! data g1 = 1 + x + x^5 + x^11 + x^13, g2 = 1 + x^3 + x^5 + x^9 + x^11 + x^12 + x^13;
//! pilot g1 = 1 + x^3 + x^6 + x^7 + x^13, g2 = 1 + x + x^5 + x^7 + x^8 + x^12 + x^13.
//! Register 1 starts from all ones and is reset to all ones after 8190 chips (its 8191-chip
//! m-sequence truncated by one chip); register 2 starts from the PRN's initial phase
//! (Tables 5-2 and 5-3). Both restart at every code epoch. The data component carries the
//! 5-chip secondary code 00010, the pilot a 100-chip truncated Weil code on the Legendre
//! sequence of length 1021 with w and p per PRN (§5.2.2, Table 5-4), one secondary chip per
//! primary period.

use std::sync::OnceLock;

use super::table::numeric_rows;
use super::weil::WeilFamily;
use super::{
    Register, levels, levels_from_logic, stage, state_from_stage_1_first, two_register_code,
};

/// B2a chip rate, chips per second (BDS-SIS-ICD-B2a-1.0 §5.2.1).
pub const BDS_B2A_CHIP_RATE_HZ: f64 = 10.23e6;
/// B2a primary code length in chips: one period is 1 ms (§5.2.1).
pub const BDS_B2A_CODE_LENGTH: usize = 10230;
/// B2a pilot secondary code length in chips (§5.2.2).
pub const BDS_B2A_PILOT_SECONDARY_LENGTH: usize = 100;
/// Highest PRN in BDS-SIS-ICD-B2a-1.0 Tables 5-2 to 5-4.
pub const BDS_B2A_PRN_MAX: u8 = 63;

/// The data component's secondary code, logic chips, first chip first: 00010 (§5.2.2).
pub const BDS_B2A_DATA_SECONDARY_LOGIC: [u8; 5] = [0, 0, 0, 1, 0];
/// The data secondary code as signal levels, one chip per 1 ms primary period.
pub const BDS_B2A_DATA_SECONDARY: [i8; 5] = levels_from_logic(BDS_B2A_DATA_SECONDARY_LOGIC);

const STAGES: u32 = 13;
const ALL_ONES: u16 = (1 << STAGES) - 1;
/// Register 1 is reset after 8190 chips (§5.2.1).
const REGISTER_1_CYCLE: usize = 8190;
/// Data g1 = 1 + x + x^5 + x^11 + x^13.
const DATA_G1: u16 = stage(1) | stage(5) | stage(11) | stage(13);
/// Data g2 = 1 + x^3 + x^5 + x^9 + x^11 + x^12 + x^13.
const DATA_G2: u16 = stage(3) | stage(5) | stage(9) | stage(11) | stage(12) | stage(13);
/// Pilot g1 = 1 + x^3 + x^6 + x^7 + x^13.
const PILOT_G1: u16 = stage(3) | stage(6) | stage(7) | stage(13);
/// Pilot g2 = 1 + x + x^5 + x^7 + x^8 + x^12 + x^13.
const PILOT_G2: u16 = stage(1) | stage(5) | stage(7) | stage(8) | stage(12) | stage(13);

/// Tables 5-2 and 5-3 (register-2 initial phases); see the file's header for the sources.
const TABLE: &str = include_str!("data/bds_b2a.txt");

static PILOT_SECONDARY: WeilFamily = WeilFamily::new(
    "data/bds_b2a_pilot_secondary.txt",
    include_str!("data/bds_b2a_pilot_secondary.txt"),
    false,
    1021,
    BDS_B2A_PILOT_SECONDARY_LENGTH,
);

/// Register-2 initial phases as printed: data then pilot.
fn table() -> &'static [Vec<u32>] {
    static ROWS: OnceLock<Vec<Vec<u32>>> = OnceLock::new();
    ROWS.get_or_init(|| numeric_rows("data/bds_b2a.txt", TABLE, &[2, 2]))
}

/// The primary code of `prn` with register feedbacks `g1`, `g2` and the register-2 phase of
/// table column `column`.
fn primary(prn: u8, g1: u16, g2: u16, column: usize) -> Option<Vec<u8>> {
    let row = table().get(usize::from(prn).checked_sub(1)?)?;
    let register_1 = Register {
        stages: STAGES,
        feedback: g1,
        start: ALL_ONES,
    };
    let register_2 = Register {
        stages: STAGES,
        feedback: g2,
        start: state_from_stage_1_first(row[column], STAGES),
    };
    Some(two_register_code(
        register_1,
        REGISTER_1_CYCLE,
        register_2,
        BDS_B2A_CODE_LENGTH,
    ))
}

/// One period (10230 chips) of the B2a data primary code of `prn` as logic chips, chip 0
/// first; `None` outside 1..=63.
pub fn bds_b2a_data_logic(prn: u8) -> Option<Vec<u8>> {
    primary(prn, DATA_G1, DATA_G2, 0)
}

/// One period (10230 chips) of the B2a pilot primary code of `prn` as logic chips.
pub fn bds_b2a_pilot_logic(prn: u8) -> Option<Vec<u8>> {
    primary(prn, PILOT_G1, PILOT_G2, 1)
}

/// The B2a data primary code of `prn` as signal levels (logic 0 -> +1, logic 1 -> -1).
pub fn bds_b2a_data(prn: u8) -> Option<Vec<i8>> {
    bds_b2a_data_logic(prn).map(levels)
}

/// The B2a pilot primary code of `prn` as signal levels (logic 0 -> +1, logic 1 -> -1).
pub fn bds_b2a_pilot(prn: u8) -> Option<Vec<i8>> {
    bds_b2a_pilot_logic(prn).map(levels)
}

/// The B2a pilot secondary code of `prn` (100 chips, one per primary period) as logic chips.
pub fn bds_b2a_pilot_secondary_logic(prn: u8) -> Option<Vec<u8>> {
    PILOT_SECONDARY.code(prn)
}

/// The B2a pilot secondary code of `prn` as signal levels, chip 0 first; `None` outside
/// 1..=63.
pub fn bds_b2a_pilot_secondary(prn: u8) -> Option<Vec<i8>> {
    bds_b2a_pilot_secondary_logic(prn).map(levels)
}

#[cfg(test)]
mod tests {
    use super::super::{assert_distinct, chips_word as word, register_period};
    use super::*;

    /// First and last 24 chips (octal) printed in BDS-SIS-ICD-B2a-1.0 Tables 5-2, 5-3 and
    /// 5-4 for the PRNs whose printed values could be read here: quoted as "from the ICD"
    /// by the self-test of a public GNU Radio B2a transmitter (bds_b2a_tx.py); the ICD PDF
    /// itself was not reachable. (PRN, first 24, last 24.)
    const ICD_DATA: [(u8, u32, u32); 3] = [
        (1, 0o26771056, 0o42646672),
        (2, 0o64771737, 0o43261240),
        (63, 0o55037136, 0o06147764),
    ];
    const ICD_PILOT: [(u8, u32, u32); 2] =
        [(1, 0o26772435, 0o05133452), (63, 0o25236023, 0o01076040)];
    const ICD_PILOT_SECONDARY: [(u8, u32, u32); 1] = [(1, 0o32063050, 0o65322167)];

    fn assert_printed(
        what: &str,
        generator: fn(u8) -> Option<Vec<u8>>,
        printed: &[(u8, u32, u32)],
    ) {
        for &(prn, first, last) in printed {
            let code = generator(prn).expect("PRN in range");
            let n = code.len();
            assert_eq!(word(&code[..24]), first, "{what} PRN {prn} first 24");
            assert_eq!(word(&code[n - 24..]), last, "{what} PRN {prn} last 24");
        }
    }

    #[test]
    fn codes_match_the_chips_printed_in_the_icd() {
        assert_printed("data", bds_b2a_data_logic, &ICD_DATA);
        assert_printed("pilot", bds_b2a_pilot_logic, &ICD_PILOT);
        assert_printed(
            "pilot secondary",
            bds_b2a_pilot_secondary_logic,
            &ICD_PILOT_SECONDARY,
        );
    }

    #[test]
    fn all_four_registers_are_maximal_length_with_period_8191() {
        for feedback in [DATA_G1, DATA_G2, PILOT_G1, PILOT_G2] {
            assert_eq!(register_period(feedback, STAGES), 8191, "{feedback:013b}");
        }
    }

    #[test]
    fn all_primary_and_secondary_codes_are_distinct() {
        assert_eq!(table().len(), usize::from(BDS_B2A_PRN_MAX));
        let primaries: Vec<_> = (1..=BDS_B2A_PRN_MAX)
            .flat_map(|prn| [bds_b2a_data_logic(prn), bds_b2a_pilot_logic(prn)])
            .map(|code| code.expect("PRN in range"))
            .collect();
        assert!(primaries.iter().all(|c| c.len() == BDS_B2A_CODE_LENGTH));
        assert_distinct("B2a data and pilot", &primaries);
        let secondaries: Vec<_> = (1..=BDS_B2A_PRN_MAX)
            .map(|prn| bds_b2a_pilot_secondary_logic(prn).expect("PRN in range"))
            .collect();
        for a in 0..secondaries.len() {
            assert_eq!(secondaries[a].len(), BDS_B2A_PILOT_SECONDARY_LENGTH);
            for b in a + 1..secondaries.len() {
                assert_ne!(
                    secondaries[a],
                    secondaries[b],
                    "PRN {} and {}",
                    a + 1,
                    b + 1
                );
            }
        }
    }

    #[test]
    fn prn_outside_1_to_63_has_no_code_and_data_secondary_is_00010() {
        for prn in [0u8, 64, 255] {
            assert!(bds_b2a_data(prn).is_none());
            assert!(bds_b2a_pilot(prn).is_none());
            assert!(bds_b2a_pilot_secondary(prn).is_none());
        }
        assert_eq!(word(&BDS_B2A_DATA_SECONDARY_LOGIC), 0b00010);
        assert_eq!(BDS_B2A_DATA_SECONDARY, [1, 1, 1, -1, 1]);
        assert_eq!(bds_b2a_pilot(1).expect("PRN 1")[..2], [1, -1]); // 26772435 begins 010
    }
}
