//! Reverse (inverse) filtering of the baseline vectors, thesis section 5.5.
//!
//! Once an epoch's integers `vec(N)` are fixed they are put back into the double-difference
//! model (eq. 5.5-1), leaving the baselines as the only unknowns (eq. 5.5-2):
//! `vec(Y) - (I_m (x) A) vec(N) = (I_m (x) G) vec(B)`. A 12-state UKF then carries the two
//! baselines (ECEF) and their rates from epoch to epoch (eq. 5.5-3), which an
//! epoch-by-epoch solution cannot: the number of ambiguities changes between epochs, the
//! number of baselines does not.
//!
//! * prediction (eqs. 5.5-4..5.5-7, 5.5-10, 5.5-11): `Phi = [[I_6, T I_6], [0, I_6]]`,
//!   `Q = [[T^3/3, T^2/2], [T^2/2, T]] (x) diag(S)` (white noise on the baselines'
//!   accelerations with power spectral densities `S`, m^2/s^3);
//! * measurement (eqs. 5.5-8, 5.5-9): `Z = vec(Y) - (I_m (x) A) vec(N)`, phase and code
//!   rows of every baseline (the code rows have no ambiguity), `h(X) = (I_m (x) G) vec(B)`
//!   and `R = Q_YY = Q_M (x) Q_t`;
//! * update (eqs. 5.5-12..5.5-20): the unscented transform of
//!   [`crate::attitude::unscented`] with spread kappa (the thesis: 0.5).
//!
//! The filter starts at its first fixed epoch from that epoch's baselines (eqs. 2.4-64,
//! 2.4-65) with zero rates; it updates only on epochs whose every ambiguity is fixed (a
//! partial fix has no `vec(N)` to put back) and hands other epochs' baselines through.
//! An epoch whose update fails keeps its epoch-by-epoch baselines and the filter starts
//! again at the next fixed epoch ([`ReverseFilter::epoch`]).
//! It reads observations and the receiver's own integers, never truth.

use super::config::ReverseConfig;
use super::resolve::{AmbiguityStatus, Resolution};
use crate::attitude::config::check_filter;
use crate::attitude::filter::{process_noise, transition};
use crate::attitude::unscented::{UnscentedError, transform, update};
use crate::baseline::{BaselineError, FixedBaselines, FloatBaselines};
use nalgebra::{DMatrix, DVector, Matrix3xX, SMatrix, SVector};

/// Baselines of the filter (thesis 5.5.1: m + 1 = 3 antennas, m = 2 baselines).
pub const BASELINES: usize = 2;
/// Eq. 5.5-3: `vec(B)` (6) and its rates (6).
pub const STATES: usize = 12;

type State = SVector<f64, STATES>;
type Covariance = SMatrix<f64, STATES, STATES>;

/// Why the reverse filter could not run.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ReverseError {
    #[error("reverse baseline filter: {0}")]
    Config(String),
    #[error("reverse baseline filter: {0}")]
    Unscented(#[from] UnscentedError),
    #[error("reverse baseline filter: {0}")]
    Baseline(#[from] BaselineError),
}

impl ReverseConfig {
    /// The filter settings in their domain ([`check_filter`], `12 + kappa > 0`).
    pub fn check(&self) -> Result<(), ReverseError> {
        check_filter(
            STATES,
            ("rate_psd_m2_s3", &self.rate_psd_m2_s3),
            ("initial_rate_sigma_m_s", self.initial_rate_sigma_m_s),
            self.kappa,
        )
        .map_err(ReverseError::Config)
    }
}

/// One epoch's measurement of eqs. 5.5-2, 5.5-8, 5.5-9; made only by
/// [`BaselineMeasurement::new`], so its sizes agree with each other.
#[derive(Debug, Clone, PartialEq)]
pub struct BaselineMeasurement {
    z: DVector<f64>,
    h: DMatrix<f64>,
    r: DMatrix<f64>,
}

impl BaselineMeasurement {
    /// `Z = vec(Y) - (I_m (x) A) vec(N)` (2nm, m).
    pub fn z(&self) -> &DVector<f64> {
        &self.z
    }

    /// `H = I_m (x) G` (2nm x 3m).
    pub fn h(&self) -> &DMatrix<f64> {
        &self.h
    }

    /// `R = Q_YY = Q_M (x) Q_t` (2nm x 2nm, m^2).
    pub fn r(&self) -> &DMatrix<f64> {
        &self.r
    }

    /// The measurement of `float`'s epoch with every ambiguity fixed to `integers`
    /// (vec(N), baseline 1's first).
    pub fn new(float: &FloatBaselines, integers: &[i64]) -> Result<Self, ReverseError> {
        let model = &float.model;
        let n = model.ambiguity_count();
        let m = model.baseline_count();
        if integers.len() != n * m {
            return Err(BaselineError::Dimension {
                what: "fixed integers vec(N)",
                expected: n * m,
                found: integers.len(),
            }
            .into());
        }
        if float.observations.shape() != (2 * n, m) {
            return Err(BaselineError::Dimension {
                what: "double differences vec(Y) (2n rows, m columns)",
                expected: 2 * n * m,
                found: float.observations.len(),
            }
            .into());
        }
        let a = model.design.columns(0, n);
        let g = model.design.columns(n, 3).into_owned();
        let mut z = DVector::zeros(2 * n * m);
        for (k, ints) in integers.chunks(n).enumerate() {
            let nk = DVector::from_iterator(n, ints.iter().map(|&v| v as f64));
            z.rows_mut(2 * n * k, 2 * n)
                .copy_from(&(float.observations.column(k) - a * nk));
        }
        let q_t = model
            .weight
            .clone()
            .cholesky()
            .ok_or(BaselineError::Singular)?
            .inverse();
        Ok(Self {
            z,
            h: DMatrix::identity(m, m).kronecker(&g),
            r: model.q_m.kronecker(&q_t),
        })
    }

    /// Eq. 5.5-9: `h(X) = (I_m (x) G) vec(B)`, `vec(B)` the first 3m states.
    fn predict(&self, x: &State) -> DVector<f64> {
        &self.h * x.rows(0, self.h.ncols())
    }
}

/// The 12-state reverse baseline UKF.
#[derive(Debug, Clone)]
pub struct ReverseFilter {
    config: ReverseConfig,
    /// `(X, P)` once started.
    xp: Option<(State, Covariance)>,
}

impl ReverseFilter {
    /// A filter with `config`, started by its first fixed epoch.
    pub fn new(config: ReverseConfig) -> Result<Self, ReverseError> {
        config.check()?;
        Ok(Self { config, xp: None })
    }

    /// Eqs. 5.5-10, 5.5-11 over `dt_s` (s, finite and >= 0); nothing before the start.
    pub fn predict(&mut self, dt_s: f64) -> Result<(), ReverseError> {
        if !(dt_s.is_finite() && dt_s >= 0.0) {
            return Err(ReverseError::Config(format!(
                "prediction interval {dt_s} s must be finite and >= 0"
            )));
        }
        if let Some((x, p)) = self.xp {
            let phi = transition::<STATES>(dt_s);
            let p = phi * p * phi.transpose()
                + process_noise::<STATES>(dt_s, &self.config.rate_psd_m2_s3);
            self.xp = Some((phi * x, 0.5 * (p + p.transpose())));
        }
        Ok(())
    }

    /// Start from `ls` (two baselines and their covariance, eq. 2.4-65) with zero rates.
    fn start(&mut self, ls: &FixedBaselines) -> Result<(), ReverseError> {
        if ls.baselines.ncols() != BASELINES || ls.covariance.shape() != (6, 6) {
            return Err(BaselineError::Dimension {
                what: "baselines of the reverse filter (thesis 5.5: 12 states)",
                expected: BASELINES,
                found: ls.baselines.ncols(),
            }
            .into());
        }
        let mut x = State::zeros();
        x.rows_mut(0, 6).copy_from_slice(ls.baselines.as_slice());
        let mut p = Covariance::zeros();
        p.fixed_view_mut::<6, 6>(0, 0).copy_from(&ls.covariance);
        let s2 = self.config.initial_rate_sigma_m_s.powi(2);
        p.fixed_view_mut::<6, 6>(6, 6).fill_diagonal(s2);
        self.xp = Some((x, p));
        Ok(())
    }

    /// Eqs. 5.5-12..5.5-20 with `measurement`; a filter without a state starts from `ls`,
    /// the same epoch's epoch-by-epoch baselines, instead. Returns the filtered baselines.
    pub fn update(
        &mut self,
        measurement: &BaselineMeasurement,
        ls: &FixedBaselines,
    ) -> Result<FixedBaselines, ReverseError> {
        let Some((x, p)) = self.xp else {
            self.start(ls)?;
            return Ok(ls.clone());
        };
        let t = transform(&x, &p, self.config.kappa, |xj| measurement.predict(xj))?;
        let (x, p, _, _) = update(&x, &p, &t, &measurement.z, &measurement.r)?;
        if !x.iter().chain(p.iter()).all(|v| v.is_finite()) {
            return Err(BaselineError::NotFinite {
                what: "the reverse filter's state",
            }
            .into());
        }
        self.xp = Some((x, p));
        Ok(FixedBaselines {
            baselines: Matrix3xX::from_column_slice(x.rows(0, 6).as_slice()),
            covariance: DMatrix::from_fn(6, 6, |i, j| p[(i, j)]),
        })
    }

    /// One epoch of the chain: the filtered baselines when `resolution` fixed every
    /// ambiguity of `float`, else `ls` (the epoch-by-epoch baselines) unchanged. Where the
    /// update fails, `ls` with the failure, and the filter is cleared: its next fixed epoch
    /// starts it again.
    pub fn epoch(
        &mut self,
        float: &FloatBaselines,
        resolution: &Resolution,
        ls: FixedBaselines,
    ) -> (FixedBaselines, Option<ReverseError>) {
        let integers: Option<Vec<i64>> = resolution.integers.iter().copied().collect();
        let Some(n) = integers.filter(|_| resolution.status == AmbiguityStatus::Fixed) else {
            return (ls, None);
        };
        self.recovering(BaselineMeasurement::new(float, &n), ls)
    }

    /// The update with `measurement` (or its construction's error), or, where it fails,
    /// `ls` with the failure and the filter cleared, so that its next update starts it.
    fn recovering(
        &mut self,
        measurement: Result<BaselineMeasurement, ReverseError>,
        ls: FixedBaselines,
    ) -> (FixedBaselines, Option<ReverseError>) {
        let filtered = measurement.and_then(|measurement| self.update(&measurement, &ls));
        match filtered {
            Ok(b) => (b, None),
            Err(e) => {
                self.xp = None;
                (ls, Some(e))
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::attitude::config::THESIS_KAPPA;
    use rand::{Rng, SeedableRng};
    use rand_chacha::ChaCha8Rng;

    fn random_measurement(rng: &mut ChaCha8Rng, rows: usize) -> BaselineMeasurement {
        let h = DMatrix::from_fn(rows, 6, |_, _| rng.random_range(-1.0..1.0));
        let l = DMatrix::from_fn(rows, rows, |i, j| {
            if i >= j {
                rng.random_range(0.1..1.0) * 1e-2
            } else {
                0.0
            }
        });
        BaselineMeasurement {
            z: DVector::from_fn(rows, |_, _| rng.random_range(-1.0..1.0)),
            h,
            r: &l * l.transpose(),
        }
    }

    #[test]
    fn the_update_of_a_linear_measurement_is_the_kalman_update() {
        // Oracle: the textbook KF with H_full = [H 0], written here.
        let mut rng = ChaCha8Rng::seed_from_u64(5);
        let ls = FixedBaselines {
            baselines: Matrix3xX::from_column_slice(&[0.9, 0.1, -0.2, 0.0, 1.0, 0.1]),
            covariance: DMatrix::identity(6, 6) * 1e-3,
        };
        let mut f = ReverseFilter::new(ReverseConfig::default()).unwrap();
        let first = f.update(&random_measurement(&mut rng, 14), &ls).unwrap();
        assert_eq!(first, ls);
        f.predict(1.0).unwrap();
        let (x0, p0) = f.xp.unwrap();
        let meas = random_measurement(&mut rng, 14);
        let out = f.update(&meas, &ls).unwrap();
        let x0 = DVector::from_column_slice(x0.as_slice());
        let p0 = DMatrix::from_column_slice(STATES, STATES, p0.as_slice());
        let mut hf = DMatrix::zeros(14, STATES);
        hf.columns_mut(0, 6).copy_from(&meas.h);
        let s = &hf * &p0 * hf.transpose() + &meas.r;
        let k = &p0 * hf.transpose() * s.try_inverse().unwrap();
        let x = &x0 + &k * (&meas.z - &hf * &x0);
        let p = (DMatrix::identity(STATES, STATES) - &k * &hf) * &p0;
        let (xu, pu) = f.xp.unwrap();
        assert!((DVector::from_column_slice(xu.as_slice()) - &x).amax() < 1e-10);
        assert!((DMatrix::from_column_slice(STATES, STATES, pu.as_slice()) - &p).amax() < 1e-10);
        assert!(
            (DVector::from_column_slice(out.baselines.as_slice()) - x.rows(0, 6)).amax() < 1e-10
        );
    }

    #[test]
    fn prediction_moves_the_baselines_by_their_rates() {
        let ls = FixedBaselines {
            baselines: Matrix3xX::from_column_slice(&[1.0, 0.0, 0.0, 0.0, 1.0, 0.0]),
            covariance: DMatrix::identity(6, 6) * 1e-4,
        };
        let mut f = ReverseFilter::new(ReverseConfig::default()).unwrap();
        f.predict(1.0).unwrap();
        assert!(f.xp.is_none());
        let mut rng = ChaCha8Rng::seed_from_u64(1);
        f.update(&random_measurement(&mut rng, 8), &ls).unwrap();
        let (mut x, p) = f.xp.unwrap();
        x[6] = 0.01;
        f.xp = Some((x, p));
        f.predict(2.0).unwrap();
        let (x, p2) = f.xp.unwrap();
        assert!((x[0] - 1.02).abs() < 1e-14);
        // Rate variance 0.01 and S 1e-6 over 2 s: P_00 grows by 4 * 0.01 + 8e-6 / 3.
        assert!((p2[(0, 0)] - (1e-4 + 0.04 + 8e-6 / 3.0)).abs() < 1e-14);
        assert!(f.predict(-1.0).is_err());
    }

    /// A failed update (here a covariance made non-finite, as an overflowing prediction
    /// leaves it) hands the epoch's own baselines through with the error and clears the
    /// filter; the next epoch starts it again and the one after filters.
    #[test]
    fn a_failed_update_keeps_the_epoch_and_restarts_the_filter() {
        let ls = FixedBaselines {
            baselines: Matrix3xX::from_column_slice(&[1.0, 0.0, 0.0, 0.0, 1.0, 0.0]),
            covariance: DMatrix::identity(6, 6) * 1e-4,
        };
        let mut rng = ChaCha8Rng::seed_from_u64(2);
        let mut f = ReverseFilter::new(ReverseConfig::default()).unwrap();
        let (first, failure) = f.recovering(Ok(random_measurement(&mut rng, 8)), ls.clone());
        assert_eq!((first, failure), (ls.clone(), None));
        let (x, mut p) = f.xp.unwrap();
        p[(0, 0)] = f64::INFINITY;
        f.xp = Some((x, p));
        let (kept, failure) = f.recovering(Ok(random_measurement(&mut rng, 8)), ls.clone());
        assert_eq!(kept, ls);
        assert!(failure.is_some());
        assert!(f.xp.is_none(), "the filter is cleared");
        let bad = Err(BaselineError::NotFinite { what: "a test" }.into());
        let (kept, failure) = f.recovering(bad, ls.clone());
        assert_eq!(kept, ls);
        assert!(failure.unwrap().to_string().contains("a test"));
        let (restarted, failure) = f.recovering(Ok(random_measurement(&mut rng, 8)), ls.clone());
        assert_eq!((restarted, failure), (ls.clone(), None));
        f.predict(1.0).unwrap();
        let (filtered, failure) = f.recovering(Ok(random_measurement(&mut rng, 8)), ls.clone());
        assert!(failure.is_none());
        assert_ne!(filtered, ls, "filtered again");
    }

    #[test]
    fn config_parses_and_rejects_bad_values() {
        let c: ReverseConfig = toml::from_str("rate_psd_m2_s3 = [1, 1, 1, 2, 2, 2]").unwrap();
        assert_eq!(c.rate_psd_m2_s3[3], 2.0);
        assert_eq!(c.kappa, THESIS_KAPPA);
        assert!(toml::from_str::<ReverseConfig>("kapa = 1.0").is_err());
        for bad in [
            ReverseConfig {
                kappa: -12.0,
                ..ReverseConfig::default()
            },
            ReverseConfig {
                initial_rate_sigma_m_s: 0.0,
                ..ReverseConfig::default()
            },
            ReverseConfig {
                rate_psd_m2_s3: [f64::NAN; 6],
                ..ReverseConfig::default()
            },
            ReverseConfig {
                rate_psd_m2_s3: [1e-6, 1e-6, 1e300, 1e-6, 1e-6, 1e-6],
                ..ReverseConfig::default()
            },
            ReverseConfig {
                initial_rate_sigma_m_s: 1e300,
                ..ReverseConfig::default()
            },
        ] {
            assert!(ReverseFilter::new(bad).is_err());
        }
        let e = ReverseConfig {
            rate_psd_m2_s3: [1e-6, 1e-6, 1e300, 1e-6, 1e-6, 1e-6],
            ..ReverseConfig::default()
        }
        .check()
        .unwrap_err()
        .to_string();
        assert!(
            e.contains("rate_psd_m2_s3[2] = 1e300: allowed 0 to 1e6"),
            "{e}"
        );
    }
}
