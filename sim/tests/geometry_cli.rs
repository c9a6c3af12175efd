//! `skyforge attitude --estimate-geometry` end to end: the bundled thesis/t-4.3 (antennas
//! offset from the nominal B0 by the thesis's dB0) shortened to 600 s at the observation
//! level -> `skyforge run` -> the geometry-offset UKF of thesis 4.3 -> its CSV, HDF5 and
//! corrected geometry, which `skyforge attitude --geometry` then reads, and the report's
//! figures of it.

mod support;

use skyforge_navigation::geometry_file::BodyGeometryFile;
use skyforge_navigation::geometry_offset::align;
use skyforge_orbits::Vec3;
use std::path::Path;
use support::{dataset, short_scenario, skyforge, skyforge_ok, text};

/// The bundled thesis/t-4.3 shortened to `duration_s`, run at the observation level into
/// `d/run`, then `skyforge attitude --estimate-geometry` on it into `d/att`: what that
/// printed.
fn estimate_geometry(d: &Path, duration_s: u32) -> String {
    let scenario = short_scenario(d, "thesis/t-4.3", duration_s);
    skyforge_ok(&["run", scenario.to_str().unwrap(), "--out", "run"], d);
    attitude(
        d,
        "run/geometry.toml",
        &["--estimate-geometry", "--out", "att"],
    )
}

/// `skyforge attitude` in `d` on the run's observations with `geometry` and `extra`.
fn attitude(d: &Path, geometry: &str, extra: &[&str]) -> String {
    let mut args = vec![
        "attitude",
        "run/observations/ant1.obs.rnx",
        "run/observations/ant2.obs.rnx",
        "run/observations/ant3.obs.rnx",
        "--nav",
        "run/nav.rnx",
        "--geometry",
        geometry,
    ];
    args.extend(extra);
    skyforge_ok(&args, d)
}

/// `skyforge report` in `d` of the run with the attitude chain's `att`.
fn report(d: &Path) -> String {
    skyforge_ok(
        &["report", "run", "--attitude", "att", "--out", "r.html"],
        d,
    )
}

/// Baselines (antenna minus the master) of a geometry file's positions.
fn baselines(positions: &[Vec3]) -> [Vec3; 2] {
    [positions[1] - positions[0], positions[2] - positions[0]]
}

#[test]
fn estimates_the_offsets_and_writes_a_geometry_attitude_reads() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let printed = estimate_geometry(d, 600);
    assert!(printed.contains("plain LAMBDA"), "{printed}");

    // The truth: the scenario's true positions (nominal + offset_body_m), turned to the
    // nominal orientation (what the default estimator holds; docs/geometry.md).
    let nominal = BodyGeometryFile::read(&d.join("run/geometry.toml")).unwrap();
    let b0 = baselines(&nominal.positions());
    let truth = [Vec3::new(1.0, 0.0, 0.0), Vec3::new(0.0, 1.0, 0.0)];
    let expected = align(&truth, &b0).unwrap().baselines;
    let corrected = BodyGeometryFile::read(&d.join("att/geometry_corrected.toml")).unwrap();
    let est = baselines(&corrected.positions());
    for k in 0..2 {
        let e = (est[k] - expected[k]).amax();
        assert!(
            e < 5e-4,
            "baseline {}: {:?} against {:?}",
            k + 1,
            est[k],
            expected[k]
        );
        // ... where the nominal geometry was off by millimetres to centimetres.
        assert!((b0[k] - expected[k]).amax() > 0.005);
    }

    // CSV and HDF5 hold one row per update; the last equals the corrected geometry.
    let csv = std::fs::read_to_string(d.join("att/geometry_offsets.csv")).unwrap();
    let rows: Vec<&str> = csv.lines().collect();
    assert!(
        rows[0].starts_with("time_gpst,dx1_m,dy1_m,dz1_m"),
        "{}",
        rows[0]
    );
    let h5 = hdf5::File::open(d.join("att/geometry_offsets.h5")).unwrap();
    let offsets: Vec<f64> = dataset(&h5, "offsets");
    let cov: Vec<f64> = dataset(&h5, "offsets_covariance");
    assert_eq!(offsets.len(), 6 * (rows.len() - 1));
    assert_eq!(cov.len(), 36 * (rows.len() - 1));
    assert!(rows.len() > 500, "{} rows", rows.len());
    let last = &offsets[offsets.len() - 6..];
    for i in 0..6 {
        assert!((b0[i / 3][i % 3] + last[i] - est[i / 3][i % 3]).abs() < 1e-12);
    }
    // Its standard deviations are reported and well below a millimetre after 600 s.
    let sigma = (0..6).map(|i| cov[cov.len() - 36 + 7 * i].sqrt());
    assert!(
        sigma.clone().all(|s| s > 0.0 && s < 1e-3),
        "{:?}",
        sigma.collect::<Vec<_>>()
    );

    // The report draws the offsets' errors against the truth (thesis figs. 4.3-4/4.3-5).
    let printed = report(d);
    assert!(printed.contains("9 figures"), "{printed}");
    let page = std::fs::read_to_string(d.join("r.html")).unwrap();
    for b in [1, 2] {
        assert!(
            page.contains(&format!("Baseline {b} geometry-offset error")),
            "{b}"
        );
        assert!(page.contains(&format!(
            "Baseline {b} offset estimate minus the true offset"
        )));
    }

    // The corrected geometry is a geometry file `attitude` reads.
    attitude(d, "att/geometry_corrected.toml", &["--out", "att2"]);
}

#[test]
fn four_antennas_are_refused_before_anything_is_written() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let geometry = "[[antennas]]\nname = \"a\"\nposition_body_m = [0.0, 0.0, 0.0]\n\
                    [[antennas]]\nname = \"b\"\nposition_body_m = [1.0, 0.0, 0.0]\n\
                    [[antennas]]\nname = \"c\"\nposition_body_m = [0.0, 1.0, 0.0]\n\
                    [[antennas]]\nname = \"d\"\nposition_body_m = [1.0, 1.0, 0.0]\n";
    std::fs::write(d.join("geometry.toml"), geometry).unwrap();
    for f in ["a.rnx", "b.rnx", "c.rnx", "d.rnx", "nav.rnx"] {
        std::fs::write(d.join(f), "").unwrap();
    }
    let o = skyforge(
        &[
            "attitude",
            "a.rnx",
            "b.rnx",
            "c.rnx",
            "d.rnx",
            "--nav",
            "nav.rnx",
            "--geometry",
            "geometry.toml",
            "--estimate-geometry",
            "--out",
            "out",
        ],
        d,
    );
    let t = text(&o);
    assert!(!o.status.success(), "{t}");
    assert!(!d.join("out").exists(), "{t}");
    assert!(t.contains("--estimate-geometry with geometry.toml"), "{t}");
    assert!(t.contains("written for 2 baselines"), "{t}");
}

#[test]
fn too_short_a_run_estimates_nothing_and_the_report_still_draws() {
    // Three epochs: never the four consecutive fixed epochs the UKF starts from.
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let printed = estimate_geometry(d, 3);
    assert!(printed.contains("no update"), "{printed}");
    let report = report(d);
    assert!(report.contains("7 figures"), "{report}");
}
