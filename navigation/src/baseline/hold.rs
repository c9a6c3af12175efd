//! Ambiguity hold between epochs: integers once fixed are kept while the carrier stays
//! locked, re-expressed when the reference satellite changes, and dropped on a cycle slip.
//!
//! Per baseline and signal the hold keeps single-difference integers relative to a pivot
//! satellite, `H(i) = N_sd(i) - N_sd(pivot)`; the double difference against any reference
//! `r` held alongside is then `H(i) - H(r)` (eq. 2.3-9), whichever satellite was the
//! reference when they were fixed.

use super::differences::DdLayout;
use skyforge_gnss::signal::Signal;
use skyforge_orbits::ephemeris::SatId;
use std::collections::BTreeMap;

/// The held integers of one baseline and signal.
#[derive(Debug, Clone, PartialEq)]
struct HeldSet {
    baseline: usize,
    signal: Signal,
    pivot: SatId,
    /// `N_sd(sat) - N_sd(pivot)`; the pivot itself holds 0.
    values: BTreeMap<SatId, i64>,
}

/// Integers held between epochs for every baseline and signal.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct AmbiguityHold {
    sets: Vec<HeldSet>,
}

impl AmbiguityHold {
    /// Nothing held.
    pub fn new() -> Self {
        Self::default()
    }

    fn set(&self, baseline: usize, signal: Signal) -> Option<&HeldSet> {
        self.sets
            .iter()
            .find(|s| s.baseline == baseline && s.signal == signal)
    }

    /// The held double-difference integers of `layout` for `baselines` baselines, in the
    /// order of vec(N) (baseline 1's ambiguities first); `None` where not held.
    pub fn lookup(&self, layout: &DdLayout, baselines: usize) -> Vec<Option<i64>> {
        let mut out = Vec::with_capacity(layout.ambiguity_count() * baselines);
        for k in 0..baselines {
            for (signal, sat, reference) in layout.ambiguity_ids() {
                let held = self
                    .set(k, signal)
                    .and_then(|s| Some(s.values.get(&sat)? - s.values.get(&reference)?));
                out.push(held);
            }
        }
        out
    }

    /// Keep the fixed double differences `values` (vec(N) order, `None` = not fixed) of
    /// `layout`. A set whose pivot is not the new reference and does not hold it starts
    /// again from the new reference.
    pub fn store(&mut self, layout: &DdLayout, baselines: usize, values: &[Option<i64>]) {
        let n = layout.ambiguity_count();
        for k in 0..baselines {
            let mut row = k * n;
            for block in &layout.blocks {
                let reference = block.reference.sat;
                let fixed: Vec<(SatId, i64)> = block
                    .others
                    .iter()
                    .zip(&values[row..row + block.others.len()])
                    .filter_map(|(o, v)| Some((o.sat, (*v)?)))
                    .collect();
                row += block.others.len();
                if fixed.is_empty() {
                    continue;
                }
                let at = self
                    .sets
                    .iter()
                    .position(|s| s.baseline == k && s.signal == block.signal);
                let base = at.and_then(|i| self.sets[i].values.get(&reference).copied());
                let set = match (at, base) {
                    (Some(i), Some(_)) => &mut self.sets[i],
                    _ => {
                        if let Some(i) = at {
                            self.sets.remove(i);
                        }
                        self.sets.push(HeldSet {
                            baseline: k,
                            signal: block.signal,
                            pivot: reference,
                            values: BTreeMap::from([(reference, 0)]),
                        });
                        let last = self.sets.len() - 1;
                        &mut self.sets[last]
                    }
                };
                let base = base.unwrap_or(0);
                for (sat, dd) in fixed {
                    set.values.insert(sat, dd + base);
                }
            }
        }
    }

    /// A cycle slip (loss of lock) of `sat` on `signal` at any antenna: its integers go;
    /// if it was a pivot, every integer of that set goes with it.
    pub fn slip(&mut self, sat: SatId, signal: Signal) {
        self.sets.retain_mut(|s| {
            if s.signal != signal {
                return true;
            }
            if s.pivot == sat {
                return false;
            }
            s.values.remove(&sat);
            true
        });
    }

    /// Forget everything (e.g. after the held integers failed a consistency test).
    pub fn clear(&mut self) {
        self.sets.clear();
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::baseline::differences::{DdBlock, LineOfSight};
    use nalgebra::Vector3;

    fn los(prn: u8) -> LineOfSight {
        LineOfSight {
            sat: SatId::gps(prn),
            los_ecef: Vector3::z(),
            elevation_rad: 1.0,
            delay_gradient: Vector3::zeros(),
        }
    }

    fn layout(reference: u8, others: &[u8]) -> DdLayout {
        DdLayout {
            blocks: vec![DdBlock {
                signal: Signal::GpsL1Ca,
                reference: los(reference),
                others: others.iter().map(|&p| los(p)).collect(),
            }],
        }
    }

    /// Single-difference integers of two baselines; double differences follow from them.
    const SD: [[i64; 6]; 2] = [[0, 17, -4, 250, 9, -31], [0, -2, 88, 5, 13, 40]];

    fn dd(reference: u8, others: &[u8]) -> Vec<Option<i64>> {
        (0..2)
            .flat_map(|k| {
                others
                    .iter()
                    .map(move |&p| Some(SD[k][p as usize] - SD[k][reference as usize]))
            })
            .collect()
    }

    #[test]
    fn held_integers_follow_a_change_of_reference() {
        let mut hold = AmbiguityHold::new();
        hold.store(&layout(1, &[2, 3, 4]), 2, &dd(1, &[2, 3, 4]));
        // Satellite 3 becomes the reference: the held values re-express exactly.
        assert_eq!(hold.lookup(&layout(3, &[1, 2, 4]), 2), dd(3, &[1, 2, 4]));
        // A satellite never fixed is not held.
        let got = hold.lookup(&layout(3, &[2, 5]), 2);
        assert_eq!(got, vec![dd(3, &[2])[0], None, dd(3, &[2])[1], None]);
    }

    #[test]
    fn new_fixes_join_a_set_through_a_held_reference() {
        let mut hold = AmbiguityHold::new();
        hold.store(&layout(1, &[2, 3]), 2, &dd(1, &[2, 3]));
        hold.store(&layout(2, &[5]), 2, &dd(2, &[5]));
        assert_eq!(hold.lookup(&layout(1, &[3, 5]), 2), dd(1, &[3, 5]));
    }

    #[test]
    fn a_slip_drops_the_satellite_and_a_pivot_slip_drops_the_set() {
        let mut hold = AmbiguityHold::new();
        hold.store(&layout(1, &[2, 3]), 2, &dd(1, &[2, 3]));
        hold.slip(SatId::gps(3), Signal::GpsL1Ca);
        assert_eq!(
            hold.lookup(&layout(1, &[2, 3]), 2),
            vec![dd(1, &[2])[0], None, dd(1, &[2])[1], None]
        );
        hold.slip(SatId::gps(1), Signal::GpsL1Ca);
        assert_eq!(hold.lookup(&layout(2, &[4]), 2), vec![None, None]);
        assert_eq!(hold.lookup(&layout(1, &[2]), 2), vec![None, None]);
    }
}
