//! The reduced-dynamic filter's state: a fixed block (orbit, clock, inter-system biases)
//! followed by states that come and go with the satellites ([`Slot`]): a range bias per
//! satellite, its signal-in-space error, and an ambiguity per carrier-phase arc.

use super::observed::ArcKey;
use nalgebra::{DMatrix, DVector};
use skyforge_orbits::Vec3;
use skyforge_orbits::ephemeris::SatId;

/// A state that exists while its satellite or arc is observed.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Slot {
    /// The satellite's range error (m): its broadcast orbit and clock against the truth.
    Bias(SatId),
    /// The arc's carrier-phase ambiguity (m).
    Ambiguity(ArcKey),
}

#[derive(Debug, Clone)]
pub(super) struct State {
    /// GPST of the state, seconds since the filter's start.
    pub t_s: f64,
    /// The receiver's epoch tag of the state (s since the start).
    pub tag_s: f64,
    pub x: DVector<f64>,
    pub p: DMatrix<f64>,
    /// The index of the first slot's state.
    pub first_slot: usize,
    /// The slots, in state order.
    pub slots: Vec<Slot>,
}

impl State {
    pub fn r_eci(&self) -> Vec3 {
        Vec3::new(self.x[0], self.x[1], self.x[2])
    }

    pub fn v_eci(&self) -> Vec3 {
        Vec3::new(self.x[3], self.x[4], self.x[5])
    }

    /// The state index of `slot`, if it exists.
    pub fn index(&self, slot: &Slot) -> Option<usize> {
        (self.slots.iter())
            .position(|s| s == slot)
            .map(|i| self.first_slot + i)
    }

    /// Keep the fixed block and the slots `keep` accepts, with their covariance.
    pub fn retain(&mut self, keep: impl Fn(&Slot) -> bool) {
        let kept: Vec<usize> = (0..self.first_slot)
            .chain(
                (self.slots.iter().enumerate())
                    .filter(|(_, s)| keep(s))
                    .map(|(i, _)| self.first_slot + i),
            )
            .collect();
        if kept.len() == self.x.len() {
            return;
        }
        self.slots = (kept[self.first_slot..].iter())
            .map(|&i| self.slots[i - self.first_slot])
            .collect();
        self.x = DVector::from_iterator(kept.len(), kept.iter().map(|&i| self.x[i]));
        self.p = DMatrix::from_fn(kept.len(), kept.len(), |i, j| self.p[(kept[i], kept[j])]);
    }

    /// A new slot with `value` and `variance`, uncorrelated with the rest.
    pub fn push(&mut self, slot: Slot, value: f64, variance: f64) {
        let n = self.x.len();
        self.x = self.x.clone().insert_row(n, value);
        self.p = self.p.clone().insert_row(n, 0.0).insert_column(n, 0.0);
        self.p[(n, n)] = variance;
        self.slots.push(slot);
    }

    /// State `k` starts again at `value` with `variance`, uncorrelated with the rest.
    pub fn restart(&mut self, k: usize, value: f64, variance: f64) {
        self.x[k] = value;
        self.p.row_mut(k).fill(0.0);
        self.p.column_mut(k).fill(0.0);
        self.p[(k, k)] = variance;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use skyforge_gnss::signal::Signal;

    /// Slots come and go with their covariance; the fixed block stays.
    #[test]
    fn slots_keep_their_covariance_when_others_leave() {
        let mut s = State {
            t_s: 0.0,
            tag_s: 0.0,
            x: DVector::from_vec(vec![1.0, 2.0]),
            p: DMatrix::from_diagonal(&DVector::from_vec(vec![1.0, 2.0])),
            first_slot: 2,
            slots: Vec::new(),
        };
        let arc = Slot::Ambiguity(ArcKey {
            sat: SatId::gps(3),
            signal: Signal::GpsL1Ca,
            second: None,
        });
        s.push(Slot::Bias(SatId::gps(1)), 10.0, 3.0);
        s.push(Slot::Bias(SatId::gps(2)), 20.0, 4.0);
        s.push(arc, 30.0, 5.0);
        s.p[(2, 4)] = 0.5;
        s.p[(4, 2)] = 0.5;
        s.retain(|slot| *slot != Slot::Bias(SatId::gps(2)));
        assert_eq!(s.x.as_slice(), [1.0, 2.0, 10.0, 30.0]);
        assert_eq!(s.index(&arc), Some(3));
        assert_eq!(s.p[(2, 3)], 0.5);
        assert_eq!(s.p[(3, 3)], 5.0);
        s.restart(3, 7.0, 9.0);
        assert_eq!((s.x[3], s.p[(2, 3)], s.p[(3, 3)]), (7.0, 0.0, 9.0));
    }
}
