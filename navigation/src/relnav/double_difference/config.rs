//! The `[double_difference]` table of `skyforge relnav`'s settings (mode
//! `double-difference`): the measurement weights, the process noise of the relative
//! dynamics and of the ionosphere, and the integer tests. Every default is an assumption a
//! user can change; each is checked against a range (docs/orbit-determination.md).

use crate::orbit_determination::reduced_dynamic::ReducedDynamicConfig;
use serde::Deserialize;
use skyforge_gnss::observation::{ElevationNoise, WEIGHT_SIGMA0_M};
use skyforge_orbits::check::{Allowed, Invalid, check_table};

/// The double-difference filter's settings.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct DoubleDifferenceConfig {
    /// Undifferenced carrier-phase noise (m) of either receiver by elevation (thesis eq.
    /// 2.4-9). # assumed: 2 mm at every elevation (a0 = 0): a 45 dB-Hz receiver's phase;
    /// on a LEO the local elevation does not set the noise.
    pub phase: ElevationNoise,
    /// Undifferenced code noise (m) by elevation (thesis eq. 2.4-10). # assumed: 0.3 m,
    /// a0 = 0, as `phase`.
    pub code: ElevationNoise,
    /// White acceleration per axis held over a step (m/s^2), the process noise of the
    /// relative dynamics (the difference of two orbits under the same gravity field).
    /// # assumed: 1e-6 m/s^2: with the world's gravity field (`[target_orbit.forces]`),
    /// what the model leaves out across 200 km is the drag difference of two like
    /// spacecraft, about 1e-8 m/s^2 at 500 km; a field without J3..J6 would leave 5e-6.
    pub acceleration_sigma_mps2: f64,
    /// Random walk of each satellite's single-difference slant ionosphere on the first
    /// signal (m per sqrt(s)). # assumed: 1 mm/sqrt(s): at 500 km a LEO sees about a tenth
    /// of the ground delay (docs/scenario.md), which 200 km apart differs by centimetres
    /// and changes by millimetres per second.
    pub iono_sigma_m_per_sqrt_s: f64,
    /// Random walk of the receivers' clock difference `c (dt_c - dt_t)` (m per sqrt(s)).
    /// # assumed: 1000 m/sqrt(s), free at every epoch (two independent oscillators,
    /// TCXOs drift by up to a microsecond per second): the carrier phase carries its
    /// memory through the constant ambiguities.
    pub clock_sigma_m_per_sqrt_s: f64,
    /// A new satellite's single-difference ionosphere: 0 with this sigma (m).
    /// # assumed: 0.5 m, beyond the differential delay of two LEOs 200 km apart.
    pub iono_initial_sigma_m: f64,
    /// A new or re-initialised ambiguity's sigma (cycles) about its code-minus-phase
    /// value. # assumed: 30 cycles, uninformative beyond the code's metres.
    pub ambiguity_initial_sigma_cycles: f64,
    /// The ratio test: second-best over best squared norm at least this.
    /// # assumed: 3, the customary fixed threshold.
    pub ratio_threshold: f64,
    /// The bootstrapped success rate of the integers fixed at least this.
    /// # assumed: 0.999, the relative chain's.
    pub min_success_rate: f64,
    /// A change of a receiver's geometry-free phase `lambda1 phi1 - lambda2 phi2` between
    /// epochs larger than this (m) is a cycle slip. # assumed: 0.05 m: the ionosphere moves
    /// it by millimetres per second, one cycle of either signal by 19-24 cm.
    pub slip_threshold_m: f64,
    /// A satellite missing for longer than this (s) starts afresh.
    /// # assumed: 1.5 s, one missed epoch at 1 Hz.
    pub max_gap_s: f64,
    /// Check the held integers every epoch against a float filter that never holds, by
    /// `held_test` (`fixing::check_held`); `false`: fix and hold without a check.
    pub check_held: bool,
    /// The tests of that check. Default `twin-lambda`, the check as it was before the
    /// consistency test: both tests were the default of the first run (2026-12-02,
    /// chosen before it), which measured that without satellite errors both change
    /// nothing and that with `modern` ones the consistency test releases right integers
    /// as often as wrong ones (seeds 2 and 3: 26 -> 55 mm, 99.8 -> 70-93 % fixed; the
    /// filter had no model of the satellites' orbit errors, now `orbit_error_sigma_m`,
    /// docs/orbit-determination.md);
    /// the default went back after that run, a design decision, not a reproduction's.
    pub held_test: HeldTest,
    /// The consistency test's false-alarm probability per epoch (`fixing::inconsistent`).
    /// # assumed: 1e-6, chosen before the first run: the test runs every epoch, 86 400 a
    /// day at 1 Hz, so a day of right integers is released by chance 0.09 times at most
    /// (fewer: successive epochs' statistics are correlated), and a false release costs
    /// only a refix from the twin's float values.
    pub consistency_false_alarm: f64,
    /// Steady-state 1-sigma per ECEF axis of the position error at either end of a line
    /// of sight, each satellite's broadcast orbit and the target's from its orbit filter
    /// (the anchor): first-order Gauss-Markov states in the single differences
    /// ([`super::filter`]'s module docs, "Orbit errors"). 0, the default, keeps the states
    /// out and every output as before: the bar's navigation file is exact (`grace-relnav`).
    /// With broadcast orbits set about 1 m. # assumed: 1 m is the order of both ends'
    /// errors: the along-track error of GPS broadcast orbits, the largest of their three
    /// and across the line of sight (radial and clock, most of the reduced-dynamic filter's
    /// 0.6 m SISRE, lie along it or cancel between the receivers), and a fix on those
    /// orbits (PDOP 1.5-2 times that SISRE), rounded up. Measured with 1 m under `modern`
    /// errors (2026-12-02, docs/orbit-determination.md): the covariance honest and the
    /// consistency test calibrated, but the integers fixed only from 947 s.
    pub orbit_error_sigma_m: f64,
    /// Correlation time of the satellites' orbit-error states (s).
    /// # assumed: 2 h, the reduced-dynamic filter's `satellite_tau_s` (broadcast
    /// ephemerides are fitted over 4 h and replaced every 2 h). The anchor's own,
    /// shorter one is `filter::ANCHOR_TAU_S`.
    pub orbit_error_tau_s: f64,
}

/// Which tests of the held integers against the float twin run (`fixing::check_held`);
/// either releases them.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Default)]
pub enum HeldTest {
    /// LAMBDA on the twin's float values of the held double differences resolves, with
    /// the ratio and success-rate tests, to other integers (`fixing::resolves_otherwise`).
    #[default]
    #[serde(rename = "twin-lambda")]
    TwinLambda,
    /// The held double differences' values differ from the twin's by more than their
    /// covariance allows, a chi-square test (`fixing::inconsistent`).
    #[serde(rename = "consistency")]
    Consistency,
    /// Both.
    #[serde(rename = "twin-lambda+consistency")]
    TwinLambdaAndConsistency,
}

impl HeldTest {
    /// Whether the twin-LAMBDA test runs.
    pub fn lambda(self) -> bool {
        self != HeldTest::Consistency
    }

    /// Whether the consistency test runs.
    pub fn consistency(self) -> bool {
        self != HeldTest::TwinLambda
    }
}

impl Default for DoubleDifferenceConfig {
    fn default() -> Self {
        Self {
            phase: ElevationNoise::constant(0.002),
            code: ElevationNoise::constant(0.3),
            acceleration_sigma_mps2: 1e-6,
            iono_sigma_m_per_sqrt_s: 1e-3,
            clock_sigma_m_per_sqrt_s: 1000.0,
            iono_initial_sigma_m: 0.5,
            ambiguity_initial_sigma_cycles: 30.0,
            ratio_threshold: 3.0,
            min_success_rate: 0.999,
            slip_threshold_m: 0.05,
            max_gap_s: 1.5,
            check_held: true,
            held_test: HeldTest::default(),
            consistency_false_alarm: 1e-6,
            orbit_error_sigma_m: 0.0,
            orbit_error_tau_s: ReducedDynamicConfig::default().satellite_tau_s,
        }
    }
}

impl DoubleDifferenceConfig {
    /// Every field inside its range; the error names `double_difference.<field>`.
    pub fn check(&self) -> Result<(), Invalid> {
        let within = |e: Invalid| e.within("double_difference");
        self.phase.check("phase", WEIGHT_SIGMA0_M).map_err(within)?;
        self.code.check("code", WEIGHT_SIGMA0_M).map_err(within)?;
        check_table(&[
            (
                "acceleration_sigma_mps2",
                self.acceleration_sigma_mps2,
                Allowed::above(0.0, 10.0, "m/s^2"),
            ),
            (
                "iono_sigma_m_per_sqrt_s",
                self.iono_sigma_m_per_sqrt_s,
                Allowed::above(0.0, 10.0, "m/sqrt(s)"),
            ),
            (
                "clock_sigma_m_per_sqrt_s",
                self.clock_sigma_m_per_sqrt_s,
                Allowed::above(0.0, 1e6, "m/sqrt(s)"),
            ),
            (
                "iono_initial_sigma_m",
                self.iono_initial_sigma_m,
                Allowed::above(0.0, 100.0, "m"),
            ),
            (
                "ambiguity_initial_sigma_cycles",
                self.ambiguity_initial_sigma_cycles,
                Allowed::above(0.0, 1e6, "cycles"),
            ),
            (
                "ratio_threshold",
                self.ratio_threshold,
                Allowed::closed(1.0, 1e6, ""),
            ),
            (
                "min_success_rate",
                self.min_success_rate,
                Allowed::above(0.0, 1.0, ""),
            ),
            (
                "slip_threshold_m",
                self.slip_threshold_m,
                Allowed::above(0.0, 100.0, "m"),
            ),
            (
                "max_gap_s",
                self.max_gap_s,
                Allowed::above(0.0, 3600.0, "s"),
            ),
            (
                "consistency_false_alarm",
                self.consistency_false_alarm,
                Allowed::above(0.0, 0.5, ""),
            ),
            (
                "orbit_error_sigma_m",
                self.orbit_error_sigma_m,
                Allowed::closed(0.0, 1000.0, "m"),
            ),
            (
                "orbit_error_tau_s",
                self.orbit_error_tau_s,
                Allowed::above(0.0, 1e7, "s"),
            ),
        ])
        .map_err(within)
    }
}
