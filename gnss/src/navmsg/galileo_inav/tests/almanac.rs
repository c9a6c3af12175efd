//! Almanac words 7-10.

use super::super::words;
use super::super::{InavAssembler, InavEncoder, InavParams};
use super::{WEEK, decode_pages, epoch, frame_page_at};
use hifitime::Unit;
use skyforge_orbits::ephemeris::{NavMessage, nominal};
use skyforge_orbits::time::TimeOrigin;

#[test]
fn a_frame_carries_the_whole_nominal_constellation_within_kilometres() {
    let set = nominal::galileo(epoch());
    let enc = InavEncoder::new(&set[0], &set, &InavParams::default(), WEEK).unwrap();
    let first = frame_page_at(&enc, epoch());
    let mut asm = InavAssembler::new();
    for page in decode_pages(&enc, first, 360) {
        asm.push(&page);
    }
    let almanac = asm.almanac();
    let mut prns: Vec<u8> = set.iter().map(|e| e.sat.prn).collect();
    prns.sort_unstable();
    assert_eq!(almanac.iter().map(|a| a.sat.prn).collect::<Vec<_>>(), prns);
    let origin = TimeOrigin::new(epoch());
    for a in &almanac {
        let e = set.iter().find(|e| e.sat == a.sat).unwrap();
        assert_eq!(
            (a.toe, a.message, a.health),
            (epoch(), NavMessage::GalileoInav, 0)
        );
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
fn almanac_health_and_an_out_of_sequence_word_are_handled() {
    let mut set = nominal::galileo(epoch());
    set.truncate(3);
    // Satellite 2: E1-B HS 3, E5b HS 2.
    set[1].health = (3 << 1) | (2 << 7);
    let enc = InavEncoder::new(&set[0], &set, &InavParams::default(), WEEK).unwrap();
    let first = frame_page_at(&enc, epoch());
    let pages = decode_pages(&enc, first, 30);
    let mut asm = InavAssembler::new();
    pages.iter().for_each(|p| {
        asm.push(p);
    });
    let almanac = asm.almanac();
    assert_eq!(almanac.len(), 3);
    let second = almanac.iter().find(|a| a.sat == set[1].sat).unwrap();
    assert_eq!(second.health, set[1].health);
    // Without word 9 the triple is dropped: no satellite is built from two triples.
    let mut asm = InavAssembler::new();
    pages.iter().filter(|p| p.word_type != 9).for_each(|p| {
        asm.push(p);
    });
    assert!(asm.almanac().is_empty());
}

#[test]
fn an_empty_almanac_set_sends_empty_slots() {
    let e = super::realistic(9, epoch() + Unit::Minute * 17);
    let enc = InavEncoder::new(&e, &[], &InavParams::default(), WEEK).unwrap();
    let first = frame_page_at(&enc, e.toe);
    let pages = decode_pages(&enc, first, 30);
    let w7 = pages.iter().find(|p| p.word_type == 7).unwrap();
    // IODa, WNa, t0a: toe 10:17 -> t0a 10:10.
    assert_eq!(w7.field("t0a"), Some((10 * 3600 + 600) / 600));
    assert_eq!(w7.field("WNa"), Some(i64::from(WEEK % 4)));
    assert_eq!(w7.field("SVID"), Some(0));
    for wt in 7..=10 {
        let p = pages.iter().find(|p| p.word_type == wt).unwrap();
        assert_eq!(p.fields().count(), words::layout(wt).unwrap().len());
    }
    let mut asm = InavAssembler::new();
    pages.iter().for_each(|p| {
        asm.push(p);
    });
    assert!(asm.almanac().is_empty());
}
