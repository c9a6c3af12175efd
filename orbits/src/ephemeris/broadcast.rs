//! Broadcast ephemeris parameters and the user algorithms: GPS LNAV (IS-GPS-200 table
//! 20-IV, relativistic clock correction, TGD) and BeiDou D1/D2 (BDS-SIS-ICD, MEO/IGSO and
//! the GEO transformation, BDT) and Galileo I/NAV and F/NAV (Galileo OS SIS ICD Issue 2.1
//! §5.1.1 and §5.1.4: the GPS user algorithm with the GTRF constants, GST).
//!
//! Velocity is the analytic time derivative of the same model (not a finite difference), so
//! position and velocity are exactly consistent; the tests check it against a central
//! difference of the position.

use super::sat_id::{SatId, System, SystemConstants, system_constants};
use crate::Vec3;
use crate::angles::wrap_pi;
use crate::time::TimeOrigin;
use hifitime::{Epoch, TimeScale};
use std::f64::consts::{PI, TAU};

/// Tilt of the BeiDou GEO computation frame (-5 deg about X), BDS-SIS-ICD 5.2.4.
const BDS_GEO_TILT_RAD: f64 = -5.0 * PI / 180.0;

/// Convergence threshold of the Kepler-equation iteration (rad).
const KEPLER_TOL_RAD: f64 = 1e-15;
/// Iteration cap of the Kepler solver (Newton converges in 3-5 steps for e < 0.1).
const KEPLER_MAX_ITER: usize = 30;

/// The navigation message an ephemeris is broadcast in: it says which signals the clock
/// polynomial refers to and which group delay [`ClockParams::tgd_s`] holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum NavMessage {
    /// GPS LNAV: clock for the L1/L2 P(Y) ionosphere-free pair, TGD (IS-GPS-200
    /// 20.3.3.3.3.2).
    GpsLnav,
    /// BeiDou D1/D2: clock for B3I, TGD1 for B1I (BDS-SIS-ICD-B1I-3.0 §5.2.4.10).
    BdsD1D2,
    /// Galileo I/NAV (E1-B, E5b-I): clock for the E1/E5b pair, BGD(E1,E5b) (Galileo OS SIS
    /// ICD §5.1.5).
    GalileoInav,
    /// Galileo F/NAV (E5a-I): clock for the E1/E5a pair, BGD(E1,E5a) (Galileo OS SIS ICD
    /// §5.1.5).
    GalileoFnav,
}

impl NavMessage {
    /// The message SkyForge assumes for `system` where nothing says otherwise: the message
    /// of the signal it transmits (Galileo: F/NAV, the message of E5a).
    pub fn default_for(system: System) -> Self {
        match system {
            System::Gps => Self::GpsLnav,
            System::Beidou => Self::BdsD1D2,
            System::Galileo => Self::GalileoFnav,
        }
    }
}

/// How the orbit is evaluated.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum OrbitClass {
    /// GPS, and BeiDou MEO/IGSO: the standard Keplerian user algorithm.
    Standard,
    /// BeiDou GEO: computed in an inertial-like frame, then rotated by -5 deg about X and
    /// by the Earth rotation since toe about Z (BDS-SIS-ICD 5.2.4).
    BeidouGeo,
}

/// One set of broadcast ephemeris and clock parameters, as the navigation message carries
/// them (SI units: m, rad, s, rad/s).
#[derive(Debug, Clone, PartialEq)]
pub struct BroadcastEphemeris {
    pub sat: SatId,
    pub class: OrbitClass,
    /// The message the set is broadcast in.
    pub message: NavMessage,
    /// Reference time of ephemeris (in the system's own time scale).
    pub toe: Epoch,
    /// Reference time of clock.
    pub toc: Epoch,
    /// Keplerian elements at toe and their rates.
    pub orbit: KeplerElements,
    /// Harmonic correction amplitudes.
    pub harmonics: HarmonicCorrections,
    /// Clock polynomial at toc and group delay.
    pub clock: ClockParams,
    /// Issue of data (IODE for GPS, AODE for BeiDou).
    pub iode: u32,
    /// Issue of data, clock (IODC for GPS, AODC for BeiDou).
    pub iodc: u32,
    /// 0 = healthy.
    pub health: u32,
    /// Fit interval (s) around toe within which the set may be used.
    pub fit_interval_s: f64,
}

/// The Keplerian part of an ephemeris: elements at toe and their rates (m^1/2, rad,
/// rad/s).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct KeplerElements {
    pub sqrt_a: f64,
    pub e: f64,
    pub i0: f64,
    pub omega0: f64,
    pub omega: f64,
    pub m0: f64,
    pub delta_n: f64,
    pub idot: f64,
    pub omega_dot: f64,
}

impl KeplerElements {
    /// The corrected mean motion n = sqrt(mu / A^3) + delta_n (rad/s), A = sqrt_a^2
    /// (IS-GPS-200 table 20-IV; BDS-SIS-ICD-B1I-3.0 table 5-11).
    pub fn mean_motion_rad_s(&self, gm: f64) -> f64 {
        let a_m = self.sqrt_a * self.sqrt_a;
        (gm / (a_m * a_m * a_m)).sqrt() + self.delta_n
    }
}

/// The harmonic correction amplitudes of an ephemeris: argument of latitude and
/// inclination (rad), radius (m).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct HarmonicCorrections {
    pub cuc: f64,
    pub cus: f64,
    pub crc: f64,
    pub crs: f64,
    pub cic: f64,
    pub cis: f64,
}

/// The clock part of an ephemeris: polynomial (s, s/s, s/s^2) and group delay (s).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ClockParams {
    pub af0: f64,
    pub af1: f64,
    pub af2: f64,
    /// The message's group delay ([`NavMessage`]): GPS TGD; BeiDou TGD1 (B1I); Galileo
    /// BGD(E1,E5b) in I/NAV, BGD(E1,E5a) in F/NAV.
    pub tgd_s: f64,
    /// A second group delay where the message has one: Galileo I/NAV's BGD(E1,E5a); 0
    /// otherwise (BeiDou's TGD2 is not kept).
    pub tgd2_s: f64,
}

/// An ephemeris bound to a scenario time origin: evaluates at `t_s` seconds since the start.
///
/// Built only by [`BroadcastEphemeris::bind`], which also precomputes the constants of the
/// user algorithm (the public fields are read-only in spirit: changing `eph` afterwards
/// does not update them; bind again instead).
#[derive(Debug, Clone, PartialEq)]
pub struct BoundEphemeris {
    pub eph: BroadcastEphemeris,
    /// toe, seconds since the scenario start.
    pub toe_s: f64,
    /// toc, seconds since the scenario start.
    pub toc_s: f64,
    k: Precomputed,
}

/// Per-ephemeris constants of the user algorithm, computed once in `bind`.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Precomputed {
    /// Semi-major axis A = sqrt_a^2 (m).
    a_m: f64,
    /// Corrected mean motion n = sqrt(mu / A^3) + delta_n (rad/s).
    n_rad_s: f64,
    /// sqrt(1 - e^2).
    sqrt_1_e2: f64,
    /// Omega at tk = 0: Omega0 - OMEGA_E * toe_sow (rad).
    node_at_toe_rad: f64,
    /// dOmega/dtk: Omega_dot - OMEGA_E (standard) or Omega_dot (BeiDou GEO frame) (rad/s).
    node_rate_rad_s: f64,
    /// Earth rotation rate of the system (rad/s).
    omega_e_rad_s: f64,
    /// F e sqrt(A) (s), the amplitude of the relativistic clock term.
    rel_amp_s: f64,
    geo: bool,
}

/// The orbit in the (possibly rotating) computation frame at one instant, with what the
/// velocity needs.
struct PlaneState {
    r_m: Vec3,
    sin_e: f64,
    cos_e: f64,
    sin_2phi: f64,
    cos_2phi: f64,
    r_orb_m: f64,
    sin_u: f64,
    cos_u: f64,
    sin_i: f64,
    cos_i: f64,
    sin_o: f64,
    cos_o: f64,
}

impl BroadcastEphemeris {
    /// The ephemeris of `sat` with `orbit`, `harmonics` and `clock` referred to `toe`
    /// (also the clock's reference time toc), usable for `fit_interval_s` around it;
    /// issues of data 0, healthy, in the system's default message
    /// ([`NavMessage::default_for`]). Other values (a separate toc, issues of data, health,
    /// the message) are set with struct-update syntax on the result.
    pub fn from_elements(
        sat: SatId,
        class: OrbitClass,
        toe: Epoch,
        orbit: KeplerElements,
        harmonics: HarmonicCorrections,
        clock: ClockParams,
        fit_interval_s: f64,
    ) -> Self {
        Self {
            sat,
            class,
            message: NavMessage::default_for(sat.system),
            toe,
            toc: toe,
            orbit,
            harmonics,
            clock,
            iode: 0,
            iodc: 0,
            health: 0,
            fit_interval_s,
        }
    }

    /// The same clock with toc moved to `toc` (any class): the polynomial re-centred,
    /// af0' = af0 + af1 dc + af2 dc^2, af1' = af1 + 2 af2 dc with dc = toc' - toc (exact).
    pub fn reexpressed_clock(&self, toc: Epoch) -> Self {
        let mut out = self.clone();
        let dc = (toc - self.toc).to_seconds();
        if dc != 0.0 {
            out.toc = toc;
            out.clock.af0 = self.clock.af0 + self.clock.af1 * dc + self.clock.af2 * dc * dc;
            out.clock.af1 = self.clock.af1 + 2.0 * self.clock.af2 * dc;
        }
        out
    }

    /// The same orbit and clock with toe moved to `toe` and toc to `toc`, for a message
    /// whose reference times lie on a grid (BeiDou 8 s, Galileo 60 s); `None` for a BeiDou
    /// GEO set, whose computation frame is tied to the Earth at toe. The clock as
    /// [`Self::reexpressed_clock`]; with d = toe' - toe, exact for any set of the standard
    /// algorithm: M0' = M0 + n d, i0' = i0 + IDOT d,
    /// Omega0' = Omega0 + Omega_dot d + OMEGA_E (toe'_sow - toe_sow - d), so that mean
    /// anomaly, node and inclination (IS-GPS-200 table 20-IV) are the same functions of
    /// time, across a week boundary too.
    pub fn reexpressed(&self, toe: Epoch, toc: Epoch) -> Option<Self> {
        if self.class != OrbitClass::Standard {
            return None;
        }
        let k = system_constants(self.sat.system);
        let mut out = self.reexpressed_clock(toc);
        let d = (toe - self.toe).to_seconds();
        if d == 0.0 {
            // Nothing moves: the orbit as it was, bit for bit.
            return Some(out);
        }
        let sow_shift = seconds_of_week(toe, k.scale) - seconds_of_week(self.toe, k.scale) - d;
        out.toe = toe;
        out.orbit.m0 = wrap_pi(self.orbit.m0 + self.orbit.mean_motion_rad_s(k.gm) * d);
        out.orbit.i0 = self.orbit.i0 + self.orbit.idot * d;
        out.orbit.omega0 =
            wrap_pi(self.orbit.omega0 + self.orbit.omega_dot * d + k.omega_e * sow_shift);
        Some(out)
    }

    /// Bind to a scenario origin.
    pub fn bind(&self, origin: &TimeOrigin) -> BoundEphemeris {
        let toe_s = (self.toe - origin.start()).to_seconds();
        let toc_s = (self.toc - origin.start()).to_seconds();
        let SystemConstants {
            gm,
            omega_e,
            f_rel,
            scale,
        } = system_constants(self.sat.system);
        let toe_sow = seconds_of_week(self.toe, scale);
        let a_m = self.orbit.sqrt_a * self.orbit.sqrt_a;
        let geo = self.class == OrbitClass::BeidouGeo;
        let k = Precomputed {
            a_m,
            n_rad_s: self.orbit.mean_motion_rad_s(gm),
            sqrt_1_e2: (1.0 - self.orbit.e * self.orbit.e).sqrt(),
            node_at_toe_rad: self.orbit.omega0 - omega_e * toe_sow,
            node_rate_rad_s: if geo {
                self.orbit.omega_dot
            } else {
                self.orbit.omega_dot - omega_e
            },
            omega_e_rad_s: omega_e,
            rel_amp_s: f_rel * self.orbit.e * self.orbit.sqrt_a,
            geo,
        };
        BoundEphemeris {
            eph: self.clone(),
            toe_s,
            toc_s,
            k,
        }
    }
}

/// Seconds of week of `epoch` in `scale` (GPST, BDT or GST, whose weeks begin with GPST's),
/// exact to the nanosecond.
pub(crate) fn seconds_of_week(epoch: Epoch, scale: TimeScale) -> f64 {
    let (_, ns) = epoch.to_time_scale(scale).to_time_of_week();
    ns as f64 * 1e-9
}

/// Eccentric anomaly from the mean anomaly (Kepler's equation M = E - e sin E), Newton
/// iteration to |dE| <= 1e-15 rad (IS-GPS-200 table 20-IV).
fn eccentric_anomaly(m_rad: f64, e: f64) -> f64 {
    let m = m_rad - TAU * (m_rad / TAU).round();
    let mut ea = if e < 0.8 { m } else { PI.copysign(m) };
    for _ in 0..KEPLER_MAX_ITER {
        let (s, c) = ea.sin_cos();
        let d = (ea - e * s - m) / (1.0 - e * c);
        ea -= d;
        if d.abs() <= KEPLER_TOL_RAD {
            break;
        }
    }
    ea
}

impl BoundEphemeris {
    /// The user algorithm up to the position in the computation frame (ECEF for the
    /// standard class, the BeiDou GEO inertial-like frame otherwise).
    /// IS-GPS-200 table 20-IV; BDS-SIS-ICD 5.2.4.
    #[inline]
    fn plane_state(&self, tk: f64) -> PlaneState {
        let p = &self.eph;
        let k = &self.k;
        let ea = eccentric_anomaly(p.orbit.m0 + k.n_rad_s * tk, p.orbit.e);
        let (sin_e, cos_e) = ea.sin_cos();
        let nu = (k.sqrt_1_e2 * sin_e).atan2(cos_e - p.orbit.e);
        let phi = nu + p.orbit.omega;
        let (sin_2phi, cos_2phi) = (2.0 * phi).sin_cos();
        let u_rad = phi + p.harmonics.cus * sin_2phi + p.harmonics.cuc * cos_2phi;
        let r_orb_m = k.a_m * (1.0 - p.orbit.e * cos_e)
            + p.harmonics.crs * sin_2phi
            + p.harmonics.crc * cos_2phi;
        let i_rad = p.orbit.i0
            + p.orbit.idot * tk
            + p.harmonics.cis * sin_2phi
            + p.harmonics.cic * cos_2phi;
        let node_rad = k.node_at_toe_rad + k.node_rate_rad_s * tk;
        let (sin_u, cos_u) = u_rad.sin_cos();
        let (xp, yp) = (r_orb_m * cos_u, r_orb_m * sin_u);
        let (sin_i, cos_i) = i_rad.sin_cos();
        let (sin_o, cos_o) = node_rad.sin_cos();
        PlaneState {
            r_m: Vec3::new(
                xp * cos_o - yp * cos_i * sin_o,
                xp * sin_o + yp * cos_i * cos_o,
                yp * sin_i,
            ),
            sin_e,
            cos_e,
            sin_2phi,
            cos_2phi,
            r_orb_m,
            sin_u,
            cos_u,
            sin_i,
            cos_i,
            sin_o,
            cos_o,
        }
    }

    /// Rotation of the BeiDou GEO frame into ECEF: Rz(OMEGA_E tk) Rx(-5 deg)
    /// (BDS-SIS-ICD 5.2.4; both are frame rotations, R(a) = [[1,0,0],[0,c,s],[0,-s,c]]).
    #[inline]
    fn geo_to_ecef(&self, tk: f64, v: Vec3) -> Vec3 {
        let (s5, c5) = BDS_GEO_TILT_RAD.sin_cos();
        let y = c5 * v.y + s5 * v.z;
        let z = -s5 * v.y + c5 * v.z;
        let (sz, cz) = (self.k.omega_e_rad_s * tk).sin_cos();
        Vec3::new(cz * v.x + sz * y, -sz * v.x + cz * y, z)
    }

    /// Antenna phase-centre position (ECEF at the same instant, m) at `t_s`.
    pub fn position_ecef(&self, t_s: f64) -> Vec3 {
        let tk = t_s - self.toe_s;
        let st = self.plane_state(tk);
        if self.k.geo {
            self.geo_to_ecef(tk, st.r_m)
        } else {
            st.r_m
        }
    }

    /// Position and velocity (ECEF, m and m/s) at `t_s`. The velocity is the analytic
    /// derivative of the user algorithm (IS-GPS-200 table 20-IV differentiated; for the
    /// BeiDou GEO the rotating-frame term OMEGA_E x r is added).
    pub fn state_ecef(&self, t_s: f64) -> (Vec3, Vec3) {
        let (r, v, _) = self.state_and_clock_drift(t_s);
        (r, v)
    }

    /// [`Self::state_ecef`] and [`Self::clock_drift`] at `t_s` from one solution of
    /// Kepler's equation.
    pub fn state_and_clock_drift(&self, t_s: f64) -> (Vec3, Vec3, f64) {
        let tk = t_s - self.toe_s;
        let p = &self.eph;
        let k = &self.k;
        let st = self.plane_state(tk);
        let one_m_ecos = 1.0 - p.orbit.e * st.cos_e;
        let e_dot = k.n_rad_s / one_m_ecos;
        let clock_drift = self.clock_drift_from(t_s, st.cos_e, e_dot);
        let nu_dot = k.sqrt_1_e2 * e_dot / one_m_ecos;
        let (s2, c2) = (st.sin_2phi, st.cos_2phi);
        let u_dot = nu_dot * (1.0 + 2.0 * (p.harmonics.cus * c2 - p.harmonics.cuc * s2));
        let r_dot = k.a_m * p.orbit.e * st.sin_e * e_dot
            + 2.0 * nu_dot * (p.harmonics.crs * c2 - p.harmonics.crc * s2);
        let i_dot = p.orbit.idot + 2.0 * nu_dot * (p.harmonics.cis * c2 - p.harmonics.cic * s2);
        let node_dot = k.node_rate_rad_s;

        let (sin_u, cos_u) = (st.sin_u, st.cos_u);
        let yp = st.r_orb_m * sin_u;
        let xp_dot = r_dot * cos_u - st.r_orb_m * u_dot * sin_u;
        let yp_dot = r_dot * sin_u + st.r_orb_m * u_dot * cos_u;
        let (sin_i, cos_i) = (st.sin_i, st.cos_i);
        let (sin_o, cos_o) = (st.sin_o, st.cos_o);
        let r = st.r_m;
        let v = Vec3::new(
            xp_dot * cos_o - yp_dot * cos_i * sin_o + yp * sin_i * sin_o * i_dot - r.y * node_dot,
            xp_dot * sin_o + yp_dot * cos_i * cos_o - yp * sin_i * cos_o * i_dot + r.x * node_dot,
            yp_dot * sin_i + yp * cos_i * i_dot,
        );
        if k.geo {
            let r_ecef = self.geo_to_ecef(tk, r);
            let w = k.omega_e_rad_s;
            let v_ecef = self.geo_to_ecef(tk, v) + Vec3::new(w * r_ecef.y, -w * r_ecef.x, 0.0);
            (r_ecef, v_ecef, clock_drift)
        } else {
            (r, v, clock_drift)
        }
    }

    /// Eccentric anomaly at `t_s` (rad).
    fn eccentric_anomaly_at(&self, t_s: f64) -> f64 {
        eccentric_anomaly(
            self.eph.orbit.m0 + self.k.n_rad_s * (t_s - self.toe_s),
            self.eph.orbit.e,
        )
    }

    /// Satellite clock offset (s) at `t_s`: polynomial plus relativistic correction, without TGD.
    /// IS-GPS-200 20.3.3.3.3.1: af0 + af1 dt + af2 dt^2 + F e sqrt(A) sin(Ek), dt = t - toc.
    pub fn clock_offset_s(&self, t_s: f64) -> f64 {
        self.clock_offset_from(t_s, self.eccentric_anomaly_at(t_s).sin())
    }

    /// [`Self::clock_offset_s`] at `t_s` with sin(Ek) known.
    fn clock_offset_from(&self, t_s: f64, sin_e: f64) -> f64 {
        let dt = t_s - self.toc_s;
        let p = &self.eph;
        p.clock.af0 + dt * (p.clock.af1 + dt * p.clock.af2) + self.k.rel_amp_s * sin_e
    }

    /// [`Self::clock_offset_s`] and [`Self::clock_drift`] at `t_s` from one solution of
    /// Kepler's equation.
    pub fn clock_offset_and_drift(&self, t_s: f64) -> (f64, f64) {
        let (sin_e, cos_e) = self.eccentric_anomaly_at(t_s).sin_cos();
        let e_dot = self.k.n_rad_s / (1.0 - self.eph.orbit.e * cos_e);
        (
            self.clock_offset_from(t_s, sin_e),
            self.clock_drift_from(t_s, cos_e, e_dot),
        )
    }

    /// Satellite clock drift (s/s) at `t_s`, including the relativistic term's derivative
    /// F e sqrt(A) cos(Ek) dEk/dt with dEk/dt = n / (1 - e cos Ek).
    pub fn clock_drift(&self, t_s: f64) -> f64 {
        let cos_e = self.eccentric_anomaly_at(t_s).cos();
        let e_dot = self.k.n_rad_s / (1.0 - self.eph.orbit.e * cos_e);
        self.clock_drift_from(t_s, cos_e, e_dot)
    }

    /// [`Self::clock_drift`] at `t_s` with cos(Ek) and dEk/dt known.
    fn clock_drift_from(&self, t_s: f64, cos_e: f64, e_dot: f64) -> f64 {
        let dt = t_s - self.toc_s;
        let p = &self.eph;
        p.clock.af1 + 2.0 * p.clock.af2 * dt + self.k.rel_amp_s * cos_e * e_dot
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::constants::{GM_GPS, OMEGA_E_GPS};
    use hifitime::Unit;
    use proptest::prelude::*;

    /// A GPS-like ephemeris with eccentricity and all harmonic terms non-zero.
    fn gps_eph(toe: Epoch) -> BroadcastEphemeris {
        let orbit = KeplerElements {
            sqrt_a: 5153.65,
            e: 0.0125,
            i0: 0.9898,
            omega0: 2.337,
            omega: 0.9395,
            m0: -2.6358,
            delta_n: 3.65e-9,
            idot: -2.0e-11,
            omega_dot: -7.465e-9,
        };
        let harmonics = HarmonicCorrections {
            cuc: -3.58e-6,
            cus: 1.12e-5,
            crc: 176.9,
            crs: -66.8,
            cic: -2.98e-8,
            cis: -2.42e-7,
        };
        let clock = ClockParams {
            af0: 2.0375e-4,
            af1: -3.865e-12,
            af2: 1.0e-19,
            tgd_s: 4.66e-9,
            tgd2_s: 0.0,
        };
        BroadcastEphemeris {
            iode: 59,
            iodc: 59,
            ..BroadcastEphemeris::from_elements(
                SatId::gps(7),
                OrbitClass::Standard,
                toe,
                orbit,
                harmonics,
                clock,
                4.0 * 3600.0,
            )
        }
    }

    fn origin() -> TimeOrigin {
        TimeOrigin::new(Epoch::from_gregorian(
            2023,
            3,
            12,
            0,
            0,
            0,
            0,
            TimeScale::GPST,
        ))
    }

    fn toe() -> Epoch {
        origin().start() + 2.0 * Unit::Hour
    }

    #[test]
    fn a_reexpressed_set_is_the_same_orbit_and_clock() {
        let base = gps_eph(toe());
        let o = origin();
        for shift_s in [-37.0, 8.0, 29.5, 3.0 * 86_400.0 + 123.0] {
            // The last shift crosses into the next GPS week (toe Thursday 2020-06-25
            // 02:00, moved to Sunday), where the seconds of week wrap.
            let toe2 = base.toe + shift_s * Unit::Second;
            let toc2 = base.toc - 0.5 * shift_s * Unit::Second;
            let moved = base.reexpressed(toe2, toc2).expect("standard class");
            let (a, b) = (base.bind(&o), moved.bind(&o));
            for t in [0.0, 1800.0, 7200.0, 4.0 * 86_400.0] {
                let d = (a.position_ecef(t) - b.position_ecef(t)).norm();
                assert!(d < 1e-5, "shift {shift_s}: {d} m at {t} s");
                let dc = (a.clock_offset_s(t) - b.clock_offset_s(t)).abs();
                assert!(dc < 1e-15, "shift {shift_s}: clock {dc:e} s");
            }
        }
        let geo = BroadcastEphemeris {
            class: OrbitClass::BeidouGeo,
            ..base.clone()
        };
        assert!(geo.reexpressed(base.toe, base.toc).is_none());
    }

    #[test]
    fn kepler_solution_satisfies_the_equation() {
        for &e in &[0.0, 0.001, 0.02, 0.3, 0.7, 0.95] {
            for i in 0..200 {
                let m = -10.0 + 0.1 * f64::from(i);
                let ea = eccentric_anomaly(m, e);
                let resid = ea - e * ea.sin() - (m - TAU * (m / TAU).round());
                assert!(resid.abs() < 4e-15, "e={e} m={m} resid={resid:e}");
            }
        }
    }

    #[test]
    fn toe_seconds_of_week_in_system_scale() {
        // 2023-03-12 00:00 GPST is the start of GPS week 2253; the same reading in BDT is
        // the start of BDT week 897 (BDT = GPST - 14 s).
        let gps = Epoch::from_gregorian(2023, 3, 12, 0, 0, 0, 0, TimeScale::GPST);
        let bdt = Epoch::from_gregorian(2023, 3, 12, 0, 0, 0, 0, TimeScale::BDT);
        assert_eq!(gps.to_time_scale(TimeScale::GPST).to_time_of_week().0, 2253);
        assert_eq!(bdt.to_time_scale(TimeScale::BDT).to_time_of_week().0, 897);
        assert_eq!(seconds_of_week(gps, TimeScale::GPST), 0.0);
        assert_eq!(seconds_of_week(bdt, TimeScale::BDT), 0.0);
        assert!(((bdt - gps).to_seconds() - 14.0).abs() < 1e-9);
        assert_eq!(seconds_of_week(gps, TimeScale::BDT), 604_800.0 - 14.0);
    }

    #[test]
    fn bind_maps_toe_and_toc_to_scenario_seconds() {
        let b = gps_eph(toe()).bind(&origin());
        assert_eq!(b.toe_s, 7200.0);
        assert_eq!(b.toc_s, 7200.0);
    }

    #[test]
    fn radius_without_harmonics_is_a_one_minus_e_cos_e() {
        let mut eph = gps_eph(toe());
        eph.harmonics.crc = 0.0;
        eph.harmonics.crs = 0.0;
        let b = eph.bind(&origin());
        for i in 0..50 {
            let t = 7200.0 + 600.0 * f64::from(i) - 14_400.0;
            let ea = b.eccentric_anomaly_at(t);
            let expect = eph.orbit.sqrt_a.powi(2) * (1.0 - eph.orbit.e * ea.cos());
            let got = b.position_ecef(t).norm();
            assert!(
                (got - expect).abs() < 1e-6,
                "t={t} got={got} expect={expect}"
            );
        }
    }

    #[test]
    fn radius_with_harmonics_adds_the_radial_correction() {
        let eph = gps_eph(toe());
        let b = eph.bind(&origin());
        let t = 9000.0;
        let st = b.plane_state(t - b.toe_s);
        let expect = eph.orbit.sqrt_a.powi(2) * (1.0 - eph.orbit.e * st.cos_e)
            + eph.harmonics.crs * st.sin_2phi
            + eph.harmonics.crc * st.cos_2phi;
        assert!((b.position_ecef(t).norm() - expect).abs() < 1e-6);
    }

    /// Central difference with h = 0.05 s: truncation ~1e-9 m/s, rounding ~1e-7 m/s.
    fn numeric_velocity(b: &BoundEphemeris, t: f64) -> Vec3 {
        let h = 0.05;
        (b.position_ecef(t + h) - b.position_ecef(t - h)) / (2.0 * h)
    }

    /// Over 30 instants 500 s apart: the state's position is `position_ecef`'s, its
    /// velocity the position's derivative, and the one-Kepler state with clock drift the
    /// same numbers as the separate calls.
    fn assert_state_consistent(b: &BoundEphemeris) {
        for i in 0..30 {
            let t = 500.0 * f64::from(i);
            let (r, v) = b.state_ecef(t);
            assert_eq!(r, b.position_ecef(t));
            assert_eq!(b.state_and_clock_drift(t), (r, v, b.clock_drift(t)));
            let err = (v - numeric_velocity(b, t)).norm();
            assert!(err < 1e-5, "t={t} velocity error {err} m/s");
        }
    }

    #[test]
    fn velocity_is_the_derivative_of_position() {
        assert_state_consistent(&gps_eph(toe()).bind(&origin()));
    }

    #[test]
    fn geo_velocity_is_the_derivative_of_position() {
        let mut eph = gps_eph(toe());
        eph.sat = SatId::beidou(1);
        eph.class = OrbitClass::BeidouGeo;
        eph.orbit.sqrt_a = 6493.3;
        eph.orbit.i0 = 0.09;
        eph.orbit.e = 4.6e-4;
        assert_state_consistent(&eph.bind(&origin()));
    }

    #[test]
    fn clock_drift_is_the_derivative_of_clock_offset() {
        let b = gps_eph(toe()).bind(&origin());
        for i in 0..20 {
            let t = 1000.0 * f64::from(i);
            let h = 1.0;
            let num = (b.clock_offset_s(t + h) - b.clock_offset_s(t - h)) / (2.0 * h);
            let d = b.clock_drift(t);
            assert!((num - d).abs() < 1e-17, "t={t} {num:e} vs {d:e}");
            assert_eq!(b.clock_offset_and_drift(t), (b.clock_offset_s(t), d));
        }
    }

    #[test]
    fn relativistic_clock_term_amplitude() {
        // For e = 0.0125 and sqrt(A) = 5153.65 the amplitude is |F| e sqrt(A) = 28.6 ns.
        let mut eph = gps_eph(toe());
        eph.clock.af0 = 0.0;
        eph.clock.af1 = 0.0;
        eph.clock.af2 = 0.0;
        let b = eph.bind(&origin());
        let max = (0..4320)
            .map(|i| b.clock_offset_s(f64::from(i) * 10.0).abs())
            .fold(0.0, f64::max);
        let expect = 4.442_807_633e-10 * 0.0125 * 5153.65;
        assert!((max - expect).abs() < 1e-12, "{max:e} vs {expect:e}");
    }

    #[test]
    fn period_is_two_pi_over_mean_motion() {
        let mut eph = gps_eph(toe());
        eph.orbit.delta_n = 0.0;
        eph.orbit.omega_dot = OMEGA_E_GPS; // inertially fixed node in ECEF-rotating terms
        eph.orbit.idot = 0.0;
        eph.harmonics.cuc = 0.0;
        eph.harmonics.cus = 0.0;
        eph.harmonics.crc = 0.0;
        eph.harmonics.crs = 0.0;
        eph.harmonics.cic = 0.0;
        eph.harmonics.cis = 0.0;
        let b = eph.bind(&origin());
        let a = eph.orbit.sqrt_a.powi(2);
        let period = TAU / (GM_GPS / (a * a * a)).sqrt();
        // With Omega_dot = OMEGA_E the node does not move in the computation frame, so the
        // orbit closes after exactly one Keplerian period.
        let r0 = b.position_ecef(b.toe_s);
        let r1 = b.position_ecef(b.toe_s + period);
        assert!((r1 - r0).norm() < 1e-5, "{}", (r1 - r0).norm());
        let r_half = b.position_ecef(b.toe_s + period / 2.0);
        assert!((r_half - r0).norm() > 2.0e7);
    }

    proptest! {
        #[test]
        fn position_is_finite_and_radius_bounded(
            t in -1.0e5f64..1.0e5,
            e in 0.0f64..0.05,
            m0 in -PI..PI,
        ) {
            let mut eph = gps_eph(toe());
            eph.orbit.e = e;
            eph.orbit.m0 = m0;
            let b = eph.bind(&origin());
            let r = b.position_ecef(t).norm();
            let a = eph.orbit.sqrt_a.powi(2);
            prop_assert!(r > a * (1.0 - e) - 500.0 && r < a * (1.0 + e) + 500.0);
        }
    }
}
