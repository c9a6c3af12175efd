//! Set-up shared by the signal-level tests.
//! Shared by several test binaries, each using part of it.
#![allow(dead_code)]

use skyforge_orbits::ephemeris::{BroadcastEphemeris, EphemerisStore, SatId};
use skyforge_scenarios::World;
use skyforge_signals::errors::{ClockModel, PowerLaw};
use skyforge_signals::errors::{Stream, stream_rng};
use skyforge_signals::synth::BLOCK_S;
use skyforge_signals::synth::Transmitter;
use skyforge_signals::synth::constellation;
use skyforge_signals::truth::{GeometryChunk, GeometryTruth};

/// The scenario's GPS satellites at t = 0 as L1 C/A transmitters (default ionosphere
/// parameters in their messages), the store of the ephemerides they broadcast, and their
/// IDs in transmitter order.
pub fn gps_transmitters(world: &World) -> (Vec<Transmitter>, EphemerisStore, Vec<SatId>) {
    let ephs: Vec<BroadcastEphemeris> = world
        .satellites
        .iter()
        .filter_map(|&s| world.ephemerides.select(s, 0.0).map(|b| b.eph.clone()))
        .collect();
    let iono = skyforge_signals::errors::IonoConfig::default();
    let txs = constellation::gps_l1ca(&ephs, world.origin.start(), &iono.gps).unwrap();
    let store = EphemerisStore::new(
        txs.iter().map(|t| t.broadcast_ephemeris()).collect(),
        &world.origin,
    );
    let sats = txs.iter().map(|t| t.sat).collect();
    (txs, store, sats)
}

/// Bundled scenario `name`'s GPS transmitters ([`gps_transmitters`]), their IDs, and the
/// 1 s geometry of their links to its first `antennas` antennas over `epochs` epochs from
/// t = 0 (the platform propagated over [-2 s, `window_end_s`]).
pub fn gps_links(
    name: &str,
    antennas: usize,
    window_end_s: f64,
    epochs: usize,
) -> (Vec<Transmitter>, Vec<SatId>, GeometryChunk) {
    let scenario = skyforge_scenarios::resolve(name).unwrap();
    let mut world = scenario.build().unwrap();
    let (txs, store, sats) = gps_transmitters(&world);
    let truth = GeometryTruth::new(&store, &sats, &world.antennas[..antennas], 1.0);
    let window = world.platform.window(-2.0, window_end_s).unwrap();
    let chunk = truth.chunk(&window, 0.0, epochs);
    (txs, sats, chunk)
}

/// A TCXO-like receiver clock 100 us ahead, drifting at 2e-7, stepping at the synthesis
/// block.
pub fn tcxo_clock() -> ClockModel {
    tcxo_clock_stepping(BLOCK_S)
}

/// [`tcxo_clock`]'s oscillator stepped every `dt_s`.
pub fn tcxo_clock_stepping(dt_s: f64) -> ClockModel {
    let h = PowerLaw {
        h0: 2e-19,
        h_minus1: 7e-21,
        h_minus2: 2e-20,
    };
    ClockModel::new(
        &h,
        1e-4,
        2e-7,
        dt_s,
        stream_rng(3, Stream::ReceiverClock, 0),
    )
    .unwrap()
}

/// Samples written as `cf32` (little-endian f32 I, then Q) as (I, Q) pairs.
pub fn cf32_samples(bytes: &[u8]) -> Vec<(f32, f32)> {
    bytes
        .chunks_exact(8)
        .map(|c| {
            (
                f32::from_le_bytes([c[0], c[1], c[2], c[3]]),
                f32::from_le_bytes([c[4], c[5], c[6], c[7]]),
            )
        })
        .collect()
}
