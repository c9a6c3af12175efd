//! Which runs a study makes and with which seeds, how they are split into shards, and how
//! shards' results come back together. A run's seed derives from the study seed and the
//! run's index alone, so any shard layout gives every run the same result, and merged
//! results are sorted by run: the same bytes whatever the layout.

use super::file::Study;
use super::metrics::measure;
use super::summary::MetricSummary;
use skyforge_runner::run_at_level;

/// Largest shard count.
pub const MAX_SHARDS: u64 = 100_000;

/// The 64-bit finaliser of SplitMix64 (Steele, Lea & Flood 2014): distinct inputs give
/// well-mixed, distinct outputs.
fn splitmix64(x: u64) -> u64 {
    let mut z = x.wrapping_add(0x9e37_79b9_7f4a_7c15);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// The scenario seed of run `run` of a study seeded `study_seed`.
pub fn run_seed(study_seed: u64, run: u64) -> u64 {
    splitmix64(study_seed ^ splitmix64(run))
}

/// Shard `index` of `count` (1-based, as `--shard i/n` and Slurm array task ids): runs
/// `r` with `r % count == index - 1`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shard {
    pub index: u64,
    pub count: u64,
}

impl Shard {
    /// The whole study as one shard.
    pub const WHOLE: Shard = Shard { index: 1, count: 1 };

    /// The runs of this shard among `total`.
    pub fn runs(self, total: u64) -> impl Iterator<Item = u64> {
        (self.index - 1..total).step_by(self.count as usize)
    }

    /// Whether run `run` of a study of `total` runs is one of this shard's.
    pub fn holds(self, run: u64, total: u64) -> bool {
        run < total && run % self.count == self.index - 1
    }

    /// `shard-<i>-of-<n>`: the stem of its files.
    pub fn tag(self) -> String {
        format!("shard-{}-of-{}", self.index, self.count)
    }
}

impl std::str::FromStr for Shard {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        let bad = || format!("`{s}`: a shard is i/n with 1 <= i <= n <= {MAX_SHARDS}, e.g. 2/4");
        let (i, n) = s.split_once('/').ok_or_else(bad)?;
        let (index, count): (u64, u64) = (
            i.trim().parse().map_err(|_| bad())?,
            n.trim().parse().map_err(|_| bad())?,
        );
        if !(1..=count).contains(&index) || count > MAX_SHARDS {
            return Err(bad());
        }
        Ok(Self { index, count })
    }
}

/// One run's values, in the study's metric order.
#[derive(Debug, Clone, PartialEq)]
pub struct RunResult {
    pub run: u64,
    pub values: Vec<f64>,
}

impl Study {
    /// Grid point of run `run`.
    pub fn point_of(&self, run: u64) -> u64 {
        run / self.seeds
    }

    /// Make run `run`: its point's scenario with its seed, at the scenario's level,
    /// measured.
    pub fn run(&self, run: u64) -> Result<RunResult, String> {
        let seed = run_seed(self.seed, run);
        let scenario = self
            .point_scenario(self.point_of(run), seed)
            .map_err(|e| e.to_string())?;
        let made = run_at_level(&scenario).map_err(|e| format!("run {run}: {e}"))?;
        let values = measure(&made, &self.metrics).map_err(|e| format!("run {run}: {e}"))?;
        Ok(RunResult { run, values })
    }

    /// Every run of the study from the parts (shards' results, any order): each run once,
    /// sorted; an error names what is missing or repeated.
    pub fn merge(&self, parts: Vec<Vec<RunResult>>) -> Result<Vec<RunResult>, String> {
        let total = self.runs();
        let mut slots: Vec<Option<RunResult>> = Vec::new();
        slots.resize_with(usize::try_from(total).map_err(|e| e.to_string())?, || None);
        for r in parts.into_iter().flatten() {
            if r.values.len() != self.metrics.len() {
                return Err(format!(
                    "run {} holds {} values; the study keeps {} metrics",
                    r.run,
                    r.values.len(),
                    self.metrics.len()
                ));
            }
            let slot = usize::try_from(r.run)
                .ok()
                .and_then(|i| slots.get_mut(i))
                .ok_or_else(|| format!("run {} is not one of the study's {total}", r.run))?;
            match slot {
                Some(old)
                    if old
                        .values
                        .iter()
                        .map(|v| v.to_bits())
                        .ne(r.values.iter().map(|v| v.to_bits())) =>
                {
                    return Err(format!("run {} appears twice with different values", r.run));
                }
                _ => *slot = Some(r),
            }
        }
        let missing: Vec<u64> = (0..total)
            .filter(|&r| slots[r as usize].is_none())
            .collect();
        if let Some(first) = missing.first() {
            return Err(format!(
                "{} of {total} runs are missing (the first: run {first}; run r is in shard r % n + 1 of n)",
                missing.len()
            ));
        }
        Ok(slots.into_iter().flatten().collect())
    }

    /// Per point and metric, the summary of the point's runs (`runs` as [`Self::merge`]
    /// returns them).
    pub fn summarise(&self, runs: &[RunResult]) -> Vec<Vec<MetricSummary>> {
        // Each point's values per metric, gathered in one pass over the runs.
        let mut values: Vec<Vec<Vec<f64>>> = (0..self.points())
            .map(|_| vec![Vec::new(); self.metrics.len()])
            .collect();
        for r in runs {
            if let Some(point) = usize::try_from(self.point_of(r.run))
                .ok()
                .and_then(|p| values.get_mut(p))
            {
                for (column, v) in point.iter_mut().zip(&r.values) {
                    column.push(*v);
                }
            }
        }
        values
            .iter()
            .map(|point| point.iter().map(|v| MetricSummary::of(v)).collect())
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shards_partition_the_runs_whatever_their_count() {
        for count in 1..7u64 {
            let mut all: Vec<u64> = (1..=count)
                .flat_map(|i| Shard { index: i, count }.runs(20))
                .collect();
            all.sort_unstable();
            assert_eq!(all, (0..20).collect::<Vec<_>>(), "{count} shards");
        }
        assert_eq!(
            "2/4".parse::<Shard>().unwrap(),
            Shard { index: 2, count: 4 }
        );
        for bad in ["0/4", "5/4", "x/4", "4", "1/0", "1/1000000"] {
            assert!(bad.parse::<Shard>().is_err(), "{bad}");
        }
    }

    #[test]
    fn run_seeds_are_distinct_and_depend_on_the_study_seed() {
        let seeds: std::collections::HashSet<u64> = (0..10_000).map(|r| run_seed(1, r)).collect();
        assert_eq!(seeds.len(), 10_000);
        assert_ne!(run_seed(1, 5), run_seed(2, 5));
    }
}
