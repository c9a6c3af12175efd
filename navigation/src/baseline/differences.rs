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
    /// The double differences an epoch allows: for each system, the satellites that every
    /// antenna observed with phase and code on every one of `signals` of that system and
    /// that `views` has; the highest of them is the system's reference satellite
    /// (eq. 2.3-10). A system with fewer than two such satellites is left out.
    pub fn select(
        antennas: &[&[ObsRecord]],
        views: &[LineOfSight],
        signals: &[Signal],
    ) -> Result<Self, BaselineError> {
        if antennas.len() < 2 {
            return Err(BaselineError::TooFewAntennas(antennas.len()));
        }
        let mut blocks = Vec::new();
        for system in [System::Gps, System::Beidou] {
            let system_signals: Vec<Signal> = signals
                .iter()
                .copied()
                .filter(|s| s.system() == system)
                .collect();
            if system_signals.is_empty() {
                continue;
            }
            let mut common: Vec<LineOfSight> = views
                .iter()
                .filter(|v| v.sat.system == system)
                .filter(|v| {
                    system_signals.iter().all(|&signal| {
                        antennas
                            .iter()
                            .all(|records| usable(records, v.sat, signal).is_some())
                    })
                })
                .copied()
                .collect();
            if common.len() < 2 {
                continue;
            }
            // Highest first; ties broken by satellite so the choice is deterministic.
            common.sort_by(|a, b| {
                b.elevation_rad
                    .total_cmp(&a.elevation_rad)
                    .then(a.sat.cmp(&b.sat))
            });
            let reference = common[0];
            let mut others = common[1..].to_vec();
            others.sort_by_key(|v| v.sat);
            for signal in system_signals {
                blocks.push(DdBlock {
                    signal,
                    reference,
                    others: others.clone(),
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
