//! Carrier-smoothed code in the receiver's PVT (`[pvt.carrier_smoothing]`, the book's
//! growing-memory filter, eqs. 5-60..5-64): the same recording received with raw and with
//! smoothed code.

mod support;

use skyforge_orbits::Vec3;

/// Standard deviation of each ECEF axis of `fixes` about its mean (m).
fn scatter(fixes: &[(f64, Vec3, f64)]) -> Vec3 {
    let n = fixes.len() as f64;
    let mean = fixes.iter().fold(Vec3::zeros(), |a, f| a + f.1) / n;
    let sq = fixes.iter().fold(Vec3::zeros(), |a, f| {
        a + (f.1 - mean).component_mul(&(f.1 - mean))
    });
    (sq / (n - 1.0)).map(f64::sqrt)
}

/// `interop-gps-static` cut to 40 s (# assumed: long enough for some 25 fixes (the first about 13 s in)),
/// received twice with its navigation file as assistance: smoothing at least halves the
/// fixes' scatter on every axis (# assumed bar: the DLL already averages the code over a
/// few seconds, the filter over the whole run), and moves their mean by less than 0.5 m
/// (# assumed: no bias of its own; the ionosphere's code-carrier divergence over 40 s is
/// centimetres).
#[test]
fn smoothing_narrows_the_fixes_without_moving_them() {
    let dir = tempfile::tempdir().expect("tempdir");
    let text = support::bundled_edited(
        "interop-gps-static",
        &[("duration_s = 90.0", "duration_s = 40.0")],
    );
    let scenario = support::write_scenario(dir.path(), "smooth.toml", &text);
    support::skyforge_ok(&["synth", &scenario, "--out", "sim"], dir.path());
    let sim = dir.path().join("sim");
    let receive = |name: &str, config: &str| {
        let path = dir.path().join(format!("{name}.toml"));
        std::fs::write(&path, config).expect("receiver config");
        let out = dir.path().join(name);
        support::receive_all_recordings_with(&sim, &path, &out, &[], dir.path());
        support::fixes(&out)
    };
    let raw = receive("raw", "[pvt]\n");
    let smoothed = receive("smoothed", "[pvt.carrier_smoothing]\n");
    assert!(
        raw.len() >= 20 && smoothed.len() == raw.len(),
        "{} and {} fixes",
        raw.len(),
        smoothed.len()
    );
    let (s_raw, s_smooth) = (scatter(&raw), scatter(&smoothed));
    let mean =
        |f: &[(f64, Vec3, f64)]| f.iter().fold(Vec3::zeros(), |a, x| a + x.1) / f.len() as f64;
    let shift = (mean(&raw) - mean(&smoothed)).norm();
    println!(
        "SMOOTHING {} fixes: scatter raw {:.3} {:.3} {:.3} m, smoothed {:.3} {:.3} {:.3} m; means {shift:.3} m apart",
        raw.len(),
        s_raw.x,
        s_raw.y,
        s_raw.z,
        s_smooth.x,
        s_smooth.y,
        s_smooth.z
    );
    for axis in 0..3 {
        assert!(
            s_smooth[axis] <= 0.5 * s_raw[axis],
            "axis {axis}: {s_smooth} vs {s_raw}"
        );
    }
    assert!(shift < 0.5, "{shift} m");
}
