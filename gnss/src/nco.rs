//! Numerically controlled oscillator start values shared by every carrier loop over
//! samples (the synthesiser's mixer, the receiver's correlators).

/// A carrier phasor in `N` interleaved lanes: lane `l` starts at phase `p0 + l dp` (cycles),
/// and one step of all lanes turns each by `N dp`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LanePhasors<const N: usize> {
    /// cos and sin of each lane's start phase.
    pub re: [f32; N],
    pub im: [f32; N],
    /// cos and sin of the step `N dp`.
    pub step_re: f32,
    pub step_im: f32,
}

impl<const N: usize> LanePhasors<N> {
    /// Start phase `phase_cycles` (only its fraction matters), increment
    /// `cycles_per_sample`. The lane values come from two `sin_cos` calls and f64 phasor
    /// products (rounding ~1e-15 rad after `N` steps).
    pub fn new(phase_cycles: f64, cycles_per_sample: f64) -> Self {
        let frac = phase_cycles - phase_cycles.floor();
        let (mut s, mut c) = (std::f64::consts::TAU * frac).sin_cos();
        let (s1, c1) = (std::f64::consts::TAU * cycles_per_sample).sin_cos();
        let mut re = [0f32; N];
        let mut im = [0f32; N];
        for l in 0..N {
            re[l] = c as f32;
            im[l] = s as f32;
            (c, s) = (c * c1 - s * s1, c * s1 + s * c1);
        }
        let (ws, wc) = (std::f64::consts::TAU * N as f64 * cycles_per_sample).sin_cos();
        Self {
            re,
            im,
            step_re: wc as f32,
            step_im: ws as f32,
        }
    }
}

/// One step of every lane of a [`LanePhasors`] recurrence: each turned by the step
/// `w = step_re + j step_im`, in `f32`, the same operations wherever it is called.
#[inline(always)]
pub fn turn<const N: usize>(
    re: &[f32; N],
    im: &[f32; N],
    step_re: f32,
    step_im: f32,
) -> ([f32; N], [f32; N]) {
    let (mut nr, mut ni) = ([0f32; N], [0f32; N]);
    for l in 0..N {
        nr[l] = re[l] * step_re - im[l] * step_im;
        ni[l] = re[l] * step_im + im[l] * step_re;
    }
    (nr, ni)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lanes_follow_the_phase_ramp() {
        let (p0, dp) = (7.3, 0.0123);
        let z = LanePhasors::<16>::new(p0, dp);
        for l in 0..16 {
            let phase = std::f64::consts::TAU * (p0 + l as f64 * dp);
            assert!((f64::from(z.re[l]) - phase.cos()).abs() < 1e-6);
            assert!((f64::from(z.im[l]) - phase.sin()).abs() < 1e-6);
        }
        let step = std::f64::consts::TAU * 16.0 * dp;
        assert!((f64::from(z.step_re) - step.cos()).abs() < 1e-6);
        assert!((f64::from(z.step_im) - step.sin()).abs() < 1e-6);
    }
}
