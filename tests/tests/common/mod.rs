//! Set-up shared by the signal-level tests.

use skyforge_orbits::ephemeris::{BroadcastEphemeris, EphemerisStore, SatId};
use skyforge_scenarios::World;
use skyforge_signals::synth::constellation;
use skyforge_signals::synth::transmitter::Transmitter;

/// The scenario's GPS satellites at t = 0 as L1 C/A transmitters (default ionosphere
/// parameters in their messages), the store of the ephemerides they broadcast, and their
/// IDs in transmitter order.
pub fn gps_transmitters(world: &World) -> (Vec<Transmitter>, EphemerisStore, Vec<SatId>) {
    let ephs: Vec<BroadcastEphemeris> = world
        .satellites
        .iter()
        .filter_map(|&s| world.ephemerides.select(s, 0.0).map(|b| b.eph.clone()))
        .collect();
    let iono = skyforge_signals::errors::ionosphere::IonoConfig::default();
    let txs = constellation::gps_l1ca(&ephs, world.origin.start(), &iono.gps).unwrap();
    let store = EphemerisStore::new(
        txs.iter().map(|t| t.broadcast_ephemeris()).collect(),
        &world.origin,
    );
    let sats = txs.iter().map(|t| t.sat).collect();
    (txs, store, sats)
}
