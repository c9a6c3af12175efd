//! T-3.3-S: the fast synchronisation experiment of thesis section 3.3.5 (tables 3.3-1 and
//! 3.3-2) on synthesised samples. The PMF-FFT gives a coarse and a fine initial Doppler
//! from the first millisecond; the UKF carrier tracker (thesis 3.3.4) then runs on 1 ms
//! prompts, once from the fine estimate with the narrow Q ("proposed") and once from the
//! coarse estimate with the wide Q ("traditional"), and once more with equal (wide) Q
//! from both starts to compare convergence. The same runs give the data of thesis figures
//! 3.3-10 and 3.3-11, the phase and Doppler errors against time ([`curves`]).
//!
//! As in the thesis (eq. 3.3-56: "assume the C/A code is precisely synchronised") the
//! tracker is given the code timing; carrier phase and Doppler are what it estimates.

mod signal;

use crate::draw::Draw;
use crate::report::{Row, Verdict};
use crate::stats::batch_means_standard_error;
use crate::thesis::ValidateError;
use crate::thesis::curves::{Curve, CurveSeries, Mark, Value};
use nalgebra::{Matrix4, Vector4};
use num_complex::Complex64;
use signal::{SignalSource, SignalSpec};
use skyforge_gnss::codes::gps_ca;
use skyforge_receiver::acquisition::pmf_fft::{ChipTiming, PmfFft, despread_to_chips, theory};
use skyforge_receiver::tracking::{Correlator, NcoState, TapSet};
use skyforge_receiver::tracking::{THESIS_KAPPA, THESIS_PROPOSED_Q};
use skyforge_receiver::tracking::{UkfCarrier, UkfConfig};
use std::f64::consts::TAU;

/// Table identifier.
pub const TABLE: &str = "T-3.3-S";
/// Thesis 3.3.5: Rc = 1.023 MHz, fs = 12 Rc, IF 1 MHz, T = T_coh = 1 ms, M = 1024, L = 64.
const CHIP_RATE_HZ: f64 = 1.023e6;
const IF_HZ: f64 = 1.0e6;
const M_CHIPS: usize = 1024;
const L_CHIPS: usize = 64;
const T_S: f64 = 1e-3;
/// Thesis: initial Doppler -3.73 kHz, 2 kHz/s, 500 Hz/s^2, phase 0, 45 dB-Hz, 1 kbit/s.
const DOPPLER: [f64; 3] = [-3730.0, 2000.0, 500.0];
const CN0_DBHZ: f64 = 45.0;
/// Thesis: kappa = 0.5, R = diag(0.0158, 0.0158), Q as (theta, omega, alpha, alpha_t).
const KAPPA: f64 = THESIS_KAPPA;
const R: [f64; 2] = [0.0158, 0.0158];
const Q_PROPOSED: [f64; 4] = THESIS_PROPOSED_Q;
const Q_TRADITIONAL: [f64; 4] = [1e-5, 10.0, 1e7, 1e13];
/// assumed: the thesis does not name the PRN; any C/A code.
const PRN: u8 = 1;
/// assumed: the thesis gives no seed.
const SEED: u64 = 33;
/// assumed: 1 s of tracking; the thesis's figures show convergence well within it.
const DURATION_S: f64 = 1.0;
/// assumed: "converged" statistics over the second half of the run.
const STATS_FROM_S: f64 = 0.5;
/// assumed: converged once the 20 ms moving RMS Doppler error stays below twice the run's
/// own converged Doppler error std (steady state reached). (First chosen as a 0.1 rad RMS
/// phase error, then 5 Hz; changed after the runs because the first sits next to the
/// traditional filter's steady-state phase noise and the second is met by both filters
/// within the first window, so neither measures convergence.)
const CONVERGED_STD_FACTOR: f64 = 2.0;
const CONVERGE_WINDOW: usize = 20;
/// assumed: initial 1-sigma uncertainties given to the filter: phase 0.3 rad (from the
/// first prompt), Doppler: the fine estimator's own standard deviation (R_f x MCRB, eqs.
/// 3.3-54/3.3-55, about 70-80 Hz at 45 dB-Hz over 1 ms; first set to 5 Hz, which made the
/// proposed filter diverge from a 155 Hz initial error) or, for the coarse estimate, a
/// uniform error over one 499.5 Hz bin (144 Hz); rate 2.5 kHz/s and second derivative
/// 1 kHz/s^2 (LEO-sized dynamics).
const SIGMA0_PHASE_RAD: f64 = 0.3;
const SIGMA0_COARSE_HZ: f64 = 144.0;
const SIGMA0_RATE_HZPS: f64 = 2500.0;
const SIGMA0_ACCEL_HZPS2: f64 = 1000.0;

/// Milliseconds per batch of the error means' standard errors.
// assumed: 50 ms, fixed before the runs over seeds: ten batches in the half-second window,
// each longer than the narrow filter's settling of tens of milliseconds.
const BIAS_BATCH_MS: usize = 50;
/// A converged error mean is unbiased when within this many of its standard errors of 0.
// assumed: 3, a two-sided test at about 0.3 % per row, fixed with the batch length.
const BIAS_STANDARD_ERRORS: f64 = 3.0;

/// One UKF run: per 1 ms interval, its middle (s), the phase error (rad, wrapped) and
/// the Doppler error (Hz).
struct Run {
    t_s: Vec<f64>,
    errors: Vec<(f64, f64)>,
}

impl Run {
    /// (time, error) of every interval: the phase error for `column` 0, the Doppler
    /// error for 1.
    fn along(&self, column: usize) -> Vec<(f64, f64)> {
        let pick = |e: &(f64, f64)| if column == 0 { e.0 } else { e.1 };
        self.t_s
            .iter()
            .zip(&self.errors)
            .map(|(&t, e)| (t, pick(e)))
            .collect()
    }
    fn window(&self) -> &[(f64, f64)] {
        &self.errors[(STATS_FROM_S / T_S) as usize..]
    }
    fn mean_std(v: impl Iterator<Item = f64> + Clone) -> (f64, f64) {
        let n = v.clone().count() as f64;
        let mean = v.clone().sum::<f64>() / n;
        let var = v.map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1.0);
        (mean, var.sqrt())
    }
    fn phase(&self) -> (f64, f64) {
        Self::mean_std(self.window().iter().map(|e| e.0))
    }
    fn doppler(&self) -> (f64, f64) {
        Self::mean_std(self.window().iter().map(|e| e.1))
    }
    /// The standard errors of the phase and Doppler error means over the window, by
    /// batch means of [`BIAS_BATCH_MS`] (the filter's errors are correlated over many
    /// milliseconds).
    fn mean_errors(&self) -> (f64, f64) {
        let se = |f: fn(&(f64, f64)) -> f64| {
            batch_means_standard_error(self.window().iter().map(f).enumerate(), BIAS_BATCH_MS)
                .unwrap_or(f64::NAN)
        };
        (se(|e| e.0), se(|e| e.1))
    }
    /// Time (s) after which the moving RMS Doppler error stays below the threshold.
    fn convergence_s(&self) -> Option<f64> {
        let rms: Vec<f64> = self
            .errors
            .windows(CONVERGE_WINDOW)
            .map(|w| (w.iter().map(|e| e.1 * e.1).sum::<f64>() / w.len() as f64).sqrt())
            .collect();
        let limit = CONVERGED_STD_FACTOR * self.doppler().1;
        let last_bad = rms.iter().rposition(|&r| r >= limit);
        match last_bad {
            None => Some(0.0),
            Some(k) if k + 1 < rms.len() => Some((k + CONVERGE_WINDOW) as f64 * T_S),
            Some(_) => None,
        }
    }
}

use skyforge_orbits::angles::wrap_pi;

/// Track `DURATION_S` of the signal with a UKF started at Doppler `f_start_hz` (the
/// estimate for the middle of the first millisecond) with uncertainty `sigma_f_hz` and
/// process noise `q`.
fn track(
    spec: &SignalSpec,
    code: &[i8],
    f_start_hz: f64,
    sigma_f_hz: f64,
    q: [f64; 4],
    seed: u64,
) -> Result<Run, ValidateError> {
    let fs = spec.sample_rate_hz;
    let n = (fs * T_S).round() as usize;
    let mut source = SignalSource::new(*spec, code, seed);
    let mut block = Vec::with_capacity(n);
    let mut correlator = Correlator::new(
        code,
        TapSet::Three {
            early_late_spacing_chips: 0.5,
        },
    )?;
    // Normalisation: a real signal of amplitude 1 correlates to n/2 at zero error.
    let scale = 2.0 / n as f64;
    let nco_at = |k: usize, theta: f64, omega: f64| {
        // theta: Doppler phase at the middle of interval k; the NCO starts half a period
        // earlier and runs at IF + omega / 2 pi.
        let t0 = k as f64 * T_S;
        let start_phase = theta - omega * T_S / 2.0;
        NcoState {
            carrier_phase_cycles: IF_HZ * t0 + start_phase / TAU,
            carrier_cycles_per_sample: (IF_HZ + omega / TAU) / fs,
            code_phase_chips: spec.code_phase_chips(t0),
            code_chips_per_sample: (spec.code_phase_chips(t0 + T_S) - spec.code_phase_chips(t0))
                / n as f64,
        }
    };
    // Interval 0: the phase from its prompt at the starting Doppler (a receiver can do
    // this; modulo the data sign, hence the two-quadrant angle).
    source.block(n, &mut block);
    let omega0 = TAU * f_start_hz;
    let p0 = correlator.correlate(&block, &nco_at(0, 0.0, omega0))[1];
    let theta0 = (p0.im / p0.re).atan();
    let cov = Matrix4::from_diagonal(&Vector4::new(
        SIGMA0_PHASE_RAD.powi(2),
        (TAU * sigma_f_hz).powi(2),
        (TAU * SIGMA0_RATE_HZPS).powi(2),
        (TAU * SIGMA0_ACCEL_HZPS2).powi(2),
    ));
    let cfg = UkfConfig {
        period_s: T_S,
        coherent_s: T_S,
        q,
        r: R,
        kappa: KAPPA,
    };
    let mut ukf = UkfCarrier::new(cfg, [theta0, omega0, 0.0, 0.0], cov);
    let intervals = (DURATION_S / T_S) as usize;
    let mut errors = Vec::with_capacity(intervals);
    let mut t_s = Vec::with_capacity(intervals);
    for k in 1..intervals {
        let [theta, omega, _] = ukf.predict();
        source.block(n, &mut block);
        let p = correlator.correlate(&block, &nco_at(k, theta, omega))[1];
        ukf.update(Complex64::new(p.re * scale, p.im * scale));
        let [theta, omega, _, _] = ukf.state();
        let t_mid = (k as f64 + 0.5) * T_S;
        // Phase modulo pi: the data sign is not known to the tracker.
        let phase_err = wrap_pi(2.0 * (theta - spec.doppler_phase_rad(t_mid))) / 2.0;
        errors.push((phase_err, omega / TAU - spec.doppler_hz(t_mid)));
        t_s.push(t_mid);
    }
    Ok(Run { t_s, errors })
}

/// The thesis's initial Doppler errors of the fine and the coarse estimate (one
/// realisation; section 3.3.5).
const THESIS_FINE_ERROR_HZ: f64 = -2.936;
const THESIS_COARSE_ERROR_HZ: f64 = 233.1055;
/// Thesis tables 3.3-1 / 3.3-2: converged phase error mean and std (rad), Doppler error
/// mean and std (Hz), of the proposed and the traditional synchroniser.
const THESIS_PROPOSED: [f64; 4] = [0.0005, 0.0254, 0.0039, 0.2280];
const THESIS_TRADITIONAL: [f64; 4] = [0.0016, 0.0543, 0.0237, 1.9401];

/// The experiment on one seed, which both the rows and the figures' data are made of:
/// the initial estimates and the three UKF runs.
struct Experiment {
    /// Fine and coarse initial Doppler estimate minus truth (Hz).
    fine_error_hz: f64,
    coarse_error_hz: f64,
    /// The fine estimate's expected standard deviation (Hz), R_f x MCRB.
    sigma_fine_hz: f64,
    /// Fine start, narrow Q.
    proposed: Run,
    /// Coarse start, wide Q.
    traditional: Run,
    /// Fine start, wide Q (figure 3.3-10's "proposed").
    fine_wide: Run,
}

/// The experiment on the signal of `draw`'s seed.
fn experiment(draw: Draw) -> Result<Experiment, ValidateError> {
    let seed = draw.seed(SEED);
    let spec = SignalSpec {
        sample_rate_hz: 12.0 * CHIP_RATE_HZ,
        if_hz: IF_HZ,
        chip_rate_hz: CHIP_RATE_HZ,
        doppler: DOPPLER,
        phase_rad: 0.0,
        cn0_dbhz: CN0_DBHZ,
        symbol_s: 1e-3,
    };
    let code: Vec<i8> = gps_ca(PRN).map(|c| c.to_vec()).unwrap_or_default();
    // PMF-FFT on the first M chips (the C/A code plus one zero chip, thesis 3.3.1).
    let fs = spec.sample_rate_hz;
    let mut first = Vec::new();
    SignalSource::new(spec, &code, seed).block((fs * 1.1e-3) as usize, &mut first);
    let chips = despread_to_chips(
        &first,
        ChipTiming {
            sample_rate_hz: fs,
            carrier_hz: IF_HZ,
            chip_rate_hz: CHIP_RATE_HZ,
            code_start_sample: 0.0,
        },
        &code,
        M_CHIPS,
    )?;
    let pmf = PmfFft::new(M_CHIPS, L_CHIPS)?;
    let est = pmf.estimate(&chips, &mut pmf.scratch())?;
    let t_est = M_CHIPS as f64 / CHIP_RATE_HZ / 2.0;
    let truth = spec.doppler_hz(t_est);
    let (fine, coarse) = (
        est.fine_doppler_hz(CHIP_RATE_HZ),
        est.coarse_doppler_hz(CHIP_RATE_HZ),
    );
    // The fine estimate's expected spread: R_f x MCRB (eqs. 3.3-54, 3.3-55) at the chip SNR.
    let es_n0 = 10f64.powf(CN0_DBHZ / 10.0) / CHIP_RATE_HZ;
    let sigma_fine_hz = theory::variance_fd_tc(M_CHIPS, L_CHIPS, est.peak_bin, est.delta, es_n0)
        .sqrt()
        * CHIP_RATE_HZ;
    Ok(Experiment {
        fine_error_hz: fine - truth,
        coarse_error_hz: coarse - truth,
        sigma_fine_hz,
        proposed: track(&spec, &code, fine, sigma_fine_hz, Q_PROPOSED, seed)?,
        traditional: track(&spec, &code, coarse, SIGMA0_COARSE_HZ, Q_TRADITIONAL, seed)?,
        // Equal (wide) Q from both starts: same accuracy, the fine start converges sooner.
        fine_wide: track(&spec, &code, fine, sigma_fine_hz, Q_TRADITIONAL, seed)?,
    })
}

impl Experiment {
    /// The table's rows.
    fn rows(&self) -> Vec<Row> {
        let (fine_error, coarse_error) = (self.fine_error_hz, self.coarse_error_hz);
        let sigma_fine_hz = self.sigma_fine_hz;
        let half_bin_hz = CHIP_RATE_HZ / (4.0 * M_CHIPS as f64);
        let (proposed, traditional) = (&self.proposed, &self.traditional);
        let mut rows = vec![
            Row::measured(
                TABLE,
                "initial Doppler error, fine (PMF-FFT eq. 3.3-14)",
                "estimate minus truth at the middle of the first ms; thesis: one realisation",
                "Hz",
                Some(THESIS_FINE_ERROR_HZ),
                fine_error,
                (
                    format!(
                        "abs <= 3 sigma = {:.2} Hz (R_f x MCRB)",
                        3.0 * sigma_fine_hz
                    ),
                    Verdict::from_ok(fine_error.abs() <= 3.0 * sigma_fine_hz),
                ),
            ),
            Row::measured(
                TABLE,
                "initial Doppler error, coarse (peak bin)",
                "estimate minus truth; thesis: one realisation",
                "Hz",
                Some(THESIS_COARSE_ERROR_HZ),
                coarse_error,
                (
                    format!("abs <= half a bin = {half_bin_hz:.1} Hz"),
                    Verdict::from_ok(coarse_error.abs() <= half_bin_hz),
                ),
            ),
        ];
        // Thesis tables 3.3-1 / 3.3-2: converged mean and std.
        let thesis = [
            ("proposed", proposed, THESIS_PROPOSED),
            ("traditional", traditional, THESIS_TRADITIONAL),
        ];
        for (name, run, t) in thesis {
            let (pm, ps) = run.phase();
            let (dm, ds) = run.doppler();
            let (pse, dse) = run.mean_errors();
            for (what, unit, th_mean, th_std, mean, std, se) in [
                ("phase", "rad", t[0], t[1], pm, ps, pse),
                ("Doppler", "Hz", t[2], t[3], dm, ds, dse),
            ] {
                rows.push(Row::measured(
                    TABLE,
                    format!("{name}: {what} error std"),
                    "converged error standard deviation (second half of 1 s)",
                    unit,
                    Some(th_std),
                    std,
                    (
                        "within a factor 1.6".into(),
                        Verdict::from_ok(std / th_std <= 1.6 && th_std / std <= 1.6),
                    ),
                ));
                rows.push(Row::measured(
                    TABLE,
                    format!("{name}: {what} error mean"),
                    "converged error mean",
                    unit,
                    Some(th_mean),
                    mean,
                    (
                        format!(
                            "abs <= {BIAS_STANDARD_ERRORS} standard errors = {:.4} (no bias)",
                            BIAS_STANDARD_ERRORS * se
                        ),
                        Verdict::from_ok(mean.abs() <= BIAS_STANDARD_ERRORS * se),
                    ),
                ));
            }
            let converged = run.convergence_s();
            rows.push(Row::measured(
                TABLE,
                format!("{name}: convergence time"),
                "20 ms RMS Doppler error below twice its converged std from then on",
                "s",
                None,
                converged.unwrap_or(f64::NAN),
                ("reported".into(), Verdict::from_ok(converged.is_some())),
            ));
        }
        let ratio_phase = proposed.phase().1 / traditional.phase().1;
        let ratio_doppler = proposed.doppler().1 / traditional.doppler().1;
        for (what, thesis, ratio, below) in [
            (
                "phase",
                THESIS_PROPOSED[1] / THESIS_TRADITIONAL[1],
                ratio_phase,
                0.7,
            ),
            (
                "Doppler",
                THESIS_PROPOSED[3] / THESIS_TRADITIONAL[3],
                ratio_doppler,
                0.3,
            ),
        ] {
            rows.push(Row::measured(
                TABLE,
                format!("proposed / traditional {what} std"),
                "std ratio",
                "-",
                Some(thesis),
                ratio,
                (format!("below {below}"), Verdict::from_ok(ratio < below)),
            ));
        }
        // Equal (wide) Q from both starts: same accuracy, the fine start converges sooner.
        let fine_wide = &self.fine_wide;
        let (t_fine, t_coarse) = (fine_wide.convergence_s(), traditional.convergence_s());
        let same = fine_wide.doppler().1 / traditional.doppler().1;
        rows.push(Row::measured(
            TABLE,
            "equal Q: Doppler std, fine start / coarse start",
            "std ratio with the traditional Q from both starts",
            "-",
            Some(1.0),
            same,
            (
                "within 1.25 (same accuracy)".into(),
                Verdict::from_ok((0.8..=1.25).contains(&same)),
            ),
        ));
        rows.push(Row::measured(
            TABLE,
            "equal Q: convergence time, fine start",
            "20 ms RMS Doppler error below twice its converged std from then on",
            "s",
            None,
            t_fine.unwrap_or(f64::NAN),
            (
                format!(
                    "before the coarse start ({:.3} s)",
                    t_coarse.unwrap_or(f64::NAN)
                ),
                Verdict::from_ok(matches!((t_fine, t_coarse), (Some(f), Some(c)) if f < c)),
            ),
        ));
        rows
    }

    /// The data of thesis figures 3.3-10 (same Q and R: the fine start against the coarse
    /// one, both with the wide Q) and 3.3-11 (different Q: the proposed synchroniser
    /// against the traditional one): for each, the phase errors (panels (a), (c)) and the
    /// Doppler errors (panels (b), (d)) against time.
    fn curves(&self) -> Vec<Curve> {
        let traditional = &self.traditional;
        let initial = [
            Value::new(
                "initial Doppler error, fine estimate",
                "Hz",
                self.fine_error_hz,
                Some(THESIS_FINE_ERROR_HZ),
            ),
            Value::new(
                "initial Doppler error, coarse estimate",
                "Hz",
                self.coarse_error_hz,
                Some(THESIS_COARSE_ERROR_HZ),
            ),
        ];
        let mut curves = Vec::new();
        for (figure, proposed, q, thesis) in [
            ("3.3-10", &self.fine_wide, "same Q and R", None),
            (
                "3.3-11",
                &self.proposed,
                "different Q",
                Some((THESIS_PROPOSED, THESIS_TRADITIONAL)),
            ),
        ] {
            let runs = [("proposed", proposed), ("traditional", traditional)];
            type Stats = fn(&Run) -> (f64, f64);
            for (panels, what, unit, table, stats, column) in [
                ("(a), (c)", "phase", "rad", "3.3-1", Run::phase as Stats, 0),
                (
                    "(b), (d)",
                    "Doppler",
                    "Hz",
                    "3.3-2",
                    Run::doppler as Stats,
                    1,
                ),
            ] {
                let mut values = Vec::new();
                for (k, (name, run)) in runs.iter().enumerate() {
                    let (mean, std) = stats(run);
                    // Tables 3.3-1/3.3-2: (mean, std) of the phase, then of the Doppler.
                    let printed = thesis.map(|t| [t.0, t.1][k]);
                    for (stat, ours, i) in
                        [("mean", mean, 2 * column), ("std", std, 2 * column + 1)]
                    {
                        let source =
                            printed.map_or(String::new(), |_| format!(" (thesis table {table})"));
                        values.push(Value::new(
                            format!("{name}: converged {what} error {stat}{source}"),
                            unit,
                            ours,
                            printed.map(|t| t[i]),
                        ));
                    }
                }
                if column == 1 {
                    values.extend(initial.iter().cloned());
                    for (name, run) in runs {
                        values.push(Value::new(
                            format!("{name}: convergence time"),
                            "s",
                            run.convergence_s().unwrap_or(f64::NAN),
                            None,
                        ));
                    }
                }
                curves.push(Curve {
                    figure: figure.into(),
                    panels: panels.into(),
                    title: format!("{what} error against time, {q}"),
                    x_label: "time (s)".into(),
                    y_label: format!("{what} error ({unit})"),
                    series: runs
                        .iter()
                        .map(|(name, run)| {
                            CurveSeries::new(
                                format!("{name} synchroniser"),
                                Mark::Line,
                                run.along(column),
                            )
                        })
                        .collect(),
                    references: Vec::new(),
                    values,
                });
            }
        }
        curves
    }
}

/// The table's rows on the signal of `draw`'s seed.
pub fn rows(draw: crate::draw::Draw) -> Result<Vec<Row>, ValidateError> {
    Ok(experiment(draw)?.rows())
}

/// The data of thesis figures 3.3-10 and 3.3-11 on the registered seed.
pub fn curves() -> Result<Vec<Curve>, ValidateError> {
    Ok(experiment(Draw::REGISTERED)?.curves())
}

/// The rows and the figures' data on the registered seed, from one experiment.
pub fn rows_and_curves() -> Result<(Vec<Row>, Vec<Curve>), ValidateError> {
    let e = experiment(Draw::REGISTERED)?;
    Ok((e.rows(), e.curves()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn figures_draw_every_millisecond_of_the_runs_of_the_rows() {
        let e = experiment(Draw::REGISTERED).unwrap();
        let (rows, curves) = (e.rows(), e.curves());
        let ids: Vec<String> = curves.iter().map(Curve::number).collect();
        assert_eq!(
            ids,
            [
                "3.3-10 (a), (c)",
                "3.3-10 (b), (d)",
                "3.3-11 (a), (c)",
                "3.3-11 (b), (d)"
            ]
        );
        // Figure 3.3-10: the fine and the coarse start with the same Q; 3.3-11: the
        // proposed synchroniser (narrow Q) and the traditional one.
        for (k, c) in curves.iter().enumerate() {
            let column = k % 2;
            let proposed = if k < 2 { &e.fine_wide } else { &e.proposed };
            for (s, run) in c.series.iter().zip([proposed, &e.traditional]) {
                assert_eq!(s.points.len(), run.errors.len());
                assert_eq!(s.points.len(), (DURATION_S / T_S) as usize - 1);
                assert_eq!(s.points, run.along(column));
                assert!(s.points.windows(2).all(|w| w[1].0 > w[0].0));
            }
            let (at, expected) = (c.series[0].points[0].0, 1.5 * T_S);
            assert!((at - expected).abs() < 1e-12, "{at}");
        }
        // Tables 3.3-1/3.3-2 beside the rows' values, for figure 3.3-11 only.
        let value = |c: &Curve, what: &str| {
            c.values
                .iter()
                .find(|v| v.what.starts_with(what))
                .cloned()
                .unwrap()
        };
        let row = |name: &str| rows.iter().find(|r| r.row == name).unwrap();
        for (c, what, thesis) in [
            (
                &curves[2],
                "proposed: converged phase error std",
                THESIS_PROPOSED[1],
            ),
            (
                &curves[2],
                "traditional: converged phase error mean",
                THESIS_TRADITIONAL[0],
            ),
            (
                &curves[3],
                "proposed: converged Doppler error std",
                THESIS_PROPOSED[3],
            ),
            (
                &curves[3],
                "traditional: converged Doppler error std",
                THESIS_TRADITIONAL[3],
            ),
        ] {
            let v = value(c, what);
            assert_eq!(v.thesis, Some(thesis), "{what}");
            let name = what.replace("converged ", "");
            assert_eq!(v.ours, row(&name).ours, "{what}");
        }
        assert!(curves[..2].iter().all(|c| {
            c.values
                .iter()
                .filter(|v| v.what.contains("converged"))
                .all(|v| v.thesis.is_none())
        }));
        let fine = value(&curves[1], "initial Doppler error, fine");
        assert_eq!(fine.thesis, Some(THESIS_FINE_ERROR_HZ));
        assert_eq!(
            fine.ours,
            row("initial Doppler error, fine (PMF-FFT eq. 3.3-14)").ours
        );
    }

    /// With (almost) no noise the experiment's plumbing -- signal, NCO conventions, prompt
    /// normalisation, UKF -- must track the thesis dynamics to a few milliradians.
    #[test]
    fn noiseless_signal_is_tracked_to_milliradians() {
        let spec = SignalSpec {
            sample_rate_hz: 12.0 * CHIP_RATE_HZ,
            if_hz: IF_HZ,
            chip_rate_hz: CHIP_RATE_HZ,
            doppler: DOPPLER,
            phase_rad: 0.7,
            cn0_dbhz: 90.0,
            symbol_s: 1e-3,
        };
        let code: Vec<i8> = gps_ca(PRN).map(|c| c.to_vec()).unwrap_or_default();
        // Start 40 Hz off with the wide Q.
        let run = track(
            &spec,
            &code,
            spec.doppler_hz(0.5e-3) + 40.0,
            50.0,
            Q_TRADITIONAL,
            SEED,
        )
        .unwrap();
        let (pm, ps) = run.phase();
        let (dm, ds) = run.doppler();
        assert!(pm.abs() < 0.01 && ps < 0.01, "phase {pm} +/- {ps} rad");
        assert!(dm.abs() < 0.5 && ds < 0.5, "Doppler {dm} +/- {ds} Hz");
    }
}
