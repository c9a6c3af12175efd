//! The ICDs' check points: the GF(64) tables and the Annex encoding examples of the three
//! codes (each printed codeword is systematic: its first k symbols are the example's
//! input), then decoding with errors and noise.

use super::*;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::{Distribution, Normal};

/// BDS-SIS-ICD-B2a-1.0 Annex 1 (1): the LDPC(96, 48) output codeword.
const B2A_EXAMPLE: &[&str] = &[
    "001010 110010 010011 100001 001010 100110 010000 101001 101100 101111",
    "011100 000101 001110 111010 001001 110100 100010 111111 000101 011100",
    "000110 111101 000000 110001 110100 110111 000101 011001 010000 110011",
    "011011 111010 001011 010000 001001 001000 110111 100101 100011 001001",
    "110110 100111 010110 100000 011001 000100 001111 000111 100000 001000",
    "101101 111001 001011 110111 101101 111111 000000 100011 000110 101110",
    "101011 001100 100001 100101 010111 010010 000101 000010 111011 001010",
    "101111 101100 011000 101010 010011 000001 000001 001101 111000 001100",
    "111001 110101 100111 110100 101111 010111 111010 111111 101100 011111",
    "101011 000010 000110 000001 110000 101100",
];
/// BDS-SIS-ICD-B1C-1.0 Annex 1 (1): the subframe 2 LDPC(200, 100) output codeword.
const B1C_SF2_EXAMPLE: &[&str] = &[
    "001010 110010 010011 100001 001010 100110 010000 101001 101100 101111",
    "011100 000101 001110 111010 001001 110100 100010 111111 000101 011100",
    "000110 111101 000000 110001 110100 110111 000101 011001 010000 110011",
    "011011 111010 001011 010000 001001 001000 110111 100101 100011 001001",
    "110110 100111 010110 100000 011001 000100 001111 000111 001011 001111",
    "011010 000011 111001 111100 011111 011111 010101 111001 010111 000111",
    "110001 011000 001111 011001 000110 001000 111100 111101 100100 000011",
    "001111 010110 110100 000000 000010 001010 101001 101110 101001 011100",
    "100011 010010 101111 001100 101011 001011 010111 101000 110001 000101",
    "111011 110001 011111 011011 011100 010011 100000 100000 110100 110010",
    "100110 000000 110110 011100 111101 101001 101010 100111 000001 111101",
    "011100 100101 111110 101100 100000 000000 111001 010100 101101 110010",
    "101000 000100 111100 110000 101011 000101 100011 110111 000111 101000",
    "010100 110011 011011 000000 110110 001110 001001 111111 001000 010100",
    "011100 010111 011010 001111 011001 100011 100100 001111 010001 100101",
    "100000 011011 101101 110010 101000 001100 010101 111000 001110 101101",
    "111011 011010 110111 110111 011011 101010 011001 011011 100011 101011",
    "110001 101001 011111 100010 010000 010111 101011 111101 000011 010110",
    "100111 111000 000111 100101 001100 111011 111011 110111 011111 010010",
    "011110 100000 011101 011011 110110 111100 111100 001101 001000 101111",
];
/// BDS-SIS-ICD-B1C-1.0 Annex 1 (1): the subframe 3 LDPC(88, 44) output codeword.
const B1C_SF3_EXAMPLE: &[&str] = &[
    "001010 110010 010011 100001 001010 100110 010000 101001 101100 101111",
    "011100 000101 001110 111010 001001 110100 100010 111111 000101 011100",
    "000110 111101 000000 110001 110100 110111 000101 011001 010000 110011",
    "011011 111010 001011 010000 001001 001000 110111 100101 100011 001001",
    "110110 100111 010110 100000 101001 101000 101011 011101 111000 100000",
    "000001 001111 110111 010101 100111 001100 000010 101001 001000 100110",
    "000011 101000 110101 110110 010101 001000 010100 011110 111110 101001",
    "000001 000001 101110 100000 101001 110101 110001 011111 001001 000011",
    "010010 011011 101100 010111 100001 000001 000110 000101",
];

/// The bits of a printed codeword ("001010 110010 ...").
fn bits_of(groups: &[&str]) -> Vec<u8> {
    groups
        .iter()
        .flat_map(|l| l.split_whitespace())
        .flat_map(|g| g.bytes().map(|b| b - b'0'))
        .collect()
}

fn codes() -> [(&'static LdpcGf64, Vec<u8>); 3] {
    [
        (&B2A_FRAME, bits_of(B2A_EXAMPLE)),
        (&B1C_SUBFRAME2, bits_of(B1C_SF2_EXAMPLE)),
        (&B1C_SUBFRAME3, bits_of(B1C_SF3_EXAMPLE)),
    ]
}

/// BPSK soft values (0 -> +1) with Gaussian noise of variance 1 / (2 Es/N0).
fn noisy(bits: &[u8], es_n0_db: f64, seed: u64) -> Vec<f32> {
    let sigma = (0.5 / 10f64.powf(es_n0_db / 10.0)).sqrt();
    let normal = Normal::new(0.0, sigma).unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    bits.iter()
        .map(|&b| (1.0 - 2.0 * f64::from(b) + normal.sample(&mut rng)) as f32)
        .collect()
}

#[test]
fn field_tables_are_the_icd_power_to_vector_mapping() {
    // BDS-SIS-ICD-B2a-1.0 Annex 1 (2): alpha^0 .. alpha^62 in vector representation.
    let icd: [u8; 63] = [
        1, 2, 4, 8, 16, 32, 3, 6, 12, 24, 48, 35, 5, 10, 20, 40, 19, 38, 15, 30, 60, 59, 53, 41,
        17, 34, 7, 14, 28, 56, 51, 37, 9, 18, 36, 11, 22, 44, 27, 54, 47, 29, 58, 55, 45, 25, 50,
        39, 13, 26, 52, 43, 21, 42, 23, 46, 31, 62, 63, 61, 57, 49, 33,
    ];
    assert_eq!(EXP[..63], icd);
    // The vector-to-power mapping starts [inf, 0, 1, 6, 2, 12, 7, 26, 3, 32].
    assert_eq!(LOG[1..10], [0, 1, 6, 2, 12, 7, 26, 3, 32]);
    for a in 1..64u8 {
        assert_eq!(mul(a, inv(a)), 1);
    }
}

#[test]
fn icd_example_codewords_have_zero_syndrome_and_are_what_the_encoder_makes() {
    for (code, example) in codes() {
        assert_eq!(example.len(), code.code_bits());
        assert!(code.is_codeword(&example));
        let info = &example[..code.info_bits()];
        assert_eq!(code.encode_bits(info), example);
        // One flipped bit anywhere breaks a check.
        let mut bad = example.clone();
        bad[code.code_bits() - 1] ^= 1;
        assert!(!code.is_codeword(&bad));
    }
}

#[test]
fn random_words_encode_to_codewords() {
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    for (code, _) in codes() {
        for _ in 0..5 {
            let info: Vec<u8> = (0..code.info_bits())
                .map(|_| u8::from(rand::Rng::random::<bool>(&mut rng)))
                .collect();
            let word = code.encode_bits(&info);
            assert!(code.is_codeword(&word));
            assert_eq!(word[..info.len()], info[..]);
        }
    }
}

#[test]
fn the_soft_decoder_corrects_noise_at_2_5_db() {
    for (k, (code, example)) in codes().into_iter().enumerate() {
        let soft = noisy(&example, 2.5, 20 + k as u64);
        let hard_errors = soft
            .iter()
            .zip(&example)
            .filter(|&(&s, &b)| u8::from(s < 0.0) != b)
            .count();
        assert!(hard_errors > 0, "the test needs errors to correct");
        let info = code.decode_soft(&soft, 30).expect("decodes");
        assert_eq!(info, example[..code.info_bits()]);
    }
}

#[test]
fn the_decoder_refuses_noise_and_wrong_lengths() {
    let mut rng = ChaCha8Rng::seed_from_u64(5);
    let normal = Normal::new(0.0f32, 1.0).unwrap();
    let noise: Vec<f32> = (0..B2A_FRAME.code_bits())
        .map(|_| normal.sample(&mut rng))
        .collect();
    assert_eq!(B2A_FRAME.decode_soft(&noise, 20), None);
    assert_eq!(B2A_FRAME.decode_soft(&noise[1..], 20), None);
}
