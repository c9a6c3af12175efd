//! The schedule and the time the messages carry.

use super::{PER_WEEK, WEEK, decode_messages, encoder, epoch, realistic};

#[test]
fn the_schedule_repeats_10_11_30_33_from_the_week_start() {
    let enc = encoder(&realistic(7, epoch()));
    for n in [0u64, 4, 1000, PER_WEEK - 4, PER_WEEK, 5 * PER_WEEK + 8] {
        let types: Vec<u8> = (n..n + 8).map(|m| enc.message_type(m)).collect();
        assert_eq!(types, [10, 11, 30, 33, 10, 11, 30, 33], "from message {n}");
    }
    // Broadcast intervals (IS-GPS-705J Table 20-XII, L5): ephemeris 10 and 11 within
    // 24 s, a clock message (30-37) within 24 s, ISC/iono (30) and UTC (33) within 144 s.
    let types: Vec<u8> = (0..400).map(|m| enc.message_type(m)).collect();
    let worst_gap_s = |pred: &dyn Fn(u8) -> bool| {
        let at: Vec<usize> = (0..types.len()).filter(|&i| pred(types[i])).collect();
        at.windows(2).map(|w| 6 * (w[1] - w[0])).max().unwrap()
    };
    assert_eq!(worst_gap_s(&|t| t == 10), 24);
    assert_eq!(worst_gap_s(&|t| t == 11), 24);
    assert_eq!(worst_gap_s(&|t| (30..=37).contains(&t)), 18);
    assert_eq!(worst_gap_s(&|t| t == 30), 24);
    assert_eq!(worst_gap_s(&|t| t == 33), 24);
}

#[test]
fn the_tow_count_is_the_start_of_the_next_message() {
    let enc = encoder(&realistic(7, epoch()));
    let first = 3 * 14_400 + 1234; // Wednesday, an arbitrary message
    for (n, m) in (first..).zip(decode_messages(&enc, first, 9)) {
        let (week, tow) = enc.message_time(n);
        assert_eq!((week, tow), (WEEK, (6 * n) as u32));
        let (_, next_tow) = enc.message_time(n + 1);
        assert_eq!(m.next_tow_s(), next_tow, "message {n}");
        assert_eq!(u64::from(m.tow_count), n + 1);
        assert_eq!(m.msg_type, enc.message_type(n));
        assert_eq!(m.prn, 7);
        assert!(!m.alert);
    }
}

#[test]
fn the_week_rolls_over_in_the_messages() {
    let enc = encoder(&realistic(7, epoch()));
    let last = PER_WEEK - 1; // message 100799, TOW 604794, type 33
    assert_eq!(enc.message_time(last), (WEEK, 604_794));
    assert_eq!(enc.message_time(last + 1), (WEEK + 1, 0));
    let messages = decode_messages(&enc, last - 3, 6);
    let counts: Vec<u32> = messages.iter().map(|m| m.tow_count).collect();
    assert_eq!(counts, [100_797, 100_798, 100_799, 0, 1, 2]);
    // Type 10 carries the week it is sent in: the last of the week and the first of the
    // next.
    let wn: Vec<Option<i64>> = messages.iter().map(|m| m.field("WN")).collect();
    let (w0, w1) = (i64::from(WEEK), i64::from(WEEK + 1));
    assert_eq!(wn, [Some(w0), None, None, None, Some(w1), None]);
    // The assembler's clock follows: after the last message of the week, the next
    // message starts at week + 1, TOW 0.
    let mut asm = super::CnavAssembler::new();
    let times: Vec<_> = messages
        .iter()
        .map(|m| {
            asm.push(m);
            asm.time()
        })
        .collect();
    assert_eq!(
        times,
        [
            Some((WEEK, 604_782)),
            Some((WEEK, 604_788)),
            Some((WEEK, 604_794)),
            Some((WEEK + 1, 0)),
            Some((WEEK + 1, 6)),
            Some((WEEK + 1, 12)),
        ]
    );
}
