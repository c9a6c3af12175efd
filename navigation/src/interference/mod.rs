//! Jamming detection from a receiver's observations (issue #37): the C/N0 of every
//! tracked satellite falling together. A jammer raises the noise density every channel
//! sees, so all C/N0 estimates drop by the same amount (the effective-C/N0 relation,
//! docs/interference.md), while a satellite's own fades (elevation, multipath,
//! blockage) are its own.
//!
//! Per epoch, each tracked satellite's C/N0 against its reference `r_i` (an exponential
//! average of its past, time constant `reference_tau_s`, updated only while no alarm is
//! raised): `d_i = C/N0_i - r_i`. With `n` satellites referenced, the statistic is their
//! median `d` (one satellite's fade does not move it); without jamming it is about
//! `N(0, (pi / 2) s^2 / n)` (the median of `n` normal deviates), `s^2` the variance of one
//! estimate about its reference (learned the same way from the clean epochs' robust scale,
//! 1.4826 times their median absolute change, at least `sigma_floor_db`). The alarm is raised when `d < -k s sqrt(pi / (2 n))`,
//! `k = Phi^-1(1 - P_FA)` for the configured per-epoch false-alarm probability (the
//! one-sided normal quantile, as `sqrt` of the chi-square quantile of one degree of
//! freedom at `2 P_FA`), and when most satellites are lost at once (fewer than half the
//! previous epoch's, from at least `min_satellites`): a jammer beyond the loss of lock.
//! Successive epochs' estimates are correlated (the estimator's window), so the
//! false-alarm probability holds per epoch, not per independent sample.

use crate::pvt::raim::test_threshold;
use hifitime::Epoch;
use skyforge_gnss::observation::ObsEpoch;
use skyforge_gnss::signal::Signal;
use skyforge_orbits::ephemeris::SatId;
use std::collections::BTreeMap;

/// Settings of the C/N0 monitor.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Cn0MonitorConfig {
    /// False-alarm probability per epoch. # assumed: 1e-6, about one false alarm in 12
    /// days at 1 Hz.
    pub false_alarm: f64,
    /// Time constant of each satellite's reference (s). # assumed: 60 s, slower than any
    /// jammer's onset, faster than an elevation's change of the link budget.
    pub reference_tau_s: f64,
    /// Fewest referenced satellites for the mean test (and tracked before a mass loss).
    /// # assumed: 4, a fix's.
    pub min_satellites: usize,
    /// Epochs of references learned before any alarm. # assumed: 10.
    pub warm_up_epochs: usize,
    /// Smallest standard deviation of one estimate about its reference (dB).
    /// # assumed: 0.2 dB, below any 1-Hz C/N0 estimator's scatter.
    pub sigma_floor_db: f64,
}

impl Default for Cn0MonitorConfig {
    fn default() -> Self {
        Self {
            false_alarm: 1e-6,
            reference_tau_s: 60.0,
            min_satellites: 4,
            warm_up_epochs: 10,
            sigma_floor_db: 0.2,
        }
    }
}

impl Cn0MonitorConfig {
    /// Every setting in range: a false-alarm probability in (0, 0.5), a positive time
    /// constant and floor, at least one satellite. The message names the setting.
    pub fn check(&self) -> Result<(), String> {
        let ok = self.false_alarm > 0.0
            && self.false_alarm < 0.5
            && self.reference_tau_s.is_finite()
            && self.reference_tau_s > 0.0
            && self.sigma_floor_db.is_finite()
            && self.sigma_floor_db > 0.0
            && self.min_satellites >= 1;
        match ok {
            true => Ok(()),
            false => Err(format!(
                "C/N0 monitor: false_alarm {} must be in (0, 0.5), reference_tau_s {} and sigma_floor_db {} positive, min_satellites {} at least 1",
                self.false_alarm, self.reference_tau_s, self.sigma_floor_db, self.min_satellites
            )),
        }
    }
}

/// The monitor's verdict at one epoch.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JammingEpoch {
    pub t: Epoch,
    /// Satellites with a C/N0, and those of them with a reference.
    pub tracked: usize,
    pub referenced: usize,
    /// The median C/N0 change against the references (dB; negative: a drop); NaN
    /// without enough references.
    pub change_db: f64,
    /// The alarm threshold on it (dB, negative); NaN without enough references.
    pub threshold_db: f64,
    /// The median fell below the threshold, or most satellites were lost at once.
    pub alarm: bool,
}

/// The C/N0 monitor of one antenna.
#[derive(Debug, Clone)]
pub struct Cn0Monitor {
    cfg: Cn0MonitorConfig,
    /// `k` of the one-sided test.
    k: f64,
    references: BTreeMap<(SatId, Signal), f64>,
    /// The variance of one estimate about its reference (dB^2).
    variance: f64,
    epochs: usize,
    last: Option<(Epoch, usize)>,
}

impl Cn0Monitor {
    /// A monitor with checked settings.
    pub fn new(cfg: Cn0MonitorConfig) -> Result<Self, String> {
        cfg.check()?;
        Ok(Self {
            cfg,
            k: test_threshold(1, 2.0 * cfg.false_alarm).sqrt(),
            references: BTreeMap::new(),
            variance: 1.0,
            epochs: 0,
            last: None,
        })
    }

    /// The verdict at `epoch`; the references learn from it unless it raised the alarm.
    pub fn epoch(&mut self, epoch: &ObsEpoch) -> JammingEpoch {
        let cn0: Vec<((SatId, Signal), f64)> = (epoch.sats.iter())
            .filter_map(|r| Some(((r.sat, r.signal), r.cn0_dbhz.filter(|c| c.is_finite())?)))
            .collect();
        let changes: Vec<f64> = (cn0.iter())
            .filter_map(|(key, c)| Some(c - self.references.get(key)?))
            .collect();
        let n = changes.len();
        let sigma = self.variance.sqrt().max(self.cfg.sigma_floor_db);
        let (change, threshold) = if n >= self.cfg.min_satellites {
            let spread = (std::f64::consts::FRAC_PI_2 / n as f64).sqrt();
            (median(&changes), -self.k * sigma * spread)
        } else {
            (f64::NAN, f64::NAN)
        };
        let lost = self
            .last
            .is_some_and(|(_, before)| before >= self.cfg.min_satellites && 2 * cn0.len() < before);
        let warm = self.epochs >= self.cfg.warm_up_epochs;
        let alarm = warm && (change < threshold || lost);
        let dt = self
            .last
            .map_or(1.0, |(t, _)| (epoch.time - t).to_seconds().max(0.0));
        if !alarm {
            self.learn(&cn0, &changes, dt);
        }
        self.last = Some((epoch.time, cn0.len()));
        JammingEpoch {
            t: epoch.time,
            tracked: cn0.len(),
            referenced: n,
            change_db: change,
            threshold_db: threshold,
            alarm,
        }
    }

    /// The references and the variance moved towards a clean epoch's values over `dt`.
    fn learn(&mut self, cn0: &[((SatId, Signal), f64)], changes: &[f64], dt: f64) {
        let w = 1.0 - (-dt / self.cfg.reference_tau_s).exp();
        for (key, c) in cn0 {
            let r = self.references.entry(*key).or_insert(*c);
            *r += w * (c - *r);
        }
        if !changes.is_empty() {
            // A robust scale (1.4826 times the median absolute change), as the median test:
            // one satellite's fade does not inflate it.
            let absolute: Vec<f64> = changes.iter().map(|d| d.abs()).collect();
            let scale = 1.4826 * median(&absolute);
            self.variance += w * (scale * scale - self.variance);
        }
        self.epochs += 1;
    }
}

/// The median of `values` (not empty; the mean of the middle two for an even count).
fn median(values: &[f64]) -> f64 {
    let mut v = values.to_vec();
    v.sort_by(f64::total_cmp);
    let m = v.len() / 2;
    match v.len() % 2 {
        0 => 0.5 * (v[m - 1] + v[m]),
        _ => v[m],
    }
}

#[cfg(test)]
mod tests;
