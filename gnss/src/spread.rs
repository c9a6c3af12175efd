//! Code spreading in 32.32 fixed point: sample `i` of a block carries chip
//! `(x0 + i d) >> 32` counted from the block's first chip, with the first sample's code
//! phase `x0` (its fraction of a chip) and the step `d` (chips per sample). The
//! resolution is 2^-32 chip; over a 20 000-sample block the step's rounding adds up to
//! below 2^-33 x 20 000 = 2.4e-6 chip.
//!
//! With AVX-512, 16 samples at a time: whenever a sample advances the code by at most
//! one chip, the 16 samples' chips lie within a window of 16 chips from the first one's,
//! and one permutation of the window's values spreads them ([`v4::Window`]: no
//! chip-by-chip loop, no gather). The synthesiser's mixer and the receiver's correlators
//! both spread this way.

/// Samples per step of the vector path.
pub const LANES: usize = 16;

/// `2^32`, the fixed-point scale.
const SCALE: f64 = 4_294_967_296.0;

/// A block's code phase in fixed point.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct CodePhase {
    /// Phase of the first sample (chips from the block's first chip, 32.32).
    pub x0: u64,
    /// Phase step per sample (chips, 32.32).
    pub d: u64,
}

impl CodePhase {
    /// From the first sample's phase within its chip (in [0, 1); clamped) and the step
    /// per sample (chips; negative taken as 0); `None` when `n` samples' phases do not fit
    /// the fixed point.
    pub fn new(chip_fraction: f64, chips_per_sample: f64, n: usize) -> Option<Self> {
        let x0 = (chip_fraction.clamp(0.0, 1.0) * SCALE).floor();
        let d = (chips_per_sample.max(0.0) * SCALE).round();
        let last = x0 + d * n as f64;
        (last < 2f64.powi(62)).then_some(Self {
            x0: x0 as u64,
            d: d as u64,
        })
    }

    /// The chip under sample `i`, counted from the block's first chip.
    #[inline(always)]
    pub fn chip(self, i: usize) -> u64 {
        (self.x0 + i as u64 * self.d) >> 32
    }

    /// Whether the vector path applies: at most one chip per sample.
    pub fn windowed(self) -> bool {
        self.d <= 1 << 32
    }
}

#[cfg(target_arch = "x86_64")]
pub mod v4 {
    //! The AVX-512 window permutation.
    use super::LANES;
    use core::arch::x86_64::{__m512, __m512i};
    use pulp::cast;
    use pulp::x86::V4;

    /// Dword indices of the low halves of two vectors of 8 qwords (`permutex2var`).
    const LOW_DWORDS: [u32; LANES] = [0, 2, 4, 6, 8, 10, 12, 14, 16, 18, 20, 22, 24, 26, 28, 30];

    /// The lanes' phase offsets `l d` for one step `d` (32.32 chips per sample).
    #[derive(Debug, Clone, Copy)]
    pub struct Window {
        lo: __m512i,
        hi: __m512i,
        pick: __m512i,
    }

    impl Window {
        /// For a step of `d <= 2^32` ([`super::CodePhase::windowed`]).
        #[inline(always)]
        pub fn new(d: u64) -> Self {
            Self {
                lo: cast(core::array::from_fn::<u64, 8, _>(|l| l as u64 * d)),
                hi: cast(core::array::from_fn::<u64, 8, _>(|l| (l + 8) as u64 * d)),
                pick: cast(LOW_DWORDS),
            }
        }

        /// The values under 16 samples whose first lies at `frac` (32.32, below 2^32)
        /// into the window's first chip: lane `l` takes `window[(frac + l d) >> 32]`.
        #[inline(always)]
        pub fn spread(&self, simd: V4, frac: u64, window: __m512) -> __m512 {
            let f = simd.avx512f;
            let frac = f._mm512_set1_epi64(frac as i64);
            let a = f._mm512_srli_epi64::<32>(f._mm512_add_epi64(frac, self.lo));
            let b = f._mm512_srli_epi64::<32>(f._mm512_add_epi64(frac, self.hi));
            let index = f._mm512_permutex2var_epi32(a, self.pick, b);
            f._mm512_permutexvar_ps(index, window)
        }
    }
}
