//! Carrier-phase, carrier-frequency and code discriminators (Kaplan & Hegarty,
//! "Understanding GPS: Principles and Applications", 2nd ed., section 5.3: Costas and PLL
//! discriminator table, FLL discriminator table, DLL discriminator table).
//!
//! Conventions: a prompt `P = I + jQ` is the correlation of the signal with the conjugate
//! carrier replica, so `arg P` is the signal phase minus the replica phase; a positive
//! phase or frequency error means the replica must advance. Code errors are signal code
//! phase minus prompt replica code phase (chips): positive when the signal is ahead.

use num_complex::Complex;

const TAU: f64 = std::f64::consts::TAU;

/// Carrier-phase discriminator of a PLL.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Deserialize, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum PllDiscriminator {
    /// Costas two-quadrant arctangent `atan(Q / I)`: insensitive to data bit sign, range
    /// +-1/4 cycle.
    #[default]
    Costas,
    /// Four-quadrant arctangent `atan2(Q, I)`: range +-1/2 cycle; only for a data-free
    /// (pilot) or data-wiped prompt.
    FourQuadrant,
}

impl PllDiscriminator {
    /// Phase error (cycles) of a prompt.
    pub fn phase_error_cycles(self, prompt: Complex<f64>) -> f64 {
        match self {
            PllDiscriminator::Costas => costas_cycles(prompt),
            PllDiscriminator::FourQuadrant => four_quadrant_cycles(prompt),
        }
    }
}

/// Costas two-quadrant arctangent discriminator `atan(Q / I) / 2 pi` (cycles, in
/// [-1/4, 1/4]); a prompt on the Q axis gives +-1/4 by the sign of Q.
pub fn costas_cycles(prompt: Complex<f64>) -> f64 {
    if prompt.re == 0.0 {
        return 0.25_f64.copysign(prompt.im) * f64::from(u8::from(prompt.im != 0.0));
    }
    (prompt.im / prompt.re).atan() / TAU
}

/// Four-quadrant arctangent discriminator `atan2(Q, I) / 2 pi` (cycles, in [-1/2, 1/2]).
pub fn four_quadrant_cycles(prompt: Complex<f64>) -> f64 {
    prompt.im.atan2(prompt.re) / TAU
}

/// Carrier-frequency discriminator of an FLL, from two successive prompts `dt_s` apart.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Deserialize, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum FllDiscriminator {
    /// `atan(cross / dot) / (2 pi dt)`: insensitive to a data bit change between the two
    /// prompts, range +-1/(4 dt).
    #[default]
    CrossDot,
    /// `atan2(cross, dot) / (2 pi dt)`: range +-1/(2 dt), only without a data sign change
    /// between the prompts.
    Atan2,
}

impl FllDiscriminator {
    /// Frequency error (Hz) of the signal relative to the replica.
    pub fn frequency_error_hz(
        self,
        previous: Complex<f64>,
        current: Complex<f64>,
        dt_s: f64,
    ) -> f64 {
        let cross = previous.re * current.im - current.re * previous.im;
        let dot = previous.re * current.re + previous.im * current.im;
        let angle = match self {
            FllDiscriminator::CrossDot if dot == 0.0 => {
                TAU / 4.0 * cross.signum() * f64::from(u8::from(cross != 0.0))
            }
            FllDiscriminator::CrossDot => (cross / dot).atan(),
            FllDiscriminator::Atan2 => cross.atan2(dot),
        };
        angle / (TAU * dt_s)
    }
}

/// Normalised non-coherent early-minus-late envelope discriminator (chips):
/// `(1 - d/2) (|E| - |L|) / (|E| + |L|)` for early and late replicas `d` chips apart.
///
/// On the ideal triangular correlation `R(x) = 1 - |x|` it returns the code error exactly
/// while `|error| <= d/2`; the normalisation removes the dependence on signal amplitude.
pub fn dll_envelope_chips(early: Complex<f64>, late: Complex<f64>, spacing_chips: f64) -> f64 {
    let (e, l) = (early.norm(), late.norm());
    if e + l == 0.0 {
        return 0.0;
    }
    (1.0 - spacing_chips / 2.0) * (e - l) / (e + l)
}

/// [`dll_envelope_chips`] for a BOC(1,1) replica, whose correlation main peak is
/// `R(x) = 1 - 3|x|` for `|x| <= 1/2` chip (Betz, "Binary Offset Carrier Modulations for
/// Radionavigation", Navigation 48(4), 2001): `(1/3 - d/2) (|E| - |L|) / (|E| + |L|)`,
/// exact while early and late stay on the main peak's two slopes, `|error| <= d/2` and
/// `|error| + d/2 <= 1/3`.
pub fn dll_envelope_boc11_chips(
    early: Complex<f64>,
    late: Complex<f64>,
    spacing_chips: f64,
) -> f64 {
    let (e, l) = (early.norm(), late.norm());
    if e + l == 0.0 {
        return 0.0;
    }
    (1.0 / 3.0 - spacing_chips / 2.0) * (e - l) / (e + l)
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn phasor(amplitude: f64, cycles: f64) -> Complex<f64> {
        Complex::from_polar(amplitude, TAU * cycles)
    }

    proptest! {
        #[test]
        fn costas_returns_the_phase_modulo_half_a_cycle(
            a in 0.1f64..1e4, phi in -0.2499f64..0.2499, flip in proptest::bool::ANY
        ) {
            let sign = if flip { -1.0 } else { 1.0 };
            let p = phasor(a * sign, phi);
            prop_assert!((costas_cycles(p) - phi).abs() < 1e-9);
            prop_assert!((PllDiscriminator::Costas.phase_error_cycles(p) - phi).abs() < 1e-9);
        }

        #[test]
        fn four_quadrant_returns_the_phase(a in 0.1f64..1e4, phi in -0.4999f64..0.4999) {
            let p = phasor(a, phi);
            prop_assert!((PllDiscriminator::FourQuadrant.phase_error_cycles(p) - phi).abs() < 1e-9);
        }

        #[test]
        fn fll_measures_the_rotation_between_prompts(
            a in 0.1f64..1e4, phi0 in -0.5f64..0.5, f in -240.0f64..240.0, flip in proptest::bool::ANY
        ) {
            let dt = 1e-3;
            let prev = phasor(a, phi0);
            let cur = phasor(a, phi0 + f * dt);
            prop_assert!((FllDiscriminator::Atan2.frequency_error_hz(prev, cur, dt) - f).abs() < 1e-6);
            // A data sign change between the prompts does not matter to cross-dot.
            let cur = if flip { -cur } else { cur };
            prop_assert!((FllDiscriminator::CrossDot.frequency_error_hz(prev, cur, dt) - f).abs() < 1e-6);
        }

        #[test]
        fn dll_is_exact_on_the_triangle(err in -0.25f64..0.25, d in 0.5f64..1.0, a in 0.1f64..1e3) {
            // Early replica at +d/2: R(d/2 - err); late at -d/2: R(-d/2 - err).
            let r = |x: f64| (1.0 - x.abs()).max(0.0);
            let e = phasor(a * r(d / 2.0 - err), 0.3);
            let l = phasor(a * r(-d / 2.0 - err), 0.3);
            prop_assert!((dll_envelope_chips(e, l, d) - err).abs() < 1e-9);
        }

        #[test]
        fn boc11_dll_is_exact_on_its_main_peak(err in -0.15f64..0.15, d in 0.05f64..0.6, a in 0.1f64..1e3) {
            prop_assume!(err.abs() <= d / 2.0 && err.abs() + d / 2.0 <= 1.0 / 3.0);
            let r = |x: f64| 1.0 - 3.0 * x.abs();
            let e = phasor(a * r(d / 2.0 - err), 0.3);
            let l = phasor(a * r(-d / 2.0 - err), 0.3);
            prop_assert!((dll_envelope_boc11_chips(e, l, d) - err).abs() < 1e-9);
        }
    }

    #[test]
    fn degenerate_inputs_stay_finite() {
        let z = Complex::new(0.0, 0.0);
        assert_eq!(costas_cycles(z), 0.0);
        assert_eq!(costas_cycles(Complex::new(0.0, 2.0)), 0.25);
        assert_eq!(costas_cycles(Complex::new(0.0, -2.0)), -0.25);
        assert_eq!(dll_envelope_chips(z, z, 1.0), 0.0);
        let f = FllDiscriminator::CrossDot.frequency_error_hz(
            Complex::new(1.0, 0.0),
            Complex::new(0.0, 1.0),
            1e-3,
        );
        assert!((f - 250.0).abs() < 1e-9);
    }
}
