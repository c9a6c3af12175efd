//! The checks an increment passes before it may move the state: a positive interval,
//! finite values, and contiguity with the state's time and with the previous increment.

use super::error::InsError;
use hifitime::Epoch;
use skyforge_gnss::imu::ImuIncrement;

/// How far (s) an increment's start may lie from the time the state has reached, or from
/// the end of the previous increment, and still count as contiguous: the resolution of
/// the time tags in IMU files.
pub const CONTIGUITY_TOLERANCE_S: f64 = 1e-6;

/// The increment on its own: positive finite interval, finite increments.
pub(crate) fn check_values(inc: &ImuIncrement) -> Result<(), InsError> {
    if !(inc.dt_s.is_finite() && inc.dt_s > 0.0) {
        return Err(InsError::BadInterval {
            t_end: inc.t_end,
            dt_s: inc.dt_s,
        });
    }
    let finite = inc
        .dtheta_rad
        .iter()
        .chain(inc.dv_mps.iter())
        .all(|x| x.is_finite());
    if !finite {
        return Err(InsError::NonFinite { t_end: inc.t_end });
    }
    Ok(())
}

/// `inc` must begin where the state time `state_t` is: not before (out of order or
/// overlapping), not after (a gap).
pub(crate) fn check_follows(state_t: Epoch, inc: &ImuIncrement) -> Result<(), InsError> {
    let offset_s = (inc.t_end - state_t).to_seconds() - inc.dt_s;
    if inc.t_end <= state_t || offset_s < -CONTIGUITY_TOLERANCE_S {
        return Err(InsError::OutOfOrder {
            state_t,
            t_end: inc.t_end,
            dt_s: inc.dt_s,
        });
    }
    if offset_s > CONTIGUITY_TOLERANCE_S {
        return Err(InsError::Gap {
            state_t,
            t_end: inc.t_end,
            gap_s: offset_s,
        });
    }
    Ok(())
}

/// `prev`, when given, must end where `inc` begins.
pub(crate) fn check_prev(prev: &ImuIncrement, inc: &ImuIncrement) -> Result<(), InsError> {
    check_values(prev)?;
    let offset_s = (inc.t_end - prev.t_end).to_seconds() - inc.dt_s;
    if offset_s.abs() > CONTIGUITY_TOLERANCE_S {
        return Err(InsError::PrevNotAdjacent {
            prev_end: prev.t_end,
            offset_s,
        });
    }
    Ok(())
}

/// All checks of one propagation step.
pub(crate) fn check_step(
    state_t: Epoch,
    prev: Option<&ImuIncrement>,
    inc: &ImuIncrement,
) -> Result<(), InsError> {
    check_values(inc)?;
    check_follows(state_t, inc)?;
    prev.map_or(Ok(()), |p| check_prev(p, inc))
}
