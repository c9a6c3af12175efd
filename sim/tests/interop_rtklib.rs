//! Interoperability tier: RTKLIB (Debian package `rtklib`, `rnx2rtkp`) reads the RINEX 3.04
//! observation truth and the navigation file `skyforge synth` writes, and its single-point
//! solution, with RTKLIB's own broadcast (Klobuchar) ionosphere correction and no
//! troposphere (switched off in the signal for this test), recovers the site.

mod support;

use skyforge_orbits::frames::{Geodetic, geodetic_to_ecef};
use support::{require_rnx2rtkp, rnx2rtkp, rtklib_xyz_solutions, skyforge_ok};

#[test]
#[ignore = "interop tier: needs rtklib (scripts/test.sh installs it)"]
fn rtklib_single_point_solution_from_our_rinex_recovers_the_site() {
    require_rnx2rtkp();
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path();
    let toml = skyforge_ok(&["scenarios", "show", "interop-gps-static"], dir)
            .replacen("duration_s = 90.0", "duration_s = 10.0", 1)
            // The ionosphere is the term under test; RTKLIB's troposphere model is not ours.
            + "\n[errors.troposphere]\nmodel = \"off\"\n";
    std::fs::write(dir.join("short.toml"), toml).unwrap();
    skyforge_ok(&["synth", "short.toml", "--out", "out"], dir);
    let out = dir.join("out");
    std::fs::write(
        out.join("spp.conf"),
        "pos1-posmode=single\npos1-elmask=5\npos1-ionoopt=brdc\npos1-tropopt=off\npos1-sateph=brdc\npos1-navsys=1\nout-solformat=xyz\n",
    )
    .unwrap();
    rnx2rtkp(
        &["-k", "spp.conf", "-o", "spp.pos", "ant1.obs.rnx", "nav.rnx"],
        &out,
    );
    let pos = std::fs::read_to_string(out.join("spp.pos")).unwrap();
    let site = geodetic_to_ecef(&Geodetic {
        lat_rad: 30f64.to_radians(),
        lon_rad: 114f64.to_radians(),
        h_m: 50.0,
    });
    let errors: Vec<f64> = rtklib_xyz_solutions(&pos)
        .iter()
        .map(|r| (r - site).norm())
        .collect();
    println!(
        "RTKLIB single point: {} epochs, worst 3D error {:.4} m",
        errors.len(),
        errors.iter().cloned().fold(0.0, f64::max)
    );
    assert!(
        errors.len() >= 9,
        "{} RTKLIB solutions:\n{pos}",
        errors.len()
    );
    for e in errors {
        assert!(e < 0.01, "RTKLIB solution {e} m from the site");
    }
}
