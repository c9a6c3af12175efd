//! Alarm thresholds: the paper's 0.5 m for the smoothed pseudorange (or more, where its
//! fault-free spread demands it), the others from a false-alarm probability and the
//! fault-free spread of the B values by elevation.

use super::statistic::{PerStatistic, Statistic};
use crate::pvt::raim::chi2_threshold;
use serde::{Deserialize, Serialize};
use skyforge_gnss::signal::Signal;
use std::collections::BTreeMap;

/// Fault-free standard deviations of the B values by elevation, as `skyforge monitor
/// calibrate` measures them.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SigmaTable {
    /// Lower edge of each elevation bin (deg), increasing; a bin reaches the next edge,
    /// the last one 90 deg.
    pub elevation_deg: Vec<f64>,
    /// RMS of the code B value per bin (m).
    pub code_m: Vec<f64>,
    /// RMS of the smoothed-code B value per bin (m).
    pub smoothed_code_m: Vec<f64>,
    /// RMS of the carrier B value per bin (cycles).
    pub carrier_cycles: Vec<f64>,
    /// RMS of the divergence B value per bin (m/s).
    pub divergence_mps: Vec<f64>,
}

impl SigmaTable {
    /// The column of `stat`.
    pub fn column(&self, stat: Statistic) -> &[f64] {
        match stat {
            Statistic::Code => &self.code_m,
            Statistic::SmoothedCode => &self.smoothed_code_m,
            Statistic::Carrier => &self.carrier_cycles,
            Statistic::Divergence => &self.divergence_mps,
        }
    }

    /// The key of `stat`'s column in the file.
    fn key(stat: Statistic) -> &'static str {
        match stat {
            Statistic::Code => "code_m",
            Statistic::SmoothedCode => "smoothed_code_m",
            Statistic::Carrier => "carrier_cycles",
            Statistic::Divergence => "divergence_mps",
        }
    }

    /// The bin of elevation `elevation_deg` (the first below the lowest edge is 0).
    pub fn bin(&self, elevation_deg: f64) -> usize {
        self.elevation_deg
            .iter()
            .rposition(|&edge| elevation_deg >= edge)
            .unwrap_or(0)
    }

    /// The sigma of `stat` at `elevation_deg`.
    pub fn sigma(&self, stat: Statistic, elevation_deg: f64) -> f64 {
        self.column(stat)
            .get(self.bin(elevation_deg))
            .copied()
            .unwrap_or(f64::NAN)
    }

    /// Whether the table is usable: at least one bin, increasing edges in [0, 90), every
    /// column as long as the edges, every sigma finite and positive.
    pub fn check(&self) -> Result<(), String> {
        let n = self.elevation_deg.len();
        if n == 0 {
            return Err("elevation_deg is empty".into());
        }
        if self
            .elevation_deg
            .windows(2)
            .any(|w| w[1].partial_cmp(&w[0]) != Some(std::cmp::Ordering::Greater))
            || !self.elevation_deg.iter().all(|e| (0.0..90.0).contains(e))
        {
            return Err(format!(
                "elevation_deg = {:?}: must increase, each in [0, 90)",
                self.elevation_deg
            ));
        }
        for stat in Statistic::ALL {
            let col = self.column(stat);
            if col.len() != n {
                return Err(format!(
                    "{}: {} values for {n} elevation bins",
                    Self::key(stat),
                    col.len()
                ));
            }
            if let Some(v) = col.iter().find(|v| !(v.is_finite() && **v > 0.0)) {
                return Err(format!("{}: {v} is not a positive number", Self::key(stat)));
            }
        }
        Ok(())
    }
}

/// How alarms are raised.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ThresholdConfig {
    /// Probability that one fault-free B value exceeds its threshold (two-sided normal);
    /// sets the multiplier of the sigma table for code, carrier and divergence.
    pub false_alarm: f64,
    /// Threshold of the smoothed-code B value (m): paper 002 section 4.2.3. Where the
    /// receivers' fault-free smoothed code spreads wider than the paper's did (k sigma
    /// above this), k sigma is the threshold instead, so the false-alarm probability holds.
    pub smoothed_code_m: f64,
    /// The fault-free sigma table of each signal, by its tag (`gps-l1ca`, `bds-b1i`);
    /// satellites of a signal without one are not monitored.
    pub sigma: BTreeMap<String, SigmaTable>,
    /// Sigma tables of the BeiDou GEOs alone, by signal tag (`monitor calibrate-files
    /// --geo-apart`): a static station sees their code errors wander far more than the
    /// other satellites' (docs/integrity.md). GEOs of a signal without one use `sigma`.
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub sigma_geo: BTreeMap<String, SigmaTable>,
}

impl ThresholdConfig {
    /// The multiplier `k` with `P(|N(0, 1)| > k) = false_alarm`.
    pub fn multiplier(&self) -> f64 {
        chi2_threshold(1, self.false_alarm).sqrt()
    }

    /// Thresholds of the four B values of `signal` at `elevation_deg` (from a BeiDou GEO
    /// when `geo`), given the multiplier `k`; `None` without a sigma table for the signal.
    pub fn at(
        &self,
        k: f64,
        signal: Signal,
        geo: bool,
        elevation_deg: f64,
    ) -> Option<PerStatistic<f64>> {
        let own = geo.then(|| self.sigma_geo.get(signal.tag())).flatten();
        let table = own.or_else(|| self.sigma.get(signal.tag()))?;
        Some(Statistic::ALL.map(|stat| {
            let spread = k * table.sigma(stat, elevation_deg);
            match stat {
                Statistic::SmoothedCode => self.smoothed_code_m.max(spread),
                _ => spread,
            }
        }))
    }

    /// Whether the settings are usable.
    pub fn check(&self) -> Result<(), String> {
        if !(self.false_alarm > 0.0 && self.false_alarm < 0.5) {
            return Err(format!(
                "false_alarm = {}: must be in (0, 0.5)",
                self.false_alarm
            ));
        }
        if !(self.smoothed_code_m.is_finite() && self.smoothed_code_m > 0.0) {
            return Err(format!(
                "smoothed_code_m = {}: must be a positive number",
                self.smoothed_code_m
            ));
        }
        if self.sigma.is_empty() {
            return Err(
                "sigma: no table (one per signal: [thresholds.sigma.gps-l1ca], ...)".into(),
            );
        }
        for (key, tables) in [("sigma", &self.sigma), ("sigma_geo", &self.sigma_geo)] {
            for (tag, table) in tables {
                tag.parse::<Signal>().map_err(|_| {
                    format!("{key}.{tag}: not a signal (gps-l1ca, bds-b1i, gps-l2)")
                })?;
                table.check().map_err(|e| format!("{key}.{tag}: {e}"))?;
            }
        }
        Ok(())
    }
}

/// Per elevation bin and statistic: count and sum of squares.
type Sums = Vec<PerStatistic<(u64, f64)>>;

/// Accumulates fault-free B values by signal, statistic and elevation bin into sigma
/// tables.
#[derive(Debug, Clone)]
pub struct SigmaCalibrator {
    edges_deg: Vec<f64>,
    sums: BTreeMap<Signal, Sums>,
}

impl SigmaCalibrator {
    /// A calibrator over the bins starting at `edges_deg` (increasing).
    pub fn new(edges_deg: Vec<f64>) -> Self {
        Self {
            edges_deg,
            sums: BTreeMap::new(),
        }
    }

    /// Take one B value of `stat` of `signal` at `elevation_deg`.
    pub fn add(&mut self, signal: Signal, stat: Statistic, elevation_deg: f64, b: f64) {
        let Some(bin) = self.edges_deg.iter().rposition(|&e| elevation_deg >= e) else {
            return;
        };
        let bins = self.edges_deg.len();
        let sums = self
            .sums
            .entry(signal)
            .or_insert_with(|| vec![[(0, 0.0); 4]; bins]);
        let (n, s) = &mut sums[bin][stat.index()];
        *n += 1;
        *s += b * b;
    }

    /// Take everything `other` (with the same bins) has taken.
    pub fn merge(&mut self, other: &SigmaCalibrator) {
        let bins = self.edges_deg.len();
        for (signal, theirs) in &other.sums {
            let mine = self
                .sums
                .entry(*signal)
                .or_insert_with(|| vec![[(0, 0.0); 4]; bins]);
            for (m, t) in mine.iter_mut().flatten().zip(theirs.iter().flatten()) {
                m.0 += t.0;
                m.1 += t.1;
            }
        }
    }

    /// Values taken per bin of `signal` (the fewest over the statistics).
    pub fn counts(&self, signal: Signal) -> Vec<u64> {
        self.sums.get(&signal).map_or_else(
            || vec![0; self.edges_deg.len()],
            |sums| {
                sums.iter()
                    .map(|bin| bin.iter().map(|c| c.0).min().unwrap_or(0))
                    .collect()
            },
        )
    }

    /// The signals that have values but lack one statistic's altogether (no table).
    pub fn incomplete(&self) -> Vec<Signal> {
        self.sums
            .iter()
            .filter(|(_, sums)| self.table(sums).is_none())
            .map(|(signal, _)| *signal)
            .collect()
    }

    /// The RMS table of each signal seen, by tag. An empty bin takes the value of the
    /// nearest bin below it with data (above it for the lowest), so every elevation has
    /// a threshold.
    pub fn tables(&self) -> BTreeMap<String, SigmaTable> {
        self.sums
            .iter()
            .filter_map(|(signal, sums)| Some((signal.tag().to_string(), self.table(sums)?)))
            .collect()
    }

    fn table(&self, sums: &Sums) -> Option<SigmaTable> {
        let column = |stat: Statistic| -> Option<Vec<f64>> {
            let rms: Vec<Option<f64>> = sums
                .iter()
                .map(|bin| {
                    let (n, s) = bin[stat.index()];
                    (n > 0).then(|| (s / n as f64).sqrt())
                })
                .collect();
            let first = rms.iter().flatten().next().copied()?;
            let mut last = first;
            Some(
                rms.iter()
                    .map(|v| {
                        last = v.unwrap_or(last);
                        last
                    })
                    .collect(),
            )
        };
        Some(SigmaTable {
            elevation_deg: self.edges_deg.clone(),
            code_m: column(Statistic::Code)?,
            smoothed_code_m: column(Statistic::SmoothedCode)?,
            carrier_cycles: column(Statistic::Carrier)?,
            divergence_mps: column(Statistic::Divergence)?,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn table() -> SigmaTable {
        SigmaTable {
            elevation_deg: vec![10.0, 30.0, 60.0],
            code_m: vec![1.0, 0.5, 0.3],
            smoothed_code_m: vec![0.1, 0.05, 0.03],
            carrier_cycles: vec![0.02, 0.01, 0.01],
            divergence_mps: vec![1e-3, 5e-4, 3e-4],
        }
    }

    #[test]
    fn bins_start_at_their_edges() {
        let t = table();
        assert_eq!(t.bin(5.0), 0);
        assert_eq!(t.bin(10.0), 0);
        assert_eq!(t.bin(29.9), 0);
        assert_eq!(t.bin(30.0), 1);
        assert_eq!(t.bin(89.0), 2);
        assert_eq!(t.sigma(Statistic::Code, 45.0), 0.5);
        assert!(t.check().is_ok());
    }

    #[test]
    fn thresholds_scale_the_sigma_and_keep_the_papers_smoothed_limit_as_a_floor() {
        let cfg = ThresholdConfig {
            false_alarm: 0.05,
            smoothed_code_m: 0.5,
            sigma: BTreeMap::from([("gps-l1ca".to_string(), table())]),
            sigma_geo: BTreeMap::new(),
        };
        assert!(cfg.check().is_ok());
        let k = cfg.multiplier();
        assert!((k - 1.959_964).abs() < 1e-4, "{k}");
        assert!(cfg.at(k, Signal::BdsB1I, false, 70.0).is_none());
        let t = cfg.at(k, Signal::GpsL1Ca, false, 70.0).unwrap();
        assert!((t[Statistic::Code.index()] - 0.3 * k).abs() < 1e-12);
        assert_eq!(t[Statistic::SmoothedCode.index()], 0.5);
        // A smoothed-code spread wider than the paper's limit allows sets the threshold.
        let mut wide = table();
        wide.smoothed_code_m = vec![0.4; 3];
        let cfg = ThresholdConfig {
            sigma: BTreeMap::from([("gps-l1ca".to_string(), wide)]),
            ..cfg
        };
        let t = cfg.at(k, Signal::GpsL1Ca, false, 70.0).unwrap();
        assert!((t[Statistic::SmoothedCode.index()] - 0.4 * k).abs() < 1e-12);
    }

    #[test]
    fn geos_take_their_own_table_where_there_is_one() {
        let mut geo = table();
        geo.code_m = vec![2.0; 3];
        let cfg = ThresholdConfig {
            false_alarm: 0.05,
            smoothed_code_m: 0.5,
            sigma: BTreeMap::from([
                ("bds-b1i".to_string(), table()),
                ("gps-l1ca".to_string(), table()),
            ]),
            sigma_geo: BTreeMap::from([("bds-b1i".to_string(), geo)]),
        };
        assert!(cfg.check().is_ok());
        let k = cfg.multiplier();
        let code = |signal, geo| cfg.at(k, signal, geo, 70.0).unwrap()[Statistic::Code.index()];
        assert!((code(Signal::BdsB1I, true) - 2.0 * k).abs() < 1e-12);
        assert!((code(Signal::BdsB1I, false) - 0.3 * k).abs() < 1e-12);
        // No GEO table for the signal: the common one.
        assert!((code(Signal::GpsL1Ca, true) - 0.3 * k).abs() < 1e-12);
        let bad = ThresholdConfig {
            sigma_geo: BTreeMap::from([("gal-e6".to_string(), table())]),
            ..cfg
        };
        assert!(bad.check().unwrap_err().contains("sigma_geo.gal-e6"));
    }

    #[test]
    fn bad_tables_are_refused_by_name() {
        let mut t = table();
        t.carrier_cycles.pop();
        assert!(t.check().unwrap_err().contains("carrier_cycles"));
        let cfg = ThresholdConfig {
            false_alarm: 1e-7,
            smoothed_code_m: 0.5,
            sigma: BTreeMap::from([("gal-e6".to_string(), table())]),
            sigma_geo: BTreeMap::new(),
        };
        assert!(
            cfg.check()
                .unwrap_err()
                .contains("sigma.gal-e6: not a signal")
        );
        let mut t = table();
        t.elevation_deg = vec![30.0, 10.0, 60.0];
        assert!(t.check().unwrap_err().contains("must increase"));
        let mut t = table();
        t.divergence_mps[1] = 0.0;
        assert!(t.check().unwrap_err().contains("divergence_mps"));
    }

    #[test]
    fn the_calibrator_gives_the_rms_per_bin_and_fills_empty_bins() {
        let mut c = SigmaCalibrator::new(vec![10.0, 30.0, 60.0]);
        let gps = Signal::GpsL1Ca;
        for stat in Statistic::ALL {
            c.add(gps, stat, 20.0, 3.0);
            c.add(gps, stat, 70.0, 1.0);
            c.add(gps, stat, 5.0, 100.0); // below the lowest edge: not counted
        }
        let mut other = SigmaCalibrator::new(vec![10.0, 30.0, 60.0]);
        for stat in Statistic::ALL {
            other.add(gps, stat, 20.0, -4.0);
            other.add(Signal::BdsB1I, stat, 40.0, 2.0);
        }
        c.merge(&other);
        let tables = c.tables();
        let t = &tables["gps-l1ca"];
        assert!((t.code_m[0] - 12.5f64.sqrt()).abs() < 1e-12);
        assert_eq!(t.code_m[1], t.code_m[0]);
        assert_eq!(t.carrier_cycles[2], 1.0);
        assert_eq!(c.counts(gps), vec![2, 0, 1]);
        assert_eq!(tables["bds-b1i"].code_m, vec![2.0; 3]);
        assert!(SigmaCalibrator::new(vec![10.0]).tables().is_empty());
    }
}
