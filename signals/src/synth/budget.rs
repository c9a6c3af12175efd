//! What a synthesis session needs before it runs (`skyforge synth --dry-run`): the bytes
//! of each sample recording (exact) and an upper bound of its peak memory.
//!
//! Memory model (issue #11), each term an upper bound:
//! - [`FIXED_BYTES`]: the program, its libraries, the ephemerides and the writers' buffers
//!   (measured: a 3 s, 4 Msps, one-antenna run without signal truth peaks at 26 MB);
//! - one slice of rendered samples ([`SLICE_BYTES`], or the whole 1 s interval when it is
//!   smaller) and its block under way;
//! - per rendering thread, the scratch of one 1 ms block (I and Q before and after the
//!   filter, as f32, plus its bytes);
//! - the signal truth of one geometry step of the widest band at `truth_rate_hz`
//!   (whole seconds at the observation level), counted as if every satellite were
//!   visible to every antenna, held twice (the synthesiser's list and the
//!   per-antenna copy a sink receives) with its column copies;
//! - one chunk of geometry epochs.

use super::config::BLOCK_S;
use super::render::{LinkTruth, SLICE_BYTES, blocks_per_slice};
use super::session::{GEOMETRY_STEP_S, SynthSession};
use crate::truth::geometry::{LinkGeometry, epoch_count};
use std::mem::size_of;

/// The program, libraries, ephemerides and writer buffers (bytes; see the module docs).
pub const FIXED_BYTES: u64 = 40 << 20;
/// Columns a truth writer copies out of each signal-truth record (f64 each).
const TRUTH_COLUMNS: u64 = 12;

/// A session's needs.
#[derive(Debug, Clone, PartialEq)]
pub struct Budget {
    /// Bytes of each sample recording (one per band and antenna; 0 at the observation
    /// level, which writes none).
    pub recording_bytes: u64,
    /// Recordings written.
    pub recordings: usize,
    /// Upper bound of the peak memory (bytes).
    pub memory_bytes: u64,
    /// Signal-truth records written, at most (every link visible throughout).
    pub truth_records_max: u64,
    /// Geometry epochs.
    pub epochs: u64,
}

impl SynthSession<'_> {
    /// What this session needs when run with `chunk_epochs` geometry epochs per chunk on
    /// `threads` rendering threads.
    pub fn budget(&self, chunk_epochs: usize, threads: usize) -> Budget {
        let signal = self.signal_config();
        let n_ant = self.world().antennas.len() as u64;
        let n_sats = self.satellites().len() as u64;
        let epochs = epoch_count(self.world().duration_s, GEOMETRY_STEP_S) as u64;
        let blocks_per_step = (GEOMETRY_STEP_S / BLOCK_S).round() as u64;
        let n = signal.samples_per_block() as u64;
        let block_bytes = signal.block_bytes() as u64;
        let samples = self.renders_samples();
        let recording_bytes = if samples {
            epochs.saturating_sub(1) * blocks_per_step * block_bytes
        } else {
            0
        };
        let sliced = if samples {
            let per_slice = blocks_per_slice(signal.block_bytes(), SLICE_BYTES);
            per_slice.min(blocks_per_step) * block_bytes + block_bytes
        } else {
            0
        };
        let margin = self.filter_margin() as u64;
        let scratch = if samples {
            threads as u64 * ((n + 2 * margin) * 8 + n * 8 + block_bytes)
        } else {
            0
        };
        let per_step = blocks_per_step
            .checked_div(self.truth_every_blocks())
            .unwrap_or(0);
        let widest_band = self.bands().iter().map(|b| b.count).max().unwrap_or(0) as u64;
        let record = size_of::<LinkTruth>() as u64 + 8 * TRUTH_COLUMNS;
        let truth = per_step * n_ant * widest_band * 2 * record;
        let chunk = chunk_epochs as u64 * n_ant * n_sats * size_of::<LinkGeometry>() as u64;
        Budget {
            recording_bytes,
            recordings: if samples {
                self.bands().len() * n_ant as usize
            } else {
                0
            },
            memory_bytes: FIXED_BYTES + sliced + scratch + truth + chunk,
            truth_records_max: per_step * n_ant * n_sats * epochs.saturating_sub(1),
            epochs,
        }
    }
}
