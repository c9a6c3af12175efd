//! Embedded default constellations expressed as broadcast ephemerides (so the orbit a
//! signal follows and the ephemeris its navigation message carries are the same model).
//! Sources of the slot data are documented on each function.
//!
//! Common model of every embedded satellite: circular orbit (e = 0, omega = 0, so M0 is
//! the argument of latitude at toe), no harmonic corrections, delta_n = 0, idot = 0, zero
//! clock, health 0, toe = toc = the given epoch, fit interval [`NOMINAL_FIT_S`]
//! (effectively unlimited). Omega_dot is the J2 secular nodal drift
//! -3/2 J2 (R_E/a)^2 n cos i (GPS: -7.8e-9 rad/s, BeiDou MEO: -6.6e-9 rad/s) for MEO and
//! IGSO satellites and 0 for GEO satellites (station-kept on the equator).
//!
//! Slot positions are given as the Earth-fixed longitude of the ascending node and the
//! argument of latitude *at toe*: Omega0 is set so that
//! Omega(tk = 0) = Omega0 - OMEGA_E * toe_sow equals that longitude.

use super::broadcast::{
    ClockParams, HarmonicCorrections, KeplerElements, OrbitClass, seconds_of_week,
};
use super::sat_id::{SystemConstants, system_constants};
use super::{BroadcastEphemeris, SatId, config::BeidouSet};
use crate::constants::{J2, WGS84_A_M};
use hifitime::Epoch;
use std::f64::consts::PI;

/// Fit interval of embedded ephemerides (s): ~31 years, i.e. never expires.
pub const NOMINAL_FIT_S: f64 = 1e9;

/// GPS nominal semi-major axis (m), SPS PS (2001) 3.1 / Table 3-1 notes.
pub const GPS_A_M: f64 = 26_559.7e3;
/// GPS nominal inclination (deg).
pub const GPS_I_DEG: f64 = 55.0;
/// BeiDou MEO semi-major axis (m).
pub const BDS_MEO_A_M: f64 = 27_906.1e3;
/// BeiDou GEO/IGSO semi-major axis (m).
pub const BDS_GSO_A_M: f64 = 42_164.2e3;
/// BeiDou MEO and IGSO inclination (deg).
pub const BDS_I_DEG: f64 = 55.0;

/// GPS baseline 24-slot constellation: (slot, RAAN deg, argument of latitude deg) at the
/// defined epoch 1993-07-01 00:00 UT, Greenwich hour angle 18h36m14.4s.
/// Source: GPS SPS Performance Standard (October 2001), Table 3-1 "Reference Orbit Slot
/// Assignments as of the Defined Epoch" (the same 24 baseline slots as Table 3.2-1 of the
/// 2008/2020 editions).
pub const GPS_SLOTS: [(&str, f64, f64); 24] = [
    ("A1", 272.847, 268.126),
    ("A2", 272.847, 161.786),
    ("A3", 272.847, 11.676),
    ("A4", 272.847, 41.806),
    ("B1", 332.847, 80.956),
    ("B2", 332.847, 173.336),
    ("B3", 332.847, 309.976),
    ("B4", 332.847, 204.376),
    ("C1", 32.847, 111.876),
    ("C2", 32.847, 11.796),
    ("C3", 32.847, 339.666),
    ("C4", 32.847, 241.556),
    ("D1", 92.847, 135.226),
    ("D2", 92.847, 265.446),
    ("D3", 92.847, 35.156),
    ("D4", 92.847, 167.356),
    ("E1", 152.847, 197.046),
    ("E2", 152.847, 302.596),
    ("E3", 152.847, 66.066),
    ("E4", 152.847, 333.686),
    ("F1", 212.847, 238.886),
    ("F2", 212.847, 345.226),
    ("F3", 212.847, 105.206),
    ("F4", 212.847, 135.346),
];

/// Greenwich hour angle at the GPS slot-table epoch: 18h36m14.4s = 279.06 deg.
pub const GPS_SLOT_EPOCH_GHA_DEG: f64 = (18.0 + 36.0 / 60.0 + 14.4 / 3600.0) * 15.0;

/// Number of embedded GPS satellites.
pub const GPS_COUNT: usize = 31;

/// One satellite slot: Earth-fixed node longitude and argument of latitude at toe.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Slot {
    node_lon_deg: f64,
    arg_lat_deg: f64,
}

/// The 31 GPS slots in PRN order: PRNs 1-24 take the 24 baseline slots in table order
/// (A1..A4, B1..B4, ..., F1..F4); PRNs 25-31 are the extra satellites, each placed at the
/// midpoint of the currently largest in-plane gap in argument of latitude (greedy, ties to
/// the first plane in A..F order). This is a documented rule, not a real assignment date:
/// the SPS PS expandable-slot table could not be verified for this build. The rule gives
/// (RAAN, argument of latitude) = PRN 25 (332.847, 15.466), 26 (152.847, 131.556),
/// 27 (92.847, 330.301), 28 (32.847, 176.716), 29 (212.847, 45.216),
/// 30 (272.847, 101.796), 31 (212.847, 292.056) deg.
fn gps_slots() -> Vec<Slot> {
    let mut planes: Vec<(f64, Vec<f64>)> = Vec::new();
    for &(_, raan, u) in &GPS_SLOTS {
        match planes.iter_mut().find(|(r, _)| *r == raan) {
            Some((_, us)) => us.push(u),
            None => planes.push((raan, vec![u])),
        }
    }
    let mut extras = Vec::new();
    for _ in 0..GPS_COUNT - GPS_SLOTS.len() {
        let mut best = (0usize, 0.0f64, -1.0f64); // plane, midpoint, gap
        for (p, (_, us)) in planes.iter().enumerate() {
            let mut sorted = us.clone();
            sorted.sort_by(f64::total_cmp);
            for (k, &u) in sorted.iter().enumerate() {
                let next = sorted.get(k + 1).copied().unwrap_or(sorted[0] + 360.0);
                if next - u > best.2 {
                    best = (p, (u + 0.5 * (next - u)).rem_euclid(360.0), next - u);
                }
            }
        }
        planes[best.0].1.push(best.1);
        extras.push((planes[best.0].0, best.1));
    }
    GPS_SLOTS
        .iter()
        .map(|&(_, raan, u)| (raan, u))
        .chain(extras)
        .map(|(raan, u)| Slot {
            node_lon_deg: raan - GPS_SLOT_EPOCH_GHA_DEG,
            arg_lat_deg: u,
        })
        .collect()
}

/// [`gps`] at `start` in a store whose times count from `start`.
pub fn gps_store(start: Epoch) -> super::EphemerisStore {
    super::EphemerisStore::new(gps(start), &crate::time::TimeOrigin::new(start))
}

/// The nominal GPS constellation (31 PRNs), with toe/toc at `epoch`.
///
/// Slots: [`GPS_SLOTS`] (SPS PS Table 3-1) plus 7 extra satellites (see the PRN rule on
/// `gps_slots`: PRN n <= 24 sits in the n-th table slot). Epoch mapping (a documented
/// assumption): the constellation is placed at toe in the Earth-fixed geometry it had at
/// the table epoch, i.e. node longitude = RAAN - GHA(table epoch) and the table argument of
/// latitude; the time between the table epoch and `epoch` is ignored. a = 26559.7 km,
/// e = 0, i = 55 deg.
pub fn gps(epoch: Epoch) -> Vec<BroadcastEphemeris> {
    gps_slots()
        .into_iter()
        .zip(1u8..)
        .map(|(slot, prn)| circular(SatId::gps(prn), epoch, GPS_A_M, GPS_I_DEG, slot))
        .collect()
}

/// BeiDou MEO Walker 24/3/1 planes: Earth-fixed node longitude of plane 1 at toe (deg),
/// argument of latitude of slot 1 of plane 1 (deg). Values rounded from the broadcast
/// ephemerides of BRD400DLR_S_20230710000 at 2023-03-12 00:00 BDT (planes at -66.6, 53.4
/// and 173.4 deg; slot phases 28 + 45 j + 15 k deg).
const BDS_MEO_WALKER: Walker = Walker {
    plane1_node_deg: -66.6,
    slot1_arg_lat_deg: 28.0,
};

/// BDS-3 MEO PRNs per plane (k = 0, 1, 2), in slot order (increasing argument of
/// latitude), as measured in the 2023-03-12 broadcast ephemerides (see the test tier).
pub const BDS3_MEO_PLANES: [[u8; 8]; 3] = [
    [20, 32, 41, 33, 42, 21, 22, 19],
    [23, 25, 24, 26, 45, 36, 46, 37],
    [44, 35, 29, 30, 27, 28, 43, 34],
];

/// A Walker 24/3/1 constellation placed at toe: the Earth-fixed node longitude of its
/// first plane and the argument of latitude of that plane's first slot (deg).
struct Walker {
    plane1_node_deg: f64,
    slot1_arg_lat_deg: f64,
}

impl Walker {
    /// Slot j (45 deg apart) of plane k (120 deg apart), inter-plane phase 360 F / T =
    /// 15 deg.
    fn slot(&self, k: usize, j: usize) -> Slot {
        self.in_plane(
            k,
            self.slot1_arg_lat_deg + 45.0 * j as f64 + 15.0 * k as f64,
        )
    }

    /// Plane k at argument of latitude `arg_lat_deg` (a satellite off the slots).
    fn in_plane(&self, k: usize, arg_lat_deg: f64) -> Slot {
        Slot {
            node_lon_deg: self.plane1_node_deg + 120.0 * k as f64,
            arg_lat_deg,
        }
    }
}

/// An IGSO whose northbound equator crossing is at `cross_lon_deg` and whose argument of
/// latitude at toe is `arg_lat_deg`: with n ~ OMEGA_E the node longitude at toe is the
/// crossing longitude minus the argument of latitude.
fn igso_slot(cross_lon_deg: f64, arg_lat_deg: f64) -> Slot {
    Slot {
        node_lon_deg: cross_lon_deg - arg_lat_deg,
        arg_lat_deg,
    }
}

/// The nominal BeiDou constellation of `set`, with toe/toc at `epoch`.
///
/// BDS-3 (30 satellites):
/// - 24 MEO, Walker 24/3/1, a = 27906.1 km, i = 55 deg; PRN-to-plane/slot assignment as
///   broadcast on 2023-03-12 (planes: C19-C22, C32, C33, C41, C42 / C23-C26, C36, C37,
///   C45, C46 / C27-C30, C34, C35, C43, C44), see [`BDS3_MEO_PLANES`].
/// - 3 IGSO C38, C39, C40, a = 42164.2 km, i = 55 deg, on one ground track crossing the
///   equator northbound at 118 deg E, 120 deg apart in argument of latitude (C40 0,
///   C39 120, C38 240 deg at toe: the order seen on 2023-03-12).
/// - 3 GEO: C59 140 deg E and C60 80 deg E (both confirmed by their 2023-03-12 broadcast
///   ephemerides), C61 110.5 deg E (BDS-3 GEO slots 80/110.5/140 deg E as announced;
///   C61 is not in the bundled files).
///
/// BDS-2 (15 satellites, the 2018 operational set):
/// - 5 GEO: C01 140, C02 80, C03 110.5, C04 160, C05 58.75 deg E (IGS MGEX BeiDou status
///   page for C01, C03, C04; BDS-2 GEO slots for C02, C05; C05 confirmed by its
///   2020-06-24 broadcast ephemeris).
/// - 7 IGSO, i = 55 deg: C06, C07, C08 on the 118 deg E track (arguments of latitude at
///   toe 120, 0, 240 deg), C16 in C06's plane 4 deg ahead of it; C09, C10, C13 on the
///   95 deg E track (120, 0, 240 deg). Tracks: MGEX (C06-C08 ~117-119 deg E, C09/C10
///   ~95 deg E); phasing: the 2023-03-12 broadcast snapshot, rounded.
/// - 3 MEO: C11 and C12 in the third Walker plane (arguments of latitude 308 and
///   353 deg), C14 in the first plane (188 deg), from the same snapshot.
pub fn beidou(set: BeidouSet, epoch: Epoch) -> Vec<BroadcastEphemeris> {
    let meo = |prn, slot| circular(SatId::beidou(prn), epoch, BDS_MEO_A_M, BDS_I_DEG, slot);
    let igso = |prn, cross, u| {
        circular(
            SatId::beidou(prn),
            epoch,
            BDS_GSO_A_M,
            BDS_I_DEG,
            igso_slot(cross, u),
        )
    };
    let geo = |prn, lon| geostationary(SatId::beidou(prn), epoch, lon);
    let mut out = Vec::new();
    match set {
        BeidouSet::Bds3 => {
            for (k, plane) in BDS3_MEO_PLANES.iter().enumerate() {
                for (j, &prn) in plane.iter().enumerate() {
                    out.push(meo(prn, BDS_MEO_WALKER.slot(k, j)));
                }
            }
            out.push(igso(38, 118.0, 240.0));
            out.push(igso(39, 118.0, 120.0));
            out.push(igso(40, 118.0, 0.0));
            out.push(geo(59, 140.0));
            out.push(geo(60, 80.0));
            out.push(geo(61, 110.5));
        }
        BeidouSet::Bds2 => {
            for (prn, lon) in [(1, 140.0), (2, 80.0), (3, 110.5), (4, 160.0), (5, 58.75)] {
                out.push(geo(prn, lon));
            }
            for (prn, cross, u) in [
                (6, 118.0, 120.0),
                (7, 118.0, 0.0),
                (8, 118.0, 240.0),
                (9, 95.0, 120.0),
                (10, 95.0, 0.0),
                (13, 95.0, 240.0),
                (16, 118.0, 124.0),
            ] {
                out.push(igso(prn, cross, u));
            }
            out.push(meo(11, BDS_MEO_WALKER.in_plane(2, 308.0)));
            out.push(meo(12, BDS_MEO_WALKER.in_plane(2, 353.0)));
            out.push(meo(14, BDS_MEO_WALKER.in_plane(0, 188.0)));
        }
    }
    out.sort_by_key(|e| e.sat);
    out
}

/// Galileo nominal semi-major axis (m), Galileo OS SDD Issue 1.2 §2.1 (reference
/// constellation: Walker 24/3/1, 29 600.318 km, 56 deg).
pub const GAL_A_M: f64 = 29_600.318e3;
/// Galileo nominal inclination (deg), Galileo OS SDD §2.1.
pub const GAL_I_DEG: f64 = 56.0;

/// Galileo Walker 24/3/1 planes: Earth-fixed node longitude of the first plane at toe
/// (deg) and the argument of latitude of its first slot (deg). Rounded from the I/NAV
/// ephemerides of BRD400DLR_S_20230710000 at 2023-03-12 00:00 GST (planes at -155.3,
/// -35.2 and 85.1 deg; slot phases 30 + 45 j + 15 k deg; see the test tier).
const GAL_WALKER: Walker = Walker {
    plane1_node_deg: -155.2,
    slot1_arg_lat_deg: 30.0,
};

/// Galileo PRNs per plane (k = 0, 1, 2, planes 120 deg apart eastward) in slot order
/// (j = 0..8, increasing argument of latitude), as broadcast on 2023-03-12; 0 marks the
/// slot that was empty that day.
pub const GAL_PLANES: [[u8; 8]; 3] = [
    [15, 34, 36, 11, 12, 33, 26, 13],
    [9, 4, 19, 0, 7, 8, 3, 5],
    [21, 27, 30, 2, 25, 24, 31, 1],
];

/// The Galileo satellite outside the Walker slots on 2023-03-12: E10 in the first plane,
/// halfway between slots 3 and 4 (argument of latitude 187.3 deg measured; 187.5 used).
pub const GAL_AUXILIARY: (u8, f64) = (10, 187.5);

/// The nominal Galileo constellation (24 satellites), with toe/toc at `epoch`: 23 in the
/// Walker 24/3/1 slots of [`GAL_PLANES`] and E10 in its auxiliary slot, a = 29 600.318
/// km, i = 56 deg, in the F/NAV message (that of E5a, the Galileo signal SkyForge
/// transmits). E14 and E18 (eccentric orbits) and the
/// satellites not healthy on 2023-03-12 are left out.
pub fn galileo(epoch: Epoch) -> Vec<BroadcastEphemeris> {
    let meo = |prn, slot| circular(SatId::galileo(prn), epoch, GAL_A_M, GAL_I_DEG, slot);
    let mut out = Vec::new();
    for (k, plane) in GAL_PLANES.iter().enumerate() {
        for (j, &prn) in plane.iter().enumerate().filter(|(_, p)| **p != 0) {
            out.push(meo(prn, GAL_WALKER.slot(k, j)));
        }
    }
    let (prn, u) = GAL_AUXILIARY;
    out.push(meo(prn, GAL_WALKER.in_plane(0, u)));
    out.sort_by_key(|e| e.sat);
    out
}

/// J2 secular drift of the node, -3/2 J2 (R_E / a)^2 n cos i (rad/s).
pub fn j2_nodal_rate_rad_s(gm: f64, a_m: f64, i_rad: f64) -> f64 {
    let n = (gm / (a_m * a_m * a_m)).sqrt();
    -1.5 * J2 * (WGS84_A_M / a_m).powi(2) * n * i_rad.cos()
}

use crate::angles::wrap_pi;

/// The ephemeris template: circular, no corrections, zero clock, healthy.
fn template(sat: SatId, class: OrbitClass, epoch: Epoch, a_m: f64) -> BroadcastEphemeris {
    let orbit = KeplerElements {
        sqrt_a: a_m.sqrt(),
        ..KeplerElements::default()
    };
    BroadcastEphemeris::from_elements(
        sat,
        class,
        epoch,
        orbit,
        HarmonicCorrections::default(),
        ClockParams::default(),
        NOMINAL_FIT_S,
    )
}

/// A circular inclined orbit (standard user algorithm) in `slot` at toe.
fn circular(sat: SatId, epoch: Epoch, a_m: f64, i_deg: f64, slot: Slot) -> BroadcastEphemeris {
    let SystemConstants {
        omega_e, gm, scale, ..
    } = system_constants(sat.system);
    let i0 = i_deg.to_radians();
    let toe_sow = seconds_of_week(epoch, scale);
    let base = template(sat, OrbitClass::Standard, epoch, a_m);
    BroadcastEphemeris {
        orbit: KeplerElements {
            i0,
            omega0: wrap_pi(slot.node_lon_deg.to_radians() + omega_e * toe_sow),
            m0: wrap_pi(slot.arg_lat_deg.to_radians()),
            omega_dot: j2_nodal_rate_rad_s(gm, a_m, i0),
            ..base.orbit
        },
        ..base
    }
}

/// A geostationary satellite at `lon_deg` east, in the BeiDou GEO convention
/// (BDS-SIS-ICD 5.2.4): in the computation frame, which is the ECEF frame at toe tilted
/// by +5 deg about X, an orbit of inclination 5 deg with its node on the -X axis
/// (Omega = 180 deg) is exactly equatorial after the Rx(-5 deg) rotation, and the argument
/// of latitude u maps to the longitude u + 180 deg.
fn geostationary(sat: SatId, epoch: Epoch, lon_deg: f64) -> BroadcastEphemeris {
    let SystemConstants { omega_e, scale, .. } = system_constants(sat.system);
    let toe_sow = seconds_of_week(epoch, scale);
    let base = template(sat, OrbitClass::BeidouGeo, epoch, BDS_GSO_A_M);
    BroadcastEphemeris {
        orbit: KeplerElements {
            i0: 5.0f64.to_radians(),
            omega0: wrap_pi(PI + omega_e * toe_sow),
            m0: wrap_pi(lon_deg.to_radians() - PI),
            ..base.orbit
        },
        ..base
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Vec3;
    use crate::constants::{GM_BDS, GM_GPS};
    use crate::ephemeris::BoundEphemeris;
    use crate::ephemeris::System;
    use crate::fixtures::{angle_diff_deg, node_and_arg_lat};
    use crate::time::TimeOrigin;
    use hifitime::TimeScale;

    fn epoch() -> Epoch {
        // Mid-week, odd seconds: exercises the toe seconds-of-week handling.
        Epoch::from_gregorian(2023, 3, 15, 7, 13, 27, 0, TimeScale::UTC)
    }

    fn bound(ephs: &[BroadcastEphemeris]) -> Vec<BoundEphemeris> {
        let origin = TimeOrigin::new(epoch());
        ephs.iter().map(|e| e.bind(&origin)).collect()
    }

    fn lon_lat_deg(r: Vec3) -> (f64, f64) {
        (
            r.y.atan2(r.x).to_degrees(),
            (r.z / r.norm()).asin().to_degrees(),
        )
    }

    #[test]
    fn counts_and_unique_prns() {
        let g = gps(epoch());
        assert_eq!(g.len(), 31);
        let mut prns: Vec<u8> = g.iter().map(|e| e.sat.prn).collect();
        prns.dedup();
        assert_eq!(prns, (1..=31).collect::<Vec<u8>>());
        let b3 = beidou(BeidouSet::Bds3, epoch());
        assert_eq!(b3.len(), 30);
        let geo = b3
            .iter()
            .filter(|e| e.class == OrbitClass::BeidouGeo)
            .count();
        assert_eq!(geo, 3);
        let b2 = beidou(BeidouSet::Bds2, epoch());
        assert_eq!(b2.len(), 15);
        for set in [&b3, &b2] {
            let mut sats: Vec<SatId> = set.iter().map(|e| e.sat).collect();
            sats.dedup();
            assert_eq!(sats.len(), set.len());
        }
        assert!(
            g.iter()
                .chain(&b3)
                .all(|e| e.health == 0 && e.toe == epoch())
        );
    }

    #[test]
    fn galileo_is_24_satellites_on_their_slots() {
        let g = galileo(epoch());
        assert_eq!(g.len(), 24);
        let mut sats: Vec<SatId> = g.iter().map(|e| e.sat).collect();
        sats.dedup();
        assert_eq!(sats.len(), 24);
        for b in bound(&g) {
            let (node, u) = node_and_arg_lat(&b, 0.0);
            let plane = GAL_PLANES
                .iter()
                .position(|p| p.contains(&b.eph.sat.prn))
                .unwrap_or(0);
            let node_expected = -155.2 + 120.0 * plane as f64;
            assert!(angle_diff_deg(node, node_expected).abs() < 0.01, "{node}");
            // Walker 24/3/1: slots 45 deg apart, planes phased by 15 deg.
            let auxiliary = b.eph.sat.prn == GAL_AUXILIARY.0;
            let expected_phase = if auxiliary { 22.5 } else { 0.0 };
            let off = (u - 30.0 - 15.0 * plane as f64 - expected_phase + 22.5).rem_euclid(45.0);
            assert!((off - 22.5).abs() < 0.01, "{}: u {u}", b.eph.sat);
            assert_eq!(b.eph.message, crate::ephemeris::NavMessage::GalileoFnav);
            for k in 0..5 {
                let r = b.position_ecef(3600.0 * f64::from(k)).norm();
                assert!((r - 29_600.318e3).abs() < 1e-3);
            }
            assert!((b.eph.orbit.i0.to_degrees() - 56.0).abs() < 1e-12);
        }
    }

    #[test]
    fn radii_are_the_nominal_semi_major_axes() {
        let all: Vec<_> = gps(epoch())
            .into_iter()
            .chain(beidou(BeidouSet::Bds3, epoch()))
            .chain(beidou(BeidouSet::Bds2, epoch()))
            .collect();
        for b in bound(&all) {
            let a = match (
                b.eph.sat.system,
                b.eph.orbit.sqrt_a > 6000.0,
                b.eph.orbit.sqrt_a > 5200.0,
            ) {
                (System::Gps, _, _) => 26_559.7e3,
                (_, true, _) => 42_164.2e3,
                _ => 27_906.1e3,
            };
            for k in 0..10 {
                let r = b.position_ecef(3600.0 * f64::from(k)).norm();
                assert!((r - a).abs() < 1e-3, "{} r={r}", b.eph.sat);
            }
        }
    }

    #[test]
    fn gps_slots_match_the_table_at_toe() {
        let g = bound(&gps(epoch()));
        for (b, &(slot, raan, u)) in g.iter().zip(GPS_SLOTS.iter()) {
            let (node, arg) = node_and_arg_lat(b, 0.0);
            assert!(
                angle_diff_deg(node, raan - 279.06).abs() < 0.01,
                "{slot}: node {node}"
            );
            assert!(angle_diff_deg(arg, u).abs() < 0.01, "{slot}: u {arg}");
            let i = b.eph.orbit.i0.to_degrees();
            assert!((i - 55.0).abs() < 1e-12);
        }
        // The extras sit in the six planes and keep >= 20 deg from any other satellite
        // of their plane.
        for b in &g[24..] {
            let (node, u) = node_and_arg_lat(b, 0.0);
            let mates: Vec<f64> = g
                .iter()
                .filter(|o| o.eph.sat != b.eph.sat)
                .map(|o| node_and_arg_lat(o, 0.0))
                .filter(|(n, _)| angle_diff_deg(*n, node).abs() < 0.01)
                .map(|(_, v)| v)
                .collect();
            assert!(
                mates.len() >= 4,
                "{} in a plane of {}",
                b.eph.sat,
                mates.len()
            );
            for v in mates {
                assert!(
                    angle_diff_deg(u, v).abs() > 20.0,
                    "{} {u} vs {v}",
                    b.eph.sat
                );
            }
        }
    }

    #[test]
    fn gps_j2_nodal_drift() {
        // Analytical J2 secular rate for a = 26559.7 km, i = 55 deg: about -0.0388 deg/day
        // (14 deg/year westward). External check: the real GPS broadcast Omega_dot values
        // of the bundled 2020 and 2022 RINEX files lie between -9.34e-9 and -7.22e-9 rad/s
        // (e.g. G01 -7.465e-9 on 2023-03-12, G02 -8.690e-9 on 2022-01-01).
        let rate = j2_nodal_rate_rad_s(GM_GPS, GPS_A_M, 55f64.to_radians());
        let deg_per_day = rate.to_degrees() * 86_400.0;
        assert!((deg_per_day + 0.0388).abs() < 0.001, "{deg_per_day}");
        assert!((-9.34e-9..-7.22e-9).contains(&rate), "{rate:e}");
    }

    #[test]
    fn geo_longitudes_are_held_over_a_day() {
        let expect = [(59, 140.0), (60, 80.0), (61, 110.5)];
        let b3 = bound(&beidou(BeidouSet::Bds3, epoch()));
        let b2 = bound(&beidou(BeidouSet::Bds2, epoch()));
        let expect2 = [(1, 140.0), (2, 80.0), (3, 110.5), (4, 160.0), (5, 58.75)];
        for (set, exp) in [(&b3, &expect[..]), (&b2, &expect2[..])] {
            for &(prn, lon0) in exp {
                let b = set.iter().find(|b| b.eph.sat.prn == prn).unwrap();
                assert_eq!(b.eph.class, OrbitClass::BeidouGeo);
                for k in 0..=48 {
                    let (lon, lat) = lon_lat_deg(b.position_ecef(1800.0 * f64::from(k)));
                    assert!((lon - lon0).abs() < 0.1, "C{prn:02} lon {lon} at {k}");
                    assert!(lat.abs() < 1e-6, "C{prn:02} lat {lat}");
                }
            }
        }
    }

    /// Time and longitude of the first northbound equator crossing after t = 0.
    fn northbound_crossing(b: &BoundEphemeris) -> (f64, f64) {
        let mut t = 0.0;
        let mut prev = b.position_ecef(t);
        while t < 90_000.0 {
            let r = b.position_ecef(t + 60.0);
            if prev.z < 0.0 && r.z >= 0.0 {
                // Bisect to 1 ms.
                let (mut lo, mut hi) = (t, t + 60.0);
                while hi - lo > 1e-3 {
                    let mid = 0.5 * (lo + hi);
                    if b.position_ecef(mid).z < 0.0 {
                        lo = mid;
                    } else {
                        hi = mid;
                    }
                }
                return (hi, lon_lat_deg(b.position_ecef(hi)).0);
            }
            prev = r;
            t += 60.0;
        }
        panic!("{} never crosses northbound", b.eph.sat);
    }

    #[test]
    fn igso_ground_track_crossings() {
        let b3 = bound(&beidou(BeidouSet::Bds3, epoch()));
        let mut times = Vec::new();
        for prn in [38, 39, 40] {
            let b = b3.iter().find(|b| b.eph.sat.prn == prn).unwrap();
            let (t, lon) = northbound_crossing(b);
            assert!((lon - 118.0).abs() < 0.5, "C{prn} crosses at {lon}");
            times.push(t);
        }
        // 120 deg apart in argument of latitude = 8 h apart on the common track:
        // C40 crosses at once (u = 0), then C39 after 16 h... (u = 120 -> 240 deg to go).
        times.sort_by(f64::total_cmp);
        for w in times.windows(2) {
            assert!(((w[1] - w[0]) / 3600.0 - 7.98).abs() < 0.1, "{times:?}");
        }
        let b2 = bound(&beidou(BeidouSet::Bds2, epoch()));
        for (prn, track) in [
            (6, 118.0),
            (7, 118.0),
            (8, 118.0),
            (16, 118.0),
            (9, 95.0),
            (10, 95.0),
            (13, 95.0),
        ] {
            let b = b2.iter().find(|b| b.eph.sat.prn == prn).unwrap();
            let (_, lon) = northbound_crossing(b);
            assert!((lon - track).abs() < 0.5, "C{prn:02} crosses at {lon}");
        }
    }

    #[test]
    fn walker_24_3_1_phasing() {
        let b3 = bound(&beidou(BeidouSet::Bds3, epoch()));
        for (k, plane) in BDS3_MEO_PLANES.iter().enumerate() {
            for (j, prn) in plane.iter().enumerate() {
                let b = b3.iter().find(|b| b.eph.sat.prn == *prn).unwrap();
                let (node, u) = node_and_arg_lat(b, 0.0);
                let node_expect = -66.6 + 120.0 * k as f64;
                let u_expect = 28.0 + 45.0 * j as f64 + 15.0 * k as f64;
                assert!(
                    angle_diff_deg(node, node_expect).abs() < 0.01,
                    "C{prn} node {node}"
                );
                assert!(angle_diff_deg(u, u_expect).abs() < 0.01, "C{prn} u {u}");
            }
        }
    }

    #[test]
    fn orbital_period_is_keplerian() {
        // With the node drift removed the position in the rotating frame repeats after
        // one Keplerian period plus the Earth's rotation over it; check the inertial
        // angle swept instead: u advances by 360 deg in 2 pi / sqrt(mu / a^3).
        for (gm, a) in [(GM_GPS, GPS_A_M), (GM_BDS, BDS_MEO_A_M)] {
            let period = 2.0 * PI / (gm / a.powi(3)).sqrt();
            let ephs = if gm == GM_GPS {
                gps(epoch())
            } else {
                beidou(BeidouSet::Bds3, epoch())
            };
            let b = &bound(&ephs)[0];
            let (_, u0) = node_and_arg_lat(b, 0.0);
            let (_, u1) = node_and_arg_lat(b, period);
            let (_, uh) = node_and_arg_lat(b, period / 2.0);
            assert!(angle_diff_deg(u1, u0).abs() < 1e-6, "{u0} {u1}");
            assert!((angle_diff_deg(uh, u0).abs() - 180.0).abs() < 1e-6);
        }
    }
}
