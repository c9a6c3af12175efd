//! Run a scenario's geometry truth in memory, chunk by chunk.

use super::ValidateError;
use skyforge_orbits::ephemeris::SatId;
use skyforge_scenarios::Scenario;
use skyforge_signals::truth::geometry::{GeometryChunk, GeometryTruth};
use std::convert::Infallible;

/// Epochs per chunk: one hour at 1 Hz.
const CHUNK_EPOCHS: usize = 3600;

/// Build `scenario` and feed every geometry chunk, with the satellite list, to `visit`.
pub fn for_each_chunk(
    scenario: &Scenario,
    mut visit: impl FnMut(&GeometryChunk, &[SatId]),
) -> Result<(), ValidateError> {
    let world = scenario.build()?;
    let mut platform = world.platform;
    let truth = GeometryTruth::new(
        &world.ephemerides,
        &world.satellites,
        &world.antennas,
        world.step_s,
    );
    truth
        .stream(&mut platform, world.duration_s, CHUNK_EPOCHS, |chunk| {
            visit(&chunk, &world.satellites);
            Ok::<(), Infallible>(())
        })
        .map_err(|e| ValidateError::Geometry(e.to_string()))
}
