//! The two-sample coning and sculling corrections (Savage 1998 parts 1 and 2; Groves 2013
//! sec. 5.5.4): what the raw increments miss when the rotation axis itself turns within
//! an interval, from the previous interval's increments under a linear-rate model.

use skyforge_gnss::imu::ImuIncrement;
use skyforge_orbits::Vec3;

/// The body's rotation vector over the interval relative to inertial space (rad), Savage
/// 1998 part 1, two-sample coning algorithm: `phi = alpha_k + (1/12) alpha_{k-1} x
/// alpha_k`. Without a previous increment the raw angle increment `alpha_k`.
pub(crate) fn rotation_vector(prev: Option<&ImuIncrement>, inc: &ImuIncrement) -> Vec3 {
    let coning = prev.map_or_else(Vec3::zeros, |p| p.dtheta_rad.cross(&inc.dtheta_rad) / 12.0);
    inc.dtheta_rad + coning
}

/// Savage 1998 part 2, two-sample sculling term `(1/12)(a_{k-1} x v_k + v_{k-1} x a_k)`
/// (m/s), body axes at the start of the interval; zero without a previous increment.
///
/// The angle increments `a` are the body's rotation relative to the Earth, since the
/// ECEF velocity integrates the specific force in the Earth-fixed frame: the measured
/// `alpha` less the Earth's rotation seen in body axes over that interval. With
/// `w = C^T w_ie tau` at the start of the current interval, that rotation is
/// `w - (1/2) alpha_k x w` over the current interval and `w + (1/2) alpha_{k-1} x w`
/// over the previous one (the Earth's rate at each interval's middle, to first order).
/// The term then vanishes for a constant rate relative to the Earth and a constant
/// specific force, where `rotation::interval_mean` alone is exact. The rotation
/// compensation `(1/2) a_k x v_k` is carried by `rotation::interval_mean`.
pub(crate) fn sculling(prev: Option<&ImuIncrement>, inc: &ImuIncrement, w: &Vec3) -> Vec3 {
    prev.map_or_else(Vec3::zeros, |p| {
        let a_prev = p.dtheta_rad - w - p.dtheta_rad.cross(w) * 0.5;
        let a_cur = inc.dtheta_rad - w + inc.dtheta_rad.cross(w) * 0.5;
        (a_prev.cross(&inc.dv_mps) + p.dv_mps.cross(&a_cur)) / 12.0
    })
}
