//! Code tables kept as text data files (`codes/data/*.txt`), compiled in with `include_str!`.
//!
//! A table file holds one row per PRN, PRN 1 first and in order, as whitespace-separated
//! columns: the PRN in decimal, then the ICD's columns written as the ICD prints them (octal,
//! binary or hexadecimal, the radix fixed per column by the reader). Lines starting with `#`
//! (the source and column names) and blank lines are skipped. The files are part of the
//! source, so a malformed one is a programming error: the readers panic naming the file and
//! the line, and every file is read by the unit tests.

/// The value columns of every row of table `name` (the PRN column dropped; row i is PRN
/// i + 1), each column read in the radix given for it in `radices`.
pub(super) fn numeric_rows(name: &str, text: &str, radices: &[u32]) -> Vec<Vec<u32>> {
    rows(name, text)
        .map(|(line, fields)| {
            assert_eq!(
                fields.len(),
                radices.len(),
                "{name} line {line}: {} value columns, expected {}",
                fields.len(),
                radices.len()
            );
            fields
                .iter()
                .zip(radices)
                .map(|(field, &radix)| {
                    u32::from_str_radix(field, radix).unwrap_or_else(|_| {
                        panic!("{name} line {line}: {field:?} is not a base-{radix} number")
                    })
                })
                .collect()
        })
        .collect()
}

/// The chips of every row of a hexadecimal code table `name` (row i is PRN i + 1): one column
/// of hexadecimal digits, the first chip in the most significant bit of the first digit, of
/// which the first `length` chips are kept (the ICD pads the last digit with zeros).
pub(super) fn hex_chip_rows(name: &str, text: &str, length: usize) -> Vec<Vec<u8>> {
    rows(name, text)
        .map(|(line, fields)| {
            assert_eq!(
                fields.len(),
                1,
                "{name} line {line}: expected one hex column"
            );
            let chips = hex_chips(fields[0])
                .unwrap_or_else(|| panic!("{name} line {line}: not hexadecimal"));
            assert!(
                chips.len() >= length && chips.len() < length + 4,
                "{name} line {line}: {} chips, expected {length}",
                chips.len()
            );
            chips[..length].to_vec()
        })
        .collect()
}

/// The chips of hexadecimal digits, 4 per digit, most significant bit first; `None` if a
/// character is not a hexadecimal digit.
pub(super) fn hex_chips(hex: &str) -> Option<Vec<u8>> {
    let mut chips = Vec::with_capacity(4 * hex.len());
    for digit in hex.chars() {
        let value = digit.to_digit(16)?;
        chips.extend((0..4).rev().map(|bit| ((value >> bit) & 1) as u8));
    }
    Some(chips)
}

/// (line number, value fields) of every data row, checking that the PRN column counts 1, 2, ...
fn rows<'a>(name: &'a str, text: &'a str) -> impl Iterator<Item = (usize, Vec<&'a str>)> + 'a {
    text.lines()
        .enumerate()
        .filter(|(_, line)| !line.trim().is_empty() && !line.trim_start().starts_with('#'))
        .enumerate()
        .map(move |(index, (line, text))| {
            let mut fields = text.split_whitespace();
            let prn = fields.next().and_then(|f| f.parse::<usize>().ok());
            assert_eq!(prn, Some(index + 1), "{name} line {}: PRN column", line + 1);
            (line + 1, fields.collect())
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    const SAMPLE: &str = "# source\n# PRN a b\n1 17 101\n\n2 7 11\n";

    #[test]
    fn numeric_rows_read_each_column_in_its_radix() {
        let rows = numeric_rows("sample", SAMPLE, &[8, 2]);
        assert_eq!(rows, vec![vec![0o17, 0b101], vec![7, 3]]);
    }

    #[test]
    #[should_panic(expected = "sample line 3")]
    fn a_digit_outside_the_radix_names_the_line() {
        numeric_rows("sample", "# c\n\n1 9\n", &[8]);
    }

    #[test]
    #[should_panic(expected = "PRN column")]
    fn rows_out_of_prn_order_are_refused() {
        numeric_rows("sample", "2 1\n", &[10]);
    }

    #[test]
    fn hex_rows_keep_the_first_chips_of_a_padded_last_digit() {
        // 380AD90: the 25 chips 0011100000001010110110010 and three padding zeros.
        let rows = hex_chip_rows("cs25", "1 380AD90\n", 25);
        let text: String = rows[0].iter().map(|c| char::from(b'0' + c)).collect();
        assert_eq!(text, "0011100000001010110110010");
        assert_eq!(hex_chips("F0"), Some(vec![1, 1, 1, 1, 0, 0, 0, 0]));
        assert_eq!(hex_chips("G"), None);
    }
}
