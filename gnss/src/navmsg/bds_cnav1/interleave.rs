//! The block interleaver of B-CNAV1 subframes 2 and 3 (BDS-SIS-ICD-B1C-1.0 6.2.2.4,
//! Figure 6-4): a 36 x 48 array written by rows, two rows of subframe 2 then one of
//! subframe 3 until subframe 3 ends in row 33, the last three rows subframe 2, and read
//! by columns.

const ROWS: usize = 36;
const COLS: usize = 48;
/// Encoded symbols of subframe 2 (subframe 3 has 528).
pub(super) const SF2_SYMBOLS: usize = 1200;

/// For each array row, whether it holds subframe 3.
fn is_sf3_row(r: usize) -> bool {
    r < 33 && r % 3 == 2
}

/// The position in the interleaved (read-out) order of each written symbol: subframe 2's
/// 1200 first, then subframe 3's 528.
fn positions() -> Vec<usize> {
    let (mut sf2, mut sf3) = (Vec::new(), Vec::new());
    for r in 0..ROWS {
        for c in 0..COLS {
            let out = c * ROWS + r;
            if is_sf3_row(r) { &mut sf3 } else { &mut sf2 }.push(out);
        }
    }
    sf2.extend(sf3);
    sf2
}

/// Interleave the symbols of subframes 2 and 3 (written order: subframe 2 then 3).
pub(super) fn interleave<T: Copy + Default>(sf2_sf3: &[T]) -> Vec<T> {
    let mut out = vec![T::default(); ROWS * COLS];
    for (&p, &x) in positions().iter().zip(sf2_sf3) {
        out[p] = x;
    }
    out
}

/// The inverse: subframe 2's symbols then subframe 3's.
pub(super) fn deinterleave<T: Copy>(symbols: &[T]) -> Vec<T> {
    positions().iter().map(|&p| symbols[p]).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_array_is_filled_as_the_icd_describes() {
        let written: Vec<u32> = (0..1728).collect();
        let out = interleave(&written);
        // Column 1 read top to bottom: rows 1, 2 are subframe 2 (symbols 0, 48), row 3
        // subframe 3's first symbol (1200), row 4 subframe 2 again (96).
        assert_eq!(out[..4], [0, 48, 1200, 96]);
        // The 528th subframe 3 symbol is the last cell of row 33.
        assert_eq!(out[47 * ROWS + 32], 1727);
        // Rows 34-36 hold the last 144 subframe 2 symbols.
        assert_eq!(out[33], 1056);
        assert_eq!(out[47 * ROWS + 35], 1199);
        assert_eq!(deinterleave(&out), written);
        assert_eq!(SF2_SYMBOLS + 528, ROWS * COLS);
    }
}
