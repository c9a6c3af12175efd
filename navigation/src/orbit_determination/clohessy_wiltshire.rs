//! Relative motion about a circular reference orbit (Clohessy-Wiltshire / Hill): the
//! transition matrix and the input matrix of book eq. 5-34, which the book references but
//! never prints.
//!
//! Axes are the book's target orbit frame (eq. 5-53): x along-track forward, y along the
//! negative orbit normal, z towards the Earth's centre (the frame rotates at
//! `[0, -n, 0]`). Book eq. 5-53: `x'' - 2n z' = f_x`, `y'' + n^2 y = f_y`,
//! `z'' - 3n^2 z + 2n x' = f_z`. The state is `[x, y, z, x', y', z']`.

use nalgebra::{Matrix6, Matrix6x3};

/// `Phi(t, 0)` of book eq. 5-34 for mean motion `n_rad_s` (the standard solution of eq.
/// 5-53 without input, checked against the equations by substitution in the tests).
pub fn transition(n_rad_s: f64, t_s: f64) -> Matrix6<f64> {
    let n = n_rad_s;
    let (s, c) = (n * t_s).sin_cos();
    let nt = n * t_s;
    #[rustfmt::skip]
    let phi = Matrix6::new(
        // x
        1.0, 0.0, -6.0 * (s - nt), (4.0 * s - 3.0 * nt) / n, 0.0, 2.0 * (1.0 - c) / n,
        // y
        0.0, c, 0.0, 0.0, s / n, 0.0,
        // z
        0.0, 0.0, 4.0 - 3.0 * c, -2.0 * (1.0 - c) / n, 0.0, s / n,
        // x'
        0.0, 0.0, 6.0 * n * (1.0 - c), 4.0 * c - 3.0, 0.0, 2.0 * s,
        // y'
        0.0, -n * s, 0.0, 0.0, c, 0.0,
        // z'
        0.0, 0.0, 3.0 * n * s, -2.0 * s, 0.0, c,
    );
    phi
}

/// Gauss-Legendre nodes and weights on [-1, 1], eight points (exact for polynomials of
/// degree 15; `Phi`'s entries are sines and cosines of `n t`, a fraction of a radian over
/// a filter step).
const GAUSS8: [(f64, f64); 8] = [
    (-0.960_289_856_497_536_2, 0.101_228_536_290_376_26),
    (-0.796_666_477_413_626_7, 0.222_381_034_453_374_47),
    (-0.525_532_409_916_329, 0.313_706_645_877_887_3),
    (-0.183_434_642_495_649_8, 0.362_683_783_378_362),
    (0.183_434_642_495_649_8, 0.362_683_783_378_362),
    (0.525_532_409_916_329, 0.313_706_645_877_887_3),
    (0.796_666_477_413_626_7, 0.222_381_034_453_374_47),
    (0.960_289_856_497_536_2, 0.101_228_536_290_376_26),
];

/// `Gamma(t, 0)` of book eq. 5-34: the state at `t` from a constant acceleration `U`
/// (book eq. 5-39) applied from 0, `integral_0^t Phi(t - tau) [0; I] dtau`.
pub fn input(n_rad_s: f64, t_s: f64) -> Matrix6x3<f64> {
    let mut b = Matrix6x3::zeros();
    b.fixed_view_mut::<3, 3>(3, 0).fill_with_identity();
    let half = 0.5 * t_s;
    GAUSS8
        .iter()
        .map(|&(x, w)| transition(n_rad_s, half - half * x) * b * (w * half))
        .fold(Matrix6x3::zeros(), |sum, term| sum + term)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The right-hand side of book eq. 5-53 for state `s` and input `f`.
    fn rates(
        n: f64,
        s: &nalgebra::Vector6<f64>,
        f: &nalgebra::Vector3<f64>,
    ) -> nalgebra::Vector6<f64> {
        nalgebra::Vector6::new(
            s[3],
            s[4],
            s[5],
            2.0 * n * s[5] + f[0],
            -n * n * s[1] + f[1],
            3.0 * n * n * s[2] - 2.0 * n * s[3] + f[2],
        )
    }

    #[test]
    fn the_transition_solves_the_hill_equations_and_composes() {
        let n = 0.001_03;
        let s0 = nalgebra::Vector6::new(10.0, -4.0, 3.0, 0.2, -0.1, 0.05);
        let zero = nalgebra::Vector3::zeros();
        for t in [0.0, 30.0, 600.0, 3000.0] {
            assert!(
                (transition(n, t) * transition(n, 200.0) - transition(n, t + 200.0)).norm() < 1e-9
            );
            let h = 1e-3;
            let d = (transition(n, t + h) * s0 - transition(n, t - h) * s0) / (2.0 * h);
            let expected = rates(n, &(transition(n, t) * s0), &zero);
            assert!(
                (d - expected).norm() < 1e-7,
                "t = {t}: {}",
                (d - expected).norm()
            );
        }
        assert_eq!(transition(n, 0.0), Matrix6::identity());
    }

    /// The input matrix against a fine fourth-order Runge-Kutta integration of eq. 5-53
    /// with the constant input.
    #[test]
    fn the_input_matrix_matches_an_integration_of_the_equations() {
        let n = 0.001_03;
        let f = nalgebra::Vector3::new(2e-5, -1e-5, 3e-5);
        let t = 60.0;
        let mut s = nalgebra::Vector6::zeros();
        let steps = 600;
        let h = t / f64::from(steps);
        for _ in 0..steps {
            let k1 = rates(n, &s, &f);
            let k2 = rates(n, &(s + k1 * (h / 2.0)), &f);
            let k3 = rates(n, &(s + k2 * (h / 2.0)), &f);
            let k4 = rates(n, &(s + k3 * h), &f);
            s += (k1 + k2 * 2.0 + k3 * 2.0 + k4) * (h / 6.0);
        }
        let g = input(n, t) * f;
        assert!((g - s).norm() < 1e-10 * (1.0 + s.norm()), "{g} vs {s}");
        assert!(s.norm() > 1e-3);
    }
}
