//! The hand geometry the RAIM unit tests share: unit vectors to six satellites in NED,
//! one clock, and the solver's elevation-dependent sigmas.

use nalgebra::{DMatrix, DVector};

/// Design matrix (NED line-of-sight columns, then the clock) and weights of six
/// satellites (az, el in degrees). Satellite 0 near the zenith has the least redundancy
/// (S_00 = 0.23), satellite 3 at 15 deg the most (0.44).
pub(crate) fn six_satellites() -> (DMatrix<f64>, DVector<f64>) {
    let sats = [
        (0.0, 80.0),
        (40.0, 25.0),
        (110.0, 40.0),
        (190.0, 15.0),
        (250.0, 55.0),
        (320.0, 30.0),
    ];
    let mut h = DMatrix::zeros(sats.len(), 4);
    let mut w = DVector::zeros(sats.len());
    for (i, (az, el)) in sats.iter().enumerate() {
        let (az, el) = (f64::to_radians(*az), f64::to_radians(*el));
        let los = [el.cos() * az.cos(), el.cos() * az.sin(), -el.sin()];
        for k in 0..3 {
            h[(i, k)] = -los[k];
        }
        h[(i, 3)] = 1.0;
        w[i] = 0.3f64.hypot(0.3 / el.sin()).powi(-2);
    }
    (h, w)
}
