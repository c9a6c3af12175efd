//! One satellite as seen at the receive epoch: transmit time, clock, Sagnac-rotated
//! position, range, line of sight and angles.

use skyforge_orbits::constants::{C_MPS, OMEGA_E_BDS, OMEGA_E_GPS};
use skyforge_orbits::ephemeris::{BoundEphemeris, System};
use skyforge_orbits::frames::geodetic::{Geodetic, ecef_to_geodetic};
use skyforge_orbits::frames::ned::{az_el, c_ecef_ned};
use skyforge_orbits::{Mat3, Vec3};

/// A receiver position this far from the geocentre is a position (m); before the first
/// iteration the estimate is the geocentre and angles are meaningless.
const MIN_POSITION_NORM_M: f64 = 6.0e6;

/// The satellite of one measurement, for a receiver at `r_rx_m`.
#[derive(Debug, Clone, Copy)]
pub struct SatView {
    /// Position at transmit time in the ECEF frame of the receive instant (m).
    pub r_ecef_m: Vec3,
    /// Its velocity in that frame (m/s).
    pub v_ecef_mps: Vec3,
    /// Satellite clock offset for the signal: polynomial + relativity - group delay (s).
    pub clock_s: f64,
    /// Satellite clock drift (s/s).
    pub clock_drift: f64,
    /// Geometric range (m).
    pub range_m: f64,
    /// Unit vector receiver -> satellite (ECEF).
    pub los: Vec3,
    /// Azimuth and elevation at the receiver (rad), when the receiver position is known.
    pub az_el_rad: Option<(f64, f64)>,
}

/// Earth rotation rate of the system's reference frame (rad/s).
fn omega_e(system: System) -> f64 {
    match system {
        System::Gps => OMEGA_E_GPS,
        System::Beidou => OMEGA_E_BDS,
    }
}

/// Rotation about Z by `-angle` (the frame turning by `angle` while the signal flies).
fn earth_turned(v: &Vec3, angle_rad: f64) -> Vec3 {
    let (s, c) = angle_rad.sin_cos();
    Vec3::new(c * v.x + s * v.y, -s * v.x + c * v.y, v.z)
}

/// The satellite of `eph` whose signal, received at `t_rx_s` (receiver time tag, s since
/// the ephemeris origin), measured `pseudorange_m`.
///
/// The transmit time in satellite time is `t_rx - P / c` whatever the receiver clock (the
/// pseudorange carries it); the satellite clock turns it into system time. The position
/// is then rotated by the Earth's rotation during the flight time (IS-GPS-200
/// 20.3.3.4.3.3.2), iterated twice for the flight time itself.
pub fn sat_view(eph: &BoundEphemeris, t_rx_s: f64, pseudorange_m: f64, r_rx_m: &Vec3) -> SatView {
    Transmitted::of(eph, t_rx_s, pseudorange_m).seen_from(r_rx_m, local_frame(r_rx_m).as_ref())
}

/// The ECEF-to-NED rotation at `r_rx_m`, when it is a position (not the geocentre an
/// iteration starts from): what azimuth and elevation need, once per receiver position.
pub fn local_frame(r_rx_m: &Vec3) -> Option<Mat3> {
    local_frame_at(r_rx_m, || ecef_to_geodetic(r_rx_m))
}

/// [`local_frame`] with the geodetic position of `r_rx_m` given by `geodetic` (called
/// only when `r_rx_m` is a position).
pub fn local_frame_at(r_rx_m: &Vec3, geodetic: impl FnOnce() -> Geodetic) -> Option<Mat3> {
    (r_rx_m.norm() > MIN_POSITION_NORM_M).then(|| {
        let g = geodetic();
        c_ecef_ned(g.lat_rad, g.lon_rad)
    })
}

/// The satellite of one measurement at its transmit time, in the ECEF frame of that
/// instant: all of [`sat_view`] that does not depend on where the receiver is, so that a
/// least-squares iteration moving the receiver computes it once.
#[derive(Debug, Clone, Copy)]
pub struct Transmitted {
    r_ecef_m: Vec3,
    v_ecef_mps: Vec3,
    clock_s: f64,
    clock_drift: f64,
    omega_e: f64,
}

impl Transmitted {
    /// The satellite of `eph` whose signal, received at `t_rx_s`, measured `pseudorange_m`.
    pub fn of(eph: &BoundEphemeris, t_rx_s: f64, pseudorange_m: f64) -> Self {
        let t_sv = t_rx_s - pseudorange_m / C_MPS;
        // IS-GPS-200 20.3.3.3.3.1: dt evaluated at t_sv is accurate to far below a ns.
        let clock_s = eph.clock_offset_s(t_sv) - eph.eph.tgd_s;
        let t_tx = t_sv - clock_s;
        let (r_ecef_m, v_ecef_mps, clock_drift) = eph.state_and_clock_drift(t_tx);
        Transmitted {
            r_ecef_m,
            v_ecef_mps,
            clock_s,
            clock_drift,
            omega_e: omega_e(eph.eph.sat.system),
        }
    }

    /// The same satellite `dt_s` seconds later, moved along its velocity: what a receiver
    /// a baseline away sees when its flight time differs by `-dt_s`. The acceleration of a
    /// GNSS orbit (0.6 m/s^2) leaves 0.3 dt^2 m: 3e-11 m at the 10 us of a 3 km baseline.
    pub fn later(&self, dt_s: f64) -> Self {
        Self {
            r_ecef_m: self.r_ecef_m + self.v_ecef_mps * dt_s,
            clock_s: self.clock_s + self.clock_drift * dt_s,
            ..*self
        }
    }

    /// The view from `r_rx_m`, with azimuth and elevation when `frame` (the receiver's
    /// [`local_frame`]) is given.
    pub fn seen_from(&self, r_rx_m: &Vec3, frame: Option<&Mat3>) -> SatView {
        let (r0, w) = (self.r_ecef_m, self.omega_e);
        let mut flight_s = (r0 - r_rx_m).norm() / C_MPS;
        let mut r = r0;
        for _ in 0..2 {
            r = earth_turned(&r0, w * flight_s);
            flight_s = (r - r_rx_m).norm() / C_MPS;
        }
        let v = earth_turned(&self.v_ecef_mps, w * flight_s);
        let d = r - r_rx_m;
        let range_m = d.norm();
        let los = d / range_m;
        SatView {
            r_ecef_m: r,
            v_ecef_mps: v,
            clock_s: self.clock_s,
            clock_drift: self.clock_drift,
            range_m,
            los,
            az_el_rad: frame.map(|c| az_el(&(c * los))),
        }
    }
}
