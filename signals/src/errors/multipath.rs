//! Multipath: extra copies of a satellite's signal, each delayed, scaled and phase-shifted
//! relative to the direct one, given either as fixed taps or as specular reflections off
//! flat surfaces of the spacecraft body, plus the code-tracking bias such paths cause in a
//! standard delay lock loop.
//!
//! - Surfaces (Yuan 2000, section 5.4.3, eqs. 5-24..5-26, after Van Nee): for a reflector
//!   with normal `n` at distance `d` from the antenna and a satellite in direction `u`,
//!   `cos i = n . u / (|n| |u|)` and the extra path is `2 d cos i` (the image-antenna
//!   construction). The surface does not block the direct signal.
//! - DLL bias (Yuan 2000 section 5.4.3, Van Nee): ideal triangular correlation
//!   `R(tau) = 1 - (N + 1) / N |tau| / T_c` for `|tau| < T_c`, `-1/N` elsewhere in the
//!   period; a non-coherent early-minus-late power DLL locks where
//!   `|y_e|^2 - |y_l|^2 = 0` with `y_e,l = sum a_k R(tau - tau_k -+ D/2) e^{j theta_k}`.
//!
//! A [`Path`]'s `phase_rad` is the phase the path carries beyond its delay: the reflected
//! signal is `a s(t - delay / c) e^{j phase}`, where `s` includes the carrier, so the
//! delay's own carrier rotation (`-2 pi delay / lambda`) is not in `phase_rad`. The DLL
//! bias needs the full carrier phase at the correlator: see [`Path::at_carrier`].

use skyforge_orbits::Vec3;
use skyforge_orbits::check::{Allowed, Invalid};
use skyforge_orbits::ephemeris::SatId;

/// `[errors.multipath]`.
#[derive(Debug, Clone, PartialEq, Default, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MultipathConfig {
    /// `[[errors.multipath.taps]]`.
    #[serde(default)]
    pub taps: Vec<TapConfig>,
    /// `[[errors.multipath.surfaces]]`.
    #[serde(default)]
    pub surfaces: Vec<SurfaceConfig>,
}

/// A fixed extra path: applies to `antenna` (name; None = every antenna) x `satellite`
/// (`"G05"`, `"C23"`; None = every satellite).
#[derive(Debug, Clone, PartialEq, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TapConfig {
    #[serde(default)]
    pub antenna: Option<String>,
    #[serde(default)]
    pub satellite: Option<String>,
    /// Extra path length (m, > 0).
    pub delay_m: f64,
    /// Amplitude relative to the direct path (linear, in (0, 1)).
    pub relative_amplitude: f64,
    /// Phase at t = 0 (deg), default 0.
    #[serde(default)]
    pub phase_deg: f64,
    /// Phase rate of the path relative to the direct one (Hz), default 0.
    #[serde(default)]
    pub doppler_hz: f64,
}

/// A flat reflecting surface fixed to the platform body (Van Nee geometry, Yuan 2000
/// eqs. 5-24..5-26).
#[derive(Debug, Clone, PartialEq, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SurfaceConfig {
    /// Unique name (reports, truth).
    pub name: String,
    /// A point of the surface, body frame (m), from the centre of mass.
    pub point_body_m: [f64; 3],
    /// Normal on the reflecting side, body frame (any length; it is normalised).
    pub normal_body: [f64; 3],
    /// Amplitude reflection coefficient (linear, in (0, 1)).
    pub reflection_coefficient: f64,
    /// Phase shift of the reflection (deg), default 180 (conductor).
    #[serde(default = "default_surface_phase_deg")]
    pub phase_deg: f64,
    /// Half sizes (m) of a finite rectangle centred on `point_body_m`, along the in-plane
    /// axes of [`SurfaceConfig::in_plane_axes`]; None = infinite plane.
    #[serde(default)]
    pub half_size_m: Option<[f64; 2]>,
    /// Antennas that see this surface (names); None = every antenna.
    #[serde(default)]
    pub antennas: Option<Vec<String>>,
}

fn default_surface_phase_deg() -> f64 {
    180.0
}

/// One reflected path at one instant, relative to the direct path.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Path {
    /// Extra path length (m).
    pub delay_m: f64,
    /// Amplitude relative to the direct path (linear).
    pub relative_amplitude: f64,
    /// Phase beyond the delay's own carrier rotation (rad; module docs).
    pub phase_rad: f64,
}

impl Path {
    /// The same path with `phase_rad` turned into the full carrier phase relative to the
    /// direct path at a carrier of wavelength `wavelength_m`: `phase - 2 pi delay / lambda`,
    /// wrapped to `[0, 2 pi)`. This is what [`dll_bias_m`] expects.
    pub fn at_carrier(&self, wavelength_m: f64) -> Path {
        let cycles = self.phase_rad / std::f64::consts::TAU - self.delay_m / wavelength_m;
        Path {
            phase_rad: std::f64::consts::TAU * (cycles - cycles.floor()),
            ..*self
        }
    }
}

/// Smallest accepted normal length before normalisation.
const MIN_NORMAL_NORM: f64 = 1e-9;

/// Most taps, and most surfaces, of a scenario.
// assumed: every reflected path is mixed like a satellite's direct signal (one more
// channel per link) and enters the code truth's DLL search, so 64 paths per link make a
// run up to 65 times slower; measured channel models (land-mobile, aircraft, LEO body)
// use a few to a few tens of echoes. 5000 taps on 2 s of signal ran for minutes.
pub const MAX_PATHS: usize = 64;

impl MultipathConfig {
    /// Checks every tap and surface; field paths like `taps[1].delay_m`,
    /// `surfaces[0].normal_body`. Antenna names are checked against the scenario by
    /// [`MultipathConfig::check_antennas`].
    pub fn check(&self) -> Result<(), Invalid> {
        for (field, n) in [("taps", self.taps.len()), ("surfaces", self.surfaces.len())] {
            if n > MAX_PATHS {
                return Err(Invalid::new(
                    field,
                    format!("{n} entries"),
                    format!("at most {MAX_PATHS} (each is mixed like another satellite)"),
                ));
            }
        }
        for (i, tap) in self.taps.iter().enumerate() {
            tap.check().map_err(|e| e.within(&format!("taps[{i}]")))?;
        }
        for (i, surface) in self.surfaces.iter().enumerate() {
            surface
                .check()
                .map_err(|e| e.within(&format!("surfaces[{i}]")))?;
            if self.surfaces[..i].iter().any(|s| s.name == surface.name) {
                return Err(Invalid::new(
                    format!("surfaces[{i}].name"),
                    format!("{:?}", surface.name),
                    "must be unique among the surfaces",
                ));
            }
        }
        Ok(())
    }

    /// The reflected paths of the link (`antenna` name, `sat`), at most (a surface's path
    /// exists only while the geometry allows it).
    pub fn paths_of(&self, antenna: &str, sat: SatId) -> usize {
        self.taps
            .iter()
            .filter(|t| t.applies_to(antenna, sat))
            .count()
            + self
                .surfaces
                .iter()
                .filter(|s| s.applies_to(antenna))
                .count()
    }

    /// Every antenna named by a tap or surface is one of `antennas`.
    pub fn check_antennas(&self, antennas: &[&str]) -> Result<(), Invalid> {
        let unknown = |field: String, name: &str| {
            Invalid::new(
                field,
                format!("{name:?}"),
                format!("must be one of the scenario's antennas {antennas:?}"),
            )
        };
        for (i, tap) in self.taps.iter().enumerate() {
            if let Some(name) = &tap.antenna
                && !antennas.contains(&name.as_str())
            {
                return Err(unknown(format!("taps[{i}].antenna"), name));
            }
        }
        for (i, surface) in self.surfaces.iter().enumerate() {
            for (j, name) in surface.antennas.iter().flatten().enumerate() {
                if !antennas.contains(&name.as_str()) {
                    return Err(unknown(format!("surfaces[{i}].antennas[{j}]"), name));
                }
            }
        }
        Ok(())
    }
}

impl TapConfig {
    /// Checks: delay, phase and Doppler in their ranges, amplitude in (0, 1), satellite a
    /// valid id, antenna non-empty.
    pub fn check(&self) -> Result<(), Invalid> {
        DELAY_M.check("delay_m", self.delay_m)?;
        check_unit_open("relative_amplitude", self.relative_amplitude)?;
        PHASE_DEG.check("phase_deg", self.phase_deg)?;
        DOPPLER_HZ.check("doppler_hz", self.doppler_hz)?;
        if let Some(text) = &self.satellite {
            text.parse::<SatId>().map_err(|e| {
                Invalid::new(
                    "satellite",
                    format!("{text:?}"),
                    format!("{e}; omit it for every satellite"),
                )
            })?;
        }
        if let Some(name) = &self.antenna {
            check_name("antenna", name)?;
        }
        Ok(())
    }

    /// Whether the tap applies to the link (`antenna` name, `sat`). A satellite text that
    /// does not parse matches nothing (`check` rejects it).
    pub fn applies_to(&self, antenna: &str, sat: SatId) -> bool {
        self.antenna.as_deref().is_none_or(|a| a == antenna)
            && self
                .satellite
                .as_deref()
                .is_none_or(|s| s.parse::<SatId>().is_ok_and(|parsed| parsed == sat))
    }
}

impl SurfaceConfig {
    /// Checks: name non-empty, point, normal (non-zero), phase and half sizes in their
    /// ranges, coefficient in (0, 1), antenna names non-empty.
    pub fn check(&self) -> Result<(), Invalid> {
        check_name("name", &self.name)?;
        for (field, v, allowed) in [
            ("point_body_m", &self.point_body_m, POINT_M),
            ("normal_body", &self.normal_body, NORMAL),
        ] {
            for (k, x) in v.iter().enumerate() {
                allowed.check(&format!("{field}[{k}]"), *x)?;
            }
        }
        if Vec3::from(self.normal_body).norm() < MIN_NORMAL_NORM {
            return Err(Invalid::new(
                "normal_body",
                format!("{:?}", self.normal_body),
                "must be a non-zero direction (any length; it is normalised)",
            ));
        }
        check_unit_open("reflection_coefficient", self.reflection_coefficient)?;
        PHASE_DEG.check("phase_deg", self.phase_deg)?;
        if let Some(half) = &self.half_size_m {
            for (k, h) in half.iter().enumerate() {
                HALF_SIZE_M
                    .check(&format!("half_size_m[{k}]"), *h)
                    .map_err(|e| Invalid {
                        allowed: format!("{} (omit half_size_m for an infinite plane)", e.allowed),
                        ..e
                    })?;
            }
        }
        for (j, name) in self.antennas.iter().flatten().enumerate() {
            check_name(&format!("antennas[{j}]"), name)?;
        }
        Ok(())
    }

    /// Whether antenna `antenna` (name) sees this surface.
    pub fn applies_to(&self, antenna: &str) -> bool {
        self.antennas
            .as_ref()
            .is_none_or(|names| names.iter().any(|n| n == antenna))
    }

    /// Unit normal and in-plane axes `(n, e1, e2)` of the surface (body frame): `e1` is the
    /// body X axis made orthogonal to `n` (the body Y axis when `n` is within ~26 deg of
    /// X, |n_x| > 0.9), `e2 = n x e1`. `half_size_m` is measured along `e1` and `e2`.
    pub fn in_plane_axes(&self) -> (Vec3, Vec3, Vec3) {
        let n = Vec3::from(self.normal_body).normalize();
        let seed = if n.x.abs() > 0.9 {
            Vec3::y()
        } else {
            Vec3::x()
        };
        let e1 = (seed - n * seed.dot(&n)).normalize();
        (n, e1, n.cross(&e1))
    }
}

/// Extra path length of a tap (m): assumed up to 10 km (multipath models use metres to
/// hundreds of metres; farther reflections arrive far below the direct signal).
const DELAY_M: Allowed = Allowed::above(0.0, 10e3, "m");
/// A phase (deg): one turn either way.
const PHASE_DEG: Allowed = Allowed::closed(-360.0, 360.0, "deg");
/// Fading rate of a tap relative to the direct path (Hz): assumed up to 10 kHz, the
/// Doppler difference of a LEO's ground reflection.
const DOPPLER_HZ: Allowed = Allowed::closed(-10e3, 10e3, "Hz");
/// A surface's point in the body frame (m): as an antenna's lever arm, within 10 km.
const POINT_M: Allowed = Allowed::closed(-10e3, 10e3, "m");
/// A surface normal's components: any length (it is normalised) short of overflowing.
const NORMAL: Allowed = Allowed::closed(-1e6, 1e6, "");
/// A finite surface's half size (m): up to 10 km.
const HALF_SIZE_M: Allowed = Allowed::above(0.0, 10e3, "m");

fn check_unit_open(field: &str, value: f64) -> Result<(), Invalid> {
    if value > 0.0 && value < 1.0 {
        Ok(())
    } else {
        Err(Invalid::new(
            field,
            value,
            "must be a linear amplitude ratio in (0, 1)",
        ))
    }
}

fn check_name(field: &str, name: &str) -> Result<(), Invalid> {
    if name.trim().is_empty() {
        Err(Invalid::new(
            field,
            format!("{name:?}"),
            "must be a non-empty name",
        ))
    } else {
        Ok(())
    }
}

/// The specular reflection of a far-away transmitter in direction `los_body` (unit, body
/// frame, antenna -> satellite) off `surface`, seen by an antenna at `antenna_body_m`.
///
/// Some(path) when the geometry allows it: the satellite in front of the reflecting side
/// (`n . u > 0`), the antenna in front of it (`d = n . (A - P) > 0`), and, for a finite
/// surface, the reflection point `R = A - 2 d n + (d / cos i) u` inside the rectangle.
/// Delay `2 d cos i` (Yuan eq. 5-25 as a length), amplitude the reflection coefficient,
/// phase the surface's phase. Call after [`SurfaceConfig::check`].
pub fn surface_path(
    surface: &SurfaceConfig,
    antenna_body_m: &Vec3,
    los_body: &Vec3,
) -> Option<Path> {
    let (n, e1, e2) = surface.in_plane_axes();
    let u = los_body.normalize();
    // Yuan eq. 5-24.
    let cos_i = n.dot(&u);
    let point_m = Vec3::from(surface.point_body_m);
    let d_m = n.dot(&(antenna_body_m - point_m));
    if !(cos_i > 0.0 && d_m > 0.0) {
        return None;
    }
    if let Some([h1, h2]) = surface.half_size_m {
        let image_m = antenna_body_m - 2.0 * d_m * n;
        let offset_m = image_m + (d_m / cos_i) * u - point_m;
        if offset_m.dot(&e1).abs() > h1 || offset_m.dot(&e2).abs() > h2 {
            return None;
        }
    }
    Some(Path {
        delay_m: 2.0 * d_m * cos_i,
        relative_amplitude: surface.reflection_coefficient,
        phase_rad: surface.phase_deg.to_radians(),
    })
}

/// The path of tap `tap` at time `t_s` (s from the scenario start): its delay and
/// amplitude, phase `phase_deg + 360 doppler_hz t_s` in radians, not wrapped (the renderer
/// interpolates it linearly between epochs, which a wrap would break).
pub fn tap_path(tap: &TapConfig, t_s: f64) -> Path {
    Path {
        delay_m: tap.delay_m,
        relative_amplitude: tap.relative_amplitude,
        phase_rad: std::f64::consts::TAU * (tap.phase_deg / 360.0 + tap.doppler_hz * t_s),
    }
}

/// Search reach beyond the direct path's correlation triangle and the early-late window
/// (chips); bounds the cost for long reflections, which cannot move the lock point.
const MAX_SEARCH_DELAY_CHIPS: f64 = 2.0;

/// Number of bisection steps: halves the search step (<= 0.05 chip) to ~1e-16 chip.
const BISECTION_STEPS: u32 = 60;

/// Code-tracking bias (m) of a non-coherent early-minus-late power DLL with early-late
/// spacing `spacing_chips`, chip length `chip_m`, ideal triangular correlation of a code
/// of `code_len_chips` chips (Van Nee model, Yuan 2000 section 5.4.3), for the direct path
/// plus `paths` at one instant.
///
/// Each path's `phase_rad` is taken as its full carrier phase relative to the direct path
/// at the correlator ([`Path::at_carrier`]). The result is the stable zero of
/// `D(tau) = |y_e|^2 - |y_l|^2` (D rising through zero) nearest to 0, searched within
/// `1 + spacing / 2 + min(longest delay, 2)` chips on a grid of `min(spacing / 8, 0.05)`
/// chips and refined by bisection; positive = the pseudorange is
/// too long. NaN when no stable zero exists within reach (only when the reflections
/// together are about as strong as the direct path).
pub fn dll_bias_m(paths: &[Path], chip_m: f64, code_len_chips: u32, spacing_chips: f64) -> f64 {
    let half_spacing = 0.5 * spacing_chips;
    let n_chips = f64::from(code_len_chips.max(1));
    let discriminator = |tau: f64| {
        let early = correlate(paths, chip_m, n_chips, tau - half_spacing);
        let late = correlate(paths, chip_m, n_chips, tau + half_spacing);
        early.0 * early.0 + early.1 * early.1 - late.0 * late.0 - late.1 * late.1
    };
    let max_delay_chips = paths.iter().map(|p| p.delay_m / chip_m).fold(0.0, f64::max);
    // A lock point further out would be tracking a reflection, not a biased direct path.
    let reach = 1.0 + half_spacing + max_delay_chips.min(MAX_SEARCH_DELAY_CHIPS);
    let step = (spacing_chips / 8.0).min(0.05);
    if !(chip_m > 0.0 && step > 0.0 && reach.is_finite()) {
        return f64::NAN;
    }
    let steps = (reach / step).ceil() as usize;
    // Upward crossing in [lo, hi]: D(lo) < 0 <= D(hi).
    let crossing = |lo: f64, hi: f64| -> Option<f64> {
        if !(discriminator(lo) < 0.0 && discriminator(hi) >= 0.0) {
            return None;
        }
        let (mut lo, mut hi) = (lo, hi);
        for _ in 0..BISECTION_STEPS {
            let mid = 0.5 * (lo + hi);
            if discriminator(mid) < 0.0 {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        Some(0.5 * (lo + hi))
    };
    for k in 0..steps {
        let near = k as f64 * step;
        let far = near + step;
        let found = [crossing(-far, -near), crossing(near, far)]
            .into_iter()
            .flatten()
            .min_by(|a, b| a.abs().total_cmp(&b.abs()));
        if let Some(tau_chips) = found {
            return tau_chips * chip_m;
        }
    }
    f64::NAN
}

/// Complex correlator output (I, Q) of the direct path plus `paths` against a replica at
/// offset `tau_chips` (positive: replica late).
fn correlate(paths: &[Path], chip_m: f64, n_chips: f64, tau_chips: f64) -> (f64, f64) {
    paths
        .iter()
        .fold((triangle(tau_chips, n_chips), 0.0), |(i, q), p| {
            let r = p.relative_amplitude * triangle(tau_chips - p.delay_m / chip_m, n_chips);
            let (sin, cos) = p.phase_rad.sin_cos();
            (i + r * cos, q + r * sin)
        })
}

/// Ideal periodic correlation of an `n_chips` code at offset `tau_chips` (Yuan 2000,
/// Van Nee): `1 - (N + 1)/N |tau|` within a chip of a peak, `-1/N` elsewhere.
fn triangle(tau_chips: f64, n_chips: f64) -> f64 {
    let tau = tau_chips - n_chips * (tau_chips / n_chips).round();
    if tau.abs() < 1.0 {
        1.0 - (n_chips + 1.0) / n_chips * tau.abs()
    } else {
        -1.0 / n_chips
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::{FRAC_PI_2, PI};

    /// GPS C/A chip length (m): c / 1.023 MHz.
    const CA_CHIP_M: f64 = 299_792_458.0 / 1.023e6;

    fn surface(point: [f64; 3], normal: [f64; 3], half: Option<[f64; 2]>) -> SurfaceConfig {
        SurfaceConfig {
            name: "panel".into(),
            point_body_m: point,
            normal_body: normal,
            reflection_coefficient: 0.4,
            phase_deg: 180.0,
            half_size_m: half,
            antennas: None,
        }
    }

    fn path(delay_chips: f64, a: f64, phase_rad: f64) -> Path {
        Path {
            delay_m: delay_chips * CA_CHIP_M,
            relative_amplitude: a,
            phase_rad,
        }
    }

    /// The reflection is checked against ray geometry with a satellite at a finite but
    /// large distance S: the point R where the ray A -> S' of the image antenna crosses the
    /// plane must satisfy the law of reflection, and the extra length |S R| + |R A| - |S A|
    /// must equal the model's `2 d cos i` (to the ~1e-7 m parallax of a 2e7 m distance).
    #[test]
    fn mirror_geometry_matches_ray_tracing() {
        let cases = [
            (
                [0.0, 0.0, 0.0],
                [0.0, 0.0, 1.0],
                [0.3, -0.2, 1.5],
                [0.3, 0.4, 0.8],
            ),
            (
                [1.0, 2.0, -0.5],
                [0.2, -0.3, 0.9],
                [0.7, 1.1, 2.0],
                [-0.1, 0.2, 0.9],
            ),
            (
                [0.0, -1.0, 0.0],
                [0.0, -1.0, 0.1],
                [0.5, -3.0, 0.2],
                [0.1, -0.9, 0.3],
            ),
        ];
        for (point, normal, antenna, los) in cases {
            let s = surface(point, normal, None);
            let a_m = Vec3::from(antenna);
            let u = Vec3::from(los).normalize();
            let got = surface_path(&s, &a_m, &u).expect("visible reflection");
            let n = Vec3::from(normal).normalize();
            let p_m = Vec3::from(point);
            let sat_m = a_m + 2e7 * u;
            let image_m = a_m - 2.0 * n.dot(&(a_m - p_m)) * n;
            // Where the straight line image -> satellite meets the plane.
            let dir = (sat_m - image_m).normalize();
            let r_m = image_m + dir * (n.dot(&(p_m - image_m)) / n.dot(&dir));
            assert!(n.dot(&(r_m - p_m)).abs() < 1e-9);
            // Law of reflection: the incoming ray mirrored about the plane leaves towards A.
            let incoming = (r_m - sat_m).normalize();
            let mirrored = incoming - 2.0 * incoming.dot(&n) * n;
            assert!((mirrored - (a_m - r_m).normalize()).norm() < 1e-9);
            let extra_m = (sat_m - r_m).norm() + (a_m - r_m).norm() - (sat_m - a_m).norm();
            assert!(
                (got.delay_m - extra_m).abs() < 1e-5,
                "{} vs {extra_m}",
                got.delay_m
            );
            assert_eq!(got.relative_amplitude, 0.4);
            assert!((got.phase_rad - PI).abs() < 1e-15);
        }
    }

    #[test]
    fn visibility_rules() {
        let plane = surface([0.0; 3], [0.0, 0.0, 1.0], None);
        let antenna = Vec3::new(0.0, 0.0, 1.0);
        let i30 = 30f64.to_radians();
        let u = Vec3::new(i30.sin(), 0.0, i30.cos());
        // Hand: d = 1 m, cos i = cos 30 deg: 2 cos 30 = 1.732 m.
        let p = surface_path(&plane, &antenna, &u).expect("in front");
        assert!((p.delay_m - 3f64.sqrt()).abs() < 1e-12);
        // Satellite behind the reflecting side, or grazing.
        assert_eq!(
            surface_path(&plane, &antenna, &Vec3::new(0.6, 0.0, -0.8)),
            None
        );
        assert_eq!(
            surface_path(&plane, &antenna, &Vec3::new(1.0, 0.0, 0.0)),
            None
        );
        // Antenna behind the surface, or on it.
        assert_eq!(surface_path(&plane, &Vec3::new(0.0, 0.0, -1.0), &u), None);
        assert_eq!(surface_path(&plane, &Vec3::new(3.0, 0.0, 0.0), &u), None);
        // Finite plate: the reflection point is at x = d tan i = 0.577 m, y = 0 (axes X, Y).
        let small = surface([0.0; 3], [0.0, 0.0, 1.0], Some([0.5, 1.0]));
        assert_eq!(surface_path(&small, &antenna, &u), None);
        let large = surface([0.0; 3], [0.0, 0.0, 1.0], Some([0.6, 0.01]));
        assert!(surface_path(&large, &antenna, &u).is_some());
        // Moved by 0.1 m along Y (the second in-plane axis) the plate of half width 0.05
        // misses it.
        let shifted = surface([0.0, 0.1, 0.0], [0.0, 0.0, 1.0], Some([0.6, 0.05]));
        assert_eq!(surface_path(&shifted, &antenna, &u), None);
        let (n, e1, e2) = small.in_plane_axes();
        assert_eq!((n, e1, e2), (Vec3::z(), Vec3::x(), Vec3::y()));
        // A normal along X takes Y as the first in-plane axis.
        let side = surface([0.0; 3], [2.0, 0.0, 0.0], None);
        assert_eq!(side.in_plane_axes(), (Vec3::x(), Vec3::y(), Vec3::z()));
    }

    /// Wide correlator (spacing 1 chip, half spacing h = 0.5), one reflection of amplitude
    /// a and delay delta chips, replica offset tau, triangle slope k = (N + 1)/N. With the
    /// reflection in phase (theta = 0) or anti-phase (pi) both correlators are real and
    /// positive, so the lock point has y_e = y_l. For small delta (the early replica of the
    /// reflection on its rising edge, the late one on its falling edge):
    /// `[1 - k(h - tau)] +- a[1 - k(h + delta - tau)] = [1 - k(h + tau)] +- a[1 - k(h + tau - delta)]`
    /// gives `tau (1 +- a) = +- a delta`: tau = a delta / (1 + a) in phase (valid for
    /// delta < 0.5 (1 + a)) and tau = -a delta / (1 - a) in anti-phase (delta < 0.5 (1 - a)),
    /// independent of N. (The envelope is not symmetric: the anti-phase branch is larger.)
    #[test]
    fn wide_correlator_matches_the_analytic_bias() {
        for (delta, a) in [(0.2, 0.5), (0.1, 0.3), (0.05, 0.8)] {
            let in_phase = dll_bias_m(&[path(delta, a, 0.0)], CA_CHIP_M, 1023, 1.0);
            let expected = a * delta / (1.0 + a) * CA_CHIP_M;
            assert!(
                (in_phase - expected).abs() < 1e-9,
                "{in_phase} vs {expected}"
            );
        }
        for (delta, a) in [(0.2, 0.2), (0.1, 0.5), (0.02, 0.8)] {
            let anti = dll_bias_m(&[path(delta, a, PI)], CA_CHIP_M, 1023, 1.0);
            let expected = -a * delta / (1.0 - a) * CA_CHIP_M;
            assert!((anti - expected).abs() < 1e-9, "{anti} vs {expected}");
        }
    }

    /// Same derivation with half spacing h = 0.05 chip (narrow correlator): the formulas
    /// hold while the reflection stays within the early-late window, delta < h (1 +- a).
    #[test]
    fn narrow_correlator_small_delay_bias() {
        let in_phase = dll_bias_m(&[path(0.05, 0.5, 0.0)], CA_CHIP_M, 1023, 0.1);
        assert!((in_phase - 0.05 * 0.5 / 1.5 * CA_CHIP_M).abs() < 1e-9);
        let anti = dll_bias_m(&[path(0.02, 0.5, PI)], CA_CHIP_M, 1023, 0.1);
        assert!((anti + 0.02 * 0.5 / 0.5 * CA_CHIP_M).abs() < 1e-9);
    }

    #[test]
    fn no_bias_without_paths_or_beyond_one_and_a_half_chips() {
        assert!(dll_bias_m(&[], CA_CHIP_M, 1023, 1.0).abs() < 1e-9);
        for phase in [0.0, 1.0, FRAC_PI_2, PI, 4.0] {
            for delta in [1.5, 1.6, 3.0, 500.0] {
                let b = dll_bias_m(&[path(delta, 0.6, phase)], CA_CHIP_M, 1023, 1.0);
                assert!(b.abs() < 1e-9, "delta {delta} phase {phase}: {b}");
            }
            // A narrow correlator is free of reflections beyond 1 + 0.05 chips.
            let b = dll_bias_m(&[path(1.06, 0.6, phase)], CA_CHIP_M, 1023, 0.1);
            assert!(b.abs() < 1e-9);
        }
        // Just inside 1.5 chips an in-phase reflection still biases the wide correlator.
        assert!(dll_bias_m(&[path(1.4, 0.6, 0.0)], CA_CHIP_M, 1023, 1.0) > 1e-3);
    }

    #[test]
    fn coincident_paths_add_their_amplitudes() {
        // Two in-phase copies of a = 0.25 at the same delay are one path of a = 0.5.
        let split = [path(0.3, 0.25, 0.0), path(0.3, 0.25, 0.0)];
        let merged = dll_bias_m(&[path(0.3, 0.5, 0.0)], CA_CHIP_M, 1023, 1.0);
        assert!((dll_bias_m(&split, CA_CHIP_M, 1023, 1.0) - merged).abs() < 1e-9);
        // Opposite phases cancel.
        let cancel = [path(0.3, 0.25, 0.0), path(0.3, 0.25, PI)];
        assert!(dll_bias_m(&cancel, CA_CHIP_M, 1023, 1.0).abs() < 1e-9);
    }

    #[test]
    fn tap_phase_and_carrier_phase() {
        let tap = TapConfig {
            antenna: None,
            satellite: Some("G05".into()),
            delay_m: 10.0,
            relative_amplitude: 0.3,
            phase_deg: 90.0,
            doppler_hz: 0.25,
        };
        // 90 deg + 360 * 0.25 * 2 = 270 deg.
        let p = tap_path(&tap, 2.0);
        assert!((p.phase_rad - 1.5 * PI).abs() < 1e-12);
        assert_eq!((p.delay_m, p.relative_amplitude), (10.0, 0.3));
        // After 1e6 s the phase has grown by 250 000 whole cycles, unwrapped.
        let late = tap_path(&tap, 1e6).phase_rad - 250_000.0 * std::f64::consts::TAU;
        assert!((late - FRAC_PI_2).abs() < 1e-9);
        // A quarter-wavelength delay rotates the carrier by -90 deg: 180 - 90 = 90 deg.
        let lambda = 0.19;
        let q = Path {
            delay_m: 0.25 * lambda,
            relative_amplitude: 0.3,
            phase_rad: PI,
        }
        .at_carrier(lambda);
        assert!((q.phase_rad - FRAC_PI_2).abs() < 1e-12);
        assert!(tap.applies_to("any", SatId::gps(5)));
        assert!(!tap.applies_to("any", SatId::gps(6)));
        let named = TapConfig {
            antenna: Some("top".into()),
            satellite: None,
            ..tap
        };
        assert!(named.applies_to("top", SatId::beidou(3)));
        assert!(!named.applies_to("side", SatId::beidou(3)));
    }

    fn tap() -> TapConfig {
        TapConfig {
            antenna: None,
            satellite: None,
            delay_m: 5.0,
            relative_amplitude: 0.5,
            phase_deg: 0.0,
            doppler_hz: 0.0,
        }
    }

    #[test]
    fn check_names_bad_fields() {
        let ok = MultipathConfig {
            taps: vec![tap(), tap()],
            surfaces: vec![surface([0.0; 3], [0.0, 0.0, 1.0], Some([1.0, 2.0]))],
        };
        assert_eq!(ok.check(), Ok(()));
        let with_tap = |t: TapConfig| MultipathConfig {
            taps: vec![tap(), t],
            surfaces: vec![],
        };
        let with_surface = |s: SurfaceConfig| MultipathConfig {
            taps: vec![],
            surfaces: vec![surface([0.0; 3], [0.0, 0.0, 1.0], None), s],
        };
        let base = || SurfaceConfig {
            name: "other".into(),
            ..surface([0.0; 3], [0.0, 0.0, 1.0], None)
        };
        let cases = [
            (
                with_tap(TapConfig {
                    delay_m: 0.0,
                    ..tap()
                }),
                "taps[1].delay_m",
            ),
            (
                with_tap(TapConfig {
                    relative_amplitude: 1.0,
                    ..tap()
                }),
                "taps[1].relative_amplitude",
            ),
            (
                with_tap(TapConfig {
                    phase_deg: f64::NAN,
                    ..tap()
                }),
                "taps[1].phase_deg",
            ),
            (
                with_tap(TapConfig {
                    doppler_hz: f64::INFINITY,
                    ..tap()
                }),
                "taps[1].doppler_hz",
            ),
            (
                with_tap(TapConfig {
                    satellite: Some("R11".into()),
                    ..tap()
                }),
                "taps[1].satellite",
            ),
            (
                with_surface(surface([0.0; 3], [0.0, 0.0, 1.0], None)),
                "surfaces[1].name",
            ),
            (
                with_surface(SurfaceConfig {
                    normal_body: [0.0; 3],
                    ..base()
                }),
                "surfaces[1].normal_body",
            ),
            (
                with_surface(SurfaceConfig {
                    point_body_m: [0.0, f64::NAN, 0.0],
                    ..base()
                }),
                "surfaces[1].point_body_m[1]",
            ),
            (
                with_surface(SurfaceConfig {
                    reflection_coefficient: 0.0,
                    ..base()
                }),
                "surfaces[1].reflection_coefficient",
            ),
            (
                with_surface(SurfaceConfig {
                    half_size_m: Some([1.0, -1.0]),
                    ..base()
                }),
                "surfaces[1].half_size_m[1]",
            ),
            (
                with_surface(SurfaceConfig {
                    antennas: Some(vec!["".into()]),
                    ..base()
                }),
                "surfaces[1].antennas[0]",
            ),
        ];
        for (config, field) in cases {
            assert_eq!(config.check().expect_err(field).field, field);
        }
        let named = MultipathConfig {
            taps: vec![TapConfig {
                antenna: Some("top".into()),
                ..tap()
            }],
            surfaces: vec![SurfaceConfig {
                antennas: Some(vec!["top".into(), "bottom".into()]),
                ..base()
            }],
        };
        assert_eq!(
            named.check_antennas(&["top"]).expect_err("bottom").field,
            "surfaces[0].antennas[1]"
        );
        assert_eq!(named.check_antennas(&["top", "bottom"]), Ok(()));
        assert!(named.surfaces[0].applies_to("bottom"));
        assert!(!named.surfaces[0].applies_to("side"));
    }

    #[test]
    fn deserialises_with_defaults() {
        let json = r#"{"taps": [{"delay_m": 3, "relative_amplitude": 0.2}],
            "surfaces": [{"name": "wall", "point_body_m": [0, 0, 0], "normal_body": [1, 0, 0],
                          "reflection_coefficient": 0.3}]}"#;
        let c: MultipathConfig = serde_json::from_str(json).expect("multipath");
        assert_eq!((c.taps[0].phase_deg, c.taps[0].doppler_hz), (0.0, 0.0));
        assert_eq!(c.surfaces[0].phase_deg, 180.0);
        assert_eq!(c.surfaces[0].half_size_m, None);
        assert_eq!(c.check(), Ok(()));
        let empty: MultipathConfig = serde_json::from_str("{}").expect("empty");
        assert_eq!(empty, MultipathConfig::default());
    }

    proptest::proptest! {
        /// For any geometry a visible reflection is delayed by 0..2 |A - P|: d <= |A - P|
        /// and cos i <= 1.
        #[test]
        fn delay_is_bounded_by_twice_the_point_distance(
            p in proptest::array::uniform3(-5.0..5.0f64),
            n in proptest::array::uniform3(-1.0..1.0f64),
            a in proptest::array::uniform3(-5.0..5.0f64),
            u in proptest::array::uniform3(-1.0..1.0f64),
            half in proptest::option::of(proptest::array::uniform2(0.1..10.0f64)),
        ) {
            let (n_v, u_v) = (Vec3::from(n), Vec3::from(u));
            proptest::prop_assume!(n_v.norm() > 1e-3 && u_v.norm() > 1e-3);
            let s = surface(p, n, half);
            let a_m = Vec3::from(a);
            if let Some(path) = surface_path(&s, &a_m, &u_v.normalize()) {
                let bound = 2.0 * (a_m - Vec3::from(p)).norm();
                proptest::prop_assert!(path.delay_m >= 0.0);
                proptest::prop_assert!(path.delay_m <= bound * (1.0 + 1e-12));
            }
        }

        /// In-phase reflections lengthen and anti-phase ones shorten the pseudorange.
        #[test]
        fn bias_sign_follows_the_phase(delta in 0.01..1.0f64, a in 0.05..0.9f64) {
            proptest::prop_assert!(dll_bias_m(&[path(delta, a, 0.0)], CA_CHIP_M, 1023, 1.0) > 0.0);
            proptest::prop_assert!(dll_bias_m(&[path(delta, a, PI)], CA_CHIP_M, 1023, 1.0) < 0.0);
        }
    }
}
