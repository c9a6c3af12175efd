//! Issue #11: the synthesiser renders a geometry interval in slices of bounded size, so
//! that memory does not grow with the sample rate; the samples must not depend on the
//! slice size. One second of two antennas, every visible GPS satellite, a drifting shared
//! receiver clock, a band filter and 4-bit quantisation (so that components clip), rendered
//! whole (the former behaviour: every block of the interval at once) and one block at a
//! time.

mod common;

use skyforge_gnss::sample_format::SampleFormat;
use skyforge_signals::synth::SignalConfig;
use skyforge_signals::synth::render::{LinkEnd, Synthesiser, append_to};
use skyforge_signals::synth::{BandFilter, FilterConfig};

/// Samples of two antennas over [0 s, 1 s] and the clipped count, `slice_bytes` at a time.
fn render(slice_bytes: usize) -> (Vec<Vec<u8>>, u64) {
    let (txs, _, chunk) = common::gps_links("thesis-leo", 2, 4.0, 2);
    let cfg = SignalConfig {
        sample_rate_hz: 2.046e6,
        format: SampleFormat::Ci8,
        bits: Some(4),
        cn0_dbhz: 60.0,
        truth_rate_hz: 0,
        ..SignalConfig::default()
    };
    let filter = FilterConfig {
        bandwidth_hz: 1.8e6,
        taps: 31,
    };
    let clock = common::tcxo_clock();
    let mut synth = Synthesiser::new(&cfg, &txs, 2, 5)
        .unwrap()
        .with_clocks(vec![clock])
        .with_filter(BandFilter::new(&filter, cfg.sample_rate_hz, 0.0, true).unwrap())
        .unwrap()
        .with_slice_bytes(slice_bytes);
    let mut out = vec![Vec::new(), Vec::new()];
    for k in 0..=1 {
        let links = (0..2)
            .flat_map(|a| (0..txs.len()).map(move |s| (a, s)))
            .map(|(a, s)| LinkEnd::from_geometry(chunk.link(k, a, s), cfg.cn0_dbhz))
            .collect();
        let Ok(()) = synth.push_epoch(chunk.t_s[k], links, &mut append_to(&mut out));
    }
    (out, synth.clipped())
}

#[test]
fn samples_do_not_depend_on_the_slice_size() {
    let (whole, clipped_whole) = render(usize::MAX);
    let (sliced, clipped_sliced) = render(1);
    let samples_per_second = 2_046_000 * 2;
    assert_eq!(whole[0].len(), samples_per_second);
    assert!(
        clipped_whole > 0,
        "4-bit quantisation at 60 dB-Hz should clip"
    );
    assert_eq!(clipped_whole, clipped_sliced);
    for a in 0..2 {
        assert!(whole[a] == sliced[a], "antenna {a}: samples differ");
    }
    assert!(
        whole[0] != whole[1],
        "the two antennas see different signals"
    );
}
