//! Real-data tier for the ephemeris module: broadcast orbits against precise SP3 orbits,
//! and the three bundled navigation files (RINEX 2, 3, 4).
//!
//! Run with `cargo test -p skyforge-orbits --test real_data_ephemeris -- --ignored
//! --nocapture`. The data folder comes from `SKYFORGE_DATA` (default `../shared/data`
//! next to the workspace).

use hifitime::{Epoch, TimeScale};
use skyforge_orbits::Vec3;
use skyforge_orbits::ephemeris::read_sp3;
use skyforge_orbits::ephemeris::rinex_nav::read_nav_file;
use skyforge_orbits::ephemeris::{
    BoundEphemeris, BroadcastEphemeris, EphemerisStore, NavMessage, OrbitClass, SatId, System,
    nominal,
};
use skyforge_orbits::fixtures::{angle_diff_deg, node_and_arg_lat};
use skyforge_orbits::time::TimeOrigin;
use std::collections::BTreeMap;
use std::path::PathBuf;

const IGNORE: &str = "real-data tier: cargo test -- --ignored";

fn data_dir() -> PathBuf {
    skyforge_orbits::real_data::require_dir()
}

fn load(rel: &str) -> Vec<BroadcastEphemeris> {
    let path = data_dir().join(rel);
    read_nav_file(&path).unwrap_or_else(|e| panic!("{e}"))
}

/// Longitude and latitude (deg) of an ECEF position.
fn lon_lat_deg(r: Vec3) -> (f64, f64) {
    (
        r.y.atan2(r.x).to_degrees(),
        (r.z / r.norm()).asin().to_degrees(),
    )
}

/// ACCEPTANCE: GPS broadcast orbits (RINEX 3, ESBC00DNK 2020-06-25) against the GRG final
/// precise orbits of the same day, at every 15-min SP3 epoch where a usable ephemeris
/// exists. The 3D RMS must be below 5 m for every healthy GPS satellite.
///
/// The broadcast orbit refers to the antenna phase centre, SP3 to the centre of mass; the
/// offset (GPS blocks: 0.5 to 2.6 m, almost entirely along the nadir-pointing body z axis)
/// is not removed: it is part of the bound. The mean radial difference is printed so the
/// offset can be seen.
#[test]
#[ignore = "real-data tier: cargo test -- --ignored"]
fn gps_broadcast_matches_precise_orbits() {
    let _ = IGNORE;
    let stats = broadcast_against_precise(System::Gps, None);
    assert!(
        stats.len() >= 28,
        "only {} GPS satellites compared",
        stats.len()
    );
    let compared: usize = stats.values().map(|s| s.2).sum();
    // The station file holds the sets ESBC tracked: most satellites are covered for
    // 16-20 h of the day.
    assert!(compared >= 1800, "only {compared} comparisons");
    for (sat, (ss, _, n, _)) in &stats {
        let rms = (ss / *n as f64).sqrt();
        assert!(*n >= 40, "{sat}: only {n} epochs");
        assert!(rms < 5.0, "{sat}: 3D RMS {rms:.3} m >= 5 m");
    }
}

/// The Galileo user algorithm (GTRF constants, GST, the RINEX week being the GPS week)
/// against the same day's precise orbits, once with the I/NAV sets and once with the
/// F/NAV sets of the station file: the same 5 m bound per satellite as GPS. The APC-CoM
/// offset of the Galileo satellites (about 0.6-1.0 m along the body z axis) is inside it.
#[test]
#[ignore = "real-data tier: cargo test -- --ignored"]
fn galileo_broadcast_matches_precise_orbits() {
    for message in [NavMessage::GalileoInav, NavMessage::GalileoFnav] {
        let stats = broadcast_against_precise(System::Galileo, Some(message));
        assert!(
            stats.len() >= 20,
            "{message:?}: only {} Galileo satellites compared",
            stats.len()
        );
        let compared: usize = stats.values().map(|s| s.2).sum();
        assert!(compared >= 1200, "{message:?}: only {compared} comparisons");
        for (sat, (ss, _, n, _)) in &stats {
            let rms = (ss / *n as f64).sqrt();
            assert!(*n >= 20, "{message:?} {sat}: only {n} epochs");
            assert!(rms < 5.0, "{message:?} {sat}: 3D RMS {rms:.3} m >= 5 m");
        }
    }
}

/// Per satellite of `system` (and of `message`, where given): the sum of squared 3D
/// errors, the radial error sum, the count and the largest error of the broadcast orbit
/// of the 2020-06-25 station file against the precise orbit, at every 15-min SP3 epoch
/// where a usable ephemeris exists. Prints the table.
fn broadcast_against_precise(
    system: System,
    message: Option<NavMessage>,
) -> BTreeMap<SatId, (f64, f64, usize, f64)> {
    let ephs: Vec<_> = load("nav/ESBC00DNK_R_20201770000_01D_MN.rnx.gz")
        .into_iter()
        .filter(|e| e.sat.system == system && message.is_none_or(|m| e.message == m))
        .collect();
    let sp3 = read_sp3(&data_dir().join("sp3/GRG0MGXFIN_20201770000_01D_15M_ORB.SP3.gz"))
        .unwrap_or_else(|e| panic!("{e}"));
    let origin = TimeOrigin::new(Epoch::from_gregorian(
        2020,
        6,
        25,
        0,
        0,
        0,
        0,
        TimeScale::GPST,
    ));
    let store = EphemerisStore::new(ephs, &origin);
    let mut stats: BTreeMap<SatId, (f64, f64, usize, f64)> = BTreeMap::new();
    let mut missing = 0usize;
    for rec in sp3.iter().filter(|r| r.sat.system == system) {
        let t = (rec.epoch - origin.start()).to_seconds();
        let Some(b) = store.select(rec.sat, t) else {
            missing += 1;
            continue;
        };
        let d = b.position_ecef(t) - rec.r_ecef_m;
        let radial = d.dot(&rec.r_ecef_m.normalize());
        let s = stats.entry(rec.sat).or_insert((0.0, 0.0, 0, 0.0));
        s.0 += d.norm_squared();
        s.1 += radial;
        s.2 += 1;
        s.3 = f64::max(s.3, d.norm());
    }
    println!("{system:?} {message:?}");
    println!("sat  epochs  3D-RMS(m)  max(m)  mean-radial(m)   [broadcast APC - SP3 CoM]");
    let mut worst = 0.0f64;
    for (sat, (ss, rad, n, max)) in &stats {
        let rms = (ss / *n as f64).sqrt();
        worst = worst.max(rms);
        println!(
            "{sat}  {n:6}  {rms:9.3}  {max:6.3}  {:14.3}",
            rad / *n as f64
        );
    }
    println!(
        "{} satellites, worst RMS {worst:.3} m, {missing} SP3 records without a usable \
         ephemeris, {} comparisons",
        stats.len(),
        stats.values().map(|s| s.2).sum::<usize>()
    );
    stats
}

/// The embedded Galileo plane/slot assignment (`nominal::GAL_PLANES`) against the real
/// I/NAV ephemerides of 2023-03-12 00:00 GST: the satellites of one nominal plane share
/// the node longitude (within 1 deg of the embedded one), and every satellite is within
/// 6 deg of its embedded argument of latitude.
#[test]
#[ignore = "real-data tier: cargo test -- --ignored"]
fn galileo_planes_match_the_embedded_assignment() {
    let ephs: Vec<_> = load("nav/BRD400DLR_S_20230710000_01D_MN.rnx.gz")
        .into_iter()
        .filter(|e| e.message == NavMessage::GalileoInav)
        .collect();
    let t0 = Epoch::from_gregorian(2023, 3, 12, 0, 0, 0, 0, TimeScale::GST);
    let origin = TimeOrigin::new(t0);
    let store = EphemerisStore::new(ephs, &origin);
    let nominal = EphemerisStore::new(nominal::galileo(t0), &origin);
    assert_eq!(nominal.satellites().len(), 24);
    for sat in nominal.satellites() {
        let b = store
            .select(sat, 0.0)
            .or_else(|| store.ephemerides(sat).first())
            .unwrap_or_else(|| panic!("no ephemeris for {sat}"));
        let (node, u) = node_and_arg_lat(b, 0.0);
        let embedded = nominal.select(sat, 0.0).expect("embedded set");
        let (node0, u0) = node_and_arg_lat(embedded, 0.0);
        println!("{sat}: node {node:8.2} (embedded {node0:8.2}), u {u:7.2} ({u0:7.2})");
        assert!(angle_diff_deg(node, node0).abs() < 1.0, "{sat}: node");
        assert!(angle_diff_deg(u, u0).abs() < 6.0, "{sat}: u");
    }
}

/// Counts per system and BeiDou orbit type of one file.
fn census(ephs: &[BroadcastEphemeris]) -> (usize, usize, usize, usize, usize) {
    let gps = ephs.iter().filter(|e| e.sat.system == System::Gps).count();
    let bds: Vec<_> = ephs
        .iter()
        .filter(|e| e.sat.system == System::Beidou)
        .collect();
    let geo = bds
        .iter()
        .filter(|e| e.class == OrbitClass::BeidouGeo)
        .count();
    // IGSO: geosynchronous semi-major axis (sqrt(A) ~ 6493 m^1/2) but not GEO.
    let igso = bds
        .iter()
        .filter(|e| e.class == OrbitClass::Standard && e.orbit.sqrt_a > 6000.0)
        .count();
    let meo = bds.iter().filter(|e| e.orbit.sqrt_a < 6000.0).count();
    (gps, bds.len(), geo, igso, meo)
}

/// The three navigation files load with plausible contents.
#[test]
#[ignore = "real-data tier: cargo test -- --ignored"]
fn all_navigation_files_load() {
    let files = [
        ("nav/brdc0010.22n", 2),
        ("nav/ESBC00DNK_R_20201770000_01D_MN.rnx.gz", 3),
        ("nav/BRD400DLR_S_20230710000_01D_MN.rnx.gz", 4),
    ];
    for (rel, version) in files {
        let ephs = load(rel);
        let (gps, bds, geo, igso, meo) = census(&ephs);
        let gps_sats: std::collections::BTreeSet<_> = ephs
            .iter()
            .filter(|e| e.sat.system == System::Gps)
            .map(|e| e.sat)
            .collect();
        let bds_sats: std::collections::BTreeSet<_> = ephs
            .iter()
            .filter(|e| e.sat.system == System::Beidou)
            .map(|e| e.sat)
            .collect();
        println!(
            "RINEX {version} {rel}: GPS {gps} sets / {} sats; BeiDou {bds} sets / {} sats \
             (GEO {geo}, IGSO {igso}, MEO {meo} sets)",
            gps_sats.len(),
            bds_sats.len()
        );
        // A day of GPS: ~31 satellites, a set every 2 h each.
        assert!(
            (28..=32).contains(&gps_sats.len()),
            "{rel}: {} GPS sats",
            gps_sats.len()
        );
        assert!((250..=31 * 24).contains(&gps), "{rel}: {gps} GPS sets");
        if version == 2 {
            assert_eq!(bds, 0);
        } else {
            assert!(
                bds_sats.len() >= 25,
                "{rel}: {} BeiDou sats",
                bds_sats.len()
            );
            assert!(
                geo > 0 && igso > 0 && meo > 0,
                "{rel}: GEO/IGSO/MEO {geo}/{igso}/{meo}"
            );
            // Hourly sets (a station file holds only those it tracked).
            assert!(bds >= 8 * bds_sats.len(), "{rel}: {bds} BeiDou sets");
        }
        // Galileo: I/NAV and F/NAV sets of the 24+ satellites in the version 3 and 4 files.
        let gal = |m: NavMessage| ephs.iter().filter(|e| e.message == m).count();
        let gal_sats: std::collections::BTreeSet<_> = ephs
            .iter()
            .filter(|e| e.sat.system == System::Galileo)
            .map(|e| e.sat)
            .collect();
        let (inav, fnav) = (gal(NavMessage::GalileoInav), gal(NavMessage::GalileoFnav));
        println!(
            "  Galileo: {} sats, {inav} I/NAV and {fnav} F/NAV sets",
            gal_sats.len()
        );
        if version == 2 {
            assert!(gal_sats.is_empty());
        } else {
            assert!(
                gal_sats.len() >= 22,
                "{rel}: {} Galileo sats",
                gal_sats.len()
            );
            assert!(inav >= 6 * gal_sats.len() && fnav >= 6 * gal_sats.len());
        }
        // Every set evaluates to a radius between its perigee and apogee at its toe, and
        // the semi-major axis is a MEO's or a geosynchronous one's (Galileo E14 and E18
        // fly eccentric orbits with their perigee near 23 800 km).
        let origin = TimeOrigin::new(ephs[0].toe);
        for e in &ephs {
            let b = e.bind(&origin);
            let r = b.position_ecef(b.toe_s).norm();
            let a = e.orbit.sqrt_a * e.orbit.sqrt_a;
            assert!((2.5e7..4.3e7).contains(&a), "{}: a = {a}", e.sat);
            let (lo, hi) = (a * (1.0 - e.orbit.e), a * (1.0 + e.orbit.e));
            assert!(
                (lo - 2e4..hi + 2e4).contains(&r),
                "{} at toe: r = {r}",
                e.sat
            );
        }
    }
}

/// BeiDou GEO satellites in the 2020 and 2023 files: stationary over the day at their
/// slots (BDS-2: 58.75, 80, 110.5, 140, 160 deg E; BDS-3 GEO: 80, 110.5, 140 deg E, plus
/// replacement satellites). Prints the measured longitudes and the IGSO equator-crossing
/// longitudes (BDS-2/3 IGSO tracks centred near 118 and 95 deg E).
#[test]
#[ignore = "real-data tier: cargo test -- --ignored"]
fn beidou_geo_and_igso_ground_tracks() {
    for rel in [
        "nav/ESBC00DNK_R_20201770000_01D_MN.rnx.gz",
        "nav/BRD400DLR_S_20230710000_01D_MN.rnx.gz",
    ] {
        let ephs = load(rel);
        let origin = TimeOrigin::new(ephs[0].toe);
        let store = EphemerisStore::new(ephs.clone(), &origin);
        println!("{rel}");
        for sat in store.satellites() {
            let sets = store.ephemerides(sat);
            let Some(first) = sets.first() else { continue };
            let t0 = first.toe_s;
            let t1 = sets.last().map_or(t0, |b| b.toe_s);
            let positions: Vec<Vec3> = (0..=((t1 - t0) / 300.0) as usize)
                .filter_map(|k| {
                    let t = t0 + 300.0 * k as f64;
                    store.select(sat, t).map(|b| b.position_ecef(t))
                })
                .collect();
            if first.eph.class == OrbitClass::BeidouGeo {
                let lons: Vec<f64> = positions.iter().map(|&r| lon_lat_deg(r).0).collect();
                let lats: Vec<f64> = positions.iter().map(|&r| lon_lat_deg(r).1).collect();
                let (lo, hi) = min_max(&lons);
                let (la, lb) = min_max(&lats);
                println!("  GEO  {sat}: lon {lo:8.3}..{hi:8.3} E  lat {la:6.2}..{lb:6.2}");
                assert!(hi - lo < 1.0, "{sat} drifts {lo}..{hi}");
                assert!(la.abs() < 3.0 && lb.abs() < 3.0, "{sat} lat {la}..{lb}");
            } else if first.eph.orbit.sqrt_a > 6000.0 {
                // Northbound equator crossings.
                let crossings: Vec<f64> = positions
                    .windows(2)
                    .filter(|w| w[0].z < 0.0 && w[1].z >= 0.0)
                    .map(|w| lon_lat_deg(w[1]).0)
                    .collect();
                let incl = first.eph.orbit.i0.to_degrees();
                println!(
                    "  IGSO {sat}: i {incl:5.2} deg, northbound crossing at {crossings:.2?} E"
                );
                for lon in &crossings {
                    assert!((85.0..130.0).contains(lon), "{sat} crosses at {lon}");
                }
            }
        }
    }
}

fn min_max(v: &[f64]) -> (f64, f64) {
    v.iter()
        .fold((f64::MAX, f64::MIN), |(a, b), &x| (a.min(x), b.max(x)))
}

/// The embedded BDS-3 MEO plane/slot assignment (`nominal::BDS3_MEO_PLANES`) against the
/// real broadcast ephemerides of 2023-03-12 00:00 BDT: the satellites of one nominal plane
/// share the node longitude, the planes are 120 deg apart, and sorting a plane by argument
/// of latitude gives the nominal slot order with 45 deg spacing.
#[test]
#[ignore = "real-data tier: cargo test -- --ignored"]
fn beidou_meo_planes_match_the_embedded_assignment() {
    let ephs = load("nav/BRD400DLR_S_20230710000_01D_MN.rnx.gz");
    let t0 = Epoch::from_gregorian(2023, 3, 12, 0, 0, 0, 0, TimeScale::BDT);
    let origin = TimeOrigin::new(t0);
    let store = EphemerisStore::new(ephs, &origin);
    let mut plane_nodes = Vec::new();
    for (k, plane) in nominal::BDS3_MEO_PLANES.iter().enumerate() {
        let mut nodes = Vec::new();
        let mut us = Vec::new();
        for &prn in plane {
            // The set in use at t0, else the day's first (extrapolated a few hours: fine
            // at the degree level checked here).
            let sat = SatId::beidou(prn);
            let b = store
                .select(sat, 0.0)
                .or_else(|| store.ephemerides(sat).first())
                .unwrap_or_else(|| panic!("no ephemeris for {sat}"));
            let (node, u) = node_and_arg_lat(b, 0.0);
            println!("plane {k} C{prn}: node {node:8.2} deg, u {u:7.2} deg");
            nodes.push(node);
            us.push(u);
        }
        for n in &nodes {
            assert!(
                angle_diff_deg(*n, nodes[0]).abs() < 3.0,
                "plane {k}: {nodes:?}"
            );
        }
        // Slot order: consecutive slots 45 +- 8 deg apart.
        for j in 0..8 {
            let d = angle_diff_deg(us[(j + 1) % 8], us[j]);
            assert!(
                (d - 45.0).abs() < 8.0,
                "plane {k} slots {j}->{}: {d}",
                j + 1
            );
        }
        plane_nodes.push(nodes[0]);
    }
    for k in 0..3 {
        let d = angle_diff_deg(plane_nodes[(k + 1) % 3], plane_nodes[k]);
        assert!((d - 120.0).abs() < 5.0, "planes {k}->{}: {d}", k + 1);
    }
}

/// How far a BeiDou set can be used from its toe: each set of the RINEX 4 file evaluated
/// `dt` after its toe, against the set whose toe is at that instant. Supports the 6 h
/// BeiDou validity (`rinex_nav`), which only matters at the end of a file.
#[test]
#[ignore = "real-data tier: cargo test -- --ignored"]
fn beidou_sets_extrapolate_for_hours() {
    let ephs = load("nav/BRD400DLR_S_20230710000_01D_MN.rnx.gz");
    let start = Epoch::from_gregorian_utc_at_midnight(2023, 3, 12);
    let origin = TimeOrigin::new(start);
    let mut by_sat: BTreeMap<SatId, Vec<BoundEphemeris>> = BTreeMap::new();
    for e in ephs
        .iter()
        .filter(|e| e.sat.system == System::Beidou && e.health == 0)
    {
        by_sat.entry(e.sat).or_default().push(e.bind(&origin));
    }
    for dt_h in [1.0, 2.0, 3.0] {
        let mut worst: f64 = 0.0;
        let mut n = 0;
        for sets in by_sat.values() {
            for a in sets {
                let t = a.toe_s + dt_h * 3600.0;
                if let Some(b) = sets.iter().find(|b| (b.toe_s - t).abs() < 1.0) {
                    worst = worst.max((a.position_ecef(t) - b.position_ecef(t)).norm());
                    n += 1;
                }
            }
        }
        println!(
            "BeiDou set used {dt_h} h after toe: worst 3D difference {worst:.1} m over {n} pairs"
        );
        assert!(n > 100, "too few pairs at {dt_h} h: {n}");
        assert!(worst < 25.0, "{dt_h} h: {worst} m");
    }
}
