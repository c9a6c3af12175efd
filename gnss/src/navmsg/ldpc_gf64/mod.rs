//! The 64-ary LDPC codes of the BeiDou B-CNAV1 (B1C) and B-CNAV2 (B2a) messages:
//! GF(2^6) arithmetic, encoding, syndrome check and a soft decoder.
//!
//! BDS-SIS-ICD-B1C-1.0 6.2.2.2-6.2.2.3 and BDS-SIS-ICD-B2a-1.0 6.2.2: each code symbol is
//! 6 bits, an element of GF(2^6) with primitive polynomial p(x) = 1 + x + x^6, in vector
//! representation with the MSB first. H = [H1, H2] is m x n, H1 (m x k) over the
//! information symbols, H2 (m x m) over the check symbols; every row has four non-zero
//! elements ([`tables`]).
//!
//! Encoding (the ICDs' Annex 1): from H c^T = 0 with c = [m, p], p^T = H2^-1 H1 m^T
//! (characteristic 2: no signs). The dense matrix H2^-1 H1 is derived once per code by
//! Gauss-Jordan elimination of [H2 | H1] over GF(64) and kept.
//!
//! Decoding: min-sum belief propagation over GF(64) in the cost domain (the ICDs' Annex
//! 2 "extended min-sum" without truncation, n_m = q = 64): the channel cost of a symbol
//! value is the sum of |soft| over its bits that disagree with the hard decision, check
//! nodes combine the other edges' messages by min-convolution over GF(64) addition, and
//! decoding stops at the first iteration whose hard decisions have a zero syndrome.

mod tables;
#[cfg(test)]
mod tests;

use std::sync::OnceLock;

/// Bits per code symbol.
pub const GF64_BITS: usize = 6;
/// Field size.
const Q: usize = 64;
/// p(x) = 1 + x + x^6 as a bit mask.
const PRIMITIVE: u16 = 0b100_0011;

/// alpha^i for i = 0..125 (twice the period, so that products need no reduction).
const EXP: [u8; 126] = build_exp();
/// log_alpha(x) for x = 1..63 (entry 0 unused).
const LOG: [u8; Q] = build_log();

const fn build_exp() -> [u8; 126] {
    let mut t = [0u8; 126];
    let mut x: u16 = 1;
    let mut i = 0;
    while i < 63 {
        t[i] = x as u8;
        t[i + 63] = x as u8;
        x <<= 1;
        if x & 0x40 != 0 {
            x ^= PRIMITIVE;
        }
        i += 1;
    }
    t
}

const fn build_log() -> [u8; Q] {
    let exp = build_exp();
    let mut t = [0u8; Q];
    let mut i = 0;
    while i < 63 {
        t[exp[i] as usize] = i as u8;
        i += 1;
    }
    t
}

/// Product in GF(64).
fn mul(a: u8, b: u8) -> u8 {
    if a == 0 || b == 0 {
        0
    } else {
        EXP[LOG[a as usize] as usize + LOG[b as usize] as usize]
    }
}

/// Inverse in GF(64) of a non-zero element.
fn inv(a: u8) -> u8 {
    EXP[(63 - LOG[a as usize] as usize) % 63]
}

/// One 64-ary LDPC(n, k) code, k = n - m, given by its ICD parity-check matrix.
#[derive(Debug)]
pub struct LdpcGf64 {
    /// Check rows m.
    m: usize,
    /// Code symbols n.
    n: usize,
    index: &'static [[u8; 4]],
    element: &'static [[u8; 4]],
    /// H2^-1 H1 (m x k), derived on first use.
    parity: OnceLock<Vec<Vec<u8>>>,
}

/// BDS-SIS-ICD-B1C-1.0 6.2.2.2: LDPC(200, 100) of B-CNAV1 subframe 2.
pub static B1C_SUBFRAME2: LdpcGf64 =
    LdpcGf64::new(&tables::B1C_SF2_INDEX, &tables::B1C_SF2_ELEMENT);
/// BDS-SIS-ICD-B1C-1.0 6.2.2.3: LDPC(88, 44) of B-CNAV1 subframe 3.
pub static B1C_SUBFRAME3: LdpcGf64 =
    LdpcGf64::new(&tables::B1C_SF3_INDEX, &tables::B1C_SF3_ELEMENT);
/// BDS-SIS-ICD-B2a-1.0 6.2.2: LDPC(96, 48) of the B-CNAV2 frame.
pub static B2A_FRAME: LdpcGf64 = LdpcGf64::new(&tables::B2A_INDEX, &tables::B2A_ELEMENT);

impl LdpcGf64 {
    const fn new(index: &'static [[u8; 4]], element: &'static [[u8; 4]]) -> Self {
        let m = index.len();
        Self {
            m,
            n: 2 * m,
            index,
            element,
            parity: OnceLock::new(),
        }
    }

    /// Information bits k x 6.
    pub fn info_bits(&self) -> usize {
        (self.n - self.m) * GF64_BITS
    }

    /// Code bits n x 6.
    pub fn code_bits(&self) -> usize {
        self.n * GF64_BITS
    }

    /// Encode `info_bits()` bits (0/1, MSB of the first symbol first): the information
    /// bits followed by the check bits.
    pub fn encode_bits(&self, bits: &[u8]) -> Vec<u8> {
        assert_eq!(bits.len(), self.info_bits(), "LDPC information length");
        let info = to_symbols(bits);
        let parity = self.parity();
        let mut code = info.clone();
        code.extend(
            parity
                .iter()
                .map(|row| row.iter().zip(&info).fold(0, |s, (&p, &x)| s ^ mul(p, x))),
        );
        to_bits(&code)
    }

    /// Whether `code_bits()` bits form a codeword (H c^T = 0).
    pub fn is_codeword(&self, bits: &[u8]) -> bool {
        bits.len() == self.code_bits() && self.syndrome_is_zero(&to_symbols(bits))
    }

    fn syndrome_is_zero(&self, symbols: &[u8]) -> bool {
        self.index.iter().zip(self.element).all(|(idx, el)| {
            idx.iter()
                .zip(el)
                .fold(0, |s, (&j, &h)| s ^ mul(h, symbols[j as usize]))
                == 0
        })
    }

    /// H2^-1 H1, by Gauss-Jordan elimination of [H2 | H1].
    fn parity(&self) -> &Vec<Vec<u8>> {
        self.parity.get_or_init(|| {
            let (m, k) = (self.m, self.n - self.m);
            // Row i: H2 in columns 0..m, H1 in columns m..m + k.
            let mut a = vec![vec![0u8; m + k]; m];
            for (i, (idx, el)) in self.index.iter().zip(self.element).enumerate() {
                for (&j, &h) in idx.iter().zip(el) {
                    let j = j as usize;
                    let col = if j < k { m + j } else { j - k };
                    a[i][col] = h;
                }
            }
            for c in 0..m {
                // H2 of every ICD code is invertible (the tests encode the ICD examples).
                let Some(pivot) = (c..m).find(|&r| a[r][c] != 0) else {
                    continue;
                };
                a.swap(c, pivot);
                let scale = inv(a[c][c]);
                a[c].iter_mut().for_each(|x| *x = mul(*x, scale));
                let pivot_row = a[c].clone();
                for (r, row) in a.iter_mut().enumerate() {
                    let f = row[c];
                    if r != c && f != 0 {
                        for (x, &p) in row.iter_mut().zip(&pivot_row) {
                            *x ^= mul(f, p);
                        }
                    }
                }
            }
            a.into_iter().map(|row| row[m..].to_vec()).collect()
        })
    }

    /// Decode `code_bits()` soft bits (positive = logic 0, magnitude the confidence, 0 an
    /// erasure) in at most `max_iterations` min-sum iterations: the information bits of
    /// the first codeword found, or `None`.
    pub fn decode_soft(&self, soft: &[f32], max_iterations: usize) -> Option<Vec<u8>> {
        if soft.len() != self.code_bits() {
            return None;
        }
        let channel: Vec<[f32; Q]> = soft.chunks(GF64_BITS).map(symbol_costs).collect();
        // The edges of each variable: (check, slot).
        let mut var_edges = vec![Vec::new(); self.n];
        for (i, idx) in self.index.iter().enumerate() {
            for (t, &j) in idx.iter().enumerate() {
                var_edges[j as usize].push((i, t));
            }
        }
        let mut c2v = vec![[[0f32; Q]; 4]; self.m];
        let mut v2c = vec![[[0f32; Q]; 4]; self.m];
        let mut hard = vec![0u8; self.n];
        for _ in 0..=max_iterations {
            for (v, edges) in var_edges.iter().enumerate() {
                let mut total = channel[v];
                for &(i, t) in edges {
                    add_into(&mut total, &c2v[i][t]);
                }
                hard[v] = argmin(&total);
                for &(i, t) in edges {
                    let msg = &mut v2c[i][t];
                    for x in 0..Q {
                        msg[x] = total[x] - c2v[i][t][x];
                    }
                    normalise(msg);
                }
            }
            if self.syndrome_is_zero(&hard) {
                return Some(to_bits(&hard[..self.n - self.m]));
            }
            for (i, el) in self.element.iter().enumerate() {
                c2v[i] = check_update(&v2c[i], el);
            }
        }
        None
    }
}

/// The check-to-variable messages of one check of four edges with elements `h`, from
/// the variable-to-check messages `v2c` (both indexed by the variable's value).
fn check_update(v2c: &[[f32; Q]; 4], h: &[u8; 4]) -> [[f32; Q]; 4] {
    // Edge domain: U_t(h_t x) = V_t(x).
    let mut u = [[0f32; Q]; 4];
    for t in 0..4 {
        for x in 0..Q {
            u[t][mul(h[t], x as u8) as usize] = v2c[t][x];
        }
    }
    let f01 = min_convolve(&u[0], &u[1]);
    let b23 = min_convolve(&u[2], &u[3]);
    let w = [
        min_convolve(&u[1], &b23),
        min_convolve(&u[0], &b23),
        min_convolve(&f01, &u[3]),
        min_convolve(&f01, &u[2]),
    ];
    let mut out = [[0f32; Q]; 4];
    for t in 0..4 {
        for x in 0..Q {
            out[t][x] = w[t][mul(h[t], x as u8) as usize];
        }
        normalise(&mut out[t]);
    }
    out
}

/// out(a + b) = min over a, b of A(a) + B(b) (GF(64) addition is XOR).
fn min_convolve(a: &[f32; Q], b: &[f32; Q]) -> [f32; Q] {
    let mut out = [f32::INFINITY; Q];
    for (x, &ax) in a.iter().enumerate() {
        for (y, &by) in b.iter().enumerate() {
            let s = ax + by;
            if s < out[x ^ y] {
                out[x ^ y] = s;
            }
        }
    }
    out
}

/// The cost of each symbol value for six soft bits: the sum of |soft| over the bits
/// that disagree with the hard decision (0 for the most likely value).
fn symbol_costs(soft: &[f32]) -> [f32; Q] {
    let mut cost = [0f32; Q];
    for (x, c) in cost.iter_mut().enumerate() {
        *c = soft
            .iter()
            .enumerate()
            .map(|(b, &y)| {
                let bit = (x >> (GF64_BITS - 1 - b)) & 1;
                if (bit == 1) != (y < 0.0) {
                    y.abs()
                } else {
                    0.0
                }
            })
            .sum();
    }
    cost
}

fn add_into(total: &mut [f32; Q], msg: &[f32; Q]) {
    total.iter_mut().zip(msg).for_each(|(t, m)| *t += m);
}

fn normalise(msg: &mut [f32; Q]) {
    let min = msg.iter().copied().fold(f32::INFINITY, f32::min);
    msg.iter_mut().for_each(|x| *x -= min);
}

fn argmin(cost: &[f32; Q]) -> u8 {
    (0..Q).fold(0, |best, x| if cost[x] < cost[best] { x } else { best }) as u8
}

/// Bits (MSB first) to 6-bit symbols.
fn to_symbols(bits: &[u8]) -> Vec<u8> {
    bits.chunks(GF64_BITS)
        .map(|c| c.iter().fold(0u8, |s, &b| (s << 1) | (b & 1)))
        .collect()
}

/// 6-bit symbols to bits, MSB first.
fn to_bits(symbols: &[u8]) -> Vec<u8> {
    symbols
        .iter()
        .flat_map(|&s| (0..GF64_BITS).rev().map(move |k| (s >> k) & 1))
        .collect()
}
