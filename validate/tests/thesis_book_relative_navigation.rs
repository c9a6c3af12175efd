//! `validate thesis --only B-5.6` (book sections 5.6.4-5.6.5): the bundled
//! `book-relnav-leo` (a chaser 32 km behind a target at 500 km, e = 0.01, SA-era
//! satellite errors) on its four registered seeds. Checked: the table's three rows, each
//! finite and positive; relative DGPS far better than standalone (reproduced: 0.020 of
//! the chaser's standalone RMS at the first run); the carrier-smoothed steady-state
//! position inside the contract's [0.1, 0.8] m (0.57 m); the velocity the recorded miss
//! (0.96 m/s against the book's 0.002: the calibrated Doppler noise of SkyForge's
//! receiver, about 0.15 m/s per satellite, docs/orbit-determination.md). The second
//! set-up, the same rows through the book's relative filter (registered 2026-12-01
//! before its first run): relative DGPS reproduced (0.0100), the steady-state position
//! reproduced (0.714 m), the velocity a miss at 0.0063 m/s against the 0.0032 bar
//! (seeds 1 and 2 inside it; 150 times the unfiltered velocity's accuracy). The book's
//! pseudorange relative DGPS (eq. 5-59, registered 2026-12-01 before its first run):
//! 0.50 m, 0.0066 of standalone (reproduced). The events
//! of the book's figures 5-36/5-38 on `book-relnav-events` (registered 2026-12-01 before
//! their first run; carrier-smoothed, each vehicle on its own satellites): the error
//! while the sets differ 8.6 times the steady-state largest (bar > 3, reproduced); the
//! jump after the chaser's missing pseudoranges 0.19 of the mismatch's (bar < 1,
//! reproduced); the velocity after it 0.70 of its steady-state largest (bar < 2,
//! reproduced); the transient a miss: 6 of 8 draws never settle within 0.8 m before the
//! next satellite change (the ionosphere's code-carrier divergence under unequal
//! smoothing ages, docs/orbit-determination.md). The table is printed (`-- --nocapture`).

mod thesis_support;

use skyforge_validate::report::Verdict;
use thesis_support::table_and_figures;

#[test]
fn b_5_6_relative_dgps_and_carrier_smoothing_where_measured() {
    let (rows, _) = table_and_figures("B-5.6");
    for r in &rows {
        println!(
            "{:44} book {:8.4} ours {:8.4} {:?}  {}",
            r.row,
            r.thesis.unwrap_or(f64::NAN),
            r.ours.unwrap_or(f64::NAN),
            r.verdict,
            r.note
        );
    }
    assert_eq!(rows.len(), 11, "{rows:#?}");
    for r in &rows {
        assert_eq!(r.table, "B-5.6");
        let v = r.ours.unwrap();
        assert!(v.is_finite() && v > 0.0, "{r:?}");
    }
    let filtered = |r: &&skyforge_validate::report::Row| r.row.ends_with("(relative filter)");
    for name in [
        "pseudorange relative DGPS (eq. 5-59)",
        "events: satellite-set mismatch",
        "events: re-initialisation jump",
        "events: velocity after",
    ] {
        let r = rows.iter().find(|r| r.row.starts_with(name)).expect(name);
        assert_eq!(r.verdict, Verdict::Reproduced, "{r:?}");
    }
    let transient = (rows.iter())
        .find(|r| r.row.starts_with("events: transient"))
        .unwrap();
    assert!(
        transient.verdict == Verdict::Deviates && !transient.note.contains("window's end: 0 of"),
        "no longer the recorded miss: {transient:?}"
    );
    let row = |name: &str| {
        (rows.iter())
            .find(|r| r.row.starts_with(name) && !filtered(r))
            .expect(name)
    };
    let filtered_row = |name: &str| {
        (rows.iter())
            .find(|r| r.row.starts_with(name) && filtered(r))
            .expect(name)
    };
    let dgps = row("relative DGPS");
    assert_eq!(dgps.verdict, Verdict::Reproduced, "{dgps:?}");
    let position = row("carrier-smoothed, max |position");
    assert_eq!(position.verdict, Verdict::Reproduced, "{position:?}");
    let velocity = row("carrier-smoothed, max |velocity");
    assert!(
        velocity.verdict == Verdict::Deviates && velocity.ours.unwrap() > 0.1,
        "no longer the recorded miss: {velocity:?}"
    );
    let dgps = filtered_row("relative DGPS");
    assert_eq!(dgps.verdict, Verdict::Reproduced, "{dgps:?}");
    let position = filtered_row("carrier-smoothed, max |position");
    assert_eq!(position.verdict, Verdict::Reproduced, "{position:?}");
    // The recorded miss of the first run (0.0063 m/s); a regression guard set after it:
    // the filter keeps the velocity under 0.02 m/s.
    let velocity = filtered_row("carrier-smoothed, max |velocity");
    assert!(
        velocity.verdict == Verdict::Deviates && velocity.ours.unwrap() < 0.02,
        "no longer the recorded miss: {velocity:?}"
    );
}
