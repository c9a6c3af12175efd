//! `validate thesis --only B-5.5` (book section 5.5.4, Table 5-3): the bundled
//! `book-od-leo` on its four registered seeds at the text's orbit (a = 7271 km) and at the
//! title's 500 km, single-point fixes every 60 s into the position filter. Checked: the
//! selection runs this table alone, every row is there with a finite positive value, and
//! the RSS rows are where they were measured at the first run (position 29.9 m, inside
//! the contract's factor 1.6 of the book's 29.9 m; velocity 0.041 m/s, a miss, six times
//! below the book's 0.255 m/s: the filter's assumed process noise lets the dynamics carry
//! the velocity, where the book's velocity errors, eight times the orbit rate times its
//! position errors, say the book's filter followed its fixes). The second set-up
//! (registered 2026-12-01 before its first run: the text's orbit with the calibrated
//! Doppler noise) gave the same picture: position RSS 30.3 m, reproduced; velocity RSS
//! 0.040 m/s, the same miss, so the truth's Doppler of the first set-up was not its
//! cause. The table is printed
//! (`cargo test -p skyforge-validate --test thesis_book_orbit_determination -- --nocapture`).

mod thesis_support;

use skyforge_validate::report::Verdict;
use thesis_support::table_and_figures;

#[test]
fn b_5_5_writes_every_row_and_its_rss_where_measured() {
    let (rows, _) = table_and_figures("B-5.5");
    for r in &rows {
        println!(
            "{:32} book {:8.4} ours {:8.4} {:?}  {}",
            r.row,
            r.thesis.unwrap_or(f64::NAN),
            r.ours.unwrap_or(f64::NAN),
            r.verdict,
            r.note
        );
    }
    // Six axes, position and velocity RSS at two orbits, two sampling rows, height and
    // eccentricity; the second set-up's six axes and two RSS rows.
    assert_eq!(rows.len(), 22, "{rows:#?}");
    for r in &rows {
        assert_eq!(r.table, "B-5.5");
        let v = r.ours.unwrap();
        assert!(v.is_finite() && v > 0.0, "{r:?}");
    }
    let row = |name: &str| rows.iter().find(|r| r.row == name).expect(name);
    for suffix in ["", " (Doppler noise)"] {
        let position = row(&format!("position RSS, a = 7271 km{suffix}"));
        assert_eq!(position.verdict, Verdict::Reproduced, "{position:?}");
        let velocity = row(&format!("velocity RSS, a = 7271 km{suffix}"));
        assert!(
            velocity.ours.unwrap() < 0.255 / 1.6 && velocity.verdict == Verdict::Deviates,
            "no longer the recorded miss: {velocity:?}"
        );
    }
}
