//! Run a scenario's geometry truth in memory, chunk by chunk.

use super::ValidateError;
use skyforge_orbits::ephemeris::SatId;
use skyforge_scenarios::Scenario;
use skyforge_signals::truth::GeometryChunk;
use std::convert::Infallible;

/// Epochs per chunk: one hour at 1 Hz.
const CHUNK_EPOCHS: usize = 3600;

/// Build `scenario` and feed every geometry chunk, with the satellite list, to `visit`.
pub fn for_each_chunk(
    scenario: &Scenario,
    mut visit: impl FnMut(&GeometryChunk, &[SatId]),
) -> Result<(), ValidateError> {
    let mut world = scenario.build()?;
    let satellites = world.satellites.clone();
    world
        .stream_geometry(CHUNK_EPOCHS, |chunk| {
            visit(&chunk, &satellites);
            Ok::<(), Infallible>(())
        })
        .map_err(|e| ValidateError::Geometry(e.to_string()))
}
