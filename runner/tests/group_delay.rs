//! The signal follows each satellite's clock as the user of that signal sees it: the
//! broadcast polynomial minus the broadcast group delay (GPS L1 C/A: TGD, IS-GPS-200
//! 20.3.3.3.3.2). The same scenario from two navigation files that differ only in TGD must
//! give observation truths that differ by exactly c TGD on every pseudorange and every
//! carrier phase (in metres), and by nothing else.

mod support;

use hifitime::{Epoch, TimeScale};
use skyforge_orbits::constants::C_MPS;
use skyforge_orbits::ephemeris::{nominal, write_nav};

/// A 3 s static GPS site at the observation level, noiseless, its constellation from
/// `nav.rnx` in `dir`: the nominal GPS sets with TGD `tgd_s`.
fn truth_with_tgd(dir: &std::path::Path, tgd_s: f64) -> Vec<(String, f64, f64)> {
    let start = Epoch::from_gregorian(2023, 3, 12, 0, 0, 0, 0, TimeScale::GPST);
    let mut ephs = nominal::gps(start);
    for e in &mut ephs {
        e.clock.tgd_s = tgd_s;
    }
    let mut nav = Vec::new();
    write_nav(
        &ephs,
        &skyforge_orbits::ephemeris::NavHeader::new("test"),
        &mut nav,
    )
    .expect("nav text");
    std::fs::write(dir.join("nav.rnx"), nav).expect("write nav");
    let head = "[time]\nstart = \"2023-03-12T00:00:00 GPST\"\nduration_s = 3.0\n\n\
        [gnss.gps]\nsource = \"rinex\"\nnav_file = \"nav.rnx\"\n";
    let tail = support::observation_level("", 0.0, 0.0);
    let run = support::run_static_site("tgd", 1, head, &tail, dir);
    run.truth[0]
        .epochs
        .iter()
        .flat_map(|e| {
            e.sats.iter().map(move |r| {
                let lambda = r.signal.wavelength_m();
                (
                    format!("{} {}", e.time, r.sat),
                    r.pseudorange_m.expect("code"),
                    r.carrier_phase_cycles.expect("phase") * lambda,
                )
            })
        })
        .collect()
}

#[test]
fn every_observable_moves_by_c_tgd() {
    let dir = tempfile::tempdir().expect("tempdir");
    let without = truth_with_tgd(dir.path(), 0.0);
    // assumed: about 10 ns, a TGD of the size GPS broadcasts, on the LNAV field's 2^-31 s
    // grid (the message quantises TGD, and the signal follows the quantised value).
    let tgd_s = 21.0 * 2f64.powi(-31);
    let with = truth_with_tgd(dir.path(), tgd_s);
    assert_eq!(without.len(), with.len());
    assert!(without.len() >= 4 * 3, "{} records", without.len());
    let expect_m = C_MPS * tgd_s;
    for ((key, p0, l0), (key1, p1, l1)) in without.iter().zip(&with) {
        assert_eq!(key, key1);
        assert!((p1 - p0 - expect_m).abs() < 1e-6, "{key}: code {}", p1 - p0);
        assert!(
            (l1 - l0 - expect_m).abs() < 1e-6,
            "{key}: phase {}",
            l1 - l0
        );
    }
}
