//! `[errors.receiver_clock] relativity = true`: a LEO receiver's clock keeps its proper
//! time (book eqs. 5-16/5-17), and every pseudorange of the observation truth moves by c
//! times the relativistic offset.

mod support;

use skyforge_formats::truth::TruthFile;
use skyforge_gnss::observation::read_obs_file;
use skyforge_orbits::Vec3;
use skyforge_orbits::constants::{C_MPS, GM_GPS, OMEGA_E_GPS};
use std::collections::BTreeMap;
use std::path::Path;

/// The book's orbit (a = 7271 km, e = 0.001) under the point mass alone (so the closed
/// form is exact), 600 s at the observation level, an OCXO.
fn scenario(relativity: bool) -> String {
    format!(
        r#"
name = "rel-clock"
seed = 2
[time]
start = "2023-03-12T00:00:00 GPST"
duration_s = 600.0
[gnss.beidou]
enabled = false
[platform.leo.elements]
semi_major_axis_km = 7271.0
eccentricity = 0.001
inclination_deg = 98.0
raan_deg = 0.0
arg_perigee_deg = 0.0
mean_anomaly_deg = 0.0
[platform.leo.forces]
j2 = false
drag = false
[[antennas]]
name = "ant1"
position_body_m = [0.0, 0.0, 0.0]
[signal]
cn0_dbhz = 45.0
[errors.receiver_clock]
preset = "ocxo"
relativity = {relativity}
[observation]
level = "observation"
"#
    )
}

/// Each epoch's pseudoranges of the observation truth, by satellite.
fn pseudoranges(path: &Path) -> Vec<BTreeMap<String, f64>> {
    let file = read_obs_file(path).unwrap();
    (file.epochs.iter())
        .map(|e| {
            (e.sats.iter())
                .filter_map(|r| Some((r.sat.to_string(), r.pseudorange_m?)))
                .collect()
        })
        .collect()
}

/// On every epoch every satellite's pseudorange moves by the same amount, c times the
/// Keplerian closed form `-(3 mu / (2a) - W0) t / c^2 - 2 (r . v - r0 . v0) / c^2` (a
/// from the first state) within 5 mm (# assumed bar: the RINEX millimetre and the
/// observation instants moving with the clock, 1e-7 s at 7 km/s); over the 600 s the
/// secular part reaches about 39 m.
#[test]
fn pseudoranges_move_by_the_proper_time_of_the_orbit() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    for (name, on) in [("off", false), ("on", true)] {
        std::fs::write(d.join(format!("{name}.toml")), scenario(on)).unwrap();
        support::skyforge_ok(&["synth", &format!("{name}.toml"), "--out", name], d);
    }
    let (off, on) = (
        pseudoranges(&d.join("off/ant1.obs.rnx")),
        pseudoranges(&d.join("on/ant1.obs.rnx")),
    );
    let truth = TruthFile::open(&d.join("on/truth.h5")).unwrap();
    let p = truth.platform(1 << 20).unwrap();
    let inertial =
        |k: usize| p.v_ecef_mps[k] + Vec3::new(0.0, 0.0, OMEGA_E_GPS).cross(&p.r_ecef_m[k]);
    let a = 1.0 / (2.0 / p.r_ecef_m[0].norm() - inertial(0).norm_squared() / GM_GPS);
    let w0 = 62_636_856.0;
    let rv0 = p.r_ecef_m[0].dot(&inertial(0));
    assert_eq!(off.len(), on.len());
    let mut last = 0.0;
    for (k, (a_off, a_on)) in off.iter().zip(&on).enumerate() {
        let t = p.t_s[k];
        let rv = p.r_ecef_m[k].dot(&inertial(k));
        let expected = C_MPS
            * (-(1.5 * GM_GPS / a - w0) * t / (C_MPS * C_MPS) - 2.0 * (rv - rv0) / (C_MPS * C_MPS));
        for (sat, pr) in a_on {
            let Some(pr_off) = a_off.get(sat) else {
                continue;
            };
            let moved = pr - pr_off;
            assert!(
                (moved - expected).abs() < 5e-3,
                "t {t} {sat}: {moved} m vs {expected} m"
            );
        }
        last = expected;
    }
    assert!(
        (last + 39.2).abs() < 0.5,
        "secular part over 600 s: {last} m"
    );
}
