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
}
