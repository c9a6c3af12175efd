//! One seed of T-4.3: the observation-level run, the chain's fixed baselines (its fixed
//! integers checked against the truth's), the estimation run (the printed 22-state UKF,
//! and the default estimator for SkyForge's own rows) and the comparison run (the 6-state
//! UKF on `B0` and on the corrected `B0'`).

use super::{COMPARISON_EPOCHS, ESTIMATION_EPOCHS, SCENARIO};
use crate::attitude::compare::{
    IntegerCheck, PhaseOffsets, attitude_errors_deg, check_integers, phase_offsets, whole_second,
};
use crate::attitude::epochs::{FixedEpoch, true_attitudes};
use crate::attitude::nominal_geometry;
use crate::attitude::seeds::SEEDS;
use crate::draw::Draw;
use crate::thesis::ValidateError;
use crate::thesis::attitude_runs::{mean, std};
use rayon::prelude::*;
use skyforge_navigation::attitude::AttitudeFilter;
use skyforge_navigation::attitude::UkfAttitude;
use skyforge_navigation::attitude::{AttitudeConfig, THESIS_KAPPA};
use skyforge_navigation::attitude::{BodyGeometry, wrap_diff};
use skyforge_navigation::geometry_offset::{
    OffsetConfig, OffsetEstimator, OffsetState, Orientation, Step, THESIS_OFFSET_RATE_PSD,
    THESIS_RATE_PSD, WindowWeighting,
};
use skyforge_navigation::geometry_offset::{align, invariants};
use skyforge_navigation::relative::Constraint;
use skyforge_navigation::relative::{AmbiguityStatus, RelativeConfig};
use skyforge_navigation::relative::{FilesError, run_files};
use skyforge_orbits::frames::YawPitchRoll;
use skyforge_orbits::{Mat3, Vec3};
use skyforge_runner::{ObservationRun, observation_run};

/// Thesis 4.3.4: the cut-off above the local horizon (deg).
const CUT_OFF_DEG: f64 = 5.0;

/// Per-axis error series (deg or deg/s) with the time of each value.
#[derive(Default)]
pub(super) struct AxisSeries {
    /// Seconds since the run's start.
    t_s: Vec<f64>,
    values: [Vec<f64>; 3],
}

impl AxisSeries {
    pub(super) fn push(&mut self, t_s: f64, e: [f64; 3]) {
        self.t_s.push(t_s);
        for (s, v) in self.values.iter_mut().zip(e) {
            s.push(v);
        }
    }

    /// The std of each axis.
    pub fn std(&self) -> [f64; 3] {
        [0, 1, 2].map(|i| std(&self.values[i]))
    }

    /// The mean of each axis.
    pub fn mean(&self) -> [f64; 3] {
        [0, 1, 2].map(|i| mean(&self.values[i]))
    }

    /// Axis `i` (0 yaw, 1 pitch, 2 roll) against time.
    pub fn points(&self, i: usize) -> Vec<(f64, f64)> {
        self.t_s
            .iter()
            .copied()
            .zip(self.values[i].iter().copied())
            .collect()
    }
}

/// The printed filter's errors at every update of the estimation run.
#[derive(Default)]
pub(super) struct Estimation {
    pub xi: AxisSeries,
    /// The `xi_t` error against the true attitude of the antennas turned to the
    /// estimate's orientation (what the baselines determine).
    pub xi_turned: AxisSeries,
    pub rates: AxisSeries,
    /// Errors of the six offsets (m).
    pub offsets: [Vec<f64>; 6],
    /// The same against the true geometry turned to the estimate's orientation (m).
    pub offsets_turned: [Vec<f64>; 6],
    /// The estimated common offset rate `Delta'` (m/s) against time (figure 4.3-6).
    pub offset_rate: Vec<(f64, f64)>,
}

impl Estimation {
    /// One update's state `s` against the truth (`b0` nominal, `b_true` true baselines).
    fn record(
        &mut self,
        s: &OffsetState,
        b0: &[Vec3; 2],
        b_true: &[Vec3; 2],
        truth: &[YawPitchRoll],
    ) {
        let Some(k) = whole(s.oldest_t_s) else { return };
        self.offset_rate.push((s.oldest_t_s, s.offset_rate_m_s));
        let est = [b0[0] + s.offsets_m[0], b0[1] + s.offsets_m[1]];
        let Ok(turn) = align(b_true, &est) else {
            return;
        };
        if let Some(t) = truth.get(k) {
            let turned = YawPitchRoll::from_c_ref_body(&(turn.rotation * t.c_ref_body()));
            let t_s = s.oldest_t_s;
            self.xi.push(t_s, attitude_errors_deg(&s.window[0], t));
            self.xi_turned
                .push(t_s, attitude_errors_deg(&s.window[0], &turned));
        }
        if let Some(tr) = true_rate(truth, k) {
            self.rates
                .push(s.oldest_t_s, rate_errors_deg(&s.rates_rad_s, &tr));
        }
        let (turned, est, truth) = (six(&turn.baselines), six(&est), six(b_true));
        for i in 0..6 {
            self.offsets[i].push(est[i] - truth[i]);
            self.offsets_turned[i].push(est[i] - turned[i]);
        }
    }
}

/// The chain's fixed integers against the truth's double-difference integers (the check
/// of the other attitude tables, `attitude::compare`).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(super) struct Integers {
    pub check: IntegerCheck,
    /// Epochs with every ambiguity fixed (those the estimators take) and a wrong integer.
    pub wrong_epochs: usize,
}

impl Integers {
    /// Two seeds' together.
    pub fn merge(self, other: Self) -> Self {
        Self {
            check: self.check.merge(other.check),
            wrong_epochs: self.wrong_epochs + other.wrong_epochs,
        }
    }
}

/// What one seed gave.
pub(super) struct SeedResult {
    pub seed: u64,
    pub estimation: Estimation,
    /// The final shape (lengths, dot product) error of the printed filter (m, m, m^2).
    pub shape_final: [f64; 3],
    /// The default estimator's final offsets against the truth turned to the nominal
    /// orientation (m).
    pub pinned_final: [f64; 6],
    pub after: AxisSeries,
    pub before: AxisSeries,
    /// The same attitude errors against the true attitude of the antennas turned to the
    /// orientation of `B0'` (after) and of `B0` (before): what is left once the constant
    /// misalignment of the told geometry, which baselines do not see, is taken out.
    pub after_turned: AxisSeries,
    pub before_turned: AxisSeries,
    pub rate_after: AxisSeries,
    pub rate_before: AxisSeries,
    /// Fixed epochs in the estimation and the comparison run.
    pub fixed: [usize; 2],
    /// The chain's fixed integers over the whole run against the truth's.
    pub integers: Integers,
}

/// The chain's settings: plain LAMBDA (the thesis's method, and one that does not lean on
/// the wrong nominal geometry), the cut-off of 4.3.4, LS attitude (unused here).
fn chain_config() -> RelativeConfig {
    RelativeConfig {
        constraint: Constraint::None,
        elevation_mask_deg: Some(CUT_OFF_DEG),
        ..RelativeConfig::default()
    }
}

/// Thesis 4.3.4's filter as printed.
fn thesis_offset_config() -> OffsetConfig {
    OffsetConfig {
        rate_psd_rad2_s3: [THESIS_RATE_PSD; 3],
        offset_rate_psd_m2_s3: THESIS_OFFSET_RATE_PSD,
        kappa: THESIS_KAPPA,
        window_weighting: WindowWeighting::Thesis,
        orientation: Orientation::Free,
        ..OffsetConfig::default()
    }
}

/// The true rates at second `k` (rad/s): central difference of the 1 s truth.
fn true_rate(truth: &[YawPitchRoll], k: usize) -> Option<Vec3> {
    let (a, b) = (truth.get(k.checked_sub(1)?)?, truth.get(k + 1)?);
    Some(
        Vec3::new(
            wrap_diff(b.yaw_rad, a.yaw_rad),
            wrap_diff(b.pitch_rad, a.pitch_rad),
            wrap_diff(b.roll_rad, a.roll_rad),
        ) / 2.0,
    )
}

fn rate_errors_deg(est: &Vec3, truth: &Vec3) -> [f64; 3] {
    [0, 1, 2].map(|i| (est[i] - truth[i]).to_degrees())
}

fn whole(t_s: f64) -> Option<usize> {
    (t_s >= 0.0).then(|| t_s.round() as usize)
}

fn six(b: &[Vec3; 2]) -> [f64; 6] {
    [0, 1, 2, 3, 4, 5].map(|i| b[i / 3][i % 3])
}

/// The body baselines of `run`: nominal and true (antenna minus the master).
fn body_baselines(run: &ObservationRun) -> ([Vec3; 2], [Vec3; 2]) {
    let rel = |p: &[Vec3]| [p[1] - p[0], p[2] - p[0]];
    (rel(&run.nominal_body_m), rel(&run.true_body_m))
}

/// The estimation run with `config`; records the thesis's series when `record`.
fn estimate(
    epochs: &[FixedEpoch],
    b0: &[Vec3; 2],
    config: OffsetConfig,
    mut record: impl FnMut(&OffsetEstimator),
) -> Result<(OffsetEstimator, usize), ValidateError> {
    let fail = |e: &dyn std::fmt::Display| ValidateError::Pipeline(format!("{SCENARIO}: {e}"));
    let nominal = BodyGeometry::new(b0).map_err(|e| fail(&e))?;
    let mut f = OffsetEstimator::new(config, nominal).map_err(|e| fail(&e))?;
    let mut fixed = 0;
    for e in epochs.iter().take(ESTIMATION_EPOCHS) {
        let Some(b) = &e.baselines else { continue };
        fixed += 1;
        if let Step::Updated { .. } = f.push(e.t_s, b.clone()).map_err(|e| fail(&e))? {
            record(&f);
        }
    }
    Ok((f, fixed))
}

/// The chain over every epoch of `run` (told the nominal geometry) with
/// [`chain_config`]: the fixed baselines of each epoch, and every fixed integer against the
/// truth's.
fn chain(run: &ObservationRun) -> Result<(Vec<FixedEpoch>, Integers), FilesError> {
    let offsets: Vec<PhaseOffsets> = run
        .measured
        .iter()
        .zip(&run.truth)
        .map(|(m, t)| phase_offsets(m, t, run.start))
        .collect();
    let (mut epochs, mut integers) = (Vec::new(), Integers::default());
    run_files(
        &run.measured,
        run.ephemerides.clone(),
        &nominal_geometry(run),
        chain_config(),
        |o| {
            let t_s = (o.time - run.start).to_seconds();
            let mut baselines = None;
            if let Ok(e) = &o.result {
                let wrong = integers.check.wrong;
                let second = whole_second(o.time, run.start);
                check_integers(e, second, &offsets, &mut integers.check);
                if e.resolution.status == AmbiguityStatus::Fixed {
                    integers.wrong_epochs += usize::from(integers.check.wrong > wrong);
                    baselines = e.fixed_ned.clone();
                }
            }
            epochs.push(FixedEpoch { t_s, baselines });
        },
    )?;
    Ok((epochs, integers))
}

/// The comparison run: the 6-state UKF on `geometry`, errors per fixed epoch against the
/// truth and against the truth turned by `turn` (the rotation taking the true antenna
/// baselines closest to `geometry`'s: `shape::align`).
fn compare(
    epochs: &[FixedEpoch],
    geometry: BodyGeometry,
    turn: &Mat3,
    truth: &[YawPitchRoll],
) -> Result<(AxisSeries, AxisSeries, AxisSeries, usize), ValidateError> {
    let fail = |e: &dyn std::fmt::Display| ValidateError::Pipeline(format!("{SCENARIO}: {e}"));
    let config = AttitudeConfig {
        rate_psd_rad2_s3: [THESIS_RATE_PSD; 3],
        kappa: THESIS_KAPPA,
        ..AttitudeConfig::default()
    };
    let mut ukf = UkfAttitude::new(&config, geometry, None).map_err(|e| fail(&e))?;
    let (mut att, mut turned, mut rates, mut fixed, mut last) = (
        AxisSeries::default(),
        AxisSeries::default(),
        AxisSeries::default(),
        0,
        None,
    );
    for e in epochs
        .iter()
        .skip(ESTIMATION_EPOCHS)
        .take(COMPARISON_EPOCHS)
    {
        let Some(b) = &e.baselines else { continue };
        fixed += 1;
        if let Some(t0) = last {
            ukf.predict(e.t_s - t0).map_err(|e| fail(&e))?;
        }
        last = Some(e.t_s);
        let info = ukf.update(b).map_err(|e| fail(&e))?;
        let (Some(state), Some(k)) = (ukf.state(), whole(e.t_s)) else {
            continue;
        };
        if info.initialised {
            continue;
        }
        if let Some(t) = truth.get(k) {
            att.push(e.t_s, attitude_errors_deg(&state.angles, t));
            let t_turned = YawPitchRoll::from_c_ref_body(&(turn * t.c_ref_body()));
            turned.push(e.t_s, attitude_errors_deg(&state.angles, &t_turned));
        }
        if let (Some(r), Some(tr)) = (state.rates_rad_s, true_rate(truth, k)) {
            rates.push(e.t_s, rate_errors_deg(&r, &tr));
        }
    }
    Ok((att, turned, rates, fixed))
}

/// The default estimator's final offsets against the true geometry turned to the
/// nominal orientation (m).
fn pinned_error(
    epochs: &[FixedEpoch],
    b0: &[Vec3; 2],
    b_true: &[Vec3; 2],
) -> Result<[f64; 6], ValidateError> {
    let fail = |e: &dyn std::fmt::Display| ValidateError::Pipeline(format!("{SCENARIO}: {e}"));
    let (pinned, _) = estimate(epochs, b0, OffsetConfig::default(), |_| {})?;
    let g = pinned.corrected_geometry().map_err(|e| fail(&e))?;
    let est = six(&[g.baselines()[0], g.baselines()[1]]);
    let truth = six(&align(b_true, b0).map_err(|e| fail(&e))?.baselines);
    Ok([0, 1, 2, 3, 4, 5].map(|i| est[i] - truth[i]))
}

/// One seed of the scenario.
fn run_seed(scenario: &skyforge_scenarios::Scenario) -> Result<SeedResult, ValidateError> {
    let fail = |e: &dyn std::fmt::Display| {
        ValidateError::Pipeline(format!("{SCENARIO} seed {}: {e}", scenario.seed))
    };
    let run = observation_run(scenario).map_err(|e| fail(&e))?;
    let (epochs, integers) = chain(&run).map_err(|e| fail(&e))?;
    let truth = true_attitudes(&run);
    let (b0, b_true) = body_baselines(&run);
    let mut estimation = Estimation::default();
    let (thesis, fixed_estimation) = estimate(&epochs, &b0, thesis_offset_config(), |f| {
        if let Some(s) = f.state() {
            estimation.record(&s, &b0, &b_true, &truth);
        }
    })?;
    let corrected = thesis.corrected_geometry().map_err(|e| fail(&e))?;
    let shape =
        invariants(&[corrected.baselines()[0], corrected.baselines()[1]]) - invariants(&b_true);
    let corrected_turn = align(
        &b_true,
        &[corrected.baselines()[0], corrected.baselines()[1]],
    )
    .map_err(|e| fail(&e))?
    .rotation;
    let nominal_turn = align(&b_true, &b0).map_err(|e| fail(&e))?.rotation;
    let nominal = BodyGeometry::new(&b0).map_err(|e| fail(&e))?;
    let (after, after_turned, rate_after, fixed_comparison) =
        compare(&epochs, corrected, &corrected_turn, &truth)?;
    let (before, before_turned, rate_before, _) = compare(&epochs, nominal, &nominal_turn, &truth)?;
    Ok(SeedResult {
        seed: scenario.seed,
        estimation,
        shape_final: [shape.x, shape.y, shape.z],
        pinned_final: pinned_error(&epochs, &b0, &b_true)?,
        after,
        before,
        after_turned,
        before_turned,
        rate_after,
        rate_before,
        fixed: [fixed_estimation, fixed_comparison],
        integers,
    })
}

/// The scenario on the seeds of `draw` (registered: [`SEEDS`] seeds, its own and the
/// next ones), in parallel.
pub(super) fn runs(draw: Draw) -> Result<Vec<SeedResult>, ValidateError> {
    let scenario = skyforge_scenarios::named(SCENARIO)?;
    draw.seeds(scenario.seed, SEEDS)
        .into_par_iter()
        .map(|seed| {
            let mut s = scenario.clone();
            s.seed = seed;
            run_seed(&s)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn seeds_merge_their_integer_checks() {
        let mut a = Integers::default();
        a.check.add(3.04, 3);
        a.check.add(4.1, 3);
        a.wrong_epochs = 1;
        let mut b = Integers::default();
        b.check.add(-1.97, -2);
        let both = a.merge(b);
        assert_eq!(
            (both.check.checked, both.check.wrong, both.wrong_epochs),
            (3, 1, 1)
        );
        assert!((both.check.largest_distance_cycles - 0.1).abs() < 1e-9);
    }
}
