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
        self.encode_after(&[], bits)
    }

    /// Encode `bits` as the continuation of a stream whose earlier bits were `history`:
    /// the encoder starts in the state those bits left (only the last K - 1 matter; a
    /// shorter history is preceded by zeros), as a continuous, never-reset code such as
    /// GPS L5 CNAV's does at every message boundary.
    pub fn encode_after(self, history: &[u8], bits: &[u8]) -> Vec<u8> {
        let mut state = history.iter().fold(0usize, |s, &b| push_bit(s, b) >> 1);
        let mut out = Vec::with_capacity(2 * bits.len());
        for &bit in bits {
            let w = push_bit(state, bit);
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
        let mut start = [f32::NEG_INFINITY; STATES];
        start[0] = 0.0;
        self.decode_from(start, soft, terminated)
    }

    /// Maximum-likelihood decoding of a window cut out of a continuous stream (soft pairs
    /// G1, G2 as in [`Self::decode_soft`]): every start state is equally likely and the
    /// best final state is taken. The first and last few bits of the window rest on fewer
    /// symbols than the others; a caller that needs them as well protected decodes a
    /// window reaching some constraint lengths beyond them on both sides.
    pub fn decode_soft_window(self, soft: &[f32]) -> Vec<u8> {
        self.decode_from([0.0; STATES], soft, false)
    }

    fn decode_from(self, start: [f32; STATES], soft: &[f32], terminated: bool) -> Vec<u8> {
        let steps = soft.len() / 2;
        let mut metric = start;
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

/// The 7-bit window of the next input `bit` (bit 6) after the state `state`.
fn push_bit(state: usize, bit: u8) -> usize {
    (usize::from(bit & 1) << (K - 1)) | state
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

    /// A random-looking but fixed bit sequence (a 16-bit LFSR, x^16 + x^14 + x^13 + x^11 + 1).
    fn lfsr_bits(n: usize) -> Vec<u8> {
        let mut r: u16 = 0xACE1;
        (0..n)
            .map(|_| {
                let b = (r ^ (r >> 2) ^ (r >> 3) ^ (r >> 5)) & 1;
                r = (r >> 1) | (b << 15);
                b as u8
            })
            .collect()
    }

    #[test]
    fn encoding_after_a_history_continues_the_stream() {
        let bits = lfsr_bits(400);
        let whole = ConvK7::GPS_L5.encode(&bits);
        for cut in [0, 1, 5, 6, 7, 123, 399] {
            let tail = ConvK7::GPS_L5.encode_after(&bits[..cut], &bits[cut..]);
            assert_eq!(tail, whole[2 * cut..], "cut at bit {cut}");
        }
        // Only the last six bits of the history matter.
        let mut other = bits[..100].to_vec();
        other[..94].iter_mut().for_each(|b| *b ^= 1);
        assert_eq!(
            ConvK7::GPS_L5.encode_after(&other, &bits[100..]),
            whole[200..]
        );
        // By hand: after history 1 (state 100000), input 0 gives G1 = b_t-1 = 1 and
        // G2 = 0 (G2 has no b_t-1 tap).
        assert_eq!(ConvK7::GPS_L5.encode_after(&[1], &[0]), [1, 0]);
    }

    #[test]
    fn a_window_of_a_continuous_stream_decodes_without_its_start_state() {
        let code = ConvK7::GPS_L5;
        let bits = lfsr_bits(1000);
        let soft: Vec<f32> = code
            .encode(&bits)
            .iter()
            .map(|&s| if s == 0 { 1.0 } else { -1.0 })
            .collect();
        // Error-free: every bit of the window, its edges included.
        let window = &soft[2 * 300..2 * 700];
        assert_eq!(code.decode_soft_window(window), bits[300..700]);
        // One error in 15 symbols: the bits 35 or more from either edge come back.
        let mut noisy = window.to_vec();
        for s in noisy.iter_mut().skip(3).step_by(15) {
            *s = -*s;
        }
        let got = code.decode_soft_window(&noisy);
        assert_eq!(got[35..365], bits[335..665]);
    }

    #[test]
    fn inverted_g2_is_not_decodable_as_plain() {
        let msg = with_tail(&[1, 0, 1, 1, 0, 0, 1, 0, 1, 1, 1, 0, 1]);
        let gal = ConvK7::GALILEO.encode(&msg);
        assert_eq!(ConvK7::GALILEO.decode_hard(&gal, true), msg);
        assert_ne!(ConvK7::GPS_L5.decode_hard(&gal, true), msg);
    }
}
