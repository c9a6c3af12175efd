//! Page schedule and the time the pages carry.

use super::{WEEK, decode_pages, encoder, epoch, realistic};
use hifitime::Unit;

#[test]
fn subframes_send_types_1_to_4_then_5_and_6_alternately() {
    let enc = encoder(&realistic(7, epoch()));
    for frame in [0u64, 1, 57, 1007] {
        let types: Vec<u8> = (0..60).map(|i| enc.page_type(frame * 60 + i)).collect();
        for (sf, sub) in types.chunks(5).enumerate() {
            let alm = if sf % 2 == 0 { 5 } else { 6 };
            assert_eq!(sub, [1, 2, 3, 4, alm], "frame {frame} subframe {}", sf + 1);
        }
    }
}

#[test]
fn decoded_wn_and_tow_are_the_page_start() {
    let enc = encoder(&realistic(7, epoch()));
    let first = 3 * 8640 + 1234; // Wednesday, an arbitrary page
    for (n, page) in (first..).zip(decode_pages(&enc, first, 25)) {
        let (wn, tow) = enc.page_time(n);
        assert_eq!((wn, tow), (WEEK, (n * 10) as u32));
        assert_eq!(page.page_type, enc.page_type(n));
        assert_eq!(
            page.tow().map(|t| t == tow),
            (page.page_type <= 4).then_some(true)
        );
        assert_eq!(
            page.wn().map(|w| w == wn),
            (page.page_type <= 3).then_some(true)
        );
        // The page's symbols start TOW seconds into the week, 500 symbols per page.
        let start = enc.week_start() + Unit::Second * f64::from(tow);
        let k =
            ((start - enc.week_start()).to_seconds() * super::super::FNAV_SYMBOL_RATE_HZ) as u64;
        assert_eq!(k, n * 500);
    }
}

#[test]
fn the_week_rolls_over_in_the_pages() {
    let enc = encoder(&realistic(7, epoch()));
    let last = 60_479; // last page of week WEEK
    let pages = decode_pages(&enc, last - 3, 6);
    let times: Vec<(Option<u32>, Option<u32>)> = pages.iter().map(|p| (p.wn(), p.tow())).collect();
    assert_eq!(enc.page_time(last), (WEEK, 604_790));
    assert_eq!(enc.page_time(last + 1), (WEEK + 1, 0));
    // Pages 60476..60481: types 2, 3, 4, 6 (end of frame 1007), then 1, 2 of week + 1.
    assert_eq!(
        times,
        [
            (Some(WEEK), Some(604_760)),
            (Some(WEEK), Some(604_770)),
            (None, Some(604_780)),
            (None, None),
            (Some(WEEK + 1), Some(0)),
            (Some(WEEK + 1), Some(10)),
        ]
    );
}

#[test]
fn symbols_and_symbol_agree_across_page_boundaries() {
    let enc = encoder(&realistic(7, epoch()));
    let first = 500 * 77 + 321;
    let run = enc.symbols(first, 1400);
    assert_eq!(run.len(), 1400);
    for (i, &s) in run.iter().enumerate().step_by(7) {
        assert_eq!(s, enc.symbol(first + i as u64));
    }
    assert_eq!(run[500 - 321..500 - 321 + 12], super::super::FNAV_SYNC);
}
