//! Putting toe and toc on the message's 8 s grid (their scale factor is 2^3 s,
//! BDS-SIS-ICD-B1I-3.0 §5.2.4) without changing the orbit or the clock the signal follows.
//!
//! A set whose toe is not a multiple of 8 s (e.g. the embedded nominal constellation,
//! built at the scenario start) is re-expressed at the nearest multiple, toe' = toe + d,
//! |d| <= 4 s:
//! - clock: the polynomial is re-centred on toc': a0' = a0 + a1 d + a2 d^2,
//!   a1' = a1 + 2 a2 d (exact);
//! - MEO/IGSO (standard algorithm): `BroadcastEphemeris::reexpressed` (M0, i0 and Omega0
//!   moved with the time; exact for any set);
//! - GEO: the computation frame is tied to the Earth at toe (r_ECEF = Rz(-OMEGA_E tk)
//!   Rx(5 deg) r_GEO), so moving toe rotates that frame by
//!   Q = Rx(-5 deg) Rz(-OMEGA_E d) Rx(5 deg); the orbit's orientation is rotated by Q and
//!   read back as (Omega, i, omega). This is exact when the orbit plane is fixed in the
//!   GEO frame and the corrections vanish (Cuc = Cus = Crc = Crs = Cic = Cis = IDOT =
//!   Omega_dot = 0, true of the embedded GEO satellites); any other GEO set off the grid is
//!   refused with [`BdsNavError::ToeOffGrid`].

use super::BdsNavError;
use super::quant::wrap_pi;
use hifitime::Epoch;
use nalgebra::Matrix3;
use skyforge_orbits::constants::{GM_BDS, OMEGA_E_BDS};
use skyforge_orbits::ephemeris::{BroadcastEphemeris, System};
use skyforge_orbits::time::bdt_week_sow;

/// Tilt of the GEO computation frame (BDS-SIS-ICD-B1I-3.0 §5.2.4, GEO user algorithm): in active rotations,
/// r_ECEF = Rz(-OMEGA_E tk) Rx(+5 deg) r_GEO.
pub(super) const GEO_TILT_RAD: f64 = 5.0 * std::f64::consts::PI / 180.0;
/// Spacing of the toe/toc grid (s).
const GRID_S: f64 = 8.0;
/// Below this sin(i) the node is undefined and the orbit is taken as equatorial.
const EQUATORIAL_SIN_I: f64 = 1e-12;

/// Active rotation about X by `a` (rad).
pub(super) fn rot_x(a: f64) -> Matrix3<f64> {
    let (s, c) = a.sin_cos();
    Matrix3::new(1.0, 0.0, 0.0, 0.0, c, -s, 0.0, s, c)
}

/// Active rotation about Z by `a` (rad).
pub(super) fn rot_z(a: f64) -> Matrix3<f64> {
    let (s, c) = a.sin_cos();
    Matrix3::new(c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0)
}

/// Orientation of an orbit (perifocal to reference frame): Rz(node) Rx(incl) Rz(argp),
/// the rotation the user algorithm applies (IS-GPS-200 table 20-IV, BDS-SIS-ICD-B1I-3.0 §5.2.4).
pub(super) fn orientation(node: f64, incl: f64, argp: f64) -> Matrix3<f64> {
    rot_z(node) * rot_x(incl) * rot_z(argp)
}

/// (node, inclination, argument of perigee) of an orientation matrix (inverse of
/// [`orientation`]); an equatorial orbit gets node 0.
pub(super) fn euler_313(m: &Matrix3<f64>) -> (f64, f64, f64) {
    let sin_i = m[(0, 2)].hypot(m[(1, 2)]);
    let incl = sin_i.atan2(m[(2, 2)]);
    if sin_i < EQUATORIAL_SIN_I {
        (0.0, incl, m[(1, 0)].atan2(m[(0, 0)]))
    } else {
        (
            m[(0, 2)].atan2(-m[(1, 2)]),
            incl,
            m[(2, 0)].atan2(m[(2, 1)]),
        )
    }
}

/// The nearest multiple of 8 s of BDT seconds of week, and the shift to it (s).
fn to_grid(t: Epoch) -> (Epoch, f64) {
    let grid = System::Beidou.on_grid(t, GRID_S);
    (grid, (grid - t).to_seconds())
}

/// `eph` with toe and toc moved to the 8 s grid, describing the same orbit and clock (see
/// the module notes for what is exact).
pub(super) fn onto_grid(eph: &BroadcastEphemeris) -> Result<BroadcastEphemeris, BdsNavError> {
    let (toc, _) = to_grid(eph.toc);
    let (toe, d) = to_grid(eph.toe);
    if let Some(moved) = eph.reexpressed(toe, toc) {
        return Ok(moved);
    }
    // GEO: the clock as for every set, then the orbit's orientation rotated with the frame.
    let mut out = eph.reexpressed_clock(toc);
    if d == 0.0 {
        return Ok(out);
    }
    out.toe = toe;
    let n_rad_s = eph.orbit.mean_motion_rad_s(GM_BDS);
    out.orbit.m0 = wrap_pi(eph.orbit.m0 + n_rad_s * d);
    let toe_sow = bdt_week_sow(eph.toe).1;
    let new_toe_sow = bdt_week_sow(toe).1;
    let corrections = [
        eph.harmonics.cuc,
        eph.harmonics.cus,
        eph.harmonics.crc,
        eph.harmonics.crs,
        eph.harmonics.cic,
        eph.harmonics.cis,
        eph.orbit.idot,
        eph.orbit.omega_dot,
    ];
    if corrections.iter().any(|&c| c != 0.0) {
        return Err(BdsNavError::ToeOffGrid {
            sat: eph.sat.to_string(),
            toe_sow,
        });
    }
    let r_geo = orientation(
        eph.orbit.omega0 - OMEGA_E_BDS * toe_sow,
        eph.orbit.i0,
        eph.orbit.omega,
    );
    let q = rot_x(-GEO_TILT_RAD) * rot_z(-OMEGA_E_BDS * d) * rot_x(GEO_TILT_RAD);
    let (node, incl, argp) = euler_313(&(q * r_geo));
    out.orbit.omega0 = wrap_pi(node + OMEGA_E_BDS * new_toe_sow);
    out.orbit.i0 = incl;
    out.orbit.omega = argp;
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use skyforge_orbits::ephemeris::BeidouSet;
    use skyforge_orbits::ephemeris::OrbitClass;
    use skyforge_orbits::ephemeris::nominal;
    use skyforge_orbits::time::TimeOrigin;
    use skyforge_orbits::time::epoch_from_bdt;

    fn odd_epoch() -> Epoch {
        epoch_from_bdt(1000, 302_403.25)
    }

    /// Largest position (m) and clock (s) difference over toe +- 1 h, 60 s steps.
    fn max_difference(a: &BroadcastEphemeris, b: &BroadcastEphemeris) -> (f64, f64) {
        let origin = TimeOrigin::new(a.toe);
        let (ba, bb) = (a.bind(&origin), b.bind(&origin));
        (-60..=60).fold((0.0f64, 0.0f64), |(dr, dc), k| {
            let t = 60.0 * f64::from(k);
            (
                dr.max((ba.position_ecef(t) - bb.position_ecef(t)).norm()),
                dc.max((ba.clock_offset_s(t) - bb.clock_offset_s(t)).abs()),
            )
        })
    }

    #[test]
    fn euler_angles_round_trip() {
        for &(node, incl, argp) in &[(0.3, 0.96, -2.0), (-3.0, 0.087, 1.2), (2.5, 1.5, 0.0)] {
            let (n, i, w) = euler_313(&orientation(node, incl, argp));
            assert!((n - node).abs() < 1e-14 && (i - incl).abs() < 1e-14);
            assert!((w - argp).abs() < 1e-14, "{w} vs {argp}");
        }
        let (n, i, w) = euler_313(&orientation(0.7, 0.0, 0.5));
        assert_eq!((n, i), (0.0, 0.0));
        assert!((w - 1.2).abs() < 1e-14);
    }

    /// Analytical expectation: re-expression is exact, so the orbit and clock do not move
    /// (only f64 rounding, micrometres at GEO radius).
    #[test]
    fn nominal_sets_are_moved_onto_the_grid_without_moving_the_orbit() {
        for set in [BeidouSet::Bds3, BeidouSet::Bds2] {
            for mut eph in nominal::beidou(set, odd_epoch()) {
                eph.clock.af0 = 1e-4;
                eph.clock.af1 = 1e-11;
                eph.clock.af2 = 1e-18;
                let grid = onto_grid(&eph).expect("nominal sets re-express");
                let sow = bdt_week_sow(grid.toe).1;
                assert_eq!(sow % 8.0, 0.0);
                assert_eq!(bdt_week_sow(grid.toc).1 % 8.0, 0.0);
                assert!((grid.toe - eph.toe).to_seconds().abs() <= 4.0);
                let (dr, dc) = max_difference(&eph, &grid);
                assert!(dr < 1e-5, "{}: {dr} m", eph.sat);
                assert!(dc < 1e-15, "{}: {dc} s", eph.sat);
            }
        }
    }

    #[test]
    fn meo_with_harmonics_and_a_week_crossing_is_exact() {
        let epoch = epoch_from_bdt(1000, 604_797.0);
        let mut eph = nominal::beidou(BeidouSet::Bds3, epoch)[0].clone();
        eph.orbit.e = 0.004;
        eph.orbit.omega = 1.1;
        eph.orbit.delta_n = 4e-9;
        eph.orbit.idot = 2e-10;
        eph.harmonics.cuc = 1e-5;
        eph.harmonics.cus = -2e-5;
        eph.harmonics.crc = 300.0;
        eph.harmonics.crs = -100.0;
        eph.harmonics.cic = 1e-7;
        eph.harmonics.cis = -2e-7;
        let grid = onto_grid(&eph).expect("standard class always re-expresses");
        assert_eq!(bdt_week_sow(grid.toe), (1001, 0.0));
        let (dr, _) = max_difference(&eph, &grid);
        assert!(dr < 1e-5, "{dr} m");
    }

    #[test]
    fn geo_with_corrections_off_the_grid_is_refused() {
        let mut geo = nominal::beidou(BeidouSet::Bds3, odd_epoch())
            .into_iter()
            .find(|e| e.class == OrbitClass::BeidouGeo)
            .expect("a GEO");
        geo.harmonics.cuc = 1e-6;
        assert!(matches!(
            onto_grid(&geo),
            Err(BdsNavError::ToeOffGrid { .. })
        ));
    }
}
