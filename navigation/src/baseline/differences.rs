//! Which satellites and signals enter the double differences of an epoch (thesis 2.3),
//! and the double-differenced observation vector of one baseline (eqs. 2.3-9, 2.4-35).

use super::BaselineError;
use crate::pvt::SatView;
use nalgebra::{DVector, Vector3};
use skyforge_gnss::observation::ObsRecord;
use skyforge_gnss::signal::Signal;
use skyforge_orbits::ephemeris::{SatId, System};

/// The direction of a satellite from the master antenna: what a double-difference row
/// needs of the geometry (eq. 2.3-10).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LineOfSight {
    pub sat: SatId,
    /// Unit vector from the master antenna to the satellite, ECEF.
    pub los_ecef: Vector3<f64>,
    pub elevation_rad: f64,
    /// Gradient (m per m, ECEF) of the satellite's delay along the path at the master
    /// antenna, for a delay that differs between the antennas (the troposphere between
    /// ground stations, [`crate::relative::troposphere`]); zero when it cancels.
    pub delay_gradient: Vector3<f64>,
}

impl LineOfSight {
    /// From the single-point solution's view of `sat` (elevation 90 deg when the view has
    /// no receiver position yet: every satellite then weighs alike).
    pub fn from_view(sat: SatId, view: &SatView) -> Self {
        Self {
            sat,
            los_ecef: view.los,
            elevation_rad: view
                .az_el_rad
                .map_or(std::f64::consts::FRAC_PI_2, |(_, e)| e),
            delay_gradient: Vector3::zeros(),
        }
    }

    /// The direction `d` with which the observed range (geometry and delay) of an antenna
    /// at baseline `b` from the master is the master's minus `d . b`, to first order.
    pub fn model_direction(&self) -> Vector3<f64> {
        self.los_ecef - self.delay_gradient
    }
}

/// The double differences of one signal: every satellite in `others` minus `reference`.
#[derive(Debug, Clone, PartialEq)]
pub struct DdBlock {
    pub signal: Signal,
    pub reference: LineOfSight,
    pub others: Vec<LineOfSight>,
}

/// The double differences of an epoch, signal by signal; phase rows come first, in block
/// order, then code rows in the same order (eq. 2.4-35).
#[derive(Debug, Clone, PartialEq)]
pub struct DdLayout {
    pub blocks: Vec<DdBlock>,
}

/// The record of `sat` on `signal` if it has both phase and code.
fn usable(records: &[ObsRecord], sat: SatId, signal: Signal) -> Option<&ObsRecord> {
    records.iter().find(|r| {
        r.sat == sat
            && r.signal == signal
            && r.carrier_phase_cycles.is_some_and(f64::is_finite)
            && r.pseudorange_m.is_some_and(f64::is_finite)
    })
}

impl DdLayout {
    /// The double differences an epoch allows: for each system and each of its
    /// `signals`, the satellites that every antenna observed with phase and code on that
    /// signal and that `views` has. The system's reference satellite (eq. 2.3-10) is the
    /// highest of those observed on every one of its signals, shared by all its signals
    /// (eqs. 2.4-46..2.4-49); a satellite missing a signal still enters the others' blocks
    /// (a receiver that has not yet timed L5 on some satellites keeps their L1 C/A). When
    /// no satellite has every signal, each signal takes its own highest. A signal with
    /// fewer than two satellites is left out.
    pub fn select(
        antennas: &[&[ObsRecord]],
        views: &[LineOfSight],
        signals: &[Signal],
    ) -> Result<Self, BaselineError> {
        if antennas.len() < 2 {
            return Err(BaselineError::TooFewAntennas(antennas.len()));
        }
        // Highest first; ties broken by satellite so the choice is deterministic.
        let mut by_elevation: Vec<LineOfSight> = views.to_vec();
        by_elevation.sort_by(|a, b| {
            b.elevation_rad
                .total_cmp(&a.elevation_rad)
                .then(a.sat.cmp(&b.sat))
        });
        let observed = |v: &LineOfSight, signal: Signal| {
            antennas
                .iter()
                .all(|records| usable(records, v.sat, signal).is_some())
        };
        let mut blocks = Vec::new();
        for system in [System::Gps, System::Beidou, System::Galileo] {
            let system_signals: Vec<Signal> = signals
                .iter()
                .copied()
                .filter(|s| s.system() == system)
                .collect();
            let shared = by_elevation
                .iter()
                .filter(|v| v.sat.system == system)
                .find(|v| system_signals.iter().all(|&s| observed(v, s)));
            for signal in system_signals {
                let seen: Vec<LineOfSight> = by_elevation
                    .iter()
                    .filter(|v| v.sat.system == system && observed(v, signal))
                    .copied()
                    .collect();
                let Some(&reference) = shared.or(seen.first()) else {
                    continue;
                };
                let mut others: Vec<LineOfSight> = seen
                    .into_iter()
                    .filter(|v| v.sat != reference.sat)
                    .collect();
                if others.is_empty() {
                    continue;
                }
                others.sort_by_key(|v| v.sat);
                blocks.push(DdBlock {
                    signal,
                    reference,
                    others,
                });
            }
        }
        let layout = Self { blocks };
        if layout.ambiguity_count() < 3 {
            let found = layout.blocks.iter().map(|b| b.others.len()).sum();
            return Err(BaselineError::TooFewDoubleDifferences { found });
        }
        Ok(layout)
    }

    /// Number of double differences of one observation type (= ambiguities per baseline).
    pub fn ambiguity_count(&self) -> usize {
        self.blocks.iter().map(|b| b.others.len()).sum()
    }

    /// The (signal, satellite, reference satellite) of each ambiguity, in row order.
    pub fn ambiguity_ids(&self) -> impl Iterator<Item = (Signal, SatId, SatId)> + '_ {
        self.blocks.iter().flat_map(|b| {
            b.others
                .iter()
                .map(move |o| (b.signal, o.sat, b.reference.sat))
        })
    }

    /// Double-differenced phase (m) and code (m) of the baseline from `master` to `rover`,
    /// phase rows first (eqs. 2.3-9, 2.4-35): `(rover - master)` for each satellite minus
    /// the same for the reference satellite.
    pub fn double_differences(
        &self,
        master: &[ObsRecord],
        rover: &[ObsRecord],
    ) -> Result<DVector<f64>, BaselineError> {
        let n = self.ambiguity_count();
        let mut y = DVector::zeros(2 * n);
        let mut row = 0;
        for block in &self.blocks {
            let lambda = block.signal.wavelength_m();
            let sd = |sat: SatId| -> Result<(f64, f64), BaselineError> {
                let missing = BaselineError::MissingObservation {
                    sat,
                    signal: block.signal,
                };
                let m = usable(master, sat, block.signal).ok_or(missing.clone())?;
                let r = usable(rover, sat, block.signal).ok_or(missing)?;
                let phase = |x: &ObsRecord| x.carrier_phase_cycles.unwrap_or(f64::NAN);
                let code = |x: &ObsRecord| x.pseudorange_m.unwrap_or(f64::NAN);
                Ok((lambda * (phase(r) - phase(m)), code(r) - code(m)))
            };
            let (ref_phase, ref_code) = sd(block.reference.sat)?;
            for other in &block.others {
                let (phase, code) = sd(other.sat)?;
                y[row] = phase - ref_phase;
                y[n + row] = code - ref_code;
                row += 1;
            }
        }
        Ok(y)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A view of `sat` at `elevation_deg`.
    fn view(sat: SatId, elevation_deg: f64) -> LineOfSight {
        let e = elevation_deg.to_radians();
        LineOfSight {
            sat,
            los_ecef: Vector3::new(e.cos(), 0.0, e.sin()),
            elevation_rad: e,
            delay_gradient: Vector3::zeros(),
        }
    }

    /// Every `(sat, signal)` of `have` with phase and code.
    fn records(have: &[(SatId, Signal)]) -> Vec<ObsRecord> {
        have.iter()
            .map(|&(sat, signal)| ObsRecord::complete(sat, signal, 2e7, 1e8, 0.0, 45.0))
            .collect()
    }

    fn block(layout: &DdLayout, signal: Signal) -> (SatId, Vec<SatId>) {
        let b = layout.blocks.iter().find(|b| b.signal == signal).unwrap();
        (b.reference.sat, b.others.iter().map(|o| o.sat).collect())
    }

    /// GPS on L1 C/A and L5 with G3 missing L5 at one antenna and the highest satellite
    /// (G1) missing L5 everywhere, Galileo on E1: G3 keeps its L1 C/A double difference;
    /// the shared GPS reference is the highest satellite with both signals (G2), not G1;
    /// Galileo forms its own block.
    #[test]
    fn a_satellite_missing_a_signal_keeps_its_other_signals() {
        let (g, e) = (SatId::gps, SatId::galileo);
        let views = [
            view(g(1), 80.0),
            view(g(2), 70.0),
            view(g(3), 60.0),
            view(g(4), 50.0),
            view(g(5), 40.0),
            view(e(11), 65.0),
            view(e(12), 55.0),
            view(e(13), 45.0),
        ];
        let mut full = vec![(g(1), Signal::GpsL1Ca), (e(11), Signal::GalE1)];
        for n in 2..=5 {
            full.push((g(n), Signal::GpsL1Ca));
            full.push((g(n), Signal::GpsL5));
        }
        full.extend([(e(12), Signal::GalE1), (e(13), Signal::GalE1)]);
        let partial: Vec<_> = full
            .iter()
            .copied()
            .filter(|&p| p != (g(3), Signal::GpsL5))
            .collect();
        let (a, b) = (records(&full), records(&partial));
        let antennas: [&[ObsRecord]; 3] = [&a, &a, &b];
        let signals = [Signal::GpsL1Ca, Signal::GpsL5, Signal::GalE1];
        let layout = DdLayout::select(&antennas, &views, &signals).unwrap();
        assert_eq!(
            block(&layout, Signal::GpsL1Ca),
            (g(2), vec![g(1), g(3), g(4), g(5)])
        );
        assert_eq!(block(&layout, Signal::GpsL5), (g(2), vec![g(4), g(5)]));
        assert_eq!(block(&layout, Signal::GalE1), (e(11), vec![e(12), e(13)]));
        assert_eq!(layout.ambiguity_count(), 8);
    }

    /// Every satellite on every signal: one reference per system (its highest), the same
    /// satellites in each of its blocks.
    #[test]
    fn satellites_with_every_signal_share_one_reference() {
        let g = SatId::gps;
        let views = [view(g(1), 30.0), view(g(2), 70.0), view(g(3), 50.0)];
        let have: Vec<_> = (1..=3)
            .flat_map(|n| [(g(n), Signal::GpsL1Ca), (g(n), Signal::GpsL5)])
            .collect();
        let a = records(&have);
        let antennas: [&[ObsRecord]; 2] = [&a, &a];
        let layout =
            DdLayout::select(&antennas, &views, &[Signal::GpsL1Ca, Signal::GpsL5]).unwrap();
        for signal in [Signal::GpsL1Ca, Signal::GpsL5] {
            assert_eq!(block(&layout, signal), (g(2), vec![g(1), g(3)]));
        }
    }
}
