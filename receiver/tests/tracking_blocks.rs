//! Block boundaries must not matter: the same samples tracked in blocks of 1 ms, 4096
//! samples, 1000 samples and an odd size give bit-identical records.

mod tracking_support;

use skyforge_receiver::tracking::TrackingConfig;
use skyforge_receiver::tracking::TrackingError;
use skyforge_receiver::tracking::{ChannelTracker, FrontEnd};
use tracking_support::TestSignal;

#[test]
fn records_do_not_depend_on_block_size() {
    let sig = TestSignal {
        if_hz: 250_000.0,
        seed: 3,
        ..TestSignal::gps_static()
    };
    let samples = sig.generate(0, (0.9 * sig.fs_hz) as usize);
    let front_end = FrontEnd {
        sample_rate_hz: sig.fs_hz,
        if_hz: sig.if_hz,
    };
    let run = |block: usize| {
        let mut ch = ChannelTracker::new(
            sig.handover(0.3, 20.0),
            front_end,
            TrackingConfig::default(),
        )
        .expect("valid channel");
        let mut out = Vec::new();
        for (k, chunk) in samples.chunks(block).enumerate() {
            out.extend(ch.process(chunk, (k * block) as u64).expect("contiguous"));
        }
        out
    };
    let reference = run(4092);
    assert!(reference.len() > 800);
    assert!(reference.last().is_some_and(|r| r.locked && r.bit_synced));
    for block in [4096, 1000, 7777, 100_003] {
        assert_eq!(run(block), reference, "block of {block} samples");
    }
}

#[test]
fn a_gap_between_blocks_is_an_error_and_a_late_start_is_fine() {
    let sig = TestSignal::gps_static();
    let front_end = FrontEnd {
        sample_rate_hz: sig.fs_hz,
        if_hz: 0.0,
    };
    let mut ch = ChannelTracker::new(sig.handover(0.0, 0.0), front_end, TrackingConfig::default())
        .expect("valid channel");
    // Starting 10.5 ms after the hand-over: the NCOs move on open loop.
    let first = 42_966;
    let samples = sig.generate(first, 40_920);
    let records = ch.process(&samples, first).expect("first block");
    assert!(records.len() >= 8);
    for r in &records {
        assert!(r.sample_index >= first);
        assert!(sig.code_error(r.sample_index, r.code_phase_chips).abs() < 0.05);
    }
    let next = first + 40_920 + 1;
    assert_eq!(
        ch.process(&samples[..10], next),
        Err(TrackingError::NonContiguous {
            expected: first + 40_920,
            got: next
        })
    );
}
