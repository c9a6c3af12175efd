//! Page schedule, the secondary synchronisation pattern and the time the pages carry.

use super::super::{INAV_SYMBOL_RATE_HZ, INAV_SYNC, SUBFRAME_WORDS};
use super::{WEEK, decode_pages, encoder, epoch, realistic};

/// The E1-B column of the nominal sub-frame table (§4.3.3, Issue 2.1), one entry per page
/// starting at GST 1, 3, ..., 29 s modulo 30 s: (word in the 1st, 3rd, ... subframes of a
/// frame, in the 2nd, 4th, ...).
const ICD_E1B: [(u8, u8); 15] = [
    (2, 2),
    (4, 4),
    (6, 6),
    (7, 9),
    (8, 10),
    (17, 18),
    (19, 20),
    (16, 16),
    (0, 0),
    (22, 22),
    (1, 1),
    (3, 3),
    (5, 5),
    (0, 0),
    (16, 16),
];

#[test]
fn the_subframe_is_the_icds_with_word_0_for_the_words_skyforge_does_not_send() {
    for (slot, (&(a, b), &[x, y])) in ICD_E1B.iter().zip(&SUBFRAME_WORDS).enumerate() {
        let sent = |icd: u8| if (16..=22).contains(&icd) { 0 } else { icd };
        assert_eq!((sent(a), sent(b)), (x, y), "slot {slot}");
    }
    let enc = encoder(&realistic(7, epoch()));
    // Page 1 starts at GST 1 s of the week, the first page of a frame; frames of 24
    // subframes alternate 7, 8 and 9, 10. A frame late in the week and the week's last.
    for first in [1u64, 1 + 360 * 57, 1 + 360 * 839] {
        let (_, tow) = enc.page_time(first);
        assert_eq!(tow % 720, 1);
        for sf in 0..24u64 {
            let types: Vec<u8> = (0..15)
                .map(|i| enc.word_type(first + sf * 15 + i))
                .collect();
            let expected: Vec<u8> = SUBFRAME_WORDS
                .iter()
                .map(|w| w[(sf % 2) as usize])
                .collect();
            assert_eq!(types, expected, "page {first} subframe {}", sf + 1);
        }
    }
    // Page 0 is the last page of the previous week's last frame.
    assert_eq!(enc.page_time(0), (WEEK - 1, 604_799));
    assert_eq!(enc.word_type(0), SUBFRAME_WORDS[14][1]);
}

#[test]
fn decoded_wn_and_tow_are_the_first_symbol_of_the_even_part() {
    let enc = encoder(&realistic(7, epoch()));
    let first = 3 * 43_200 + 1234; // Wednesday, an arbitrary page
    let mut timed = 0;
    for (n, page) in (first..).zip(decode_pages(&enc, first, 40)) {
        let (wn, tow) = enc.page_time(n);
        // E1-B pages start at odd seconds: page n at 2n - 1 s into the week.
        assert_eq!((wn, tow), (WEEK, (2 * n - 1) as u32));
        assert_eq!(page.word_type, enc.word_type(n));
        let has_time = [0, 5, 6].contains(&page.word_type);
        assert_eq!(page.tow().map(|t| t == tow), has_time.then_some(true));
        assert_eq!(
            page.wn().map(|w| w == wn),
            (page.word_type != 6 && has_time).then_some(true)
        );
        timed += usize::from(has_time);
        // The TOW is the page's first symbol: the even part's first sync symbol, 250
        // symbols a second from the week start.
        let k = (f64::from(tow) * INAV_SYMBOL_RATE_HZ) as u64;
        assert_eq!(enc.symbols(k, 10), INAV_SYNC);
        assert_eq!(enc.symbols(k, 500), enc.page_symbols(n));
    }
    assert!(timed >= 20);
}

#[test]
fn the_week_rolls_over_in_the_pages() {
    let enc = encoder(&realistic(7, epoch()));
    let last = 302_400; // starts at 604 799 s: its odd part is the next week's first second
    assert_eq!(enc.page_time(last), (WEEK, 604_799));
    assert_eq!(enc.page_time(last + 1), (WEEK + 1, 1));
    let next = encoder(&realistic(7, epoch())).symbols(604_800 * 250, 750);
    let week_after = super::super::InavEncoder::new(
        &realistic(7, epoch()),
        &[],
        &super::super::InavParams::default(),
        WEEK + 1,
    )
    .unwrap();
    assert_eq!(next, week_after.symbols(0, 750));
    // Pages 302 396..302 402: types 1, 3, 5, 0, 0 (end of frame 839), then 2, 4.
    let pages = decode_pages(&enc, last - 4, 7);
    let times: Vec<_> = pages
        .iter()
        .map(|p| (p.word_type, p.wn(), p.tow()))
        .collect();
    assert_eq!(
        times,
        [
            (1, None, None),
            (3, None, None),
            (5, Some(WEEK), Some(604_795)),
            (0, Some(WEEK), Some(604_797)),
            (0, Some(WEEK), Some(604_799)),
            (2, None, None),
            (4, None, None),
        ]
    );
}

#[test]
fn the_ssp_cycles_with_gst_modulo_6_s() {
    let enc = encoder(&realistic(7, epoch()));
    for n in 1000..1012 {
        // The odd part starts at the page's start + 1 s: 2, 4, 0 modulo 6 -> SSP1, 2, 3.
        let odd_start = u64::from(enc.page_time(n).1) + 1;
        let ssp = enc.part_bits(n)[1][106..]
            .iter()
            .fold(0u8, |a, &b| (a << 1) | b);
        let which = [2, 4, 0].iter().position(|&r| r == odd_start % 6).unwrap();
        assert_eq!(ssp, super::super::pages::SSP[which], "page {n}");
    }
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
    // Parts start every 250 symbols from symbol 0 (an odd part).
    assert_eq!(run[250 - 71..250 - 71 + 10], INAV_SYNC);
    assert_eq!(enc.symbols(0, 10), INAV_SYNC);
}
