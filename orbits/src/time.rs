//! Time scales (GPST, BDT, UTC with leap seconds through `hifitime`) and the scenario time
//! origin. Inside hot loops time is `f64` seconds since [`TimeOrigin::start`].

use hifitime::Epoch;

/// Error parsing or converting a time.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum TimeError {
    /// The text is not an epoch hifitime understands.
    #[error("cannot read epoch {text:?}: {reason}")]
    Parse { text: String, reason: String },
}

/// The instant `t = 0` of a scenario; converts between epochs and `f64` seconds.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TimeOrigin {
    start: Epoch,
}

impl TimeOrigin {
    /// An origin at `start`.
    pub fn new(start: Epoch) -> Self {
        Self { start }
    }
    /// The scenario start epoch.
    pub fn start(&self) -> Epoch {
        self.start
    }
    /// Seconds from the start to `epoch` (exact difference, then to `f64`).
    pub fn seconds_since_start(&self, epoch: Epoch) -> f64 {
        todo!("{epoch}")
    }
    /// The epoch `t_s` seconds after the start.
    pub fn epoch_at(&self, t_s: f64) -> Epoch {
        todo!("{t_s}")
    }
}

/// Parse an epoch such as `2023-03-12T00:00:00 GPST`, `... UTC`, `... BDT`.
pub fn parse_epoch(text: &str) -> Result<Epoch, TimeError> {
    todo!("{text}")
}

/// GPS week number (continuous, no roll-over) and seconds of week.
pub fn gpst_week_sow(epoch: Epoch) -> (u32, f64) {
    todo!("{epoch}")
}

/// BeiDou week number and seconds of week (BDT).
pub fn bdt_week_sow(epoch: Epoch) -> (u32, f64) {
    todo!("{epoch}")
}

/// The epoch at GPS week `week` and seconds of week `sow`.
pub fn epoch_from_gpst(week: u32, sow: f64) -> Epoch {
    todo!("{week} {sow}")
}

/// The epoch at BDT week `week` and seconds of week `sow`.
pub fn epoch_from_bdt(week: u32, sow: f64) -> Epoch {
    todo!("{week} {sow}")
}
