//! Tests of `skyforge_validate::observables::table` on observations with known errors.

mod observables_support;

use observables_support::{Rec, obs_file};
use skyforge_validate::observables::compare::compare;
use skyforge_validate::observables::table::print_comparison;

#[test]
fn every_satellite_and_the_totals_are_printed() {
    let epochs: Vec<(f64, Vec<Rec>)> = (0..10)
        .map(|k| {
            let recs = ["G05", "G07", "C01"]
                .iter()
                .enumerate()
                .map(|(i, &sat)| Rec {
                    sat,
                    pr: 2.0e7 + 1e5 * i as f64 + 100.0 * k as f64,
                    phase: 1.0e8 + 500.0 * k as f64,
                    dop: -500.0,
                    cn0: 45.0,
                    lli: 0,
                })
                .collect();
            (k as f64, recs)
        })
        .collect();
    let f = obs_file(&epochs, "GPS");
    let c = compare(&f, &f).unwrap();
    let mut out = Vec::new();
    print_comparison(&c, &mut out).unwrap();
    let text = String::from_utf8(out).unwrap();
    for needle in ["G05", "G07", "C01", "GPS", "BeiDou", "overall", "arcs: 3"] {
        assert!(text.contains(needle), "{needle}:\n{text}");
    }
}
