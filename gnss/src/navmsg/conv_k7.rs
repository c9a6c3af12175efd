//! The constraint-length 7, rate 1/2 convolutional code with generators G1 = 171 and
//! G2 = 133 (octal), and a Viterbi decoder for it.
//!
//! Galileo (OS SIS ICD §4.1.4.1, "Viterbi convolutional coding": rate 1/2, K = 7,
//! G1 = 171o, G2 = 133o, symbols sent G1 then G2, the G2 output inverted) and GPS L5 CNAV
//! (the same code without the inversion) use it. The tap of the current input bit is the
//! most significant bit of the octal generator: a lone 1 followed by zeros produces the
//! generator coefficients in order, 1111001 on G1 and 1011011 on G2.
//!
//! Soft symbols follow the BPSK convention +1 = logic 0, -1 = logic 1: a positive value
//! is a 0 symbol, its magnitude the confidence.

/// G1 = 171 octal.
pub const G1: u8 = 0o171;
/// G2 = 133 octal.
pub const G2: u8 = 0o133;
/// Constraint length.
pub const K: usize = 7;
/// Encoder states (the six previous input bits).
const STATES: usize = 1 << (K - 1);

/// The code, with or without the inversion of the G2 output.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ConvK7 {
    /// Invert every G2 symbol after encoding (Galileo) or not (GPS L5).
    pub invert_g2: bool,
}

impl ConvK7 {
    /// Galileo I/NAV, F/NAV: G2 inverted.
    pub const GALILEO: Self = Self { invert_g2: true };
    /// GPS L5 CNAV: no inversion.
    pub const GPS_L5: Self = Self { invert_g2: false };

    /// The two symbols (G1, G2) the 7-bit window `w` (current bit in bit 6) produces.
    fn outputs(self, w: usize) -> (u8, u8) {
        let parity = |g: u8| ((w as u32) & u32::from(g)).count_ones() as u8 & 1;
        (parity(G1), parity(G2) ^ u8::from(self.invert_g2))
    }

    /// Encode `bits` (0/1) from the all-zero state: two symbols per bit, G1 first. The
    /// caller appends the K - 1 zero tail bits where the message is terminated.
    pub fn encode(self, bits: &[u8]) -> Vec<u8> {
        let mut state = 0usize;
        let mut out = Vec::with_capacity(2 * bits.len());
        for &bit in bits {
            let w = (usize::from(bit & 1) << (K - 1)) | state;
            let (a, b) = self.outputs(w);
            out.extend([a, b]);
            state = w >> 1;
        }
        out
    }

    /// Maximum-likelihood decoding of soft symbols (pairs G1, G2; positive = 0) from the
    /// all-zero state. `terminated`: the message ends with K - 1 zero tail bits, so the
    /// path must end in the zero state; otherwise the best final state is taken. Returns
    /// one bit per symbol pair (tail bits included). An odd last symbol is ignored.
    pub fn decode_soft(self, soft: &[f32], terminated: bool) -> Vec<u8> {
        let steps = soft.len() / 2;
        let mut metric = [f32::NEG_INFINITY; STATES];
        metric[0] = 0.0;
        let mut decisions = Vec::with_capacity(steps);
        let branches = self.branch_table();
        for pair in soft.chunks_exact(2) {
            let (m, d) = acs_step(&metric, &branches, pair[0], pair[1]);
            metric = m;
            decisions.push(d);
        }
        let end = if terminated { 0 } else { best_state(&metric) };
        traceback(&decisions, end)
    }

    /// Hard-decision decoding of symbols 0/1 (as [`Self::decode_soft`] with +-1).
    pub fn decode_hard(self, symbols: &[u8], terminated: bool) -> Vec<u8> {
        let soft: Vec<f32> = symbols
            .iter()
            .map(|&s| if s == 0 { 1.0 } else { -1.0 })
            .collect();
        self.decode_soft(&soft, terminated)
    }

    /// For each next state and each of its two predecessors: the expected symbol signs
    /// (+1 for 0, -1 for 1).
    fn branch_table(self) -> [[(f32, f32); 2]; STATES] {
        let sign = |s: u8| if s == 0 { 1.0 } else { -1.0 };
        std::array::from_fn(|next| {
            std::array::from_fn(|x| {
                let (a, b) = self.outputs((next << 1) | x);
                (sign(a), sign(b))
            })
        })
    }
}

/// One add-compare-select step over all states: new metrics and, per next state, which
/// predecessor (0 or 1: the oldest bit of the window) survived, as one bit of a u64.
fn acs_step(
    metric: &[f32; STATES],
    branches: &[[(f32, f32); 2]; STATES],
    s1: f32,
    s2: f32,
) -> ([f32; STATES], u64) {
    let mut next_metric = [f32::NEG_INFINITY; STATES];
    let mut decisions = 0u64;
    for (next, (slot, branch)) in next_metric.iter_mut().zip(branches).enumerate() {
        let prev = (next << 1) & (STATES - 1);
        let cand = |x: usize| metric[prev | x] + branch[x].0 * s1 + branch[x].1 * s2;
        let (c0, c1) = (cand(0), cand(1));
        if c1 > c0 {
            *slot = c1;
            decisions |= 1 << next;
        } else {
            *slot = c0;
        }
    }
    (next_metric, decisions)
}

fn best_state(metric: &[f32; STATES]) -> usize {
    (0..STATES).fold(0, |best, s| if metric[s] > metric[best] { s } else { best })
}

/// Follows the survivors back from `end`; the decoded bit of a step is the newest bit of
/// the state it reached (bit K - 2).
fn traceback(decisions: &[u64], end: usize) -> Vec<u8> {
    let mut bits = vec![0u8; decisions.len()];
    let mut state = end;
    for (bit, d) in bits.iter_mut().zip(decisions).rev() {
        *bit = (state >> (K - 2)) as u8 & 1;
        let x = ((d >> state) & 1) as usize;
        state = ((state << 1) & (STATES - 1)) | x;
    }
    bits
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    #[test]
    fn impulse_response_is_the_generators() {
        let enc = ConvK7::GPS_L5.encode(&[1, 0, 0, 0, 0, 0, 0]);
        // G1 = 1111001, G2 = 1011011, interleaved G1, G2.
        assert_eq!(enc, [1, 1, 1, 0, 1, 1, 1, 1, 0, 0, 0, 1, 1, 1]);
    }

    #[test]
    fn hand_computed_sequence() {
        // Input b = 1 1 0 1, by hand: G1_t = b_t + b_t-1 + b_t-2 + b_t-3 + b_t-6 and
        // G2_t = b_t + b_t-2 + b_t-3 + b_t-5 + b_t-6 (mod 2):
        // t = 0: 1, 1; t = 1: 1+1 = 0, 1; t = 2: 0+1+1 = 0, 0+1 = 1; t = 3: 1+0+1+1 = 1, 1+1+1 = 1.
        let enc = ConvK7::GPS_L5.encode(&[1, 1, 0, 1]);
        assert_eq!(enc, [1, 1, 0, 1, 0, 1, 1, 1]);
        // Galileo inverts every G2 symbol.
        let gal = ConvK7::GALILEO.encode(&[1, 1, 0, 1]);
        assert_eq!(gal, [1, 0, 0, 0, 0, 0, 1, 0]);
    }

    fn with_tail(bits: &[u8]) -> Vec<u8> {
        let mut v = bits.to_vec();
        v.extend([0; K - 1]);
        v
    }

    proptest! {
        #[test]
        fn decodes_error_free_symbols(bits in proptest::collection::vec(0u8..2, 1..300), gal: bool) {
            let code = ConvK7 { invert_g2: gal };
            let msg = with_tail(&bits);
            let symbols = code.encode(&msg);
            prop_assert_eq!(code.decode_hard(&symbols, true), msg.clone());
            prop_assert_eq!(code.decode_hard(&symbols, false), msg);
        }

        #[test]
        fn corrects_one_error_in_twenty_symbols(
            bits in proptest::collection::vec(0u8..2, 244..245),
            offset in 0usize..20,
            gal: bool,
        ) {
            let code = ConvK7 { invert_g2: gal };
            let msg = with_tail(&bits);
            let mut symbols = code.encode(&msg);
            for s in symbols.iter_mut().skip(offset).step_by(20) {
                *s ^= 1;
            }
            prop_assert_eq!(code.decode_hard(&symbols, true), msg);
        }

        #[test]
        fn soft_decoding_corrects_weak_wrong_symbols(
            bits in proptest::collection::vec(0u8..2, 100..101),
            offset in 0usize..7,
        ) {
            let code = ConvK7::GALILEO;
            let msg = with_tail(&bits);
            let mut soft: Vec<f32> = code.encode(&msg).iter().map(|&s| if s == 0 { 1.0 } else { -1.0 }).collect();
            // Every 7th symbol flipped, but with low confidence.
            for s in soft.iter_mut().skip(offset).step_by(7) {
                *s *= -0.2;
            }
            prop_assert_eq!(code.decode_soft(&soft, true), msg);
        }
    }

    #[test]
    fn inverted_g2_is_not_decodable_as_plain() {
        let msg = with_tail(&[1, 0, 1, 1, 0, 0, 1, 0, 1, 1, 1, 0, 1]);
        let gal = ConvK7::GALILEO.encode(&msg);
        assert_eq!(ConvK7::GALILEO.decode_hard(&gal, true), msg);
        assert_ne!(ConvK7::GPS_L5.decode_hard(&gal, true), msg);
    }
}
