//! Galileo E1-B (I/NAV data) and E1-C (pilot) primary codes, and E1-C's secondary code
//! (Galileo OS SIS ICD §3.4: 4092-chip memory codes at 1.023 Mchip/s, 4 ms; CS25_1 on
//! E1-C, one chip per primary period, 100 ms; no secondary code on E1-B).
//!
//! The primary codes are the tables of the ICD's Annex C, not a generator's output, and
//! the ICD's terms of use do not let SkyForge redistribute them (docs/signals.md). SkyForge
//! reads them from the directory [`E1_CODES_ENV`] names: `galileo_e1b.txt` and
//! `galileo_e1c.txt`, one row per code number 1-50, `<number> <1023 hexadecimal digits>`
//! (the 4092 chips, first chip in the most significant bit of the first digit), lines
//! starting with `#` and blank lines skipped. Each table is checked whole: 50 rows of 4092
//! chips whose CRC-32 equals that of the ICD's table (computed from the public
//! transcription docs/signals.md names, which two others agree with digit for digit), so a
//! mistyped chip is an error, not a silent wrong code. [`E1_CODES_CHECK_ENV`] = `off`
//! skips the CRC, for tests that use made-up codes.

use super::levels_from_logic;
use skyforge_orbits::bounded_read::read_text;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

/// E1 chip rate, chips per second (Galileo OS SIS ICD §2.3.3).
pub const GALILEO_E1_CHIP_RATE_HZ: f64 = 1.023e6;
/// E1 primary code length in chips: one period is 4 ms (Galileo OS SIS ICD §3.4).
pub const GALILEO_E1_CODE_LENGTH: usize = 4092;
/// Highest code number in the ICD's E1 tables (code n is used by SVID n).
pub const GALILEO_E1_PRN_MAX: u8 = 50;

/// E1-C secondary code CS25_1, logic chips, first chip first: hexadecimal 380AD90 as the
/// ICD's secondary-code table prints it (25 chips, three padding zeros dropped).
pub const GALILEO_E1_C_CS25_LOGIC: [u8; 25] = [
    0, 0, 1, 1, 1, 0, 0, 0, 0, 0, 0, 0, 1, 0, 1, 0, 1, 1, 0, 1, 1, 0, 0, 1, 0,
];
/// CS25_1 as signal levels, one chip per 4 ms primary period.
pub const GALILEO_E1_C_SECONDARY: [i8; 25] = levels_from_logic(GALILEO_E1_C_CS25_LOGIC);

/// The environment variable naming the directory that holds the E1 code tables.
pub const E1_CODES_ENV: &str = "SKYFORGE_GALILEO_E1_CODES";
/// Set to `off` to read tables whose CRC-32 is not the ICD's (made-up codes in tests).
pub const E1_CODES_CHECK_ENV: &str = "SKYFORGE_GALILEO_E1_CODES_CHECK";

/// The two tables: file name and the CRC-32 (IEEE) of its chips, one byte (0 or 1) per chip,
/// code 1 first.
const DATA_TABLE: (&str, u32) = ("galileo_e1b.txt", 0x7e21_3250);
const PILOT_TABLE: (&str, u32) = ("galileo_e1c.txt", 0x2aa6_1004);

/// assumed: a table file larger than 1 MB is not a table (the real one is about 52 kB).
const TABLE_BYTES_MAX: u64 = 1 << 20;

/// Why the E1 code tables could not be had.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum E1CodesError {
    #[error(
        "Galileo E1 needs the ICD's E1-B and E1-C code tables, which SkyForge does not ship: set {E1_CODES_ENV} to a directory holding galileo_e1b.txt and galileo_e1c.txt (docs/signals.md)"
    )]
    NotConfigured,
    #[error("{path}: {reason}")]
    Read { path: PathBuf, reason: String },
    #[error("{path} line {line}: {what}")]
    Malformed {
        path: PathBuf,
        line: usize,
        what: String,
    },
    #[error(
        "{path}: the chips' CRC-32 is {got:08x}, the ICD table's {expected:08x}: not the ICD's codes (docs/signals.md)"
    )]
    NotTheIcds {
        path: PathBuf,
        got: u32,
        expected: u32,
    },
}

/// The E1-B and E1-C primary codes of code numbers 1-50, as signal levels.
#[derive(Debug, Clone, PartialEq)]
pub struct E1Codes {
    data: Vec<Vec<i8>>,
    pilot: Vec<Vec<i8>>,
}

impl E1Codes {
    /// The tables in `dir`, checked ([`E1CodesError`]); the CRC only when `check`.
    pub fn from_dir(dir: &Path, check: bool) -> Result<Self, E1CodesError> {
        let table = |(name, crc): (&str, u32)| {
            let path = dir.join(name);
            let text = read_text(&path, TABLE_BYTES_MAX, "code table").map_err(|e| {
                E1CodesError::Read {
                    path: path.clone(),
                    reason: e.to_string(),
                }
            })?;
            parse_table(&path, &text, check.then_some(crc))
        };
        Ok(Self {
            data: table(DATA_TABLE)?,
            pilot: table(PILOT_TABLE)?,
        })
    }
}

impl E1Codes {
    /// The E1-B primary code of `prn` as levels; `None` outside 1-50.
    pub fn data(&self, prn: u8) -> Option<&[i8]> {
        Some(self.data.get(usize::from(prn).checked_sub(1)?)?.as_slice())
    }

    /// The E1-C primary code of `prn` as levels; `None` outside 1-50.
    pub fn pilot(&self, prn: u8) -> Option<&[i8]> {
        Some(self.pilot.get(usize::from(prn).checked_sub(1)?)?.as_slice())
    }
}

/// The chips of every row of `text` (the file `path`), checked: rows 1..=50 in order, 1023
/// hexadecimal digits each, and, with `crc`, the chips' CRC-32.
fn parse_table(path: &Path, text: &str, crc: Option<u32>) -> Result<Vec<Vec<i8>>, E1CodesError> {
    let malformed = |line: usize, what: String| E1CodesError::Malformed {
        path: path.to_path_buf(),
        line,
        what,
    };
    let digits = GALILEO_E1_CODE_LENGTH / 4;
    let mut logic: Vec<Vec<u8>> = Vec::new();
    for (index, line) in text.lines().enumerate() {
        let trimmed = line.trim();
        if trimmed.is_empty() || trimmed.starts_with('#') {
            continue;
        }
        let fields: Vec<&str> = trimmed.split_whitespace().collect();
        let expected = logic.len() + 1;
        if expected > usize::from(GALILEO_E1_PRN_MAX) {
            return Err(malformed(
                index + 1,
                format!("more than {GALILEO_E1_PRN_MAX} codes"),
            ));
        }
        let [number, hex] = fields[..] else {
            return Err(malformed(
                index + 1,
                format!(
                    "expected `<code number> <{digits} hexadecimal digits>`, found {} fields",
                    fields.len()
                ),
            ));
        };
        if number.parse::<usize>().ok() != Some(expected) {
            return Err(malformed(
                index + 1,
                format!("code number {number:?}, expected {expected} (codes 1-50 in order)"),
            ));
        }
        if hex.len() != digits {
            return Err(malformed(
                index + 1,
                format!("{} digits, expected {digits}", hex.len()),
            ));
        }
        let chips = super::table::hex_chips(hex)
            .ok_or_else(|| malformed(index + 1, "not hexadecimal".into()))?;
        logic.push(chips);
    }
    if logic.len() != usize::from(GALILEO_E1_PRN_MAX) {
        return Err(malformed(
            text.lines().count(),
            format!("{} codes, expected {GALILEO_E1_PRN_MAX}", logic.len()),
        ));
    }
    if let Some(expected) = crc {
        let got = crc32fast::hash(&logic.concat());
        if got != expected {
            return Err(E1CodesError::NotTheIcds {
                path: path.to_path_buf(),
                got,
                expected,
            });
        }
    }
    Ok(logic
        .iter()
        .map(|code| code.iter().map(|&c| super::level_from_logic(c)).collect())
        .collect())
}

/// The tables of [`E1_CODES_ENV`]'s directory, read once per process.
pub fn e1_codes() -> Result<&'static E1Codes, E1CodesError> {
    static CODES: OnceLock<Result<E1Codes, E1CodesError>> = OnceLock::new();
    CODES
        .get_or_init(|| {
            let dir = std::env::var_os(E1_CODES_ENV).ok_or(E1CodesError::NotConfigured)?;
            let check = std::env::var(E1_CODES_CHECK_ENV).map_or(true, |v| v != "off");
            E1Codes::from_dir(Path::new(&dir), check)
        })
        .as_ref()
        .map_err(Clone::clone)
}

/// The E1-B primary code of `prn` as levels; `None` for a code number outside 1-50 or
/// without the tables ([`e1_codes`] says why).
pub fn galileo_e1b(prn: u8) -> Option<Vec<i8>> {
    e1_codes().ok()?.data(prn).map(<[i8]>::to_vec)
}

/// The E1-C primary code of `prn` as levels ([`galileo_e1b`]'s conditions).
pub fn galileo_e1c(prn: u8) -> Option<Vec<i8>> {
    e1_codes().ok()?.pilot(prn).map(<[i8]>::to_vec)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A made-up table of 50 codes: code n's digits all `n mod 16`.
    fn made_up() -> String {
        let mut text = String::from("# made up\n\n");
        for n in 1..=50u32 {
            let digit = char::from_digit(n % 16, 16).unwrap();
            text.push_str(&format!("{n} {}\n", String::from(digit).repeat(1023)));
        }
        text
    }

    #[test]
    fn a_table_reads_as_levels_of_its_hex_chips() {
        let codes = parse_table(Path::new("t.txt"), &made_up(), None).unwrap();
        assert_eq!(codes.len(), 50);
        assert!(codes.iter().all(|c| c.len() == GALILEO_E1_CODE_LENGTH));
        // Code 3: digit 3 = 0011 -> +1 +1 -1 -1.
        assert_eq!(codes[2][..8], [1, 1, -1, -1, 1, 1, -1, -1]);
    }

    #[test]
    fn a_wrong_crc_is_not_the_icds_table() {
        let text = made_up();
        let e = parse_table(Path::new("t.txt"), &text, Some(DATA_TABLE.1)).unwrap_err();
        assert!(matches!(e, E1CodesError::NotTheIcds { expected, .. } if expected == DATA_TABLE.1));
        // The same text with its own CRC passes.
        let chips: Vec<u8> = (1..=50u32)
            .flat_map(|n| {
                super::super::table::hex_chips(&format!("{:x}", n % 16).repeat(1023)).unwrap()
            })
            .collect();
        parse_table(Path::new("t.txt"), &text, Some(crc32fast::hash(&chips))).unwrap();
    }

    #[test]
    fn malformed_tables_name_the_line() {
        let text = made_up();
        let cases = [
            (text.replacen("3 333", "4 333", 1), 5, "code number"),
            (text.replacen("2 222", "2 22G", 1), 4, "not hexadecimal"),
            (text.replacen("1 111", "1 11", 1), 3, "1022 digits"),
            (text.replacen("1 111", "1 1 11", 1), 3, "3 fields"),
            (
                text.lines().take(20).collect::<Vec<_>>().join("\n"),
                20,
                "18 codes",
            ),
            (
                format!("{text}51 {}\n", "0".repeat(1023)),
                53,
                "more than 50",
            ),
        ];
        for (bad, line, what) in cases {
            let e = parse_table(Path::new("t.txt"), &bad, None).unwrap_err();
            let message = e.to_string();
            assert!(
                matches!(&e, E1CodesError::Malformed { line: l, .. } if *l == line)
                    && message.contains(what),
                "{message}"
            );
        }
    }

    #[test]
    fn a_missing_directory_says_which_file() {
        let e = E1Codes::from_dir(Path::new("/nonexistent/e1"), true).unwrap_err();
        assert!(e.to_string().contains("galileo_e1b.txt"), "{e}");
    }

    #[test]
    fn cs25_is_as_printed() {
        let hex: String = GALILEO_E1_C_CS25_LOGIC
            .chunks(4)
            .map(|c| {
                let v = c.iter().fold(0, |a, &b| a * 2 + u32::from(b)) << (4 - c.len());
                char::from_digit(v, 16).unwrap()
            })
            .collect();
        assert_eq!(hex.to_uppercase(), "380AD90");
    }
}
