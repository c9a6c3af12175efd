//! At the observation level the receiver clock steps every 0.1 s, not every 1 ms block
//! (`synth::session::OBSERVATION_CLOCK_STEP_BLOCKS`): the synthesiser then gives each
//! block the sample of the clock step it lies in. The truth at whole seconds must carry
//! exactly the coarse clock's phase and frequency there.

mod common;

use skyforge_orbits::constants::C_MPS;
use skyforge_signals::synth::render::{LinkEnd, Synthesiser};
use skyforge_signals::synth::{BLOCK_S, SignalConfig};

#[test]
fn truth_carries_the_coarse_clock_at_whole_seconds() {
    let (txs, _, chunk) = common::gps_links("thesis-leo", 1, 6.0, 4);
    let cfg = SignalConfig {
        truth_rate_hz: 1,
        ..SignalConfig::default()
    };
    let step_s = 100.0 * BLOCK_S;
    let mut synth = Synthesiser::new(&cfg, &txs, 1, 5)
        .unwrap()
        .with_truth_every(1000)
        .without_samples()
        .with_clocks(vec![common::tcxo_clock_stepping(step_s)]);
    let mut sink = |_: usize, _: &[u8]| Ok::<(), std::convert::Infallible>(());
    for k in 0..4 {
        let links = (0..txs.len())
            .map(|s| LinkEnd::from_geometry(chunk.link(k, 0, s), cfg.cn0_dbhz))
            .collect();
        let Ok(()) = synth.push_epoch(chunk.t_s[k], links, &mut sink);
    }
    let records = synth.take_truth();
    // Records at 0, 1 and 2 s (the interval to 3 s is rendered when 3 s is pushed).
    let times: Vec<f64> = records.iter().map(|r| r.t_s).collect();
    assert!(times.contains(&0.0) && times.contains(&2.0), "{times:?}");
    // The same clock stepped by itself: its sample at step 10 k is the truth at k seconds.
    let mut reference = common::tcxo_clock_stepping(step_s);
    let samples = reference.next_block(30);
    for r in &records {
        let k = (r.t_s / step_s).round() as usize;
        assert_eq!(r.rx_clock_m, C_MPS * samples[k].phase_s, "t {} s", r.t_s);
    }
    // A clock that wanders: the phase at 2 s is not the start phase carried by the drift.
    let drift_only = 1e-4 + 2e-7 * 2.0;
    assert!((samples[20].phase_s - drift_only).abs() > 1e-12);
}
