//! Accelerations: central body, zonal harmonics J2..J6, atmospheric drag.
//!
//! Frame: the scenario ECI frame. The zonal harmonics are evaluated with the Earth's pole
//! along ECI Z, consistent with the Earth-rotation-only ECI <-> ECEF transformation
//! (zonal terms do not depend on longitude, so the Earth rotation angle is not needed).

use super::atmosphere::{HarrisPriester, exponential_density_kg_m3, geodetic_height_m};
use super::config::{DensityModel, ForceModelConfig};
use super::sun::sun_position_eci_m;
use crate::Vec3;
use crate::constants::{GM_GPS, J2, OMEGA_E_GPS, WGS84_A_M};
use hifitime::Epoch;

/// Unnormalised EGM96 zonal coefficients J3..J6, `J_n = -sqrt(2n + 1) Cbar_n0` from the
/// fully normalised EGM96 values (Lemoine et al. 1998, NASA/TP-1998-206861; the same
/// unnormalised values are listed in Vallado, *Fundamentals of Astrodynamics and
/// Applications*, appendix D).
pub const J3: f64 = -2.532_656_485_33e-6;
/// EGM96 J4 (see [`J3`]).
pub const J4: f64 = -1.619_621_591_37e-6;
/// EGM96 J5 (see [`J3`]).
pub const J5: f64 = -2.272_960_828_69e-7;
/// EGM96 J6 (see [`J3`]).
pub const J6: f64 = 5.406_812_391_07e-7;

/// Reference radius of the zonal coefficients (WGS-84 / EGM96 equatorial radius, m).
pub const R_EARTH_M: f64 = WGS84_A_M;

/// Drag parameters.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Drag {
    /// Ballistic coefficient `Cd A / m` (m^2/kg).
    cd_area_per_mass_m2_kg: f64,
    density: Density,
}

/// A density model with what it needs.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Density {
    Exponential,
    HarrisPriester {
        model: HarrisPriester,
        /// Julian date (TT) of the scenario start, for the Sun position.
        jd_tt_start: f64,
    },
}

/// The resolved force model of a LEO (SI units, ECI).
#[derive(Debug, Clone, PartialEq)]
pub struct ForceModel {
    /// `J_n` for n = 2..=`max_degree` at index n (0 where unused).
    zonals: [f64; 7],
    max_degree: usize,
    drag: Option<Drag>,
}

impl ForceModel {
    /// Resolve `cfg` for a scenario starting at `start` (the Harris-Priester bulge needs
    /// the Sun position, its exponent the orbit inclination `inclination_rad`).
    pub fn new(cfg: &ForceModelConfig, start: Epoch, inclination_rad: f64) -> Self {
        let mut zonals = [0.0; 7];
        let max_degree = if cfg.higher_zonals {
            zonals[2] = if cfg.j2 { J2 } else { 0.0 };
            zonals[3..=6].copy_from_slice(&[J3, J4, J5, J6]);
            6
        } else if cfg.j2 {
            zonals[2] = J2;
            2
        } else {
            0
        };
        let drag = cfg.drag.then(|| Drag {
            cd_area_per_mass_m2_kg: cfg.drag_coefficient * cfg.area_m2 / cfg.mass_kg,
            density: match cfg.density_model {
                DensityModel::Exponential => Density::Exponential,
                DensityModel::HarrisPriester => Density::HarrisPriester {
                    model: HarrisPriester::for_inclination(inclination_rad),
                    jd_tt_start: start.to_jde_tt_days(),
                },
            },
        });
        Self {
            zonals,
            max_degree,
            drag,
        }
    }

    /// Gravitational parameter of the central body (m^3/s^2): the WGS-84 value GPS uses.
    pub fn gm(&self) -> f64 {
        GM_GPS
    }

    /// Total acceleration (m/s^2) at `t_s` (s since the scenario start), ECI.
    pub fn acceleration_eci(&self, t_s: f64, r_eci_m: &Vec3, v_eci_mps: &Vec3) -> Vec3 {
        self.gravity_eci(r_eci_m) + self.drag_eci(t_s, r_eci_m, v_eci_mps)
    }

    /// Point mass plus zonal harmonics (m/s^2).
    ///
    /// For each zonal term, `U_n = -(mu/r) J_n (R/r)^n P_n(s)` with `s = z/r`; its
    /// gradient is `mu J_n R^n / r^(n+2) [((n+1) P_n(s) + s P_n'(s)) r_hat - P_n'(s) z_hat]`
    /// (Legendre polynomials and derivatives by their three-term recurrences, no
    /// singularity at the poles).
    pub fn gravity_eci(&self, r_eci_m: &Vec3) -> Vec3 {
        zonal_gravitation(r_eci_m, &self.zonals, self.max_degree)
    }

    /// Drag acceleration `-1/2 rho (Cd A / m) |v_rel| v_rel` with `v_rel = v - w_E x r`
    /// (atmosphere co-rotating with the Earth); zero when drag is off.
    pub fn drag_eci(&self, t_s: f64, r_eci_m: &Vec3, v_eci_mps: &Vec3) -> Vec3 {
        let Some(drag) = &self.drag else {
            return Vec3::zeros();
        };
        let rho = self.density_with(drag, t_s, r_eci_m);
        let v_rel = v_eci_mps - Vec3::new(-OMEGA_E_GPS * r_eci_m.y, OMEGA_E_GPS * r_eci_m.x, 0.0);
        -v_rel * (0.5 * rho * drag.cd_area_per_mass_m2_kg * v_rel.norm())
    }

    /// Atmospheric density (kg/m^3) the drag model uses at `t_s` and `r_eci_m`; 0 when
    /// drag is off.
    pub fn density_kg_m3(&self, t_s: f64, r_eci_m: &Vec3) -> f64 {
        self.drag
            .as_ref()
            .map_or(0.0, |drag| self.density_with(drag, t_s, r_eci_m))
    }

    /// Ballistic coefficient `Cd A / m` (m^2/kg); 0 when drag is off.
    pub fn cd_area_per_mass_m2_kg(&self) -> f64 {
        self.drag.map_or(0.0, |d| d.cd_area_per_mass_m2_kg)
    }

    fn density_with(&self, drag: &Drag, t_s: f64, r_eci_m: &Vec3) -> f64 {
        let h_m = geodetic_height_m(r_eci_m);
        match &drag.density {
            Density::Exponential => exponential_density_kg_m3(h_m),
            Density::HarrisPriester { model, jd_tt_start } => {
                let sun = sun_position_eci_m(jd_tt_start + t_s / 86_400.0);
                model.density_kg_m3(h_m, r_eci_m, &sun)
            }
        }
    }
}

/// The zonal field's gravitation at `r_m` (m/s^2; any frame whose z is the Earth's axis):
/// the point mass plus `J_n` of `zonals` for n = 2..=`max_degree` ([`ForceModel::gravity_eci`]'s
/// formula).
pub fn zonal_gravitation(r_m: &Vec3, zonals: &[f64; 7], max_degree: usize) -> Vec3 {
    let r2 = r_m.norm_squared();
    let r = r2.sqrt();
    let r_hat = r_m / r;
    let mu_over_r2 = GM_GPS / r2;
    let mut acc = -r_hat * mu_over_r2;
    if max_degree < 2 {
        return acc;
    }
    let s = r_hat.z;
    let rho = R_EARTH_M / r;
    // P_{n-1}, P_n and their derivatives, starting at n = 1.
    let (mut p_prev, mut p) = (1.0, s);
    let (mut dp_prev, mut dp) = (0.0, 1.0);
    let mut rho_n = rho;
    let mut radial = 0.0;
    let mut axial = 0.0;
    for (n, j_n) in zonals.iter().enumerate().take(max_degree + 1).skip(2) {
        let nf = n as f64;
        let p_next = ((2.0 * nf - 1.0) * s * p - (nf - 1.0) * p_prev) / nf;
        let dp_next = dp_prev + (2.0 * nf - 1.0) * p;
        (p_prev, p) = (p, p_next);
        (dp_prev, dp) = (dp, dp_next);
        rho_n *= rho;
        let jn = j_n * rho_n;
        radial += jn * ((nf + 1.0) * p + s * dp);
        axial += jn * dp;
    }
    acc += (r_hat * radial - Vec3::z() * axial) * mu_over_r2;
    acc
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::propagate::config::ForceModelConfig;

    fn start() -> Epoch {
        Epoch::from_gregorian_utc(2023, 3, 12, 0, 0, 0, 0)
    }

    fn model(j2: bool, higher_zonals: bool, drag: bool) -> ForceModel {
        let cfg = ForceModelConfig {
            j2,
            higher_zonals,
            drag,
            ..ForceModelConfig::default()
        };
        ForceModel::new(&cfg, start(), 0.6)
    }

    #[test]
    fn zonal_coefficients_match_normalised_egm96() {
        // Fully normalised EGM96 C(n,0) from the EGM96 coefficient file (egm96_to360).
        let cbar = [
            (2, -0.484_165_371_736e-3, J2),
            (3, 0.957_254_173_792e-6, J3),
            (4, 0.539_873_863_789e-6, J4),
            (5, 0.685_323_475_630e-7, J5),
            (6, -0.149_957_994_714e-6, J6),
        ];
        for (n, c, j) in cbar {
            let expected = -c * f64::from(2 * n + 1).sqrt();
            assert!(
                (j / expected - 1.0).abs() < 1e-10,
                "J{n}: {j:e} vs {expected:e}"
            );
        }
    }

    #[test]
    fn j2_matches_textbook_cartesian_formula() {
        // a_x = -3/2 J2 mu R^2 x / r^5 (1 - 5 z^2/r^2), a_z = -3/2 J2 mu R^2 z / r^5 (3 - 5 z^2/r^2).
        let f = model(true, false, false);
        let r = Vec3::new(4.1e6, -3.3e6, 4.4e6);
        let rn = r.norm();
        let k = -1.5 * J2 * GM_GPS * R_EARTH_M.powi(2) / rn.powi(5);
        let z2 = (r.z / rn).powi(2);
        let expected = -r * GM_GPS / rn.powi(3)
            + Vec3::new(
                r.x * (1.0 - 5.0 * z2),
                r.y * (1.0 - 5.0 * z2),
                r.z * (3.0 - 5.0 * z2),
            ) * k;
        let got = f.gravity_eci(&r);
        assert!(
            (got - expected).norm() < 1e-14 * expected.norm(),
            "{got} vs {expected}"
        );
    }

    /// Zonal potential `-(mu/r) sum J_n (R/r)^n P_n(z/r)` with P_n from Rodrigues-derived
    /// closed forms, for a finite-difference oracle.
    fn zonal_potential(r: &Vec3, js: &[(usize, f64)]) -> f64 {
        let rn = r.norm();
        let s = r.z / rn;
        let p = |n: usize| match n {
            2 => (3.0 * s * s - 1.0) / 2.0,
            3 => (5.0 * s.powi(3) - 3.0 * s) / 2.0,
            4 => (35.0 * s.powi(4) - 30.0 * s * s + 3.0) / 8.0,
            5 => (63.0 * s.powi(5) - 70.0 * s.powi(3) + 15.0 * s) / 8.0,
            6 => (231.0 * s.powi(6) - 315.0 * s.powi(4) + 105.0 * s * s - 5.0) / 16.0,
            _ => 0.0,
        };
        let sum: f64 = js
            .iter()
            .map(|&(n, j)| j * (R_EARTH_M / rn).powi(n as i32) * p(n))
            .sum();
        GM_GPS / rn * (1.0 - sum)
    }

    #[test]
    fn zonal_acceleration_is_the_gradient_of_the_potential() {
        let f = model(true, true, false);
        let js = [(2, J2), (3, J3), (4, J4), (5, J5), (6, J6)];
        for r in [
            Vec3::new(4.1e6, -3.3e6, 4.4e6),
            Vec3::new(-6.9e6, 0.2e6, -1.0e6),
            Vec3::new(1.0e3, 2.0e3, 6.9e6),
        ] {
            let step = 1.0;
            let grad = Vec3::from_fn(|k, _| {
                let mut dr = Vec3::zeros();
                dr[k] = step;
                (zonal_potential(&(r + dr), &js) - zonal_potential(&(r - dr), &js)) / (2.0 * step)
            });
            let got = f.gravity_eci(&r);
            // Compare the perturbation part (central term removed) to keep precision.
            let central = -r * GM_GPS / r.norm().powi(3);
            let pert = got - central;
            let pert_fd = grad - central;
            assert!(
                (pert - pert_fd).norm() < 1e-6 * pert.norm(),
                "{pert} vs {pert_fd}"
            );
        }
    }

    #[test]
    fn two_body_when_zonals_off() {
        let f = model(false, false, false);
        let r = Vec3::new(7e6, 1e6, -2e6);
        let expected = -r * GM_GPS / r.norm().powi(3);
        assert!((f.gravity_eci(&r) - expected).norm() < 1e-15 * expected.norm());
        assert_eq!(
            f.drag_eci(0.0, &r, &Vec3::new(0.0, 7.5e3, 0.0)),
            Vec3::zeros()
        );
    }

    #[test]
    fn drag_opposes_relative_velocity_with_the_right_size() {
        let f = model(true, false, true);
        // Equatorial circular orbit at 400 km: |v_rel| = v - w r.
        let r = Vec3::new(WGS84_A_M + 400e3, 0.0, 0.0);
        let v_circ = (GM_GPS / r.x).sqrt();
        let v = Vec3::new(0.0, v_circ, 0.0);
        let a = f.drag_eci(0.0, &r, &v);
        let v_rel = v_circ - OMEGA_E_GPS * r.x;
        let expected = 0.5 * 3.725e-12 * 2.2 * 1.0 / 100.0 * v_rel * v_rel;
        assert!(
            (a.y + expected).abs() < 1e-9 * expected,
            "{a} vs {expected}"
        );
        assert_eq!(a.x, 0.0);
        assert_eq!(f.density_kg_m3(0.0, &r), 3.725e-12);
        assert!((f.cd_area_per_mass_m2_kg() - 0.022).abs() < 1e-15);
    }

    #[test]
    fn harris_priester_density_is_between_its_bounds_and_varies_with_the_sun() {
        let cfg = ForceModelConfig {
            density_model: DensityModel::HarrisPriester,
            ..ForceModelConfig::default()
        };
        let f = ForceModel::new(&cfg, start(), 0.6);
        let r_mag = WGS84_A_M + 400e3;
        let rhos: Vec<f64> = (0..24)
            .map(|k| {
                let ang = f64::from(k) * 15f64.to_radians();
                f.density_kg_m3(0.0, &Vec3::new(r_mag * ang.cos(), r_mag * ang.sin(), 0.0))
            })
            .collect();
        let max = rhos.iter().cloned().fold(0.0, f64::max);
        let min = rhos.iter().cloned().fold(1.0, f64::min);
        assert!(
            min >= 2.249e-12 * 0.999 && max <= 7.492e-12 * 1.001,
            "{min:e} {max:e}"
        );
        assert!(max / min > 2.0, "diurnal bulge expected: {min:e} {max:e}");
    }
}
