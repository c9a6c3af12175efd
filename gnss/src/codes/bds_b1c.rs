//! BeiDou B1C ranging codes: data and pilot primary codes and the pilot's secondary code
//! (BDS-SIS-ICD-B1C-1.0, 2017-12, §5.2).
//!
//! The primary codes are 10230-chip truncated Weil codes on the Legendre sequence of length
//! 10243 (§5.2.1), 10 ms at 1.023 Mcps, with w and p per PRN from Table 5-2 (data) and
//! Table 5-3 (pilot). The data component carries no secondary code. The pilot's secondary
//! code is an 1800-chip truncated Weil code on the Legendre sequence of length 3607
//! (§5.2.2, Table 5-4), one chip per 10 ms primary period (18 s). The construction is in
//! the `weil` module; the BOC/QMBOC subcarriers are not part of the codes.

use super::levels;
use super::weil::WeilFamily;

/// B1C primary chip rate, chips per second (BDS-SIS-ICD-B1C-1.0 §5.2.1).
pub const BDS_B1C_CHIP_RATE_HZ: f64 = 1.023e6;
/// B1C primary code length in chips: one period is 10 ms (§5.2.1).
pub const BDS_B1C_CODE_LENGTH: usize = 10230;
/// B1C pilot secondary code length in chips (§5.2.2).
pub const BDS_B1C_SECONDARY_LENGTH: usize = 1800;
/// Highest PRN in BDS-SIS-ICD-B1C-1.0 Tables 5-2 to 5-4.
pub const BDS_B1C_PRN_MAX: u8 = 63;

/// Length of the Legendre sequence of the primary codes (§5.2.1).
const PRIMARY_LEGENDRE_LENGTH: usize = 10243;
/// Length of the Legendre sequence of the secondary codes (§5.2.2).
const SECONDARY_LEGENDRE_LENGTH: usize = 3607;

static DATA: WeilFamily = WeilFamily::new(
    "data/bds_b1c_data.txt",
    include_str!("data/bds_b1c_data.txt"),
    true,
    PRIMARY_LEGENDRE_LENGTH,
    BDS_B1C_CODE_LENGTH,
);
static PILOT: WeilFamily = WeilFamily::new(
    "data/bds_b1c_pilot.txt",
    include_str!("data/bds_b1c_pilot.txt"),
    true,
    PRIMARY_LEGENDRE_LENGTH,
    BDS_B1C_CODE_LENGTH,
);
static PILOT_SECONDARY: WeilFamily = WeilFamily::new(
    "data/bds_b1c_pilot_secondary.txt",
    include_str!("data/bds_b1c_pilot_secondary.txt"),
    true,
    SECONDARY_LEGENDRE_LENGTH,
    BDS_B1C_SECONDARY_LENGTH,
);

/// One period (10230 chips) of the B1C data primary code of `prn` as logic chips, chip 0
/// first; `None` outside 1..=63.
pub fn bds_b1c_data_logic(prn: u8) -> Option<Vec<u8>> {
    DATA.code(prn)
}

/// One period (10230 chips) of the B1C pilot primary code of `prn` as logic chips.
pub fn bds_b1c_pilot_logic(prn: u8) -> Option<Vec<u8>> {
    PILOT.code(prn)
}

/// The B1C data primary code of `prn` as signal levels (logic 0 -> +1, logic 1 -> -1).
pub fn bds_b1c_data(prn: u8) -> Option<Vec<i8>> {
    bds_b1c_data_logic(prn).map(levels)
}

/// The B1C pilot primary code of `prn` as signal levels (logic 0 -> +1, logic 1 -> -1).
pub fn bds_b1c_pilot(prn: u8) -> Option<Vec<i8>> {
    bds_b1c_pilot_logic(prn).map(levels)
}

/// The B1C pilot secondary code of `prn` (1800 chips, one per primary period) as signal
/// levels, chip 0 first; `None` outside 1..=63.
pub fn bds_b1c_pilot_secondary(prn: u8) -> Option<Vec<i8>> {
    PILOT_SECONDARY.code(prn).map(levels)
}

#[cfg(test)]
mod tests {
    use super::super::assert_distinct;
    use super::*;

    #[test]
    fn data_codes_match_table_5_2_first_and_last_chips() {
        assert_eq!(DATA.prn_count(), usize::from(BDS_B1C_PRN_MAX));
        DATA.assert_matches_printed_chips();
    }

    #[test]
    fn pilot_codes_match_table_5_3_first_and_last_chips() {
        assert_eq!(PILOT.prn_count(), usize::from(BDS_B1C_PRN_MAX));
        PILOT.assert_matches_printed_chips();
    }

    #[test]
    fn pilot_secondary_codes_match_table_5_4_first_and_last_chips() {
        assert_eq!(PILOT_SECONDARY.prn_count(), usize::from(BDS_B1C_PRN_MAX));
        PILOT_SECONDARY.assert_matches_printed_chips();
        let levels = bds_b1c_pilot_secondary(9).expect("PRN 9");
        assert_eq!(levels.len(), BDS_B1C_SECONDARY_LENGTH);
    }

    #[test]
    fn all_data_and_pilot_codes_are_distinct() {
        let codes: Vec<_> = (1..=BDS_B1C_PRN_MAX)
            .flat_map(|prn| [bds_b1c_data_logic(prn), bds_b1c_pilot_logic(prn)])
            .map(|code| code.expect("PRN in range"))
            .collect();
        assert_distinct("B1C data and pilot", &codes);
    }

    #[test]
    fn prn_outside_1_to_63_has_no_code() {
        for prn in [0u8, 64, 255] {
            assert!(bds_b1c_data(prn).is_none());
            assert!(bds_b1c_pilot(prn).is_none());
            assert!(bds_b1c_pilot_secondary(prn).is_none());
        }
        let levels = bds_b1c_data(1).expect("PRN 1");
        assert_eq!(levels[..3], [-1, 1, -1]); // 53773116 octal begins 101
    }
}
