//! Almanac pages 5 and 6.

use super::super::{FnavAssembler, FnavEncoder, FnavParams};
use super::{WEEK, decode_pages, epoch, frame_page_at};
use hifitime::Unit;
use skyforge_orbits::ephemeris::nominal;
use skyforge_orbits::time::TimeOrigin;

#[test]
fn two_frames_carry_the_whole_nominal_constellation_within_kilometres() {
    let set = nominal::galileo(epoch());
    let enc = FnavEncoder::new(&set[0], &set, &FnavParams::default(), WEEK).unwrap();
    let first = frame_page_at(&enc, epoch());
    let mut asm = FnavAssembler::new();
    for page in decode_pages(&enc, first, 120) {
        asm.push(&page);
    }
    let almanac = asm.almanac();
    let mut prns: Vec<u8> = set.iter().map(|e| e.sat.prn).collect();
    prns.sort_unstable();
    assert_eq!(almanac.iter().map(|a| a.sat.prn).collect::<Vec<_>>(), prns);
    let origin = TimeOrigin::new(epoch());
    for a in &almanac {
        let e = set.iter().find(|e| e.sat == a.sat).unwrap();
        // t0a is toe on the 600 s grid: here the same instant.
        assert_eq!(a.toe, epoch());
        let (ba, be) = (a.bind(&origin), e.bind(&origin));
        for h in [0.0, 1.0, 3.0] {
            let t = h * 3600.0;
            let gap = (ba.position_ecef(t) - be.position_ecef(t)).norm();
            // Almanac angles are sent to 2^-15 semicircles (about 2.8 km at 29 600 km).
            assert!(gap < 10e3, "{} at {h} h: {gap} m", a.sat);
        }
        assert!((ba.clock_offset_s(0.0) - be.clock_offset_s(0.0)).abs() < 2f64.powi(-19));
    }
}

#[test]
fn an_empty_almanac_set_sends_empty_slots() {
    let e = super::realistic(9, epoch() + Unit::Minute * 17);
    let enc = FnavEncoder::new(&e, &[], &FnavParams::default(), WEEK).unwrap();
    let first = frame_page_at(&enc, e.toe);
    let pages = decode_pages(&enc, first, 10);
    let pt5 = pages.iter().find(|p| p.page_type == 5).unwrap();
    // IODa, WNa, t0a: toe 10:17 -> t0a 10:10.
    assert_eq!(pt5.field("t0a"), Some((10 * 3600 + 600) / 600));
    assert_eq!(pt5.field("WNa"), Some(i64::from(WEEK % 4)));
    assert!(
        pt5.fields()
            .filter(|(n, _)| *n == "SVID")
            .all(|(_, v)| v == 0)
    );
    let mut asm = FnavAssembler::new();
    pages.iter().for_each(|p| {
        asm.push(p);
    });
    assert!(asm.almanac().is_empty());
}
