//! Issue 13's signal-level run: the bundled thesis/t-4.3 (antennas offset from the nominal
//! B0 by the thesis's dB0) for 600 s at the signal level, three antennas' I/Q received as
//! they are rendered (`synth --receive`), then `attitude --estimate-geometry` on the
//! receiver's RINEX. Prints how far the estimate gets over the span against the truth
//! (turned to the nominal orientation, which the estimator holds; docs/geometry.md).
//! Ignored tier: about 5 minutes of synthesis and reception.

mod support;

use skyforge_navigation::geometry_file::BodyGeometryFile;
use skyforge_navigation::geometry_offset::align;
use skyforge_orbits::Vec3;
use support::{short_scenario, skyforge_ok};

/// Seconds of signal (# assumed: the "at least 600 s").
const SPAN_S: u32 = 600;

#[test]
#[ignore = "signal level: 600 s of three antennas' I/Q synthesised and received (minutes)"]
fn the_offsets_converge_on_the_receivers_own_observables() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let path = short_scenario(d, "thesis/t-4.3", SPAN_S);
    let text = std::fs::read_to_string(&path)
        .unwrap()
        .replace("level = \"observation\"", "level = \"signal\"");
    std::fs::write(&path, text).unwrap();
    skyforge_ok(
        &["synth", path.to_str().unwrap(), "--out", "sim", "--receive"],
        d,
    );
    let printed = skyforge_ok(
        &[
            "attitude",
            "sim/receive/ant1.obs.rnx",
            "sim/receive/ant2.obs.rnx",
            "sim/receive/ant3.obs.rnx",
            "--nav",
            "sim/nav.rnx",
            "--geometry",
            "sim/geometry.toml",
            "--estimate-geometry",
            "--out",
            "att",
        ],
        d,
    );
    println!("{printed}");
    let nominal = BodyGeometryFile::read(&d.join("sim/geometry.toml")).unwrap();
    let p = nominal.positions();
    let b0 = [p[1] - p[0], p[2] - p[0]];
    let truth = [Vec3::new(1.0, 0.0, 0.0), Vec3::new(0.0, 1.0, 0.0)];
    let expected = align(&truth, &b0).unwrap().baselines;
    let want: Vec<f64> = (0..6)
        .map(|i| expected[i / 3][i % 3] - b0[i / 3][i % 3])
        .collect();
    let csv = std::fs::read_to_string(d.join("att/geometry_offsets.csv")).unwrap();
    let rows: Vec<Vec<String>> = csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(str::to_owned).collect())
        .collect();
    assert!(rows.len() > 60, "{} updates", rows.len());
    // The largest offset error (mm) and the largest reported sigma after each stretch.
    let error_mm = |r: &[String]| {
        (0..6)
            .map(|i| (r[1 + i].parse::<f64>().unwrap() - want[i]).abs() * 1e3)
            .fold(0.0, f64::max)
    };
    let sigma_mm = |r: &[String]| {
        (0..6)
            .map(|i| r[7 + i].parse::<f64>().unwrap() * 1e3)
            .fold(0.0, f64::max)
    };
    for frac in [0.1, 0.25, 0.5, 1.0] {
        let r = &rows[((rows.len() as f64 * frac) as usize).clamp(1, rows.len()) - 1];
        println!(
            "after {}: largest offset error {:.2} mm, largest sigma {:.2} mm",
            r[0],
            error_mm(r),
            sigma_mm(r)
        );
    }
    let nominal_error_mm = want.iter().fold(0.0f64, |a, v| a.max(v.abs())) * 1e3;
    let last = rows.last().unwrap();
    println!("the nominal geometry is off by up to {nominal_error_mm:.1} mm");
    // Converging towards the offsets: the last estimate is far closer than the nominal
    // geometry, and within five of its own sigmas.
    assert!(
        error_mm(last) < 0.2 * nominal_error_mm,
        "{}",
        error_mm(last)
    );
    assert!(
        error_mm(last) < 5.0 * sigma_mm(last).max(0.1),
        "{}",
        error_mm(last)
    );
}
