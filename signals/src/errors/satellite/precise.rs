//! Precise orbits and clocks (SP3) as the satellites' truth: the signal leaves from where
//! an analysis centre's final product puts the satellite, while the navigation message
//! broadcasts the day's broadcast ephemeris, so the user sees the real broadcast errors of
//! that day.
//!
//! - Positions: Lagrange interpolation of degree 9 (the ten nodes centred on the interval,
//!   the usual choice for 15-min SP3 orbits, Schenewerk 2003, GPS Solutions 7). Two
//!   neighbouring intervals' polynomials share the node between them, so the path is
//!   continuous; its velocity jumps there by the interpolation error's rate, about 1e-5
//!   m/s for GPS orbits, far below any Doppler that matters.
//! - SP3 positions are centres of mass, broadcast orbits antenna phase centres. The offset
//!   (0.5 to 2.6 m for GPS blocks, almost all along the nadir-pointing body axis) is taken
//!   as each satellite's mean radial difference broadcast - precise over the run (with a
//!   two-hour margin) and added along the radial; this also removes a constant radial
//!   bias of the broadcast orbit, which the statistics of the SISRE literature keep.
//! - Clocks: linear interpolation of the SP3 clocks. A precise product's clocks refer to
//!   its own time scale, so (as the SISRE literature does) the mean over each system's
//!   satellites of (precise - broadcast) at every SP3 epoch is removed, interpolated
//!   linearly. SP3 clocks exclude the periodic relativistic correction (IGS convention),
//!   so it is added from the broadcast state, -2 r.v / c^2.
//!
//! A satellite without precise positions over the whole run follows its broadcast
//! ephemeris.

use skyforge_orbits::Vec3;
use skyforge_orbits::constants::C_MPS;
use skyforge_orbits::ephemeris::{BoundEphemeris, EphemerisStore, SatId, Sp3Record, System};
use skyforge_orbits::time::TimeOrigin;
use std::collections::BTreeMap;

/// Nodes of each interpolating polynomial (degree 9).
const LAGRANGE_NODES: usize = 10;
/// Margin around the run within which the means (antenna offset, clock datum) are taken.
const STATISTICS_MARGIN_S: f64 = 7200.0;
/// Time beyond the run a precise orbit must cover with centred windows (light times,
/// stencils and receiver look-backs stay well inside).
const COVER_MARGIN_S: f64 = 600.0;

/// One satellite's precise orbit and clock.
#[derive(Debug, Clone, PartialEq)]
pub struct PreciseOrbit {
    /// SP3 epochs, seconds from the run's start, increasing.
    t_s: Vec<f64>,
    r_ecef_m: Vec<Vec3>,
    /// Clock (s) minus its system's datum at each epoch; NaN where missing.
    clock_s: Vec<f64>,
    /// Broadcast APC - precise CoM along the radial (m), added to the CoM.
    apc_radial_m: f64,
}

/// The periodic relativistic clock correction -2 r.v / c^2 (s) of a broadcast state.
fn relativistic_s(eph: &BoundEphemeris, t_s: f64) -> f64 {
    let (r, v) = eph.state_ecef(t_s);
    -2.0 * r.dot(&v) / (C_MPS * C_MPS)
}

impl PreciseOrbit {
    /// The antenna phase centre at `t_s` (m, Earth-fixed).
    pub fn position_ecef(&self, t_s: f64) -> Vec3 {
        let com = self.centre_of_mass(t_s);
        com + com.normalize() * self.apc_radial_m
    }

    /// Degree-9 Lagrange interpolation of the centre of mass.
    fn centre_of_mass(&self, t_s: f64) -> Vec3 {
        let n = self.t_s.len();
        let after = self.t_s.partition_point(|&t| t <= t_s);
        let first = after
            .saturating_sub(LAGRANGE_NODES / 2)
            .min(n - LAGRANGE_NODES);
        let nodes = first..first + LAGRANGE_NODES;
        let mut sum = Vec3::zeros();
        for j in nodes.clone() {
            let w: f64 = nodes
                .clone()
                .filter(|&m| m != j)
                .map(|m| (t_s - self.t_s[m]) / (self.t_s[j] - self.t_s[m]))
                .product();
            sum += self.r_ecef_m[j] * w;
        }
        sum
    }

    /// The clock (s, datum removed, relativistic correction excluded) at `t_s`, linear
    /// between SP3 epochs; NaN next to a missing one.
    pub fn clock_s(&self, t_s: f64) -> f64 {
        let k = self
            .t_s
            .partition_point(|&t| t <= t_s)
            .clamp(1, self.t_s.len() - 1);
        let (t0, t1) = (self.t_s[k - 1], self.t_s[k]);
        let u = (t_s - t0) / (t1 - t0);
        self.clock_s[k - 1] * (1.0 - u) + self.clock_s[k] * u
    }

    /// Clock error against `eph` (s): the precise clock plus the relativistic correction,
    /// less the broadcast clock.
    pub fn clock_error_s(&self, eph: &BoundEphemeris, t_s: f64) -> f64 {
        self.clock_s(t_s) + relativistic_s(eph, t_s) - eph.clock_offset_s(t_s)
    }
}

/// Build the precise orbits of `satellites` from `records` for a run of `duration_s`
/// from `origin`, with `store`'s broadcast ephemerides for the antenna offsets and the
/// clock datum.
pub fn precise_orbits(
    records: &[Sp3Record],
    origin: &TimeOrigin,
    store: &EphemerisStore,
    satellites: &[SatId],
    duration_s: f64,
) -> BTreeMap<SatId, PreciseOrbit> {
    let mut by_sat: BTreeMap<SatId, Vec<(f64, Vec3, Option<f64>)>> = BTreeMap::new();
    for r in records.iter().filter(|r| satellites.contains(&r.sat)) {
        let t = (r.epoch - origin.start()).to_seconds();
        by_sat
            .entry(r.sat)
            .or_default()
            .push((t, r.r_ecef_m, r.clock_s));
    }
    let in_statistics =
        |t: f64| (-STATISTICS_MARGIN_S..=duration_s + STATISTICS_MARGIN_S).contains(&t);
    // Each system's clock datum per epoch: the mean of precise + relativity - broadcast.
    let mut datum: BTreeMap<(System, i64), (f64, usize)> = BTreeMap::new();
    for (&sat, rows) in &by_sat {
        for &(t, _, clock) in rows.iter().filter(|(t, ..)| in_statistics(*t)) {
            if let (Some(c), Some(eph)) = (clock, store.select(sat, t)) {
                let e = datum.entry((sat.system, t.round() as i64)).or_default();
                e.0 += c + relativistic_s(eph, t) - eph.clock_offset_s(t);
                e.1 += 1;
            }
        }
    }
    let mut out = BTreeMap::new();
    for (sat, mut rows) in by_sat {
        rows.sort_by(|a, b| a.0.total_cmp(&b.0));
        rows.dedup_by(|a, b| a.0 == b.0);
        let covers = rows.len() >= LAGRANGE_NODES
            && rows[LAGRANGE_NODES / 2 - 1].0 <= -COVER_MARGIN_S
            && rows[rows.len() - LAGRANGE_NODES / 2].0 >= duration_s + COVER_MARGIN_S;
        if !covers {
            continue;
        }
        let radial: Vec<f64> = rows
            .iter()
            .filter(|(t, ..)| in_statistics(*t))
            .filter_map(|&(t, r, _)| {
                let eph = store.select(sat, t)?;
                Some((eph.position_ecef(t) - r).dot(&r.normalize()))
            })
            .collect();
        let apc_radial_m = radial.iter().sum::<f64>() / radial.len().max(1) as f64;
        let clock_s = rows
            .iter()
            .map(|&(t, _, c)| {
                let mean = datum
                    .get(&(sat.system, t.round() as i64))
                    .map_or(f64::NAN, |(sum, n)| sum / *n as f64);
                c.map_or(f64::NAN, |c| c - mean)
            })
            .collect();
        out.insert(
            sat,
            PreciseOrbit {
                t_s: rows.iter().map(|r| r.0).collect(),
                r_ecef_m: rows.iter().map(|r| r.1).collect(),
                clock_s,
                apc_radial_m,
            },
        );
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Lagrange interpolation of degree 9 reproduces a polynomial of degree 9 exactly, and
    /// neighbouring intervals meet at their shared node.
    #[test]
    fn interpolation_is_exact_for_degree_nine_and_continuous() {
        let f = |t: f64| {
            let u = t / 14_400.0;
            Vec3::new(
                2.0e7 + 3.0e3 * u.powi(9) - 1e4 * u.powi(4),
                1.0e7 + 2e4 * u.powi(7),
                -1.5e7 + 5.0e5 * u.powi(2),
            )
        };
        let t_s: Vec<f64> = (-8..=16).map(|k| f64::from(k) * 900.0).collect();
        let orbit = PreciseOrbit {
            r_ecef_m: t_s.iter().map(|&t| f(t)).collect(),
            clock_s: t_s.iter().map(|&t| 1e-4 + 1e-11 * t).collect(),
            t_s,
            apc_radial_m: 0.0,
        };
        for t in [-3000.0, 0.0, 123.4, 4500.0, 8999.0] {
            let err = (orbit.centre_of_mass(t) - f(t)).norm();
            assert!(err < 1e-5, "{t}: {err}");
            assert!((orbit.clock_s(t) - (1e-4 + 1e-11 * t)).abs() < 1e-18);
        }
        let node = 2700.0;
        let (a, b) = (
            orbit.centre_of_mass(node - 1e-6),
            orbit.centre_of_mass(node + 1e-6),
        );
        assert!((a - b).norm() < 1e-4);
    }
}
