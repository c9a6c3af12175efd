//! T-3.3-R: the PMF-FFT fine Doppler estimator of thesis sections 3.3.2/3.3.3
//! (figures 3.3-5..3.3-9): the theoretical variance ratio `R_f` (eq. 3.3-55), a Monte
//! Carlo run of the receiver's own PMF-FFT on the chip-rate model of eq. 3.3-15, the
//! expectation of `fd Tc` against eq. 3.3-45 and the NMSE against the MCRB (eq. 3.3-75).
//! The same Monte Carlo gives the data of figures 3.3-7, 3.3-8 and 3.3-9 ([`curves`]).

use super::ValidateError;
use super::curves::{Curve, CurveSeries, Mark, Reference, Value};
use crate::draw::Draw;
use crate::report::{Row, Verdict};
use rayon::prelude::*;
use skyforge_receiver::acquisition::AcquisitionError;
use skyforge_receiver::acquisition::Complex32;
use skyforge_receiver::acquisition::pmf_fft::{PmfEstimate, PmfFft, PmfScratch, theory};
use skyforge_receiver::acquisition::wipe_carrier;
use skyforge_signals::synth::ThermalNoise;
use std::time::Instant;

/// Table identifier.
pub const TABLE: &str = "T-3.3-R";
/// Chips per PMF-FFT: thesis M = 1024.
const M: usize = 1024;
/// PMF lengths of figure 3.3-8; the printed values are for the first.
const L_CURVES: [usize; 4] = [64, 128, 256, 512];
/// Monte Carlo trials per point: thesis U = 1e5.
pub const TRIALS: usize = 100_000;
/// SNR of x'[n], Es/N0 = 1/sigma_z^2: thesis 0 dB.
const SNR: f64 = 1.0;
/// assumed: the thesis gives no seed; any fixed seed (results are reproducible).
const SEED: u64 = 2018;
/// Trials per parallel work item (one noise source each).
const CHUNK: usize = 1000;

/// assumed: the thesis does not list its delta grid; figures 3.3-5/3.3-8 span
/// delta in [-0.5, 0.5], sampled here every 0.1 (11 points).
fn delta_grid() -> Vec<f64> {
    (-5..=5).map(|i| f64::from(i) / 10.0).collect()
}

/// assumed: figure 3.3-9 spans |fd Tc| <= 1/(2L); sampled here at 21 points
/// i / (20 L), i = -10..=10, which include both ends and 0 and, for L = 64, offsets
/// delta of 0, +/-0.2 and +/-0.4 bins.
fn nmse_grid(l: usize) -> Vec<f64> {
    (-10..=10)
        .map(|i| f64::from(i) / (20.0 * l as f64))
        .collect()
}

/// Statistics of `fd_hat Tc` over the trials at one true `fd Tc`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct McPoint {
    pub fd_tc: f64,
    /// Mean of the estimate.
    pub mean_fd_tc: f64,
    /// Variance of the estimate about its mean: `D(fd_hat) Tc^2`.
    pub variance: f64,
    /// Mean square error about the truth: NMSE of eq. 3.3-74.
    pub mse: f64,
}

#[derive(Debug, Clone, Copy, Default)]
struct Sums {
    n: f64,
    e: f64,
    e2: f64,
}

/// `trials` runs of the receiver's PMF-FFT estimator on
/// `x'[n] = exp(j(2 pi fd Tc n + phi_t)) + z[n]`, `n < M` (eq. 3.3-15), at SNR 0 dB.
///
/// The noise is drawn where it enters the FFT: filter `i` outputs
/// `(1/M) sum_{n=iL}^{(i+1)L-1} (s[n] + z[n])`, and a sum of `L` independent complex
/// Gaussians of per-component variance `sigma^2` is exactly complex Gaussian of variance
/// `L sigma^2`, so drawing `(sqrt(L) sigma / M)`-deviates per filter gives the same
/// statistics as drawing `M` chip deviates, `L` times cheaper (the unit test
/// `filter_level_noise_matches_chip_level_noise` compares the two). The signal part is
/// the receiver's own filter outputs of the noiseless tone. Noise: the synthesiser's
/// seeded ChaCha8 thermal noise, stream `stream`, `P` samples per trial.
/// Errors are wrapped into the estimator's unambiguous range `|fd Tc| <= 1/(2L)` (the
/// PMF output rate 1/(L Tc) aliases beyond it).
/// assumed: phi_t = 2 pi frac(0.618.. t); the estimator uses |Y|^2 only and the noise is
/// circular, so the phase does not change the statistics.
pub fn monte_carlo(
    l: usize,
    fd_tc: f64,
    trials: usize,
    stream: u32,
    seed: u64,
) -> Result<McPoint, ValidateError> {
    let pmf = PmfFft::new(M, l)?;
    let sigma_chip = (0.5 / SNR).sqrt();
    let sigma = (sigma_chip * (l as f64).sqrt() / M as f64) as f32;
    let signal = filter_outputs_of_tone(&pmf, fd_tc)?;
    let noise = NoiseStream {
        seed,
        stream,
        sigma,
    };
    trial_errors(
        &pmf,
        &signal,
        noise,
        trials,
        fd_tc,
        PmfFft::estimate_filters,
    )
}

/// Where a Monte Carlo's noise comes from: the synthesiser's seeded thermal noise.
#[derive(Debug, Clone, Copy)]
struct NoiseStream {
    seed: u64,
    stream: u32,
    /// Per-component standard deviation.
    sigma: f32,
}

/// `trials` noisy trials of `clean` (see [`NoisyTrials`]) through `estimate`, the wrapped
/// errors of its fine Doppler against `fd_tc` summed in chunks on every core.
fn trial_errors(
    pmf: &PmfFft,
    clean: &[Complex32],
    noise: NoiseStream,
    trials: usize,
    fd_tc: f64,
    estimate: impl Fn(&PmfFft, &[Complex32], &mut PmfScratch) -> Result<PmfEstimate, AcquisitionError>
    + Sync,
) -> Result<McPoint, ValidateError> {
    let sums = chunked(trials, |range| {
        let mut scratch = pmf.scratch();
        let mut inputs = NoisyTrials::new(clean, noise);
        let mut s = Sums::default();
        for t in range {
            let est = estimate(pmf, inputs.trial(t), &mut scratch)?;
            s.push(est.fine_fd_tc, fd_tc, pmf.l());
        }
        Ok(s)
    })?;
    Ok(sums.point(fd_tc))
}

/// Trial `t`'s input: the clean samples turned by the trial's phase, plus the seeded
/// thermal noise of the trial's slot (`t * len` onwards) of the noise stream.
struct NoisyTrials<'a> {
    clean: &'a [Complex32],
    noise: ThermalNoise,
    re: Vec<f32>,
    im: Vec<f32>,
    out: Vec<Complex32>,
}

impl<'a> NoisyTrials<'a> {
    fn new(clean: &'a [Complex32], noise: NoiseStream) -> Self {
        let n = clean.len();
        Self {
            clean,
            noise: ThermalNoise::new(noise.seed, noise.stream, noise.sigma),
            re: vec![0.0; n],
            im: vec![0.0; n],
            out: vec![Complex32::default(); n],
        }
    }

    fn trial(&mut self, t: usize) -> &[Complex32] {
        let rot = phase(t);
        for ((r, i), &v) in self.re.iter_mut().zip(&mut self.im).zip(self.clean) {
            let v = v * rot;
            (*r, *i) = (v.re, v.im);
        }
        let n = self.clean.len();
        self.noise.add((t * n) as u64, &mut self.re, &mut self.im);
        for ((o, &r), &i) in self.out.iter_mut().zip(&self.re).zip(&self.im) {
            *o = Complex32::new(r, i);
        }
        &self.out
    }
}

/// The noiseless tone `exp(j 2 pi fd Tc n)`, `n < M`, made by the receiver's NCO.
fn tone(fd_tc: f64) -> Vec<Complex32> {
    let ones = vec![Complex32::new(1.0, 0.0); M];
    let mut tone = vec![Complex32::default(); M];
    wipe_carrier(&ones, 0, 1.0, -fd_tc, &mut tone);
    tone
}

fn filter_outputs_of_tone(pmf: &PmfFft, fd_tc: f64) -> Result<Vec<Complex32>, ValidateError> {
    let mut out = vec![Complex32::default(); pmf.p()];
    pmf.filter_outputs(&tone(fd_tc), &mut out)?;
    Ok(out)
}

/// The carrier phase of trial `t`.
fn phase(t: usize) -> Complex32 {
    let golden = 0.5 * (5f64.sqrt() - 1.0);
    let phi = std::f64::consts::TAU * (golden * t as f64).fract();
    Complex32::new(phi.cos() as f32, phi.sin() as f32)
}

/// Run `work` over `0..trials` in parallel chunks and add up their sums.
fn chunked(
    trials: usize,
    work: impl Fn(std::ops::Range<usize>) -> Result<Sums, ValidateError> + Sync,
) -> Result<Sums, ValidateError> {
    // Collected in chunk order and summed in that order: the same bits whatever the
    // threads did (a parallel reduction groups the additions as the work was split).
    let parts: Vec<Sums> = (0..trials.div_ceil(CHUNK))
        .into_par_iter()
        .map(|c| work(c * CHUNK..((c + 1) * CHUNK).min(trials)))
        .collect::<Result<_, _>>()?;
    Ok(parts.into_iter().fold(Sums::default(), |a, b| Sums {
        n: a.n + b.n,
        e: a.e + b.e,
        e2: a.e2 + b.e2,
    }))
}

impl Sums {
    /// Add one estimate's error, wrapped into the unambiguous range 1/L.
    fn push(&mut self, estimate: f64, truth: f64, l: usize) {
        let range = 1.0 / l as f64;
        let err = estimate - truth;
        let err = err - (err / range).round() * range;
        self.n += 1.0;
        self.e += err;
        self.e2 += err * err;
    }

    fn point(&self, fd_tc: f64) -> McPoint {
        let n = self.n.max(1.0);
        let mean_err = self.e / n;
        McPoint {
            fd_tc,
            mean_fd_tc: fd_tc + mean_err,
            variance: self.e2 / n - mean_err * mean_err,
            mse: self.e2 / n,
        }
    }
}

/// The thesis's values: R_f of eq. 3.3-55 at |delta| = 0 and 0.5 (M = 1024, L = 64).
const THESIS_RF_THEORY: [(f64, f64); 2] = [(0.0, 1.0147), (0.5, 1.4444)];
/// The thesis's largest Monte Carlo R_f over delta, L = 64 (figure 3.3-8 (a)).
const THESIS_RF_MAX: f64 = 1.0902;
/// The thesis's order of magnitude of the largest NMSE (figure 3.3-9).
const THESIS_NMSE_ORDER: f64 = 1e-9;
/// Steps of the theory curves drawn beside the Monte Carlo of figures 3.3-7/3.3-8: delta
/// every 1/100 bin.
const DELTA_STEPS: usize = 100;
/// Steps per FFT bin of the theory curve of figure 3.3-9: it repeats its scallop in every
/// bin (R_f and the bias depend on the offset delta within the bin), so it is drawn at
/// 20 points a bin to be seen at all.
const NMSE_STEPS_PER_BIN: usize = 20;

/// The Monte Carlo of figures 3.3-7..3.3-9 on one seed, which both the rows and the
/// figures' data are made of.
struct Points {
    /// delta of figures 3.3-7/3.3-8 ([`delta_grid`]).
    deltas: Vec<f64>,
    /// For each L of [`L_CURVES`], the point at each delta (p = 0, `fd Tc = delta / 2M`).
    by_l: Vec<Vec<McPoint>>,
    /// L = 64 at each `fd Tc` of [`nmse_grid`] (figure 3.3-9).
    nmse: Vec<McPoint>,
    /// Eq. 3.3-75.
    mcrb: f64,
    trials: usize,
    seconds: f64,
}

/// [`monte_carlo`] at every point of figures 3.3-7..3.3-9, `trials` each, on `draw`'s seed.
fn points(draw: Draw, trials: usize) -> Result<Points, ValidateError> {
    let seed = draw.seed(SEED);
    let started = Instant::now();
    let two_m = 2.0 * M as f64;
    let deltas = delta_grid();
    let mut by_l = Vec::new();
    for (li, &l) in L_CURVES.iter().enumerate() {
        let mut points = Vec::new();
        for (di, &delta) in deltas.iter().enumerate() {
            let stream = (100 * li + di) as u32;
            points.push(monte_carlo(l, delta / two_m, trials, stream, seed)?);
        }
        by_l.push(points);
    }
    let nmse = nmse_grid(L_CURVES[0])
        .iter()
        .enumerate()
        .map(|(i, &f)| monte_carlo(L_CURVES[0], f, trials, (1000 + i) as u32, seed))
        .collect::<Result<_, _>>()?;
    Ok(Points {
        deltas,
        by_l,
        nmse,
        mcrb: theory::mcrb_fd_tc(M, SNR),
        trials,
        seconds: started.elapsed().as_secs_f64(),
    })
}

/// The (x, y) with the largest y.
fn largest(points: impl Iterator<Item = (f64, f64)>) -> (f64, f64) {
    points.fold(
        (0.0, f64::NEG_INFINITY),
        |b, x| if x.1 > b.1 { x } else { b },
    )
}

/// `f` at `steps` + 1 evenly spaced points from `-half` to `half`.
fn theory_curve(half: f64, steps: usize, f: impl Fn(f64) -> f64) -> Vec<(f64, f64)> {
    (0..=steps)
        .map(|i| {
            let x = half * (2.0 * i as f64 / steps as f64 - 1.0);
            (x, f(x))
        })
        .collect()
}

impl Points {
    /// (delta, R_f) of the Monte Carlo for the `li`-th L.
    fn rf(&self, li: usize) -> impl Iterator<Item = (f64, f64)> + '_ {
        self.deltas
            .iter()
            .zip(&self.by_l[li])
            .map(|(&d, p)| (d, p.variance / self.mcrb))
    }

    /// (delta, largest R_f over delta), L = 64.
    fn max_rf(&self) -> (f64, f64) {
        largest(self.rf(0))
    }

    /// (delta, largest |E[fd_hat Tc] - eq. 3.3-45| in bins), L = 64.
    fn worst_expectation(&self) -> (f64, f64) {
        let two_m = 2.0 * M as f64;
        largest(
            self.deltas
                .iter()
                .zip(&self.by_l[0])
                .map(|(&d, p)| (d, (p.mean_fd_tc * two_m - theory::expected_delta(d)).abs())),
        )
    }

    /// The points of largest and smallest NMSE (figure 3.3-9).
    fn nmse_extremes(&self) -> (McPoint, McPoint) {
        let by = |better: fn(f64, f64) -> bool| {
            self.nmse.iter().fold(
                self.nmse[0],
                |b, p| if better(p.mse, b.mse) { *p } else { b },
            )
        };
        (by(|a, b| a > b), by(|a, b| a < b))
    }

    /// Every row of T-3.3-R.
    fn rows(&self) -> Vec<Row> {
        let mut rows = Vec::new();
        let two_m = 2.0 * M as f64;
        let (deltas, mcrb, trials) = (&self.deltas, self.mcrb, self.trials);

        // Theoretical R_f at the printed points (eq. 3.3-55, p = 0).
        for (delta, thesis) in THESIS_RF_THEORY {
            let ours = theory::rf_ratio(M, 64, 0, delta);
            rows.push(
                Row::measured(
                    TABLE,
                    format!("theoretical R_f |delta|={delta} M=1024 L=64"),
                    "variance ratio to the MCRB (eq. 3.3-55)",
                    "-",
                    Some(thesis),
                    ours,
                    (
                        "+/-1e-3".into(),
                        Verdict::from_ok((ours - thesis).abs() <= 1e-3),
                    ),
                )
                .with_note(format!("{:.4} dB", 10.0 * ours.log10())),
            );
        }

        // Max R_f over delta, L = 64 (figure 3.3-8).
        let (at, max_rf) = self.max_rf();
        rows.push(
            Row::measured(
                TABLE,
                "Monte Carlo max R_f over delta L=64 SNR 0 dB",
                "variance ratio to the MCRB",
                "-",
                Some(THESIS_RF_MAX),
                max_rf,
                (
                    "+/-10 %".into(),
                    Verdict::from_ok((max_rf / THESIS_RF_MAX - 1.0).abs() <= 0.1),
                ),
            )
            .with_note(format!(
                "at delta = {at}; eq. 3.3-55 gives {:.4} there; {trials} trials per delta",
                theory::rf_ratio(M, 64, 0, at)
            )),
        );

        // E[fd Tc] versus delta against eq. 3.3-45 (figure 3.3-7), L = 64.
        let (worst_delta, worst_dev) = self.worst_expectation();
        rows.push(
            Row::measured(
                TABLE,
                "E[fd Tc] max deviation from eq. 3.3-45 L=64",
                "mean estimate minus eq. 3.3-45 (in FFT bins 1/(2M))",
                "bin",
                None,
                worst_dev,
                ("< 0.05 bin".into(), Verdict::from_ok(worst_dev < 0.05)),
            )
            .with_note(format!(
                "largest at delta = {worst_delta}; the thesis prints the curve only"
            )),
        );

        // R_f(delta) curves against the theory drawn beside them in figure 3.3-8.
        for (li, &l) in L_CURVES.iter().enumerate() {
            for (p, &delta) in self.by_l[li].iter().zip(deltas) {
                let mc = p.variance / mcrb;
                let th = theory::rf_ratio(M, l, 0, delta);
                let mut note = format!("bias {:.2e} bin", p.mean_fd_tc * two_m - delta);
                if l >= 256 {
                    note.push_str(
                        "; thesis: for L = 256, 512 the estimate degrades markedly as |delta| nears 0.5",
                    );
                }
                let check = (
                    "not above eq. 3.3-55 by more than 10 % (thesis: MC may beat the approximate theory)".into(),
                    Verdict::from_ok(mc <= 1.1 * th),
                );
                let row = Row::measured(
                    TABLE,
                    format!("R_f(delta={delta:+.1}) L={l} Monte Carlo"),
                    "variance ratio to the MCRB; thesis column = eq. 3.3-55 curve of figure 3.3-8",
                    "-",
                    Some(th),
                    mc,
                    check,
                );
                rows.push(row.with_note(note));
            }
        }

        // NMSE versus fd Tc (figure 3.3-9), L = 64.
        let l = L_CURVES[0];
        let (max, min) = self.nmse_extremes();
        let edge = 1.0 / (2.0 * l as f64);
        let max_db = 10.0 * (max.mse / mcrb).log10();
        let theory_at_max = theory::nmse_fd_tc(M, l, max.fd_tc, SNR);
        let at_edge = (max.fd_tc.abs() - edge).abs() < 1e-12;
        let verdict = if max_db <= 3.0 && at_edge {
            Verdict::Reproduced
        } else if (max.mse / theory_at_max - 1.0).abs() <= 0.1 {
            Verdict::Explained
        } else {
            Verdict::Deviates
        };
        let row = Row::measured(
            TABLE,
            "NMSE max over fd Tc / MCRB L=64",
            "NMSE (eq. 3.3-74) over the MCRB (eq. 3.3-75)",
            "dB",
            None,
            max_db,
            ("<= 3 dB".into(), verdict),
        );
        rows.push(row.with_note(format!(
            "at fd Tc = {:.6}; eq. 3.3-53 with the PMF amplitude lambda0 (eq. 3.3-21) predicts {:.2} dB there: the PMF's sinc loses (2/pi)^2 = -3.9 dB of line SNR at |fd Tc| = 1/(2L), which the flat MCRB omits (receiver test theory::tests::mcrb_and_nmse_scale_as_the_formulas_say)",
            max.fd_tc,
            10.0 * (theory_at_max / mcrb).log10()
        )));
        rows.push(Row::measured(
            TABLE,
            "|fd Tc| of the NMSE maximum L=64",
            "NMSE curve shape (figure 3.3-9)",
            "-",
            Some(edge),
            max.fd_tc.abs(),
            ("at the range end 1/(2L)".into(), Verdict::from_ok(at_edge)),
        ));
        rows.push(
            Row::measured(
                TABLE,
                "|fd Tc| of the NMSE minimum L=64",
                "NMSE curve shape (figure 3.3-9)",
                "-",
                Some(0.0),
                min.fd_tc.abs(),
                (
                    "the grid point at 0".into(),
                    Verdict::from_ok(min.fd_tc.abs() < 1e-12),
                ),
            )
            .with_note(format!("minimum NMSE / MCRB {:.4}", min.mse / mcrb)),
        );
        let same_order = (max.mse.log10().round() - THESIS_NMSE_ORDER.log10()).abs() < 0.5;
        rows.push(
            Row::measured(
                TABLE,
                "NMSE maximum L=64",
                "NMSE of fd Tc (eq. 3.3-74)",
                "-",
                Some(THESIS_NMSE_ORDER),
                max.mse,
                (
                    "same order of magnitude (thesis: 'order 1e-9')".into(),
                    Verdict::from_ok(same_order),
                ),
            )
            .with_note(format!(
                "MCRB {mcrb:.4e}; Monte Carlo of {} + {} points x {trials} trials took {:.1} s",
                L_CURVES.len() * deltas.len(),
                self.nmse.len(),
                self.seconds
            )),
        );
        rows
    }

    /// The data of figures 3.3-7 (E[fd_hat Tc] against delta), 3.3-8 (a)..(d) (R_f
    /// against delta for each L) and 3.3-9 (NMSE against fd Tc).
    fn curves(&self) -> Vec<Curve> {
        let two_m = 2.0 * M as f64;
        let setting = format!("M = {M}, SNR {:.0} dB", 10.0 * SNR.log10());
        let mut curves = Vec::new();

        let (_, worst_dev) = self.worst_expectation();
        curves.push(Curve {
            figure: "3.3-7".into(),
            panels: String::new(),
            title: format!("E[fd_hat Tc] against delta, L = {}, {setting}", L_CURVES[0]),
            x_label: "delta (FFT bins of 1/(2 M Tc))".into(),
            y_label: "E[fd_hat Tc]".into(),
            series: vec![
                CurveSeries::new(
                    "ideal, delta / 2M",
                    Mark::Line,
                    theory_curve(0.5, DELTA_STEPS, |d| d / two_m),
                ),
                CurveSeries::new(
                    "Monte Carlo",
                    Mark::Dots,
                    self.deltas
                        .iter()
                        .zip(&self.by_l[0])
                        .map(|(&d, p)| (d, p.mean_fd_tc))
                        .collect(),
                ),
                CurveSeries::new(
                    "eq. 3.3-45",
                    Mark::Companion,
                    theory_curve(0.5, DELTA_STEPS, |d| theory::expected_delta(d) / two_m),
                ),
            ],
            references: Vec::new(),
            values: vec![Value::new(
                "largest |E[fd_hat Tc] - eq. 3.3-45| over delta",
                "bin",
                worst_dev,
                None,
            )],
        });

        for (li, &l) in L_CURVES.iter().enumerate() {
            let (_, max_rf) = largest(self.rf(li));
            let mut values = vec![Value::new(
                "largest Monte Carlo R_f over delta",
                "-",
                max_rf,
                (li == 0).then_some(THESIS_RF_MAX),
            )];
            let mut references = Vec::new();
            if li == 0 {
                values.extend(THESIS_RF_THEORY.map(|(delta, thesis)| {
                    Value::new(
                        format!("eq. 3.3-55 at |delta| = {delta}"),
                        "-",
                        theory::rf_ratio(M, l, 0, delta),
                        Some(thesis),
                    )
                }));
                references.push(Reference {
                    label: "thesis: largest Monte Carlo R_f".into(),
                    value: THESIS_RF_MAX,
                });
            }
            curves.push(Curve {
                figure: "3.3-8".into(),
                panels: format!("({})", ['a', 'b', 'c', 'd'][li]),
                title: format!("R_f against delta, L = {l}, {setting}"),
                x_label: "delta (FFT bins of 1/(2 M Tc))".into(),
                y_label: "R_f = D(fd_hat Tc) / MCRB".into(),
                series: vec![
                    CurveSeries::new("Monte Carlo", Mark::Dots, self.rf(li).collect()),
                    CurveSeries::new(
                        "eq. 3.3-55",
                        Mark::Companion,
                        theory_curve(0.5, DELTA_STEPS, |d| theory::rf_ratio(M, l, 0, d)),
                    ),
                ],
                references,
                values,
            });
        }

        let l = L_CURVES[0];
        let (max, _) = self.nmse_extremes();
        let edge = 1.0 / (2.0 * l as f64);
        curves.push(Curve {
            figure: "3.3-9".into(),
            panels: String::new(),
            title: format!("NMSE of fd_hat Tc against fd Tc, L = {l}, {setting}"),
            x_label: "fd Tc".into(),
            y_label: "NMSE (eq. 3.3-74)".into(),
            series: vec![
                CurveSeries::new(
                    "Monte Carlo",
                    Mark::Dots,
                    self.nmse.iter().map(|p| (p.fd_tc, p.mse)).collect(),
                ),
                CurveSeries::new(
                    "eq. 3.3-53 variance + eq. 3.3-45 bias^2",
                    Mark::Companion,
                    theory_curve(edge, NMSE_STEPS_PER_BIN * 2 * M / l, |f| {
                        theory::nmse_fd_tc(M, l, f, SNR)
                    }),
                ),
            ],
            references: vec![Reference {
                label: "MCRB (eq. 3.3-75)".into(),
                value: self.mcrb,
            }],
            values: vec![
                Value::new(
                    "largest NMSE (thesis: its order)",
                    "-",
                    max.mse,
                    Some(THESIS_NMSE_ORDER),
                ),
                Value::new(
                    "|fd Tc| of the largest NMSE (thesis: 1/(2L))",
                    "-",
                    max.fd_tc.abs(),
                    Some(edge),
                ),
                Value::new(
                    "largest NMSE over the MCRB",
                    "dB",
                    10.0 * (max.mse / self.mcrb).log10(),
                    None,
                ),
            ],
        });
        curves
    }
}

/// Every row of T-3.3-R.
pub fn rows(draw: crate::draw::Draw) -> Result<Vec<Row>, ValidateError> {
    Ok(points(draw, TRIALS)?.rows())
}

/// The data of thesis figures 3.3-7..3.3-9 on the registered seed.
pub fn curves() -> Result<Vec<Curve>, ValidateError> {
    Ok(points(Draw::REGISTERED, TRIALS)?.curves())
}

/// The rows and the figures' data on the registered seed, from one Monte Carlo.
pub fn rows_and_curves() -> Result<(Vec<Row>, Vec<Curve>), ValidateError> {
    let p = points(Draw::REGISTERED, TRIALS)?;
    Ok((p.rows(), p.curves()))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The chip-level twin of [`monte_carlo`]: `M` noise deviates per trial, the
    /// receiver's full PMF-FFT on the chips.
    fn monte_carlo_chips(l: usize, fd_tc: f64, trials: usize, stream: u32) -> McPoint {
        let pmf = PmfFft::new(M, l).unwrap();
        let tone = tone(fd_tc);
        let sigma = (0.5 / SNR).sqrt() as f32;
        let noise = NoiseStream {
            seed: SEED,
            stream,
            sigma,
        };
        trial_errors(&pmf, &tone, noise, trials, fd_tc, PmfFft::estimate).unwrap()
    }

    #[test]
    fn the_monte_carlo_gives_the_same_bits_every_time() {
        let first = monte_carlo(64, 0.1, 40_000, 7, SEED).unwrap();
        for _ in 0..3 {
            let again = monte_carlo(64, 0.1, 40_000, 7, SEED).unwrap();
            assert_eq!(
                (
                    again.mean_fd_tc.to_bits(),
                    again.variance.to_bits(),
                    again.mse.to_bits()
                ),
                (
                    first.mean_fd_tc.to_bits(),
                    first.variance.to_bits(),
                    first.mse.to_bits()
                )
            );
        }
    }

    #[test]
    fn filter_level_noise_matches_chip_level_noise() {
        // 20000 trials each, independent streams: a variance estimate has a standard
        // error of sqrt(2/20000) = 1 %, so the two agree within 5 %; both near eq.
        // 3.3-55 at delta = 0.3.
        let fd_tc = 0.3 / (2.0 * M as f64);
        let mcrb = theory::mcrb_fd_tc(M, SNR);
        let filters = monte_carlo(64, fd_tc, 20_000, 9000, SEED).unwrap();
        let chips = monte_carlo_chips(64, fd_tc, 20_000, 9001);
        let (rf_f, rf_c) = (filters.variance / mcrb, chips.variance / mcrb);
        assert!(
            (rf_f / rf_c - 1.0).abs() < 0.05,
            "filters {rf_f} chips {rf_c}"
        );
        assert!((filters.mean_fd_tc - chips.mean_fd_tc).abs() * 2.0 * (M as f64) < 0.005);
        let th = theory::rf_ratio(M, 64, 0, 0.3);
        assert!(rf_c < 1.1 * th && rf_c > 0.8, "chips {rf_c} theory {th}");
    }

    #[test]
    fn figures_hold_the_points_of_the_rows_and_the_theory_at_the_same_x() {
        // 200 trials a point: the figures' structure, not their statistics.
        let p = points(Draw::REGISTERED, 200).unwrap();
        let (rows, curves) = (p.rows(), p.curves());
        let ids: Vec<String> = curves
            .iter()
            .map(|c| format!("{} {}", c.figure, c.panels))
            .collect();
        assert_eq!(
            ids,
            [
                "3.3-7 ",
                "3.3-8 (a)",
                "3.3-8 (b)",
                "3.3-8 (c)",
                "3.3-8 (d)",
                "3.3-9 "
            ]
        );
        let two_m = 2.0 * M as f64;

        // Figure 3.3-7: the Monte Carlo means, eq. 3.3-45 and the ideal line.
        let [ideal, mc, eq45] = &curves[0].series[..] else {
            panic!("three series")
        };
        assert_eq!(mc.points.len(), p.deltas.len());
        for ((x, y), q) in mc.points.iter().zip(&p.by_l[0]) {
            assert_eq!((*x, *y), (q.fd_tc * two_m, q.mean_fd_tc));
        }
        assert_eq!(eq45.points.len(), DELTA_STEPS + 1);
        for &(d, y) in &eq45.points {
            assert_eq!(y, theory::expected_delta(d) / two_m);
        }
        assert!(ideal.points.iter().all(|&(d, y)| y == d / two_m));

        // Figure 3.3-8: per L, R_f of the Monte Carlo and eq. 3.3-55 at the same delta.
        for (li, &l) in L_CURVES.iter().enumerate() {
            let c = &curves[1 + li];
            assert!(c.title.contains(&format!("L = {l},")), "{}", c.title);
            let [mc, eq55] = &c.series[..] else {
                panic!("two series")
            };
            for ((&d, q), &(x, y)) in p.deltas.iter().zip(&p.by_l[li]).zip(&mc.points) {
                assert_eq!((x, y), (d, q.variance / p.mcrb));
            }
            let row = |d: f64| {
                rows.iter()
                    .find(|r| r.row == format!("R_f(delta={d:+.1}) L={l} Monte Carlo"))
                    .unwrap()
            };
            assert!(mc.points.iter().all(|&(d, y)| row(d).ours == Some(y)));
            assert_eq!(eq55.mark, Mark::Companion);
            for &(d, y) in &eq55.points {
                assert_eq!(y, theory::rf_ratio(M, l, 0, d));
            }
            assert_eq!(eq55.points.first().map(|p| p.0), Some(-0.5));
            assert_eq!(eq55.points.last().map(|p| p.0), Some(0.5));
        }
        // The printed values beside SkyForge's, the largest R_f that of the row.
        let a = &curves[1].values;
        assert_eq!(a[0].thesis, Some(THESIS_RF_MAX));
        let max_row = rows
            .iter()
            .find(|r| r.row.starts_with("Monte Carlo max R_f"))
            .unwrap();
        assert_eq!(a[0].ours, max_row.ours);
        assert_eq!(
            a[1..].iter().map(|v| v.thesis).collect::<Vec<_>>(),
            THESIS_RF_THEORY.map(|t| Some(t.1))
        );
        assert!(curves[2..5].iter().all(|c| c.values[0].thesis.is_none()));

        // Figure 3.3-9: the NMSE points, the MCRB line, the largest NMSE of the row.
        let c = &curves[5];
        assert_eq!(c.references[0].value, theory::mcrb_fd_tc(M, SNR));
        let nmse: Vec<(f64, f64)> = p.nmse.iter().map(|q| (q.fd_tc, q.mse)).collect();
        assert_eq!(c.series[0].points, nmse);
        let edge = 1.0 / (2.0 * L_CURVES[0] as f64);
        let steps = NMSE_STEPS_PER_BIN * 2 * M / L_CURVES[0];
        assert_eq!(c.series[1].points.len(), steps + 1);
        assert!(
            c.series[1]
                .points
                .iter()
                .all(|&(f, y)| f.abs() <= edge && y == theory::nmse_fd_tc(M, L_CURVES[0], f, SNR))
        );
        let max_row = rows.iter().find(|r| r.row == "NMSE maximum L=64").unwrap();
        assert_eq!(c.values[0].ours, max_row.ours);
        assert_eq!(c.values[0].thesis, Some(THESIS_NMSE_ORDER));
    }

    #[test]
    fn noise_is_at_the_requested_snr() {
        // With no signal the NMSE has nothing to do with the MCRB; instead check the
        // noise level directly: per-component sigma^2 = 1 / (2 SNR).
        let mut noise = ThermalNoise::new(SEED, 1, (0.5 / SNR).sqrt() as f32);
        let (mut re, mut im) = (vec![0f32; 50_000], vec![0f32; 50_000]);
        noise.add(0, &mut re, &mut im);
        let p: f64 = re
            .iter()
            .chain(&im)
            .map(|&v| f64::from(v).powi(2))
            .sum::<f64>()
            / 50_000.0;
        assert!((p - 1.0 / SNR).abs() < 0.02, "{p}");
    }
}
