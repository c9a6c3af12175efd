//! The orbital frame of thesis section 2.5.1: Xo along the flight direction, Zo towards
//! the Earth centre, Yo completing the right-handed triad.
//!
//! Thesis section 2.5.1, item (3) and eq. 2.5-2: with the ECI position `r` and velocity
//! `v` of the satellite, the unit axes are
//! `z = -r/|r|`, `y = (v x r)/|v x r|`, `x = y x z`, and `R_oi = [x y z]^T` maps ECI to
//! orbital components. Xo is thus perpendicular to `r` in the orbit plane, on the side of
//! the velocity (exactly along `v` for a circular orbit), and Yo is along the negative
//! orbit normal (`Yo = Zo x Xo`).

use crate::{Mat3, Vec3};

/// `c_orbital_eci` (columns are Xo, Yo, Zo in ECI) from an ECI position and velocity.
///
/// This is the transpose of the thesis' `R_oi` (eq. 2.5-2): it maps orbital components
/// to ECI components. `r` and `v` must not be parallel.
pub fn c_orbital_eci(r_eci_m: &Vec3, v_eci_mps: &Vec3) -> Mat3 {
    let z = -r_eci_m.normalize();
    let y = v_eci_mps.cross(r_eci_m).normalize();
    let x = y.cross(&z);
    Mat3::from_columns(&[x, y, z])
}

/// `c_rac_eci` (columns are the radial, along-track and cross-track unit vectors in the
/// frame of `r` and `v`): radial `r/|r|`, cross-track along the orbit normal `r x v`,
/// along-track completing the triad (the flight direction for a circular orbit). The
/// axes the signal-in-space error literature uses (radial, along, cross); in the thesis's
/// orbital frame they are -Zo, Xo and -Yo.
pub fn c_rac_eci(r_m: &Vec3, v_mps: &Vec3) -> Mat3 {
    let c = c_orbital_eci(r_m, v_mps);
    Mat3::from_columns(&[-c.column(2), c.column(0).into_owned(), -c.column(1)])
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    #[test]
    fn circular_equatorial_orbit() {
        // Prograde equatorial orbit at (R, 0, 0) moving along +Y: Xo = +Y (flight
        // direction), Zo = -X (to the Earth centre), Yo = -Z (negative orbit normal).
        let c = c_orbital_eci(&Vec3::new(7e6, 0.0, 0.0), &Vec3::new(0.0, 7.5e3, 0.0));
        assert_eq!(c.column(0).into_owned(), Vec3::new(0.0, 1.0, 0.0));
        assert_eq!(c.column(1).into_owned(), Vec3::new(0.0, 0.0, -1.0));
        assert_eq!(c.column(2).into_owned(), Vec3::new(-1.0, 0.0, 0.0));
    }

    #[test]
    fn zo_points_to_the_earth_centre_and_xo_leads() {
        // Eccentric orbit: Xo is perpendicular to r and has a positive component along v.
        let r = Vec3::new(5e6, 4e6, 2e6);
        let v = Vec3::new(-3e3, 5e3, 4e3);
        let c = c_orbital_eci(&r, &v);
        let (x, z) = (c.column(0).into_owned(), c.column(2).into_owned());
        assert!((z + r.normalize()).norm() < 1e-15);
        assert!(x.dot(&r).abs() < 1e-9 && x.dot(&v) > 0.0);
        // The orbital components of v have no Yo part (v lies in the orbit plane).
        assert!((c.transpose() * v).y.abs() < 1e-9);
    }

    #[test]
    fn rac_axes_are_radial_flight_and_normal() {
        let c = c_rac_eci(&Vec3::new(7e6, 0.0, 0.0), &Vec3::new(0.0, 7.5e3, 0.0));
        assert_eq!(c.column(0).into_owned(), Vec3::new(1.0, 0.0, 0.0));
        assert_eq!(c.column(1).into_owned(), Vec3::new(0.0, 1.0, 0.0));
        assert_eq!(c.column(2).into_owned(), Vec3::new(0.0, 0.0, 1.0));
        assert!((c.determinant() - 1.0).abs() < 1e-15);
    }

    proptest! {
        #[test]
        fn c_orbital_eci_is_a_rotation(
            x in -1e7f64..1e7, y in -1e7f64..1e7, z in -1e7f64..1e7,
            vx in -8e3f64..8e3, vy in -8e3f64..8e3, vz in -8e3f64..8e3,
        ) {
            let (r, v) = (Vec3::new(x, y, z), Vec3::new(vx, vy, vz));
            prop_assume!(r.norm() > 1e5 && v.norm() > 1.0 && r.normalize().cross(&v.normalize()).norm() > 1e-3);
            let c = c_orbital_eci(&r, &v);
            prop_assert!((c.transpose() * c - Mat3::identity()).norm() < 1e-14);
            prop_assert!((c.determinant() - 1.0).abs() < 1e-14);
        }
    }
}
