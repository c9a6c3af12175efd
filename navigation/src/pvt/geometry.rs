//! One satellite as seen at the receive epoch: transmit time, clock, Sagnac-rotated
//! position, range, line of sight and angles.

use skyforge_orbits::constants::C_MPS;
use skyforge_orbits::ephemeris::{BoundEphemeris, SatId};
use skyforge_orbits::frames::{Geodetic, ecef_to_geodetic};
use skyforge_orbits::frames::{az_el, c_ecef_ned};
use skyforge_orbits::{Mat3, Vec3};
use std::collections::BTreeMap;

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
        let clock_s = eph.clock_offset_s(t_sv) - eph.eph.clock.tgd_s;
        let t_tx = t_sv - clock_s;
        let (r_ecef_m, v_ecef_mps, clock_drift) = eph.state_and_clock_drift(t_tx);
        Transmitted {
            r_ecef_m,
            v_ecef_mps,
            clock_s,
            clock_drift,
            omega_e: eph.eph.sat.system.earth_rotation_rad_s(),
        }
    }

    /// The same satellite with its clock `dt_s` later (another signal's group delay).
    pub fn clock_shifted(self, dt_s: f64) -> Self {
        Self {
            clock_s: self.clock_s + dt_s,
            ..self
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

/// Where a least-squares solution takes each satellite at its transmit time from.
pub trait Satellites {
    /// The satellite of `eph` whose signal, received at `t_rx_s`, measured `pseudorange_m`
    /// ([`Transmitted::of`] or as good).
    fn transmitted(&mut self, eph: &BoundEphemeris, t_rx_s: f64, pseudorange_m: f64)
    -> Transmitted;
}

/// Every satellite from its broadcast ephemeris.
#[derive(Debug, Clone, Copy, Default)]
pub struct FromEphemeris;

impl Satellites for FromEphemeris {
    fn transmitted(
        &mut self,
        eph: &BoundEphemeris,
        t_rx_s: f64,
        pseudorange_m: f64,
    ) -> Transmitted {
        Transmitted::of(eph, t_rx_s, pseudorange_m)
    }
}

/// Every satellite from its broadcast ephemeris, kept with its transmit time (satellite
/// time) for the antennas of the same platform ([`NearAntenna`]).
#[derive(Debug, Clone, Default)]
pub struct Recorded {
    by_sat: BTreeMap<SatId, (f64, Transmitted)>,
}

impl Recorded {
    /// Nothing recorded yet.
    pub fn new() -> Self {
        Self::default()
    }
}

impl Satellites for Recorded {
    fn transmitted(
        &mut self,
        eph: &BoundEphemeris,
        t_rx_s: f64,
        pseudorange_m: f64,
    ) -> Transmitted {
        let tx = Transmitted::of(eph, t_rx_s, pseudorange_m);
        self.by_sat
            .insert(eph.eph.sat, (t_rx_s - pseudorange_m / C_MPS, tx));
        tx
    }
}

/// Longest move along the velocity [`NearAntenna`] makes (s): 0.3 m/s^2 x (1 ms)^2 = 3e-7 m.
const MAX_NEAR_SHIFT_S: f64 = 1e-3;

/// The satellites another antenna of the platform recorded at nearly the same transmit
/// times, each moved along its velocity to this antenna's transmit time
/// ([`Transmitted::later`]): an antenna a baseline away differs by the baseline's flight
/// time (3 ns per metre) and its receiver's sampling offset. A satellite it did not
/// record, or recorded more than [`MAX_NEAR_SHIFT_S`] away, comes from its ephemeris.
#[derive(Debug, Clone, Copy)]
pub struct NearAntenna<'a>(pub &'a Recorded);

impl Satellites for NearAntenna<'_> {
    fn transmitted(
        &mut self,
        eph: &BoundEphemeris,
        t_rx_s: f64,
        pseudorange_m: f64,
    ) -> Transmitted {
        let t_sv = t_rx_s - pseudorange_m / C_MPS;
        match self.0.by_sat.get(&eph.eph.sat) {
            Some((t_near, tx)) if (t_sv - t_near).abs() <= MAX_NEAR_SHIFT_S => {
                tx.later(t_sv - t_near)
            }
            _ => Transmitted::of(eph, t_rx_s, pseudorange_m),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use skyforge_orbits::ephemeris::nominal;

    /// An antenna 3 km from the recording one, sampling 0.5 ms later: every satellite moved
    /// from the recorded one lies within a micrometre of its own ephemeris evaluation
    /// (clock within 1e-15 s); one recorded 2 ms away comes from the ephemeris itself.
    #[test]
    fn near_antenna_moves_recorded_satellites_to_its_transmit_times() {
        let start =
            hifitime::Epoch::from_gregorian(2023, 3, 12, 0, 0, 0, 0, hifitime::TimeScale::GPST);
        let store = nominal::gps_store(start);
        let (t_a, t_b) = (600.0, 600.0005);
        let mut recorded = Recorded::new();
        let mut checked = 0;
        for prn in 1..=32 {
            let Some(eph) = store.select(SatId::gps(prn), t_a) else {
                continue;
            };
            // Pseudoranges of two antennas 3 km apart along the line of sight.
            let pr_a = 2.2e7 + f64::from(prn) * 1.0e5;
            let pr_b = pr_a - 3.0e3;
            recorded.transmitted(eph, t_a, pr_a);
            let moved = NearAntenna(&recorded).transmitted(eph, t_b, pr_b);
            let own = Transmitted::of(eph, t_b, pr_b);
            assert!((moved.r_ecef_m - own.r_ecef_m).norm() < 1e-6, "G{prn:02}");
            assert!(
                (moved.v_ecef_mps - own.v_ecef_mps).norm() < 1e-2,
                "G{prn:02}"
            );
            assert!((moved.clock_s - own.clock_s).abs() < 1e-15, "G{prn:02}");
            let far = NearAntenna(&recorded).transmitted(eph, t_a + 2e-3, pr_a);
            assert_eq!(
                far.r_ecef_m,
                Transmitted::of(eph, t_a + 2e-3, pr_a).r_ecef_m
            );
            checked += 1;
        }
        assert!(checked >= 24, "{checked} satellites");
    }
}
