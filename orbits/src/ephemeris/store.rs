//! The ephemerides of a scenario, bound to its time origin, with selection by time and
//! health.
//!
//! Selection rule (what [`EphemerisStore::select`] implements):
//! 1. only healthy sets (health 0) are stored at all;
//! 2. a set is usable at `t` when `|t - toe| <= fit_interval / 2 + SELECT_MARGIN_S`; a
//!    Galileo set (I/NAV or F/NAV) only forward, when
//!    `-SELECT_MARGIN_S <= t - toe <= fit_interval + SELECT_MARGIN_S`: Galileo broadcasts
//!    a set from about its toe on (every transmission time in the bundled 2020 and 2023
//!    files is after the toe), and a set used 2 h before its toe is off by up to 18 m
//!    (measured against the 2020-06-25 precise orbits), 0.7-1 m at 2 h after;
//! 3. among the usable sets the one with the nearest toe wins; on a tie the later toe wins
//!    (a GPS set is normally broadcast from about 2 h before its toe: in the bundled files
//!    the set with toe 02:00 has a transmission time of 00:00:18, so at 01:00 a receiver
//!    holds the later set);
//! 4. only the two sets whose toes bracket `t` are considered (toes are sorted, so this is a
//!    binary search), which gives the nearest usable toe whenever fit intervals do not
//!    differ wildly between consecutive sets.
//!
//! Two healthy sets of one satellite with the same toe: the one read last is kept.

use super::{BoundEphemeris, BroadcastEphemeris, NavMessage, SatId};
use crate::time::TimeOrigin;

/// Tolerance added to half the fit interval (s): absorbs toe offsets of a few seconds
/// (GPS cut-over sets, BDT vs GPST rounding) at the edges of the interval.
pub const SELECT_MARGIN_S: f64 = 60.0;

/// All usable ephemerides per satellite, sorted by toe.
#[derive(Debug, Clone, Default)]
pub struct EphemerisStore {
    /// Per satellite, ephemerides sorted by `toe_s`.
    sats: Vec<(SatId, Vec<BoundEphemeris>)>,
}

impl EphemerisStore {
    /// Bind and index `ephemerides` (unhealthy sets dropped).
    pub fn new(ephemerides: Vec<BroadcastEphemeris>, origin: &TimeOrigin) -> Self {
        let mut store = Self::default();
        for eph in ephemerides.iter().filter(|e| e.health == 0) {
            store.insert(vec![eph.bind(origin)], eph.sat);
        }
        store
    }

    /// Add `list` to the satellite's sets, keeping them sorted and unique by toe (later
    /// entries win).
    fn insert(&mut self, list: Vec<BoundEphemeris>, sat: SatId) {
        let idx = match self.sats.binary_search_by_key(&sat, |(s, _)| *s) {
            Ok(i) => i,
            Err(i) => {
                self.sats.insert(i, (sat, Vec::new()));
                i
            }
        };
        let sets = &mut self.sats[idx].1;
        for b in list {
            let pos = sets.partition_point(|e| e.toe_s < b.toe_s);
            if sets.get(pos).is_some_and(|e| e.toe_s == b.toe_s) {
                sets[pos] = b;
            } else {
                sets.insert(pos, b);
            }
        }
    }

    /// Merge another store into this one.
    pub fn extend(&mut self, other: EphemerisStore) {
        for (sat, list) in other.sats {
            self.insert(list, sat);
        }
    }

    /// Satellites with at least one ephemeris, in order.
    pub fn satellites(&self) -> Vec<SatId> {
        self.sats.iter().map(|(s, _)| *s).collect()
    }

    /// The stored sets of `sat`, sorted by toe (empty when none).
    pub fn ephemerides(&self, sat: SatId) -> &[BoundEphemeris] {
        self.sats
            .binary_search_by_key(&sat, |(s, _)| *s)
            .map_or(&[], |i| self.sats[i].1.as_slice())
    }

    /// Keep only the listed satellites.
    pub fn retain(&mut self, keep: impl Fn(SatId) -> bool) {
        self.sats.retain(|(s, _)| keep(*s));
    }

    /// The ephemeris to use for `sat` at `t_s`: healthy, within its fit interval, nearest
    /// toe, ties to the later toe (see the module documentation for the full rule).
    pub fn select(&self, sat: SatId, t_s: f64) -> Option<&BoundEphemeris> {
        let sets = self.ephemerides(sat);
        let after = sets.partition_point(|e| e.toe_s <= t_s);
        let usable = |e: &&BoundEphemeris| usable_at(e, t_s);
        let before = after
            .checked_sub(1)
            .and_then(|i| sets.get(i))
            .filter(usable);
        let later = sets.get(after).filter(usable);
        match (before, later) {
            (Some(b), Some(l)) => {
                if l.toe_s - t_s <= t_s - b.toe_s {
                    Some(l)
                } else {
                    Some(b)
                }
            }
            (b, l) => b.or(l),
        }
    }
}

/// Whether `e` may be used at `t_s` (rule 2 of the module documentation).
fn usable_at(e: &BoundEphemeris, t_s: f64) -> bool {
    let age_s = t_s - e.toe_s;
    let fit_s = e.eph.fit_interval_s;
    match e.eph.message {
        NavMessage::GalileoInav | NavMessage::GalileoFnav => {
            (-SELECT_MARGIN_S..=fit_s + SELECT_MARGIN_S).contains(&age_s)
        }
        NavMessage::GpsLnav | NavMessage::BdsD1D2 => age_s.abs() <= 0.5 * fit_s + SELECT_MARGIN_S,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ephemeris::{ClockParams, HarmonicCorrections, KeplerElements, OrbitClass, SatId};
    use hifitime::{Epoch, TimeScale, Unit};

    fn origin() -> TimeOrigin {
        TimeOrigin::new(Epoch::from_gregorian(
            2020,
            6,
            25,
            0,
            0,
            0,
            0,
            TimeScale::GPST,
        ))
    }

    fn eph(sat: SatId, toe_h: f64, fit_h: f64, health: u32, iode: u32) -> BroadcastEphemeris {
        let toe = origin().start() + Unit::Hour * toe_h;
        let orbit = KeplerElements {
            sqrt_a: 5153.7,
            e: 0.01,
            i0: 0.96,
            omega0: 1.0,
            omega: 0.5,
            m0: 0.1,
            ..KeplerElements::default()
        };
        BroadcastEphemeris {
            iode,
            iodc: iode,
            health,
            ..BroadcastEphemeris::from_elements(
                sat,
                OrbitClass::Standard,
                toe,
                orbit,
                HarmonicCorrections::default(),
                ClockParams::default(),
                fit_h * 3600.0,
            )
        }
    }

    fn store() -> EphemerisStore {
        let g1 = SatId::gps(1);
        EphemerisStore::new(
            vec![
                eph(g1, 4.0, 4.0, 0, 3),
                eph(g1, 0.0, 4.0, 0, 1),
                eph(g1, 2.0, 4.0, 0, 2),
                eph(g1, 6.0, 4.0, 1, 4), // unhealthy: dropped
                eph(SatId::beidou(19), 1.0, 1.0, 0, 7),
            ],
            &origin(),
        )
    }

    fn iode_at(s: &EphemerisStore, sat: SatId, t_h: f64) -> Option<u32> {
        s.select(sat, t_h * 3600.0).map(|b| b.eph.iode)
    }

    #[test]
    fn drops_unhealthy_and_sorts() {
        let s = store();
        assert_eq!(s.satellites(), vec![SatId::gps(1), SatId::beidou(19)]);
        let toes: Vec<f64> = s
            .ephemerides(SatId::gps(1))
            .iter()
            .map(|b| b.toe_s)
            .collect();
        assert_eq!(toes, vec![0.0, 7200.0, 14_400.0]);
        assert!(s.ephemerides(SatId::gps(2)).is_empty());
    }

    #[test]
    fn nearest_toe_with_ties_to_the_later() {
        let s = store();
        let g1 = SatId::gps(1);
        assert_eq!(iode_at(&s, g1, 0.5), Some(1));
        assert_eq!(iode_at(&s, g1, 1.0), Some(2)); // tie between toe 0 h and 2 h
        assert_eq!(iode_at(&s, g1, 1.01), Some(2));
        assert_eq!(iode_at(&s, g1, 3.0), Some(3));
        // Past the last toe: usable up to fit/2 + margin.
        assert_eq!(iode_at(&s, g1, 6.0), Some(3));
        assert_eq!(
            s.select(g1, 6.0 * 3600.0 + SELECT_MARGIN_S + 1.0)
                .map(|b| b.eph.iode),
            None
        );
        // Before the first toe.
        assert_eq!(iode_at(&s, g1, -2.0), Some(1));
        assert_eq!(iode_at(&s, g1, -2.1), None);
    }

    #[test]
    fn galileo_sets_are_used_forward_from_their_toe() {
        let e5 = SatId::galileo(5);
        let s = EphemerisStore::new(
            vec![eph(e5, 1.0, 4.0, 0, 10), eph(e5, 3.0, 4.0, 0, 11)],
            &origin(),
        );
        // Before the first toe: only within the margin.
        assert_eq!(iode_at(&s, e5, 0.5), None);
        assert_eq!(
            s.select(e5, 3600.0 - SELECT_MARGIN_S).map(|b| b.eph.iode),
            Some(10)
        );
        // Between toes: the earlier set until the later one is broadcast.
        assert_eq!(iode_at(&s, e5, 2.9), Some(10));
        assert_eq!(iode_at(&s, e5, 3.0), Some(11));
        // After the last toe: the whole fit interval forward, not half of it.
        assert_eq!(iode_at(&s, e5, 6.9), Some(11));
        assert_eq!(iode_at(&s, e5, 7.1), None);
    }

    #[test]
    fn beidou_hourly_fit() {
        let s = store();
        let c19 = SatId::beidou(19);
        assert_eq!(iode_at(&s, c19, 1.5), Some(7));
        assert_eq!(iode_at(&s, c19, 1.55), None);
        assert_eq!(iode_at(&s, SatId::gps(9), 1.0), None);
    }

    #[test]
    fn extend_retain_and_duplicate_toe() {
        let mut s = store();
        let g1 = SatId::gps(1);
        let other = EphemerisStore::new(
            vec![eph(g1, 2.0, 4.0, 0, 22), eph(SatId::gps(3), 0.0, 4.0, 0, 5)],
            &origin(),
        );
        s.extend(other);
        assert_eq!(s.satellites(), vec![g1, SatId::gps(3), SatId::beidou(19)]);
        assert_eq!(s.ephemerides(g1).len(), 3);
        assert_eq!(iode_at(&s, g1, 2.0), Some(22));
        s.retain(|sat| sat.system == crate::ephemeris::System::Gps);
        assert_eq!(s.satellites(), vec![g1, SatId::gps(3)]);
    }
}
