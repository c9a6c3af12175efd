//! Real-data tier for the Galileo F/NAV message: every F/NAV ephemeris of the RINEX 4 file
//! BRD400DLR_S_20230710000_01D_MN (2023-03-12) goes through the encoder and back.
//!
//! Broadcast values are multiples of the message's scale factors, so quantisation must
//! give them back: the orbit and clock of `broadcast_ephemeris()` must match the file's to
//! well below a millimetre over toe + 0..4 h (a wrong scale factor or field width shows up
//! here, or as an out-of-range error), and the pages of the set's first subframe after
//! toe must decode (sync, de-interleaving, Viterbi, CRC) to that same ephemeris.
//!
//! Run with `cargo test -p skyforge-gnss --test real_data_fnav -- --ignored --nocapture`.

use skyforge_gnss::navmsg::galileo_fnav::{
    FNAV_PAGE_S, FnavAssembler, FnavEncoder, FnavParams, decode_page,
};
use skyforge_orbits::ephemeris::{NavMessage, System};
use skyforge_orbits::time::{TimeOrigin, gpst_week_sow};

#[test]
#[ignore = "real-data tier: cargo test -- --ignored"]
fn every_fnav_set_of_the_day_survives_the_message() {
    let all: Vec<_> = skyforge_orbits::real_data::ephemerides(
        "nav/BRD400DLR_S_20230710000_01D_MN.rnx.gz",
        System::Galileo,
    )
    .into_iter()
    .filter(|e| e.message == NavMessage::GalileoFnav)
    .collect();
    assert!(all.len() > 1000, "{} F/NAV sets", all.len());
    let params = FnavParams::default();
    let (mut worst_m, mut worst_clock_s, mut decoded) = (0.0f64, 0.0f64, 0usize);
    for (k, eph) in all.iter().enumerate() {
        let week = gpst_week_sow(eph.toe).0 - 1024 - 1;
        let enc = FnavEncoder::new(eph, &all[..0], &params, week)
            .unwrap_or_else(|e| panic!("{}: {e}", eph.sat));
        let sent = enc.broadcast_ephemeris();
        let origin = TimeOrigin::new(eph.toe);
        let (a, b) = (eph.bind(&origin), sent.bind(&origin));
        for t in [0.0, 3600.0, 7200.0, 14_400.0] {
            worst_m = worst_m.max((a.position_ecef(t) - b.position_ecef(t)).norm());
            worst_clock_s = worst_clock_s.max((a.clock_offset_s(t) - b.clock_offset_s(t)).abs());
        }
        // Decode one subframe (pages 1-4 and an almanac page) of every tenth set.
        if k % 10 == 0 {
            let since_week_s = (eph.toe - enc.week_start()).to_seconds();
            let first_page = (since_week_s / FNAV_PAGE_S as f64).ceil() as u64;
            let mut asm = FnavAssembler::new();
            let mut got = None;
            for page in first_page..first_page + 10 {
                let soft: Vec<f32> = enc
                    .page_symbols(page)
                    .iter()
                    .map(|&s| if s == 0 { 1.0 } else { -1.0 })
                    .collect();
                let p = decode_page(&soft).unwrap_or_else(|e| panic!("{}: {e:?}", eph.sat));
                if let Some(e) = asm.push(&p) {
                    got = Some(e);
                }
            }
            let got = got.unwrap_or_else(|| panic!("{}: no ephemeris decoded", eph.sat));
            assert_eq!(got.eph, sent, "{}", eph.sat);
            decoded += 1;
        }
    }
    println!(
        "{} F/NAV sets: orbit within {worst_m:.2e} m and clock within {worst_clock_s:.2e} s \
         of the file over 4 h; {decoded} decoded from their pages",
        all.len()
    );
    assert!(worst_m < 1e-3, "{worst_m} m");
    assert!(worst_clock_s < 1e-12, "{worst_clock_s} s");
}
