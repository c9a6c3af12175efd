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

/// A chaser's position and velocity relative to a target, in the target's orbit frame
/// (the book's TOF: x along-track, y the negative orbit normal, z nadir; Yuan 2000 eqs.
/// 5-54 and 5-55, whose matrix `M` is `c_orbital_eci^T` of the target's state), from
/// both ECI states: `rho = M (r - r_t)` and its rate seen in the rotating frame,
/// `rho' = M (v - v_t) - w x rho` with `w = (r_t x v_t) / |r_t|^2` the frame's angular
/// velocity (the Hill equations' state, eq. 5-53).
pub fn relative_in_target_frame(
    target_r_eci_m: &Vec3,
    target_v_eci_mps: &Vec3,
    r_eci_m: &Vec3,
    v_eci_mps: &Vec3,
) -> (Vec3, Vec3) {
    relative_in_frame_of(
        target_r_eci_m,
        target_v_eci_mps,
        &(r_eci_m - target_r_eci_m),
        &(v_eci_mps - target_v_eci_mps),
    )
}

/// [`relative_in_target_frame`] of the ECI differences `dr`, `dv` (chaser less target),
/// the frame from the target state `frame_r`, `frame_v` (which need not be the one the
/// differences were taken from: a navigation filter's target state orients the frame
/// better than one noisy fix).
pub fn relative_in_frame_of(
    frame_r_eci_m: &Vec3,
    frame_v_eci_mps: &Vec3,
    dr_eci_m: &Vec3,
    dv_eci_mps: &Vec3,
) -> (Vec3, Vec3) {
    let m = c_orbital_eci(frame_r_eci_m, frame_v_eci_mps).transpose();
    let rho = m * dr_eci_m;
    let w_eci = frame_r_eci_m.cross(frame_v_eci_mps) / frame_r_eci_m.norm_squared();
    let rho_dot = m * dv_eci_mps - (m * w_eci).cross(&rho);
    (rho, rho_dot)
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// Two satellites on one circular orbit, the chaser 1 km behind: the relative state is
    /// 1 km along -x and at rest in the rotating frame (to first order in 1 km / r; the
    /// chord's radial part is (1 km)^2 / 2r, 0.07 m at 7000 km).
    #[test]
    fn a_trailing_satellite_on_the_same_circle_is_behind_and_at_rest() {
        let (r, mu) = (7.0e6_f64, 3.986_004_418e14_f64);
        let v = (mu / r).sqrt();
        let n = v / r;
        let at = |u: f64| {
            (
                Vec3::new(r * u.cos(), r * u.sin(), 0.0),
                Vec3::new(-v * u.sin(), v * u.cos(), 0.0),
            )
        };
        let (rt, vt) = at(0.3);
        let (rc, vc) = at(0.3 - 1000.0 / r);
        let (rho, rho_dot) = relative_in_target_frame(&rt, &vt, &rc, &vc);
        assert!((rho.x + 1000.0).abs() < 1e-3, "{rho:?}");
        assert!(rho.y.abs() < 1e-9);
        assert!(
            (rho.z - 1000.0 * 1000.0 / (2.0 * r)).abs() < 1e-3,
            "{rho:?}"
        );
        assert!(rho_dot.norm() < 1e-9 * v + n * 1e-3, "{rho_dot:?}");
        // A radial offset upwards is -z (z is nadir); a cross-track offset along the
        // orbit normal is -y.
        let (rho, _) = relative_in_target_frame(&rt, &vt, &(rt * 1.0001), &(vt * 1.0001));
        assert!((rho.z + 700.0).abs() < 1e-6, "{rho:?}");
        let normal = rt.cross(&vt).normalize();
        let (rho, _) = relative_in_target_frame(&rt, &vt, &(rt + normal * 50.0), &vt);
        assert!((rho.y + 50.0).abs() < 1e-9, "{rho:?}");
    }

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
