//! An independent D1/D2 decoder for the tests, written from the ICD and sharing no code
//! with the encoder: BCH(15,11) syndromes by polynomial division by g(x) = x^4 + x + 1,
//! de-interleaving, and field extraction by the bit positions of the ICD's bit-allocation
//! figures (1-based positions in the 300-bit subframe, where bits 23-30 of words 2-10
//! and bits 27-30 of word 1 are parity).

use std::f64::consts::PI;

/// g(x) = x^4 + x + 1.
const G: u32 = 0b1_0011;

/// Remainder of a 15-bit word (bit 14 = x^14) divided by g(x).
pub(crate) fn bch_syndrome(cw: u32) -> u32 {
    let mut r = cw & 0x7FFF;
    for deg in (4..15).rev() {
        if (r >> deg) & 1 == 1 {
            r ^= G << (deg - 4);
        }
    }
    r
}

/// The codeword nearest to `cw` (at most one bit flipped), or `None`.
pub(crate) fn bch_correct(cw: u32) -> Option<u32> {
    let s = bch_syndrome(cw);
    if s == 0 {
        return Some(cw & 0x7FFF);
    }
    (0..15)
        .map(|b| 1u32 << b)
        .find(|&e| bch_syndrome(e) == s)
        .map(|e| (cw ^ e) & 0x7FFF)
}

/// The two codewords of a transmitted word 2-10 (even positions, first sent, are the first
/// codeword).
pub(crate) fn deinterleave(w: u32) -> (u32, u32) {
    (0..15).fold((0, 0), |(c1, c2), k| {
        (
            (c1 << 1) | ((w >> (29 - 2 * k)) & 1),
            (c2 << 1) | ((w >> (28 - 2 * k)) & 1),
        )
    })
}

/// The subframe as the ICD draws it: per word, information bits then parity bits
/// (word 1: 26 + 4; words 2-10: 11 + 11 information bits, then the 4 parity bits of each
/// codeword). Index 0 is ICD bit 1. Fails on any codeword with a non-zero syndrome.
pub(crate) fn logical_bits(words: &[u32; 10]) -> Result<[u8; 300], String> {
    let logical = logical_words(words);
    match parity_errors(&logical).first() {
        Some(k) => Err(format!("word {k}: parity")),
        None => Ok(logical_from_words(&logical)),
    }
}

/// Transmitted words rearranged into the ICD's layout (words 2-10 de-interleaved).
pub(crate) fn logical_words(words: &[u32; 10]) -> [u32; 10] {
    let mut logical = *words;
    for w in logical.iter_mut().skip(1) {
        let (c1, c2) = deinterleave(*w);
        *w = ((c1 >> 4) << 19) | ((c2 >> 4) << 8) | ((c1 & 0xF) << 4) | (c2 & 0xF);
    }
    logical
}

/// The two codewords of a word 2-10 in the ICD's layout.
pub(crate) fn logical_codewords(w: u32) -> (u32, u32) {
    (
        ((w >> 19) << 4) | ((w >> 4) & 0xF),
        (((w >> 8) & 0x7FF) << 4) | (w & 0xF),
    )
}

/// Numbers (1-10) of the words of a subframe in the ICD's layout with a non-zero
/// syndrome.
pub(crate) fn parity_errors(logical: &[u32; 10]) -> Vec<usize> {
    let mut bad = Vec::new();
    if bch_syndrome(logical[0] & 0x7FFF) != 0 {
        bad.push(1);
    }
    for (k, &w) in logical.iter().enumerate().skip(1) {
        let (c1, c2) = logical_codewords(w);
        if bch_syndrome(c1) != 0 || bch_syndrome(c2) != 0 {
            bad.push(k + 1);
        }
    }
    bad
}

/// Bits (index 0 = ICD bit 1) of ten 30-bit words already in the ICD's layout.
pub(crate) fn logical_from_words(words: &[u32; 10]) -> [u8; 300] {
    let mut bits = [0u8; 300];
    for (i, b) in bits.iter_mut().enumerate() {
        *b = ((words[i / 30] >> (29 - i % 30)) & 1) as u8;
    }
    bits
}

/// Unsigned value of the concatenated parts (ICD position, length).
pub(crate) fn read_u(bits: &[u8; 300], parts: &[(usize, usize)]) -> u64 {
    parts
        .iter()
        .flat_map(|&(pos, len)| pos..pos + len)
        .fold(0, |v, p| (v << 1) | u64::from(bits[p - 1]))
}

/// Two's-complement value of the concatenated parts.
pub(crate) fn read_s(bits: &[u8; 300], parts: &[(usize, usize)]) -> i64 {
    let n: usize = parts.iter().map(|p| p.1).sum();
    sign_extend(read_u(bits, parts), n)
}

pub(crate) fn sign_extend(v: u64, n: usize) -> i64 {
    let shift = 64 - n;
    ((v << shift) as i64) >> shift
}

/// Every ephemeris, clock and ionosphere value the message carries, in SI units
/// (angles in rad).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(crate) struct Decoded {
    pub sow: u64,
    pub sat_h1: u64,
    pub aodc: u64,
    pub urai: u64,
    pub wn: u64,
    pub toc_s: f64,
    pub tgd1_s: f64,
    pub tgd2_s: f64,
    pub alpha: [f64; 4],
    pub beta: [f64; 4],
    pub a0: f64,
    pub a1: f64,
    pub a2: f64,
    pub aode: u64,
    pub toe_s: f64,
    pub sqrt_a: f64,
    pub e: f64,
    pub i0: f64,
    pub omega0: f64,
    pub omega: f64,
    pub m0: f64,
    pub delta_n: f64,
    pub idot: f64,
    pub omega_dot: f64,
    pub cuc: f64,
    pub cus: f64,
    pub cic: f64,
    pub cis: f64,
    pub crc: f64,
    pub crs: f64,
}

fn p2(n: i32) -> f64 {
    2f64.powi(n)
}

const ALPHA_EXP: [i32; 4] = [-30, -27, -24, -24];
const BETA_EXP: [i32; 4] = [11, 14, 16, 16];

/// Header fields: (preamble, Rev, FraID, SOW).
pub(crate) fn header(b: &[u8; 300]) -> (u64, u64, u64, u64) {
    (
        read_u(b, &[(1, 11)]),
        read_u(b, &[(12, 4)]),
        read_u(b, &[(16, 3)]),
        read_u(b, &[(19, 8), (31, 12)]),
    )
}

/// D1 subframes 1, 2, 3 (BDS-SIS-ICD-B1I-3.0 §5.2.3, subframe 1-3 bit allocation).
pub(crate) fn decode_d1(sf1: &[u8; 300], sf2: &[u8; 300], sf3: &[u8; 300]) -> Decoded {
    let mut d = Decoded {
        sow: header(sf1).3,
        sat_h1: read_u(sf1, &[(43, 1)]),
        aodc: read_u(sf1, &[(44, 5)]),
        urai: read_u(sf1, &[(49, 4)]),
        wn: read_u(sf1, &[(61, 13)]),
        toc_s: 8.0 * read_u(sf1, &[(74, 9), (91, 8)]) as f64,
        tgd1_s: 0.1e-9 * read_s(sf1, &[(99, 10)]) as f64,
        tgd2_s: 0.1e-9 * read_s(sf1, &[(109, 4), (121, 6)]) as f64,
        a2: p2(-66) * read_s(sf1, &[(215, 11)]) as f64,
        a0: p2(-33) * read_s(sf1, &[(226, 7), (241, 17)]) as f64,
        a1: p2(-50) * read_s(sf1, &[(258, 5), (271, 17)]) as f64,
        aode: read_u(sf1, &[(288, 5)]),
        ..Decoded::default()
    };
    let alpha: [&[(usize, usize)]; 4] = [&[(127, 8)], &[(135, 8)], &[(151, 8)], &[(159, 8)]];
    let beta: [&[(usize, usize)]; 4] = [
        &[(167, 6), (181, 2)],
        &[(183, 8)],
        &[(191, 8)],
        &[(199, 4), (211, 4)],
    ];
    for n in 0..4 {
        d.alpha[n] = p2(ALPHA_EXP[n]) * read_s(sf1, alpha[n]) as f64;
        d.beta[n] = p2(BETA_EXP[n]) * read_s(sf1, beta[n]) as f64;
    }
    let sc = |v: i64, n: i32| PI * p2(n) * v as f64;
    d.delta_n = sc(read_s(sf2, &[(43, 10), (61, 6)]), -43);
    d.cuc = p2(-31) * read_s(sf2, &[(67, 16), (91, 2)]) as f64;
    d.m0 = sc(read_s(sf2, &[(93, 20), (121, 12)]), -31);
    d.e = p2(-33) * read_u(sf2, &[(133, 10), (151, 22)]) as f64;
    d.cus = p2(-31) * read_s(sf2, &[(181, 18)]) as f64;
    d.crc = p2(-6) * read_s(sf2, &[(199, 4), (211, 14)]) as f64;
    d.crs = p2(-6) * read_s(sf2, &[(225, 8), (241, 10)]) as f64;
    d.sqrt_a = p2(-19) * read_u(sf2, &[(251, 12), (271, 20)]) as f64;
    let toe_msb = read_u(sf2, &[(291, 2)]);
    d.toe_s = 8.0 * ((toe_msb << 15) | read_u(sf3, &[(43, 10), (61, 5)])) as f64;
    d.i0 = sc(read_s(sf3, &[(66, 17), (91, 15)]), -31);
    d.cic = p2(-31) * read_s(sf3, &[(106, 7), (121, 11)]) as f64;
    d.omega_dot = sc(read_s(sf3, &[(132, 11), (151, 13)]), -43);
    d.cis = p2(-31) * read_s(sf3, &[(164, 9), (181, 9)]) as f64;
    d.idot = sc(read_s(sf3, &[(190, 13), (211, 1)]), -43);
    d.omega0 = sc(read_s(sf3, &[(212, 21), (241, 11)]), -31);
    d.omega = sc(read_s(sf3, &[(252, 11), (271, 21)]), -31);
    d
}

/// Field positions of D2 subframe 1 pages 1-10 after Pnum (43, 4), by page
/// (BDS-SIS-ICD-B1I-3.0 §5.3.2, subframe 1 page bit allocation). Used both to decode and
/// to mask the defined bits when comparing with broadcast pages.
pub(crate) const D2_PAGE_FIELDS: [&[(usize, usize)]; 10] = [
    // SatH1, AODC, URAI, WN, toc, TGD1, TGD2
    &[
        (47, 1),
        (48, 5),
        (61, 4),
        (65, 13),
        (78, 5),
        (91, 12),
        (103, 10),
        (121, 10),
    ],
    // alpha0-3, beta0-3
    &[
        (47, 6),
        (61, 2),
        (63, 8),
        (71, 8),
        (79, 4),
        (91, 4),
        (95, 8),
        (103, 8),
        (111, 2),
        (121, 6),
        (127, 8),
    ],
    // a0, a1 MSBs
    &[(101, 12), (121, 12), (133, 4)],
    // a1 LSBs, a2, AODE, Delta n, Cuc MSBs
    &[
        (47, 6),
        (61, 12),
        (73, 10),
        (91, 1),
        (92, 5),
        (97, 16),
        (121, 14),
    ],
    // Cuc LSBs, M0, Cus, e MSBs
    &[
        (47, 4),
        (51, 2),
        (61, 22),
        (91, 8),
        (99, 14),
        (121, 4),
        (125, 10),
    ],
    // e LSBs, sqrt(A), Cic MSBs
    &[(47, 6), (61, 16), (77, 6), (91, 22), (121, 4), (125, 10)],
    // Cic LSBs, Cis, toe, i0 MSBs
    &[
        (47, 6),
        (61, 2),
        (63, 18),
        (81, 2),
        (91, 15),
        (106, 7),
        (121, 14),
    ],
    // i0 LSBs, Crc, Crs, Omega dot MSBs
    &[
        (47, 6),
        (61, 5),
        (66, 17),
        (91, 1),
        (92, 18),
        (110, 3),
        (121, 16),
    ],
    // Omega dot LSBs, Omega0, omega MSBs
    &[(47, 5), (52, 1), (61, 22), (91, 9), (100, 13), (121, 14)],
    // omega LSBs, IDOT
    &[(47, 5), (52, 1), (61, 13)],
];

/// D2 subframe 1 pages 1-10 (in page order).
pub(crate) fn decode_d2(pages: &[[u8; 300]; 10]) -> Decoded {
    for (k, p) in pages.iter().enumerate() {
        assert_eq!(read_u(p, &[(43, 4)]), k as u64 + 1, "page number");
    }
    let pg = |n: usize| &pages[n - 1];
    // A field split over two pages: MSB parts of page n, LSB parts of page n + 1.
    let split = |n: usize, msb: &[(usize, usize)], lsb: &[(usize, usize)]| {
        let width: usize = msb.iter().chain(lsb).map(|p| p.1).sum();
        let lsb_len: usize = lsb.iter().map(|p| p.1).sum();
        let v = (read_u(pg(n), msb) << lsb_len) | read_u(pg(n + 1), lsb);
        (v, width)
    };
    let signed = |(v, n): (u64, usize)| sign_extend(v, n);
    let sc = |v: i64, n: i32| PI * p2(n) * v as f64;
    let mut d = Decoded {
        sow: header(pg(1)).3,
        sat_h1: read_u(pg(1), &[(47, 1)]),
        aodc: read_u(pg(1), &[(48, 5)]),
        urai: read_u(pg(1), &[(61, 4)]),
        wn: read_u(pg(1), &[(65, 13)]),
        toc_s: 8.0 * read_u(pg(1), &[(78, 5), (91, 12)]) as f64,
        tgd1_s: 0.1e-9 * read_s(pg(1), &[(103, 10)]) as f64,
        tgd2_s: 0.1e-9 * read_s(pg(1), &[(121, 10)]) as f64,
        a0: p2(-33) * read_s(pg(3), &[(101, 12), (121, 12)]) as f64,
        a1: p2(-50) * signed(split(3, &[(133, 4)], &[(47, 6), (61, 12)])) as f64,
        a2: p2(-66) * read_s(pg(4), &[(73, 10), (91, 1)]) as f64,
        aode: read_u(pg(4), &[(92, 5)]),
        delta_n: sc(read_s(pg(4), &[(97, 16)]), -43),
        cuc: p2(-31) * signed(split(4, &[(121, 14)], &[(47, 4)])) as f64,
        m0: sc(read_s(pg(5), &[(51, 2), (61, 22), (91, 8)]), -31),
        cus: p2(-31) * read_s(pg(5), &[(99, 14), (121, 4)]) as f64,
        e: p2(-33) * split(5, &[(125, 10)], &[(47, 6), (61, 16)]).0 as f64,
        sqrt_a: p2(-19) * read_u(pg(6), &[(77, 6), (91, 22), (121, 4)]) as f64,
        cic: p2(-31) * signed(split(6, &[(125, 10)], &[(47, 6), (61, 2)])) as f64,
        cis: p2(-31) * read_s(pg(7), &[(63, 18)]) as f64,
        toe_s: 8.0 * read_u(pg(7), &[(81, 2), (91, 15)]) as f64,
        i0: sc(
            signed(split(7, &[(106, 7), (121, 14)], &[(47, 6), (61, 5)])),
            -31,
        ),
        crc: p2(-6) * read_s(pg(8), &[(66, 17), (91, 1)]) as f64,
        crs: p2(-6) * read_s(pg(8), &[(92, 18)]) as f64,
        omega_dot: sc(signed(split(8, &[(110, 3), (121, 16)], &[(47, 5)])), -43),
        omega0: sc(read_s(pg(9), &[(52, 1), (61, 22), (91, 9)]), -31),
        omega: sc(signed(split(9, &[(100, 13), (121, 14)], &[(47, 5)])), -31),
        idot: sc(read_s(pg(10), &[(52, 1), (61, 13)]), -43),
        ..Decoded::default()
    };
    let alpha: [&[(usize, usize)]; 4] = [
        &[(47, 6), (61, 2)],
        &[(63, 8)],
        &[(71, 8)],
        &[(79, 4), (91, 4)],
    ];
    let beta: [&[(usize, usize)]; 4] =
        [&[(95, 8)], &[(103, 8)], &[(111, 2), (121, 6)], &[(127, 8)]];
    for n in 0..4 {
        d.alpha[n] = p2(ALPHA_EXP[n]) * read_s(pg(2), alpha[n]) as f64;
        d.beta[n] = p2(BETA_EXP[n]) * read_s(pg(2), beta[n]) as f64;
    }
    d
}

/// An almanac page (D1 subframe 4, subframe 5 pages 1-6; D2 subframe 5 pages 37-60,
/// 95-100), angles in semicircles as broadcast.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct DecodedAlmanac {
    pub pnum: u64,
    pub sqrt_a: f64,
    pub a1: f64,
    pub a0: f64,
    pub omega0_sc: f64,
    pub e: f64,
    pub delta_i_sc: f64,
    pub toa_s: f64,
    pub omega_dot_sc: f64,
    pub omega_sc: f64,
    pub m0_sc: f64,
    pub am_ep_id: u64,
}

pub(crate) fn decode_almanac(b: &[u8; 300]) -> DecodedAlmanac {
    DecodedAlmanac {
        pnum: read_u(b, &[(44, 7)]),
        sqrt_a: p2(-11) * read_u(b, &[(51, 2), (61, 22)]) as f64,
        a1: p2(-38) * read_s(b, &[(91, 11)]) as f64,
        a0: p2(-20) * read_s(b, &[(102, 11)]) as f64,
        omega0_sc: p2(-23) * read_s(b, &[(121, 22), (151, 2)]) as f64,
        e: p2(-21) * read_u(b, &[(153, 17)]) as f64,
        delta_i_sc: p2(-19) * read_s(b, &[(170, 3), (181, 13)]) as f64,
        toa_s: p2(12) * read_u(b, &[(194, 8)]) as f64,
        omega_dot_sc: p2(-38) * read_s(b, &[(202, 1), (211, 16)]) as f64,
        omega_sc: p2(-23) * read_s(b, &[(227, 6), (241, 18)]) as f64,
        m0_sc: p2(-23) * read_s(b, &[(259, 4), (271, 20)]) as f64,
        am_ep_id: read_u(b, &[(291, 2)]),
    }
}

/// ICD position of the information bit `k` (0-based, counting information bits only).
fn info_position(k: usize) -> usize {
    if k < 26 {
        k + 1
    } else {
        31 + ((k - 26) / 22) * 30 + (k - 26) % 22
    }
}

/// `n` consecutive information bits starting at information bit `k`.
fn info_field(k: usize, n: usize) -> Vec<(usize, usize)> {
    (k..k + n).map(|i| (info_position(i), 1)).collect()
}

/// Health words of a first (PRNs 1-19) or second (PRNs 20-30) health page, and for the
/// second page (WNa, toa in s).
pub(crate) fn decode_health(b: &[u8; 300], first: bool) -> (Vec<u64>, Option<(u64, f64)>) {
    let n = if first { 19 } else { 11 };
    let hea = (0..n)
        .map(|i| read_u(b, &info_field(46 + 9 * i, 9)))
        .collect();
    let extra = (!first).then(|| {
        let k = 46 + 9 * n;
        (
            read_u(b, &info_field(k, 8)),
            p2(12) * read_u(b, &info_field(k + 8, 8)) as f64,
        )
    });
    (hea, extra)
}

/// UTC page: (Delta t_LS, Delta t_LSF, WN_LSF, A0UTC, A1UTC, DN).
pub(crate) fn decode_utc(b: &[u8; 300]) -> (i64, i64, u64, f64, f64, u64) {
    (
        read_s(b, &[(51, 2), (61, 6)]),
        read_s(b, &[(67, 8)]),
        read_u(b, &[(75, 8)]),
        p2(-30) * read_s(b, &[(91, 22), (121, 10)]) as f64,
        p2(-50) * read_s(b, &[(131, 12), (151, 12)]) as f64,
        read_u(b, &[(163, 8)]),
    )
}
