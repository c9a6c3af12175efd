//! Sub-carriers: the square waves that split a binary-offset-carrier signal's spectrum,
//! and Galileo E1's composite CBOC(6,1,1/11) waveform (Galileo OS SIS ICD §2.3.3, the E1
//! signal's components and their sum).
//!
//! A sub-carrier is `sc(t) = sgn(sin(2 pi R_sc t))`, counted from the chip's leading edge.
//! Over one E1 chip (1/1.023 MHz) the BOC(1,1) sub-carrier (R_sc = 1.023 MHz) is + then -,
//! and the BOC(6,1) one (6.138 MHz) changes sign every twelfth of the chip, so both are
//! constant on [`CBOC_SUBCHIPS`] sub-chips of 1/12 chip. E1 is
//! `s(t) = (1/sqrt 2) [e_B(t) (alpha sc_a + beta sc_b) - e_C(t) (alpha sc_a - beta sc_b)]`,
//! alpha = sqrt(10/11), beta = sqrt(1/11): the data component E1-B and the pilot E1-C in
//! phase, each with half the power.
//!
//! BeiDou B1C (BDS-SIS-ICD-B1C-1.0 §4.2.2) is `s = s_data + j s_pilot` with
//! `s_data = (1/2) D C_d sc_a` and `s_pilot = (sqrt 3 / 2) C_p (sqrt(29/33) sc_a - j
//! sqrt(4/33) sc_b)`, `sc_a` BOC(1,1) and `sc_b` BOC(6,1): the data in phase with 1/4 of
//! the power, the pilot's BOC(1,1) part in quadrature (+j) with 29/44, and its BOC(6,1)
//! part, turned by `j (-j) = +1`, in phase with the data with 1/11 ([`b1c_qmboc`]).

/// Sub-chips per chip on which BOC(1,1) and BOC(6,1) are both constant.
pub const CBOC_SUBCHIPS: usize = 12;

/// The weight of the BOC(1,1) sub-carrier, sqrt(10/11).
const ALPHA: f64 = 0.953_462_589_245_592_4;
/// The weight of the BOC(6,1) sub-carrier, sqrt(1/11).
const BETA: f64 = 0.301_511_344_577_763_6;

/// The BOC(1,1) sub-carrier on sub-chip `k` (0..12) of a chip: +1 on the first half.
pub const fn boc11(k: usize) -> i8 {
    if k % CBOC_SUBCHIPS < CBOC_SUBCHIPS / 2 {
        1
    } else {
        -1
    }
}

/// The BOC(6,1) sub-carrier on sub-chip `k` (0..12): +1 on even sub-chips.
pub const fn boc61(k: usize) -> i8 {
    if k.is_multiple_of(2) { 1 } else { -1 }
}

/// The E1 CBOC waveform over one chip, sub-chip by sub-chip, for a data chip `data` (E1-B
/// code chip times the I/NAV symbol) and a pilot chip `pilot` (E1-C code chip times its
/// secondary chip), each +1 or -1: unit mean power over data and pilot.
pub fn e1_cboc(data: i8, pilot: i8) -> [f32; CBOC_SUBCHIPS] {
    let (d, p) = (f64::from(data), f64::from(pilot));
    std::array::from_fn(|k| {
        let (a, b) = (f64::from(boc11(k)), f64::from(boc61(k)));
        (std::f64::consts::FRAC_1_SQRT_2
            * (d * (ALPHA * a + BETA * b) - p * (ALPHA * a - BETA * b))) as f32
    })
}

/// B1C's data amplitude, 1/2 (1/4 of the power).
const B1C_DATA: f64 = 0.5;
/// B1C's pilot BOC(1,1) amplitude, sqrt(3/4 x 29/33) = sqrt(29/44).
const B1C_PILOT_A: f64 = 0.811_844_140_885_988_7;
/// B1C's pilot BOC(6,1) amplitude, sqrt(3/4 x 4/33) = sqrt(1/11).
const B1C_PILOT_B: f64 = BETA;

/// The B1C QMBOC waveform over one chip, sub-chip by sub-chip, as in-phase and quadrature
/// levels, for a data chip `data` (B1C_data code chip times the B-CNAV1 symbol) and a
/// pilot chip `pilot` (B1C_pilot code chip times its secondary chip), each +1 or -1:
/// `I = (1/2) d sc_a + sqrt(1/11) p sc_b`, `Q = sqrt(29/44) p sc_a`, unit power.
pub fn b1c_qmboc(data: i8, pilot: i8) -> ([f32; CBOC_SUBCHIPS], [f32; CBOC_SUBCHIPS]) {
    let (d, p) = (f64::from(data), f64::from(pilot));
    let i = std::array::from_fn(|k| {
        (B1C_DATA * d * f64::from(boc11(k)) + B1C_PILOT_B * p * f64::from(boc61(k))) as f32
    });
    let q = std::array::from_fn(|k| (B1C_PILOT_A * p * f64::from(boc11(k))) as f32);
    (i, q)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_weights_are_the_icds() {
        assert!((ALPHA * ALPHA - 10.0 / 11.0).abs() < 1e-15);
        assert!((BETA * BETA - 1.0 / 11.0).abs() < 1e-15);
        // BDS-SIS-ICD-B1C-1.0 §4.2.2: (sqrt 3 / 2)^2 x 29/33 and x 4/33.
        assert!((B1C_PILOT_A * B1C_PILOT_A - 0.75 * 29.0 / 33.0).abs() < 1e-15);
        assert!((B1C_PILOT_B * B1C_PILOT_B - 0.75 * 4.0 / 33.0).abs() < 1e-15);
    }

    /// B1C's QMBOC from the ICD's complex definition evaluated at each sub-chip's middle:
    /// data 1/4 of the power on I, pilot BOC(1,1) 29/44 on Q, pilot BOC(6,1) 1/11 on I.
    #[test]
    fn b1c_qmboc_is_the_icds_complex_sum() {
        let sgn = |x: f64| if x > 0.0 { 1.0 } else { -1.0 };
        for (d, p) in [(1, 1), (1, -1), (-1, 1), (-1, -1)] {
            let (i, q) = b1c_qmboc(d, p);
            let mut power = 0.0;
            for k in 0..CBOC_SUBCHIPS {
                let t = (k as f64 + 0.5) / CBOC_SUBCHIPS as f64;
                let (a, b) = (
                    sgn((std::f64::consts::TAU * t).sin()),
                    sgn((std::f64::consts::TAU * 6.0 * t).sin()),
                );
                // s_data + j s_pilot, s_pilot = sqrt(3)/2 p (sqrt(29/33) a - j sqrt(4/33) b):
                // re = s_data - Im(s_pilot), im = Re(s_pilot).
                let (dr, pa) = (0.5 * f64::from(d), 0.75f64.sqrt() * f64::from(p));
                let re = dr * a - pa * (-(4.0f64 / 33.0).sqrt() * b);
                let im = pa * (29.0f64 / 33.0).sqrt() * a;
                assert!((f64::from(i[k]) - re).abs() < 1e-6, "I {k}");
                assert!((f64::from(q[k]) - im).abs() < 1e-6, "Q {k}");
                power += re * re + im * im;
            }
            assert!((power / 12.0 - 1.0).abs() < 1e-9, "{power}");
        }
    }

    /// sgn(sin(2 pi R t)) sampled at the middle of each sub-chip, against the tables.
    #[test]
    fn sub_carriers_are_signs_of_sines() {
        for k in 0..CBOC_SUBCHIPS {
            let t_chips = (k as f64 + 0.5) / CBOC_SUBCHIPS as f64;
            let sgn = |cycles_per_chip: f64| {
                if (std::f64::consts::TAU * cycles_per_chip * t_chips).sin() > 0.0 {
                    1
                } else {
                    -1
                }
            };
            assert_eq!(boc11(k), sgn(1.0), "BOC(1,1) sub-chip {k}");
            assert_eq!(boc61(k), sgn(6.0), "BOC(6,1) sub-chip {k}");
        }
    }

    /// The pilot-free data part correlates with the BOC(1,1) replica by alpha / sqrt 2, the
    /// data-free pilot part likewise; averaged over independent data and pilot chips the
    /// power is 1 and data and pilot are orthogonal.
    #[test]
    fn data_and_pilot_share_the_power() {
        let mut power = 0.0;
        for (d, p) in [(1, 1), (1, -1), (-1, 1), (-1, -1)] {
            let w = e1_cboc(d, p);
            power += w.iter().map(|x| f64::from(*x).powi(2)).sum::<f64>() / 12.0 / 4.0;
        }
        assert!((power - 1.0).abs() < 1e-6, "{power}");
        // Data minus its pilot-inverted twin isolates the data part: sqrt 2 (alpha a + beta b).
        let (plus, minus) = (e1_cboc(1, 1), e1_cboc(1, -1));
        let data_part: Vec<f64> = (0..12)
            .map(|k| f64::from(plus[k] + minus[k]) / 2.0)
            .collect();
        let boc: f64 = (0..12)
            .map(|k| data_part[k] * f64::from(boc11(k)))
            .sum::<f64>()
            / 12.0;
        assert!(
            (boc - ALPHA * std::f64::consts::FRAC_1_SQRT_2).abs() < 1e-6,
            "{boc}"
        );
        let pilot_part: Vec<f64> = (0..12)
            .map(|k| f64::from(plus[k] - minus[k]) / 2.0)
            .collect();
        let cross: f64 = (0..12).map(|k| data_part[k] * pilot_part[k]).sum();
        // alpha^2 - beta^2 per sub-chip pair of signs: not zero, so orthogonality comes from
        // the codes, not the waveform; what the waveform gives is this constant.
        let expected = -0.5 * 12.0 * (ALPHA * ALPHA - BETA * BETA);
        assert!((cross - expected).abs() < 1e-5, "{cross}");
    }
}
