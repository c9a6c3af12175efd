//! Several vehicles in one scenario (`[[vehicles]]`): `synth` runs each into its own
//! directory with receiver-side random streams of its own and the satellites' errors
//! shared, and writes the relative truth (`relative.csv`).

mod support;

use skyforge_formats::orbit::LEO_SP3_ID;
use skyforge_formats::relative::read_relative_csv;
use skyforge_formats::truth::TruthFile;
use skyforge_gnss::observation::read_obs_file;
use skyforge_orbits::ephemeris::read_sp3_vehicle;
use std::path::Path;

/// Ten minutes at the observation level with today's satellite errors and a TCXO.
const HEAD: &str = r#"
name = "pair"
seed = 3
[time]
start = "2023-03-12T00:00:00 GPST"
duration_s = 600.0
[gnss.beidou]
enabled = false
[signal]
cn0_dbhz = 45.0
[errors.satellite]
model = "modern"
[errors.receiver_clock]
preset = "tcxo"
[observation]
level = "observation"
"#;

fn synth(dir: &Path, text: &str) {
    std::fs::write(dir.join("pair.toml"), text).unwrap();
    support::skyforge_ok(&["synth", "pair.toml", "--out", "sim"], dir);
}

/// Two vehicles on the same orbit: the same truth and the same satellite errors on every
/// link, but receiver noise and oscillators of their own (their pseudoranges differ),
/// and a relative truth of zero.
#[test]
fn vehicles_in_one_place_share_the_satellites_errors_not_their_receiver_noise() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    synth(
        d,
        &format!(
            "{HEAD}{}{}",
            support::leo_vehicle("a", 10.0),
            support::leo_vehicle("b", 10.0)
        ),
    );
    let (a, b) = (d.join("sim/a"), d.join("sim/b"));
    let truth = |v: &Path| TruthFile::open(&v.join("truth.h5")).unwrap();
    let (ta, tb) = (truth(&a), truth(&b));
    assert_eq!(ta.platform(1 << 20).unwrap(), tb.platform(1 << 20).unwrap());
    let n_sats = ta.satellite_ids(1 << 10).unwrap().len();
    let links = ta.links("ant1", 601, n_sats, 1 << 20).unwrap();
    assert_eq!(links, tb.links("ant1", 601, n_sats, 1 << 20).unwrap());
    for name in ["sat_orbit_error_m", "sat_clock_error_m"] {
        let va = ta.link_values("ant1", name, &links).unwrap();
        assert_eq!(va, tb.link_values("ant1", name, &links).unwrap(), "{name}");
        assert!(va.iter().any(|&x| x != 0.0), "{name}: the errors are on");
    }
    let obs = |v: &Path| std::fs::read_to_string(v.join("observations/ant1.obs.rnx")).unwrap();
    let (oa, ob) = (obs(&a), obs(&b));
    let body = |t: &str| t.split("END OF HEADER").nth(1).unwrap().to_string();
    assert_ne!(body(&oa), body(&ob), "receiver noise and clocks differ");
    let rows = read_relative_csv(&d.join("sim/relative.csv")).unwrap();
    assert_eq!(rows.len(), 601);
    for r in &rows {
        assert_eq!((r.vehicle.as_str(), r.target.as_str()), ("b", "a"));
        assert!(r.position_m.norm() < 1e-3 && r.velocity_mps.norm() < 1e-6);
    }
}

/// A chaser 32 km behind the target (book 5.6): the relative position's length is the
/// distance between the two truth orbits (their `truth.sp3`, to its millimetres), the
/// chaser lies behind (-x) and the along-track separation dominates.
#[test]
fn the_relative_truth_is_the_distance_between_the_orbits_in_the_target_frame() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    synth(
        d,
        &format!(
            "{HEAD}{}{}",
            support::leo_vehicle("target", 0.0),
            support::leo_vehicle("chaser", -0.2667)
        ),
    );
    let sp3 =
        |v: &str| read_sp3_vehicle(&d.join(format!("sim/{v}/truth.sp3")), LEO_SP3_ID).unwrap();
    let (t, c) = (sp3("target"), sp3("chaser"));
    let rows = read_relative_csv(&d.join("sim/relative.csv")).unwrap();
    assert_eq!(rows.len(), t.len());
    for (k, r) in rows.iter().enumerate() {
        let distance = (c[k].r_ecef_m - t[k].r_ecef_m).norm();
        assert!((r.position_m.norm() - distance).abs() < 3e-3, "epoch {k}");
        assert!(r.position_m.x < -30e3 && r.position_m.x.abs() > 50.0 * r.position_m.z.abs());
    }
}

/// `run` (geometry only) of a two-vehicle scenario writes both truths and the relative
/// truth; `--force` replaces the directory it wrote.
#[test]
fn run_writes_each_vehicle_and_the_relative_truth() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let text = format!(
        "{HEAD}{}{}",
        support::leo_vehicle("target", 0.0),
        support::leo_vehicle("chaser", -0.2667)
    )
    .replace("[observation]\nlevel = \"observation\"\n", "");
    std::fs::write(
        d.join("pair.toml"),
        text.replace("[signal]\ncn0_dbhz = 45.0\n", ""),
    )
    .unwrap();
    for force in [false, true] {
        let mut args = vec!["run", "pair.toml", "--out", "run"];
        if force {
            args.push("--force");
        }
        support::skyforge_ok(&args, d);
    }
    for f in [
        "target/truth.h5",
        "chaser/truth.h5",
        "chaser/truth.sp3",
        "relative.csv",
    ] {
        assert!(d.join("run").join(f).is_file(), "{f}");
    }
}

/// `[[vehicles.events]]`: an outage of every satellite on vehicle `b` from 100 to 110 s
/// empties its epochs there (the observation level drops what its receiver lost), while
/// `a` keeps observing.
#[test]
fn a_vehicle_event_reaches_its_receiver_alone() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let outage = "[[vehicles.events]]\nkind = \"outage\"\nstart_s = 100.0\nend_s = 110.0\n";
    synth(
        d,
        &format!(
            "{HEAD}{}{}{outage}",
            support::leo_vehicle("a", 10.0),
            support::leo_vehicle("b", 10.0)
        ),
    );
    let counts = |v: &str| {
        let file = read_obs_file(&d.join(format!("sim/{v}/observations/ant1.obs.rnx"))).unwrap();
        let start = file.epochs[0].time;
        let sats_at = |t: f64| {
            (file.epochs.iter())
                .find(|e| ((e.time - start).to_seconds() - t).abs() < 0.01)
                .map_or(0, |e| e.sats.len())
        };
        [sats_at(99.0), sats_at(105.0), sats_at(111.0)]
    };
    let (a, b) = (counts("a"), counts("b"));
    assert!(a.iter().all(|&n| n >= 4), "a: {a:?}");
    assert!(b[0] >= 4 && b[2] >= 4, "b before and after: {b:?}");
    assert_eq!(b[1], 0, "b during its outage: {b:?}");
}
