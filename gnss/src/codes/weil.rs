//! Truncated Weil codes built on Legendre sequences, the construction of the BeiDou B1C
//! primary and secondary codes (BDS-SIS-ICD-B1C-1.0 §5.2.1 and §5.2.2) and of the B2a pilot
//! secondary codes (BDS-SIS-ICD-B2a-1.0 §5.2.2).
//!
//! For a prime N the Legendre sequence is L(0) = 0, L(k) = 1 when k is a nonzero quadratic
//! residue modulo N, L(k) = 0 otherwise. The Weil code of phase difference w is
//! W(k; w) = L(k) XOR L((k + w) mod N), and a ranging code of length M is W read from the
//! truncation point p (1-based): c(n) = W((n + p - 1) mod N; w) for n = 0..M-1.

use std::sync::OnceLock;

use super::table::numeric_rows;

/// The Legendre sequence of prime length `n`, built from the squares x^2 mod n of
/// x = 1..=(n-1)/2, which are exactly the (n-1)/2 nonzero residues: O(n), no test per chip.
pub(super) fn legendre_sequence(n: usize) -> Vec<u8> {
    let mut sequence = vec![0u8; n];
    for x in 1..=(n - 1) / 2 {
        sequence[x * x % n] = 1;
    }
    sequence
}

/// The first `length` chips of the Weil code of phase difference `w` read from truncation
/// point `p` (1-based) on the Legendre sequence `legendre`.
pub(super) fn truncated_weil(legendre: &[u8], w: usize, p: usize, length: usize) -> Vec<u8> {
    let n = legendre.len();
    (0..length)
        .map(|chip| {
            let k = (chip + p - 1) % n;
            legendre[k] ^ legendre[(k + w) % n]
        })
        .collect()
}

/// A family of truncated Weil codes given by an ICD table: a data file with, per PRN, the
/// phase difference w and truncation point p in decimal, then, where the file has them, the
/// printed first and last 24 chips in octal.
pub(super) struct WeilFamily {
    name: &'static str,
    text: &'static str,
    printed_chips: bool,
    legendre_length: usize,
    code_length: usize,
    rows: OnceLock<Vec<Vec<u32>>>,
    legendre: OnceLock<Vec<u8>>,
}

impl WeilFamily {
    /// The family of table file `name` (text `text`, with the two printed-chip columns if
    /// `printed_chips`): codes of `code_length` chips on the Legendre sequence of prime
    /// length `legendre_length`.
    pub(super) const fn new(
        name: &'static str,
        text: &'static str,
        printed_chips: bool,
        legendre_length: usize,
        code_length: usize,
    ) -> Self {
        Self {
            name,
            text,
            printed_chips,
            legendre_length,
            code_length,
            rows: OnceLock::new(),
            legendre: OnceLock::new(),
        }
    }

    /// The table's rows (PRN i + 1 in row i): w, p and the printed first and last 24 chips.
    fn rows(&self) -> &[Vec<u32>] {
        let radices: &[u32] = if self.printed_chips {
            &[10, 10, 8, 8]
        } else {
            &[10, 10]
        };
        self.rows
            .get_or_init(|| numeric_rows(self.name, self.text, radices))
    }

    /// The code of `prn` as logic chips, chip 0 first; `None` for a PRN not in the table.
    pub(super) fn code(&self, prn: u8) -> Option<Vec<u8>> {
        let row = self.rows().get(usize::from(prn).checked_sub(1)?)?;
        let legendre = self
            .legendre
            .get_or_init(|| legendre_sequence(self.legendre_length));
        Some(truncated_weil(
            legendre,
            row[0] as usize,
            row[1] as usize,
            self.code_length,
        ))
    }

    /// Number of PRNs in the table.
    #[cfg(test)]
    pub(super) fn prn_count(&self) -> usize {
        self.rows().len()
    }

    /// Checks every code of the family against the first and last 24 chips the ICD prints
    /// beside its w and p, and that no two codes are equal.
    #[cfg(test)]
    pub(super) fn assert_matches_printed_chips(&self) {
        use super::{assert_distinct, chips_word as word};
        assert!(self.printed_chips, "{} prints no chips", self.name);
        let mut codes = Vec::new();
        for (index, row) in self.rows().iter().enumerate() {
            let prn = u8::try_from(index + 1).expect("small table");
            let code = self.code(prn).expect("PRN in the table");
            assert_eq!(code.len(), self.code_length);
            let (first, last) = (word(&code[..24]), word(&code[self.code_length - 24..]));
            assert_eq!(
                first, row[2],
                "{} PRN {prn}: first 24 {first:08o}",
                self.name
            );
            assert_eq!(last, row[3], "{} PRN {prn}: last 24 {last:08o}", self.name);
            codes.push(code);
        }
        assert_distinct(self.name, &codes);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Euler's criterion, the definition of a quadratic residue, chip by chip.
    fn is_residue(k: usize, n: usize) -> bool {
        let (mut result, mut base, mut exp) = (1usize, k % n, (n - 1) / 2);
        while exp > 0 {
            if exp & 1 == 1 {
                result = result * base % n;
            }
            base = base * base % n;
            exp >>= 1;
        }
        result == 1
    }

    #[test]
    fn legendre_sequences_mark_exactly_the_quadratic_residues() {
        for n in [7usize, 1021, 3607, 10243] {
            let sequence = legendre_sequence(n);
            assert_eq!(sequence[0], 0);
            for (k, &chip) in sequence.iter().enumerate().skip(1) {
                assert_eq!(chip == 1, is_residue(k, n), "n {n} k {k}");
            }
            let ones = sequence.iter().filter(|&&c| c == 1).count();
            assert_eq!(ones, (n - 1) / 2, "n {n}");
        }
    }

    #[test]
    fn truncation_point_one_starts_at_chip_zero_and_wraps() {
        let legendre = legendre_sequence(7); // 0 1 1 0 1 0 0
        assert_eq!(
            truncated_weil(&legendre, 1, 1, 7),
            vec![1, 0, 1, 1, 1, 0, 0]
        );
        assert_eq!(truncated_weil(&legendre, 1, 7, 3), vec![0, 1, 0]);
    }
}
