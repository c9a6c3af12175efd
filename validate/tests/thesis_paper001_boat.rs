//! `validate thesis --only P1-D` (paper 001's dynamic test): a boat on a park lake near
//! Changsha (bundled `paper001-boat-lake`), 600 s moored for the alignment, then a closed
//! loop of 4458 s with heave, pitch and roll waves and hull vibration; the navigation-grade
//! IMU integrated with the three BeiDou GEOs' time-differenced carrier phase, their code
//! differences and the lake's height (`navigation::gnss_ins::tdcp_aided`) at the paper's
//! 10 Hz, and alone; eight seeds, medians (about 40 s on two cores).
//!
//! Checked: the selection runs this table alone, its six rows are there with finite
//! positive values, and each keeps its verdict of the first run (2026-12-02, verdicts
//! registered before the run; the numbers of the 10 Hz run, 2026-12-02, the same verdicts
//! as at the first run's 1 Hz: 2.21 m, 6174, 7430 m, 1.32 m): the integrated maximum
//! horizontal error 1.72 m (bar: at most 56 m, the paper's under 35 m) and the pure INS
//! 21 300 times the integrated error at the return point (bar 10) are reproduced; the pure INS's 7430 m is within a factor 3
//! of the paper's 5971 m (or 597.1 m), but it is the undamped vertical channel's doing
//! (the pure INS's height is off by 140 km at the return point, median; per seed the
//! horizontal error follows the height error); the integrated error at the return point,
//! 0.37 m, **deviates** from the paper's 34.9 m (factor 2): the simulation has none of
//! what the paper blames (a GPS reference with its own errors and gaps, a real lever arm's
//! error beyond the assumed 5 cm), and the code differences with the lake's height hold
//! the position to metres. The pure INS with its height held at the lake's (two rows
//! registered 2026-12-02 before their first run, the same bars): 860 m at the return
//! point, 2240 times the integrated error, both reproduced (860 m is within a factor 3 of
//! 597.1 m, not of 5971 m). The table is printed
//! (`cargo test -p skyforge-validate --test thesis_paper001_boat -- --nocapture`).

mod thesis_support;

use skyforge_validate::report::Verdict;
use thesis_support::table_and_figures;

/// The six rows, in order, with the verdict of the registered run.
const ROWS: [(&str, Verdict); 6] = [
    (
        "integrated maximum horizontal error over the loop",
        Verdict::Reproduced,
    ),
    (
        "integrated horizontal error at the return point",
        Verdict::Deviates,
    ),
    (
        "pure INS / integrated horizontal error at the return point",
        Verdict::Reproduced,
    ),
    (
        "pure INS horizontal error at the return point",
        Verdict::Reproduced,
    ),
    (
        "pure INS (height held) / integrated horizontal error at the return point",
        Verdict::Reproduced,
    ),
    (
        "pure INS (height held) horizontal error at the return point",
        Verdict::Reproduced,
    ),
];

#[test]
fn p1_d_boat_on_the_lake_keeps_its_registered_verdicts() {
    let (rows, _) = table_and_figures("P1-D");
    for r in &rows {
        println!(
            "{:60} paper {:8.1} ours {:8.2} {:?}  {}",
            r.row,
            r.thesis.unwrap_or(f64::NAN),
            r.ours.unwrap_or(f64::NAN),
            r.verdict,
            r.note
        );
    }
    assert_eq!(rows.len(), ROWS.len(), "{rows:#?}");
    for (r, (name, verdict)) in rows.iter().zip(ROWS) {
        assert_eq!(r.table, "P1-D");
        assert_eq!(r.row, name);
        let v = r.ours.unwrap();
        assert!(v.is_finite() && v > 0.0, "{r:?}");
        assert_eq!(
            r.verdict, verdict,
            "not the registered run's verdict: {r:?}"
        );
    }
}
