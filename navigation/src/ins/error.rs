//! What can go wrong when increments from a file drive the INS: every check returns one
//! of these instead of panicking.

use hifitime::Epoch;

/// Misuse of the strapdown INS, mostly from bad or badly ordered IMU records.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum InsError {
    /// An increment's interval is zero, negative or not finite.
    #[error("IMU increment ending at {t_end}: interval {dt_s} s is not positive and finite")]
    BadInterval {
        /// End of the offending interval.
        t_end: Epoch,
        /// Its interval (s).
        dt_s: f64,
    },
    /// An angle or velocity increment holds a NaN or an infinity.
    #[error("IMU increment ending at {t_end}: an angle or velocity increment is not finite")]
    NonFinite {
        /// End of the offending interval.
        t_end: Epoch,
    },
    /// An increment does not end after the time the state has already reached, or it
    /// begins before that time (the intervals overlap).
    #[error(
        "IMU increment ending at {t_end} (interval {dt_s} s) overlaps the state time {state_t}"
    )]
    OutOfOrder {
        /// Time the state has reached.
        state_t: Epoch,
        /// End of the offending interval.
        t_end: Epoch,
        /// Its interval (s).
        dt_s: f64,
    },
    /// An increment begins later than the time the state has reached: records are missing.
    #[error("IMU increment ending at {t_end} begins {gap_s} s after the state time {state_t}")]
    Gap {
        /// Time the state has reached.
        state_t: Epoch,
        /// End of the offending interval.
        t_end: Epoch,
        /// Missing time (s).
        gap_s: f64,
    },
    /// The previous increment given for the coning and sculling corrections does not end
    /// where the current one begins.
    #[error(
        "previous IMU increment ends at {prev_end}, the current one begins {offset_s} s away from it"
    )]
    PrevNotAdjacent {
        /// End of the previous increment.
        prev_end: Epoch,
        /// Start of the current increment minus the end of the previous one (s).
        offset_s: f64,
    },
    /// An alignment or a mean was asked of no increments.
    #[error("no IMU increments given")]
    Empty,
    /// Alignment is impossible from these measurements (no specific force, or the
    /// specific force parallel to the Earth's rate, as at the poles).
    #[error("alignment is impossible: {0}")]
    Degenerate(&'static str),
    /// A fine-alignment setting is out of range.
    #[error("fine alignment setting {name} = {value} must be positive and finite")]
    BadSetting {
        /// The setting's field name.
        name: &'static str,
        /// Its value.
        value: f64,
    },
}
