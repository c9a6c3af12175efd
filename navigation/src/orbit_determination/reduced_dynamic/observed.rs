//! One epoch's observations as the reduced-dynamic filter takes them: one ranging per
//! satellite ([`crate::pvt::per_satellite`]: one signal, or the ionosphere-free
//! combination of two carriers) with its range rate, carrier phase and lock.

use crate::pvt::{IonosphereCorrection, Measurement, Ranging, per_satellite};
use skyforge_gnss::observation::{LLI_LOSS_OF_LOCK, ObsRecord};
use skyforge_gnss::signal::Signal;
use skyforge_orbits::constants::C_MPS;
use skyforge_orbits::ephemeris::{SatId, System};

/// One carrier-phase arc: a ranging whose ambiguity is a state while lock is kept.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct ArcKey {
    pub sat: SatId,
    pub signal: Signal,
    pub second: Option<Signal>,
}

impl ArcKey {
    pub fn of(r: &Ranging) -> Self {
        Self {
            sat: r.sat,
            signal: r.signal,
            second: r.second,
        }
    }
}

/// One ranging of an epoch with what the filter measures of it.
#[derive(Debug, Clone)]
pub(super) struct Observed {
    pub ranging: Ranging,
    /// The Doppler of the ranging's (first) signal (Hz).
    pub doppler_hz: Option<f64>,
    /// Carrier phase (m, combined as the pseudoranges are), when every signal of the
    /// ranging has one.
    pub phase_m: Option<f64>,
    /// Whether a signal of the ranging lost lock since the last epoch.
    pub lost_lock: bool,
}

impl Observed {
    pub fn arc(&self) -> ArcKey {
        ArcKey::of(&self.ranging)
    }

    /// The measurement of [`crate::pvt::solve`] this ranging is.
    pub fn measurement(&self) -> Measurement {
        Measurement {
            sat: self.ranging.sat,
            pseudorange_m: self.ranging.pseudorange_m,
            doppler_hz: self.doppler_hz,
            signal: self.ranging.signal,
        }
    }

    /// A new arc's ambiguity (m) and its variance, from this epoch's code: `lambda phi - P`
    /// holds the ambiguity and the code's noise (the satellites' errors cancel).
    pub fn ambiguity_start(&self, code_sigma_m: f64) -> Option<(f64, f64)> {
        let phase = self.phase_m?;
        let sigma = code_sigma_m * self.ranging.noise_factor();
        Some((phase - self.ranging.pseudorange_m, sigma * sigma))
    }
}

/// The rangings of `records` of `systems`, with `correction` choosing one signal or a
/// combination per satellite.
pub(super) fn observed(
    records: &[ObsRecord],
    systems: &[System],
    correction: IonosphereCorrection,
) -> Vec<Observed> {
    let meas: Vec<Measurement> = (records.iter())
        .filter(|r| systems.contains(&r.sat.system))
        .filter_map(Measurement::of_record)
        .collect();
    let record = |sat: SatId, s: Signal| records.iter().find(|r| r.sat == sat && r.signal == s);
    let phase_m = |r: &ObsRecord| {
        r.carrier_phase_cycles
            .map(|c| c * C_MPS / r.signal.carrier_hz())
    };
    let lost = |r: &ObsRecord| r.phase_lli & LLI_LOSS_OF_LOCK != 0;
    per_satellite(&meas, correction)
        .into_iter()
        .map(|ranging| {
            let hi = record(ranging.sat, ranging.signal);
            let lo = ranging.second.map(|s| record(ranging.sat, s));
            let (phase_m, lost_lock) = match lo {
                None => (hi.and_then(phase_m), hi.is_some_and(lost)),
                Some(lo) => {
                    let (a, b) = ranging.second.map_or((1.0, 0.0), |s| {
                        Ranging::iono_free_coefficients(ranging.signal, s)
                    });
                    let phase = (hi.and_then(phase_m))
                        .zip(lo.and_then(phase_m))
                        .map(|(h, l)| a * h - b * l);
                    (phase, hi.is_some_and(lost) || lo.is_some_and(lost))
                }
            };
            Observed {
                doppler_hz: hi.and_then(|r| r.doppler_hz),
                ranging,
                phase_m,
                lost_lock,
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn record(prn: u8, signal: Signal, code: f64, cycles: f64, lli: u8) -> ObsRecord {
        ObsRecord {
            pseudorange_m: Some(code),
            carrier_phase_cycles: Some(cycles),
            doppler_hz: Some(-100.0),
            phase_lli: lli,
            ..ObsRecord::empty(SatId::gps(prn), signal)
        }
    }

    /// Two carriers combine as the pseudoranges do: a phase that is the range on both
    /// carriers gives the range; a loss of lock on either signal is the ranging's.
    #[test]
    fn the_combination_and_the_lock_follow_both_signals() {
        let rho = 2.1e7;
        let cycles = |s: Signal| rho / (C_MPS / s.carrier_hz());
        let records = [
            record(5, Signal::GpsL1Ca, rho, cycles(Signal::GpsL1Ca), 0),
            record(
                5,
                Signal::GpsL5,
                rho,
                cycles(Signal::GpsL5),
                LLI_LOSS_OF_LOCK,
            ),
        ];
        let o = observed(
            &records,
            &[System::Gps],
            IonosphereCorrection::DualFrequency,
        );
        assert_eq!(o.len(), 1);
        assert!((o[0].phase_m.unwrap() - rho).abs() < 1e-6);
        assert!(o[0].lost_lock);
        assert_eq!(o[0].arc().second, Some(Signal::GpsL5));
        let single = observed(&records, &[System::Gps], IonosphereCorrection::Broadcast);
        assert!(!single[0].lost_lock, "L1 alone kept lock");
        assert!(observed(&records, &[System::Beidou], IonosphereCorrection::Broadcast).is_empty());
    }
}
