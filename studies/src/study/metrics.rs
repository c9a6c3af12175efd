//! The per-run statistics a study can keep: each one number per run, computed from the
//! run's observables (the observation-level model's or the receiver's), its first
//! antenna's single-point fixes and the attitude chain's comparison with the run's own
//! truth ([`skyforge_validate::attitude`]). A run without the quantity (no fixed epoch, say) gives
//! NaN, which the summaries leave out and count.

use skyforge_gnss::observation::ObsRecord;
use skyforge_gnss::signal::Signal;
use skyforge_navigation::relative::RelativeConfig;
use skyforge_orbits::ephemeris::SatId;
use skyforge_runner::ObservationRun;
use skyforge_scenarios::Scenario;
use skyforge_validate::attitude::compare::offsets;
use skyforge_validate::attitude::{ChainComparison, compare, nominal_geometry};
use skyforge_validate::stats::rms;
use std::collections::BTreeMap;

/// One per-run statistic.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Metric {
    /// Measured minus true pseudorange, RMS over every antenna, satellite and epoch (m).
    PseudorangeRms,
    /// Measured minus true carrier phase (m) with each arc's mean removed (its integer
    /// ambiguity and any constant), RMS over every antenna, satellite and epoch.
    PhaseRms,
    /// The first antenna's single-point position error (3D, ECEF), RMS over the epochs
    /// with a fix (m).
    PositionRms,
    /// Epochs with every ambiguity fixed over the epochs from the first fix on.
    FixRate,
    /// Fixed epochs with a wrong integer over the fixed epochs.
    WrongFixRate,
    /// Seconds from the start to the first fixed epoch.
    FirstFix,
    /// Baseline error norm (ECEF), RMS over fixed epochs and baselines (m).
    BaselineRms,
    /// Attitude error RMS over fixed epochs (deg), per axis.
    YawRms,
    PitchRms,
    RollRms,
}

/// Every metric, in the order of [`Metric::names`].
const ALL: [Metric; 10] = [
    Metric::PseudorangeRms,
    Metric::PhaseRms,
    Metric::PositionRms,
    Metric::FixRate,
    Metric::WrongFixRate,
    Metric::FirstFix,
    Metric::BaselineRms,
    Metric::YawRms,
    Metric::PitchRms,
    Metric::RollRms,
];

impl Metric {
    /// The name in study files and outputs.
    pub fn name(self) -> &'static str {
        match self {
            Metric::PseudorangeRms => "pseudorange_rms_m",
            Metric::PhaseRms => "phase_rms_m",
            Metric::PositionRms => "position_rms_m",
            Metric::FixRate => "fix_rate",
            Metric::WrongFixRate => "wrong_fix_rate",
            Metric::FirstFix => "first_fix_s",
            Metric::BaselineRms => "baseline_rms_m",
            Metric::YawRms => "yaw_rms_deg",
            Metric::PitchRms => "pitch_rms_deg",
            Metric::RollRms => "roll_rms_deg",
        }
    }

    /// Unit of the values.
    pub fn unit(self) -> &'static str {
        match self {
            Metric::PseudorangeRms
            | Metric::PhaseRms
            | Metric::PositionRms
            | Metric::BaselineRms => "m",
            Metric::FixRate | Metric::WrongFixRate => "1",
            Metric::FirstFix => "s",
            Metric::YawRms | Metric::PitchRms | Metric::RollRms => "deg",
        }
    }

    /// Every name, for messages.
    pub fn names() -> Vec<&'static str> {
        ALL.iter().map(|m| m.name()).collect()
    }

    /// The metric named `name`.
    pub fn from_name(name: &str) -> Option<Self> {
        ALL.into_iter().find(|m| m.name() == name)
    }

    /// Whether it needs the attitude chain (two antennas or more).
    fn needs_chain(self) -> bool {
        !matches!(
            self,
            Metric::PseudorangeRms | Metric::PhaseRms | Metric::PositionRms
        )
    }

    /// Whether `scenario` can give this metric; what it needs otherwise.
    pub fn check(self, scenario: &Scenario) -> Result<(), String> {
        if scenario.signal.is_none() {
            return Err(
                "the runs of a study synthesise the signals (or, at the observation level, their observables): the base scenario needs a [signal] table".into(),
            );
        }
        if self.needs_chain() && scenario.antennas.len() < 2 {
            return Err(format!(
                "{} comes from the attitude chain, which needs two antennas or more (the scenario has {})",
                self.name(),
                scenario.antennas.len()
            ));
        }
        Ok(())
    }
}

/// The values of `metrics` for one run (NaN where the run has none; every attitude-chain
/// metric when the master has no observation, as when a signal-level receiver found no
/// signal).
pub fn measure(run: &ObservationRun, metrics: &[Metric]) -> Result<Vec<f64>, String> {
    let observed = run.measured.first().is_some_and(|f| !f.epochs.is_empty());
    let chain = if observed && metrics.iter().any(|m| m.needs_chain()) {
        Some(
            compare(run, &nominal_geometry(run), RelativeConfig::default())
                .map_err(|e| format!("attitude chain: {e}"))?,
        )
    } else {
        None
    };
    Ok(metrics
        .iter()
        .map(|&m| match (m, &chain) {
            (Metric::PseudorangeRms, _) => pseudorange_rms(run),
            (Metric::PhaseRms, _) => phase_rms(run),
            (Metric::PositionRms, _) => position_rms(run),
            (m, Some(c)) => chain_metric(m, c),
            (_, None) => f64::NAN,
        })
        .collect())
}

/// A chain metric of `c`.
fn chain_metric(m: Metric, c: &ChainComparison) -> f64 {
    let fixed = !c.fixed.is_empty();
    let or_nan = |v: f64| if fixed { v } else { f64::NAN };
    match m {
        Metric::FixRate => c.fix_rate(),
        Metric::WrongFixRate if c.fixed_epochs == 0 => f64::NAN,
        Metric::WrongFixRate => c.fixed_epochs_wrong as f64 / c.fixed_epochs as f64,
        Metric::FirstFix => c.first_fix_s.unwrap_or(f64::NAN),
        Metric::BaselineRms => {
            let norms: Vec<f64> = c
                .fixed
                .iter()
                .flat_map(|e| e.baseline_ecef_m.iter())
                .map(|b| (b[0] * b[0] + b[1] * b[1] + b[2] * b[2]).sqrt())
                .collect();
            or_nan(rms(&norms))
        }
        Metric::YawRms => or_nan(rms(&c.attitude_axis(0))),
        Metric::PitchRms => or_nan(rms(&c.attitude_axis(1))),
        Metric::RollRms => or_nan(rms(&c.attitude_axis(2))),
        Metric::PseudorangeRms | Metric::PhaseRms | Metric::PositionRms => f64::NAN,
    }
}

/// One measured-minus-true difference: its antenna (index), satellite and signal, and the
/// difference in the observable's unit.
type Difference = (usize, SatId, Signal, f64);

/// Measured minus true `pick` (an observable of a record) wherever both exist at a whole
/// second (the observation truth's epochs), antenna by antenna in epoch order.
fn differences(run: &ObservationRun, pick: fn(&ObsRecord) -> Option<f64>) -> Vec<Difference> {
    run.measured
        .iter()
        .zip(&run.truth)
        .enumerate()
        .flat_map(|(a, (measured, truth))| {
            offsets(measured, truth, run.start, pick)
                .into_iter()
                .map(move |((_, sat, signal), d)| (a, sat, signal, d))
        })
        .collect()
}

/// RMS of `errors`, NaN when there are none.
fn rms_or_nan(errors: &[f64]) -> f64 {
    if errors.is_empty() {
        f64::NAN
    } else {
        rms(errors)
    }
}

/// RMS of measured minus true pseudorange over every antenna, satellite and epoch.
fn pseudorange_rms(run: &ObservationRun) -> f64 {
    let errors: Vec<f64> = differences(run, |r| r.pseudorange_m)
        .into_iter()
        .map(|d| d.3)
        .collect();
    rms_or_nan(&errors)
}

/// RMS of measured minus true carrier phase (m) over every antenna, satellite and epoch,
/// each arc (antenna, satellite, signal) less its own mean: the integer ambiguity and the
/// constant part go, the noise and anything that changes along the arc (a slip) stay.
fn phase_rms(run: &ObservationRun) -> f64 {
    // Ordered: the sum of squares must not depend on a hash seed (runs are compared bit
    // for bit across shard layouts).
    let mut arcs: BTreeMap<(usize, SatId, Signal), Vec<f64>> = BTreeMap::new();
    for (a, sat, signal, cycles) in differences(run, |r| r.carrier_phase_cycles) {
        arcs.entry((a, sat, signal))
            .or_default()
            .push(cycles * signal.wavelength_m());
    }
    let errors: Vec<f64> = arcs
        .values()
        .flat_map(|arc| {
            let mean = arc.iter().sum::<f64>() / arc.len() as f64;
            arc.iter().map(move |e| e - mean)
        })
        .collect();
    rms_or_nan(&errors)
}

/// RMS over the first antenna's single-point fixes ([`ObservationRun::first_antenna_fixes`])
/// of their distance (ECEF) from its true position at the fix's instant.
fn position_rms(run: &ObservationRun) -> f64 {
    let errors: Vec<f64> = run
        .first_antenna_fixes()
        .iter()
        .filter_map(|f| {
            let truth = run.true_position(0, (f.at - run.start).to_seconds())?;
            Some((f.r_ecef_m - truth).norm())
        })
        .collect();
    rms_or_nan(&errors)
}

#[cfg(test)]
mod tests {
    use super::*;
    use hifitime::{Duration, Epoch, TimeScale};
    use skyforge_gnss::observation::{ObsEpoch, ObsFile, ObsRecord};
    use skyforge_navigation::pvt::predicted_view;
    use skyforge_orbits::constants::C_MPS;
    use skyforge_orbits::ephemeris::SatId;
    use skyforge_orbits::ephemeris::nominal;
    use skyforge_orbits::ephemeris::rinex_nav_iono::BroadcastIono;
    use skyforge_orbits::frames::YawPitchRoll;
    use skyforge_orbits::platform::PlatformState;
    use skyforge_orbits::{Mat3, Vec3};
    use skyforge_runner::PositionFix;

    /// Seconds simulated.
    const SECONDS: usize = 20;
    /// The receiver clock's offset (m): 0.3 ms, 2.1 m along the track at 7 km/s were a fix
    /// compared with the truth at its tag rather than at its instant.
    const CLOCK_M: f64 = 0.3e-3 * C_MPS;

    fn start() -> Epoch {
        Epoch::from_gregorian(2023, 3, 12, 0, 0, 0, 0, TimeScale::GPST)
    }

    fn velocity() -> Vec3 {
        Vec3::new(0.0, 7_000.0, 1_000.0)
    }

    /// The platform's centre `t_s` seconds after the start: a straight line 500 km up.
    fn centre(t_s: f64) -> Vec3 {
        Vec3::new(6_878e3, 0.0, 0.0) + t_s * velocity()
    }

    /// A one-antenna run along that line, the antenna at `body_m` (body axes = ECEF), with
    /// the nominal GPS constellation (circular orbits, no clock terms) broadcast.
    fn run(
        body_m: Vec3,
        measured: Vec<ObsFile>,
        fixes: Option<Vec<PositionFix>>,
    ) -> ObservationRun {
        let platform = (0..=SECONDS)
            .map(|k| PlatformState {
                r_ecef_m: centre(k as f64),
                v_ecef_mps: velocity(),
                c_body_ecef: Mat3::identity(),
                attitude: YawPitchRoll::new(0.0, 0.0, 0.0),
            })
            .collect();
        ObservationRun {
            start: start(),
            antennas: vec!["a".into()],
            nominal_body_m: vec![body_m],
            true_body_m: vec![body_m],
            measured,
            truth: Vec::new(),
            platform,
            ephemerides: nominal::gps(start()),
            iono: BroadcastIono::default(),
            receiver_fixes: fixes,
        }
    }

    /// Error-free pseudoranges of a receiver `lever_m` off the platform's centre whose
    /// clock runs [`CLOCK_M`] ahead, tagged at whole seconds of that clock: the epoch
    /// tagged `k` s was sampled at `k - CLOCK_M / c`. Satellites 15 deg up and more; above
    /// the atmosphere, so no delay a receiver would model.
    fn observations(lever_m: Vec3) -> ObsFile {
        let store = nominal::gps_store(start());
        let epochs = (1..SECONDS)
            .map(|k| {
                let t_s = k as f64 - CLOCK_M / C_MPS;
                let r = centre(t_s) + lever_m;
                let sats = (1..=32)
                    .filter_map(|prn| {
                        let sat = SatId::gps(prn);
                        let view = predicted_view(store.select(sat, t_s)?, t_s, &r);
                        let (_, el) = view.az_el_rad?;
                        (el > 15f64.to_radians()).then(|| {
                            let pr = view.range_m + CLOCK_M;
                            let cycles = pr / Signal::GpsL1Ca.wavelength_m();
                            ObsRecord::complete(sat, Signal::GpsL1Ca, pr, cycles, 0.0, 45.0)
                        })
                    })
                    .collect::<Vec<_>>();
                assert!(sats.len() >= 6, "{} satellites up at {k} s", sats.len());
                ObsEpoch {
                    time: start() + Duration::from_seconds(k as f64),
                    sats,
                }
            })
            .collect();
        ObsFile {
            source: "a observations".into(),
            approx_ecef_m: None,
            codes: Default::default(),
            epochs,
            marker: None,
            dropped: Vec::new(),
        }
    }

    fn position(run: &ObservationRun) -> f64 {
        measure(run, &[Metric::PositionRms]).unwrap()[0]
    }

    #[test]
    fn the_position_of_observations_is_the_receivers_pvt_at_the_instant_it_solves_for() {
        // The antenna where the observations were made: no error, although it moved 2 m
        // between the tags and the instants.
        let lever = Vec3::new(0.3, -0.2, 0.5);
        let exact = run(lever, vec![observations(lever)], None);
        assert_eq!(exact.first_antenna_fixes().len(), SECONDS - 1);
        assert!(position(&exact) < 0.01, "{} m", position(&exact));
        // The same observations against an antenna 12 m away: 12 m at every epoch.
        let off = run(
            lever + Vec3::new(0.0, 0.0, 12.0),
            vec![observations(lever)],
            None,
        );
        assert!((position(&off) - 12.0).abs() < 0.01, "{} m", position(&off));
    }

    #[test]
    fn the_position_of_a_receivers_own_fixes_is_their_error_at_their_instants() {
        let lever = Vec3::new(0.3, -0.2, 0.5);
        let errors = [Vec3::new(3.0, 4.0, 0.0), Vec3::new(0.0, 0.0, -12.0)];
        let mut fixes: Vec<PositionFix> = (0..10)
            .map(|k| {
                let t_s = 2.0 * k as f64 + 0.37;
                PositionFix {
                    at: start() + Duration::from_seconds(t_s),
                    r_ecef_m: centre(t_s) + lever + errors[k % 2],
                }
            })
            .collect();
        // A fix outside the simulated span has no truth to compare with.
        fixes.push(PositionFix {
            at: start() + Duration::from_seconds(SECONDS as f64 + 3.0),
            r_ecef_m: Vec3::zeros(),
        });
        let got = position(&run(lever, Vec::new(), Some(fixes)));
        let want = ((25.0 + 144.0) / 2.0f64).sqrt();
        assert!((got - want).abs() < 1e-6, "{got} m, want {want} m");
        // No fix: no value.
        assert!(position(&run(lever, Vec::new(), Some(Vec::new()))).is_nan());
    }
}
