//! The epoch stage `pvt`: single-point position, velocity and time per antenna, with RAIM.

use super::{EpochInput, EpochStage, LastFix};
use crate::pipeline::AntennaFix;
use skyforge_navigation::pvt::{
    CarrierSmoother, Fix, Measurement, PvtConfig, PvtError, solve, solve_velocity,
};
use skyforge_orbits::Vec3;

/// Single-point position, velocity and time of each antenna (with RAIM), the previous fix
/// as the a-priori position.
pub(super) struct PvtStage {
    config: PvtConfig,
    last_fix: Vec<Option<LastFix>>,
    /// Per antenna, with `[pvt.carrier_smoothing]`.
    smoothers: Vec<CarrierSmoother>,
}

impl PvtStage {
    /// The stage for `antennas` antennas, with the PVT settings `config`.
    pub(super) fn new(config: PvtConfig, antennas: usize) -> Self {
        let smoothers = match config.carrier_smoothing {
            Some(c) => vec![CarrierSmoother::new(c); antennas],
            None => Vec::new(),
        };
        Self {
            config,
            last_fix: vec![None; antennas],
            smoothers,
        }
    }

    fn fix(&mut self, antenna: usize, input: &EpochInput<'_>) -> AntennaFix {
        let (nav, t_k) = (input.nav, input.t_s);
        let meas: Vec<Measurement> = input
            .observations
            .iter()
            .filter(|o| o.antenna == antenna && nav.has_ephemeris(o.sat, t_k))
            .map(|o| Measurement {
                sat: o.sat,
                pseudorange_m: self
                    .smoothers
                    .get_mut(antenna)
                    .and_then(|s| s.smooth_record(&o.record(), t_k))
                    .unwrap_or(o.pseudorange_m),
                doppler_hz: o.doppler_hz.is_finite().then_some(o.doppler_hz),
                signal: o.signal,
            })
            .collect();
        let (Some(origin), store) = (nav.origin(), nav.store()) else {
            return AntennaFix {
                antenna,
                fix: Err(PvtError::TooFewSatellites {
                    have: 0,
                    need: 4,
                    clocks: 1,
                }),
                velocity: None,
            };
        };
        let cfg = PvtConfig {
            iono_gps: nav.iono_gps,
            iono_bds: nav.iono_bds,
            ..self.config.clone()
        };
        let a_priori = self.last_fix[antenna].map(|f| f.r_ecef_m);
        let fix: Result<Fix, _> = solve(&meas, t_k, store, origin, &cfg, a_priori);
        let velocity = fix
            .as_ref()
            .ok()
            .and_then(|f| solve_velocity(&meas, t_k, store, f).ok());
        if let Ok(f) = &fix {
            self.last_fix[antenna] = Some(LastFix {
                t_s: t_k,
                r_ecef_m: f.r_ecef_m,
                v_ecef_mps: velocity.map_or(Vec3::zeros(), |v| v.v_ecef_mps),
            });
        }
        AntennaFix {
            antenna,
            fix,
            velocity,
        }
    }
}

impl EpochStage for PvtStage {
    fn epoch(&mut self, input: &EpochInput<'_>) -> Vec<AntennaFix> {
        (0..self.last_fix.len())
            .map(|antenna| self.fix(antenna, input))
            .collect()
    }

    fn last_fix(&self, antenna: usize) -> Option<LastFix> {
        self.last_fix.get(antenna).copied().flatten()
    }
}
