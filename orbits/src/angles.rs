//! Angles reduced to one turn, in the three conventions the code needs. One home, so a
//! yaw error, a mean anomaly and a message field all wrap the same way.

use std::f64::consts::{PI, TAU};

/// An angle wrapped into `[-pi, pi)`: the difference of two angles (rad).
pub fn wrap_pi(angle_rad: f64) -> f64 {
    (angle_rad + PI).rem_euclid(TAU) - PI
}

/// An angle wrapped into `(-pi, pi]`: pi stays pi (an attitude profile's yaw of 180 deg).
pub fn wrap_pi_upper(angle_rad: f64) -> f64 {
    let w = wrap_pi(angle_rad);
    if w == -PI { PI } else { w }
}

/// An angle reduced to `[0, 2 pi)`.
pub fn wrap_two_pi(angle_rad: f64) -> f64 {
    let wrapped = angle_rad.rem_euclid(TAU);
    if wrapped >= TAU { 0.0 } else { wrapped }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_convention_keeps_its_own_end_of_the_turn() {
        assert_eq!(wrap_pi(PI), -PI);
        assert_eq!(wrap_pi(-PI), -PI);
        assert_eq!(wrap_pi_upper(PI), PI);
        assert_eq!(wrap_pi_upper(-PI), PI);
        assert_eq!(wrap_two_pi(TAU), 0.0);
        assert_eq!(wrap_two_pi(-1e-300), 0.0);
        for k in -5..=5 {
            let a = 0.3 + f64::from(k) * TAU;
            assert!((wrap_pi(a) - 0.3).abs() < 1e-12);
            assert!((wrap_pi_upper(a) - 0.3).abs() < 1e-12);
            assert!((wrap_two_pi(a) - 0.3).abs() < 1e-12);
        }
        assert!((wrap_pi(3.0 * PI / 2.0) + PI / 2.0).abs() < 1e-15);
        assert!((wrap_two_pi(-PI / 2.0) - 3.0 * PI / 2.0).abs() < 1e-15);
    }
}
