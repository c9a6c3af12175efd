//! Test support: exact periodic correlation of logic-level codes, packed 64 chips per word.
//!
//! For codes a, b of period N in signal levels (+1/-1), the periodic correlation at shift s
//! is R(s) = sum_i a_i b_(i+s mod N) = N - 2 * popcount(a XOR rotate(b, s)), so a full
//! correlation over all N shifts costs N * N/64 word operations instead of N * N products.

/// A logic-level code of period `len`, stored twice in a row so that any rotation can be
/// read as a contiguous bit run (chip i in bit i % 64 of word i / 64).
pub(super) struct PackedCode {
    len: usize,
    doubled: Vec<u64>,
}

impl PackedCode {
    /// Packs logic chips (only the lowest bit of each is used).
    pub(super) fn new(chips: &[u8]) -> Self {
        let len = chips.len();
        // One spare word so that the two-word read at the end never leaves the vector.
        let mut doubled = vec![0u64; (2 * len).div_ceil(64) + 1];
        for (i, &chip) in chips.iter().chain(chips).enumerate() {
            doubled[i / 64] |= u64::from(chip & 1) << (i % 64);
        }
        Self { len, doubled }
    }

    /// Period in chips.
    pub(super) fn len(&self) -> usize {
        self.len
    }

    /// The 64 chips starting at chip `start` (start < 2 * len), chip `start` in bit 0.
    fn word_at(&self, start: usize) -> u64 {
        let (q, r) = (start / 64, start % 64);
        if r == 0 {
            self.doubled[q]
        } else {
            (self.doubled[q] >> r) | (self.doubled[q + 1] << (64 - r))
        }
    }

    /// Periodic correlation R(shift) = sum_i a_i b_(i+shift mod N) in signal levels.
    ///
    /// Both codes must have the same period and `shift < len`.
    pub(super) fn correlation(&self, other: &PackedCode, shift: usize) -> i64 {
        assert_eq!(self.len, other.len, "codes of different periods");
        assert!(shift < self.len, "shift out of range");
        let mut differing = 0u32;
        let mut start = 0;
        while start < self.len {
            let valid = (self.len - start).min(64);
            let mask = if valid == 64 {
                u64::MAX
            } else {
                (1u64 << valid) - 1
            };
            let a = self.word_at(start);
            let b = other.word_at(start + shift);
            differing += ((a ^ b) & mask).count_ones();
            start += 64;
        }
        self.len as i64 - 2 * i64::from(differing)
    }

    /// Every value of the periodic correlation with `other`, shift 0 first.
    pub(super) fn all_correlations(&self, other: &PackedCode) -> Vec<i64> {
        (0..self.len)
            .map(|shift| self.correlation(other, shift))
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::PackedCode;

    /// Direct O(N) evaluation of one correlation value, the definition itself.
    fn direct(a: &[u8], b: &[u8], shift: usize) -> i64 {
        let n = a.len();
        (0..n)
            .map(|i| {
                let x = 1 - 2 * i64::from(a[i] & 1);
                let y = 1 - 2 * i64::from(b[(i + shift) % n] & 1);
                x * y
            })
            .sum()
    }

    #[test]
    fn packed_correlation_equals_the_definition_for_odd_lengths() {
        // A deterministic pseudo-random pattern; lengths straddle word boundaries.
        let pattern = |seed: u64, n: usize| -> Vec<u8> {
            let mut x = seed;
            (0..n)
                .map(|_| {
                    x ^= x << 13;
                    x ^= x >> 7;
                    x ^= x << 17;
                    (x & 1) as u8
                })
                .collect()
        };
        for n in [1usize, 63, 64, 65, 127, 200] {
            let a = pattern(0x9E37_79B9_7F4A_7C15, n);
            let b = pattern(0xD1B5_4A32_D192_ED03, n);
            let pa = PackedCode::new(&a);
            let pb = PackedCode::new(&b);
            for shift in 0..n {
                assert_eq!(pa.correlation(&pb, shift), direct(&a, &b, shift), "n {n}");
            }
            assert_eq!(pa.correlation(&pa, 0), n as i64);
        }
    }
}
