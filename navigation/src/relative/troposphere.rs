//! The troposphere between antennas apart on the ground. Two stations 3.3 km apart see a
//! satellite at elevations that differ by `|b| / R_earth` (up to 5e-4 rad; at 15 deg the
//! slant delay changes by about 33 m per radian, so 1.7 cm) and from heights whose zenith
//! delays differ by about 0.3 mm per metre: a double difference does not cancel it. The
//! chain models the difference to first order in the baseline, as the gradient of the
//! master's slant delay ([`crate::baseline::LineOfSight::delay_gradient`]): it needs no
//! position of the other antennas (their single-point heights are metres off, a
//! millimetre of delay per metre at low elevation), and the estimated baseline carries it.
//! What first order leaves is the delay's curvature in height: 3.9 % of the difference over
//! 250 m of height, 0.1 % over 6 m.
//! The model is what the single-point solution removes ([`crate::pvt`]): Saastamoinen
//! zenith delays of the standard atmosphere, Chao mapping. It is zero above 50 km, so a
//! LEO platform's chain is unchanged.

use crate::pvt::solve::STANDARD_RH0;
use skyforge_orbits::Vec3;
use skyforge_orbits::frames::ecef_to_geodetic;
use skyforge_orbits::troposphere::StandardZenith;

/// Step of the central differences (m): the second-order error is `(STEP / 8 km)^2 / 6`
/// of the gradient, 3e-7; the rounding error of the delays (1e-15 m) over it is 1e-16.
const STEP_M: f64 = 10.0;

/// The standard troposphere seen from one place: its up direction and zenith delays, what
/// every satellite's slant delay there shares.
#[derive(Debug, Clone, Copy)]
pub struct Site {
    r_ecef_m: Vec3,
    up: Vec3,
    zenith: StandardZenith,
}

impl Site {
    pub fn at(r_ecef_m: &Vec3) -> Self {
        let g = ecef_to_geodetic(r_ecef_m);
        Self {
            r_ecef_m: *r_ecef_m,
            up: g.up(),
            zenith: StandardZenith::at(g.lat_rad, g.h_m, STANDARD_RH0),
        }
    }

    /// The slant delay (m) towards a satellite at `sat_ecef_m`.
    pub fn slant_m(&self, sat_ecef_m: &Vec3) -> f64 {
        let los = (sat_ecef_m - self.r_ecef_m).normalize();
        self.zenith
            .slant_m(los.dot(&self.up).clamp(-1.0, 1.0).asin())
    }
}

/// The gradient (m per m, ECEF) of the slant delay with the antenna position at one
/// place, by central differences: the six displaced places are set up once, for every
/// satellite.
#[derive(Debug, Clone, Copy)]
pub struct DelayGradient {
    /// Per ECEF axis: the place moved by `+STEP_M` and by `-STEP_M`.
    steps: [(Site, Site); 3],
}

impl DelayGradient {
    pub fn at(r_ecef_m: &Vec3) -> Self {
        Self {
            steps: [0, 1, 2].map(|axis| {
                let mut step = Vec3::zeros();
                step[axis] = STEP_M;
                (Site::at(&(r_ecef_m + step)), Site::at(&(r_ecef_m - step)))
            }),
        }
    }

    /// The gradient towards a satellite at `sat_ecef_m`.
    pub fn towards(&self, sat_ecef_m: &Vec3) -> Vec3 {
        Vec3::from(
            self.steps.map(|(up, down)| {
                (up.slant_m(sat_ecef_m) - down.slant_m(sat_ecef_m)) / (2.0 * STEP_M)
            }),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pvt::predicted_view;
    use skyforge_orbits::ephemeris::{SatId, nominal};
    use skyforge_orbits::frames::{Geodetic, geodetic_to_ecef};
    use skyforge_orbits::troposphere::standard_slant_delay_m;

    fn geo(lat_deg: f64, lon_deg: f64, h_m: f64) -> Vec3 {
        geodetic_to_ecef(&Geodetic::from_degrees(lat_deg, lon_deg, h_m))
    }

    /// Two stations 3.3 km and 250 m of height apart, every GPS satellite above 5 deg: the
    /// gradient at the master times the baseline gives the difference of the two
    /// stations' slant delays (6-65 cm here, so a wrong gradient would fail) with an error
    /// of second order: halving the baseline divides it by 4 (a wrong gradient leaves a
    /// first-order error, which halves). Over 250 m of height it is 3.9 % (the delay's
    /// curvature in height); over GEONET's 5.6 m, 0.1 %. The elevations of the oracle
    /// come from the single-point solution's local frame, not from this module's.
    #[test]
    fn the_gradient_predicts_the_delay_difference_over_a_baseline() {
        let start =
            hifitime::Epoch::from_gregorian(2005, 4, 2, 0, 0, 0, 0, hifitime::TimeScale::GPST);
        let store = nominal::gps_store(start);
        let (master, rover) = (geo(35.0, 139.0, 50.0), geo(35.02, 139.025, 300.0));
        let b = rover - master;
        let t_s = 600.0;
        let mut seen = 0;
        for prn in 1..=32u8 {
            let Some(eph) = store.select(SatId::gps(prn), t_s) else {
                continue;
            };
            let at_master = predicted_view(eph, t_s, &master);
            if at_master
                .az_el_rad
                .is_none_or(|(_, el)| el < 5f64.to_radians())
            {
                continue;
            }
            seen += 1;
            let delay = |r: &Vec3| {
                let g = ecef_to_geodetic(r);
                let view = predicted_view(eph, t_s, r);
                let (_, el) = view.az_el_rad.expect("a position has a local frame");
                standard_slant_delay_m(g.lat_rad, g.h_m, el, STANDARD_RH0)
            };
            let gradient = DelayGradient::at(&master).towards(&at_master.r_ecef_m);
            let error = |scale: f64| {
                let truth = delay(&(master + b * scale)) - delay(&master);
                (gradient.dot(&(b * scale)) - truth, truth)
            };
            let ((full, truth), (half, _)) = (error(1.0), error(0.5));
            assert!(truth.abs() > 0.05, "G{prn:02}: {truth} m");
            assert!(
                full.abs() < 0.05 * truth.abs(),
                "G{prn:02}: {full} m off a difference of {truth} m"
            );
            assert!(
                (3.5..4.5).contains(&(full / half)),
                "G{prn:02}: halving the baseline divides the error by {}",
                full / half
            );
        }
        assert!(seen >= 5, "{seen} satellites");
    }

    /// Above the troposphere (a LEO) the gradient is zero.
    #[test]
    fn no_gradient_above_the_troposphere() {
        let leo = geo(10.0, 20.0, 500e3);
        let sat = geo(30.0, 25.0, 20_200e3);
        assert_eq!(DelayGradient::at(&leo).towards(&sat), Vec3::zeros());
    }
}
