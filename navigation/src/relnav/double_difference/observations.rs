//! One epoch's single differences from the two receivers' records: each satellite at
//! each receiver's own transmit time (`pvt::Transmitted`, the pseudorange carrying the
//! receiver's clock), seen from that receiver's position at its own receive instant
//! (the Earth's rotation during the flight, `Transmitted::seen_from`), and the cycle
//! slips: a loss-of-lock flag at either receiver, or a jump of a receiver's
//! geometry-free phase `lambda_1 phi_1 - lambda_2 phi_2` between epochs (ionosphere
//! only, millimetres per second; a slip moves it by a whole wavelength of one signal).

use super::filter::{SatPair, SignalSd};
use crate::pvt::Transmitted;
use skyforge_gnss::observation::{LLI_LOSS_OF_LOCK, ObsRecord};
use skyforge_gnss::signal::Signal;
use skyforge_orbits::constants::C_MPS;
use skyforge_orbits::ephemeris::{EphemerisStore, SatId};
use skyforge_orbits::frames::{c_ecef_ned, ecef_to_geodetic};
use skyforge_orbits::{Mat3, Vec3};
use std::collections::BTreeMap;

/// One receiver at one epoch: its records, its time tag (s since the origin, its own
/// clock) and its position at its receive instant (ECEF).
pub(crate) struct Receiver<'a> {
    pub records: &'a [ObsRecord],
    pub t_tag_s: f64,
    pub r_ecef_m: Vec3,
}

/// The geometry-free phases of the previous epoch, per receiver (0 target, 1 chaser)
/// and satellite: when and what (m).
#[derive(Debug, Clone, Default)]
pub(crate) struct SlipDetector {
    last: BTreeMap<(usize, SatId), (f64, f64)>,
}

impl SlipDetector {
    /// Whether receiver `rx`'s geometry-free phase `gf_m` at `t_s` jumped by more than
    /// `threshold_m` since its last value (within `max_gap_s`).
    fn jumped(&mut self, rx: usize, sat: SatId, t_s: f64, gf_m: f64, limits: (f64, f64)) -> bool {
        let (threshold_m, max_gap_s) = limits;
        let previous = self.last.insert((rx, sat), (t_s, gf_m));
        previous.is_some_and(|(t, gf)| t_s - t <= max_gap_s && (gf_m - gf).abs() > threshold_m)
    }
}

/// The record of `sat` on `signal` with code and phase.
fn record(records: &[ObsRecord], sat: SatId, signal: Signal) -> Option<&ObsRecord> {
    (records.iter()).find(|r| {
        r.sat == sat
            && r.signal == signal
            && r.pseudorange_m.is_some()
            && r.carrier_phase_cycles.is_some()
    })
}

/// The ECEF-to-NED rotation at `r_ecef_m` (the elevations).
fn local_frame(r_ecef_m: &Vec3) -> Mat3 {
    let g = ecef_to_geodetic(r_ecef_m);
    c_ecef_ned(g.lat_rad, g.lon_rad)
}

/// What [`single_differences`] needs besides the receivers.
pub(crate) struct Settings<'a> {
    pub signals: &'a [Signal],
    pub elevation_mask_rad: f64,
    pub slip_threshold_m: f64,
    pub max_gap_s: f64,
}

/// The satellites both receivers measured code and phase of on at least one of
/// `signals`, above the mask at both, with an ephemeris: their single differences
/// (chaser minus target) at `t_s` (the target's receive instant, for the slip memory).
pub(crate) fn single_differences(
    (target, chaser): (&Receiver, &Receiver),
    store: &EphemerisStore,
    settings: &Settings,
    t_s: f64,
    slips: &mut SlipDetector,
) -> Vec<SatPair> {
    let frames = [local_frame(&target.r_ecef_m), local_frame(&chaser.r_ecef_m)];
    let sats: std::collections::BTreeSet<SatId> = target.records.iter().map(|r| r.sat).collect();
    let mut out = Vec::new();
    for sat in sats {
        let both: Vec<(Signal, &ObsRecord, &ObsRecord)> = (settings.signals.iter())
            .filter_map(|&f| {
                Some((
                    f,
                    record(target.records, sat, f)?,
                    record(chaser.records, sat, f)?,
                ))
            })
            .collect();
        let Some(&(_, first_t, first_c)) = both.first() else {
            continue;
        };
        let Some(eph) = store.select(sat, target.t_tag_s) else {
            continue;
        };
        let view = |rx: &Receiver, r: &ObsRecord, frame| {
            let p = r.pseudorange_m.unwrap_or_default();
            Transmitted::of(eph, rx.t_tag_s, p).seen_from(&rx.r_ecef_m, frame)
        };
        let vt = view(target, first_t, Some(&frames[0]));
        let vc = view(chaser, first_c, Some(&frames[1]));
        let elevation = |v: &crate::pvt::SatView| v.az_el_rad.map_or(-1.0, |(_, el)| el);
        let elevation_rad = [elevation(&vt), elevation(&vc)];
        if elevation_rad
            .iter()
            .any(|&e| e < settings.elevation_mask_rad)
        {
            continue;
        }
        // A geometry-free jump at either receiver restarts every signal of the satellite.
        let mut jumped = false;
        if both.len() >= 2 {
            let gf = |a: &ObsRecord, b: &ObsRecord| {
                a.carrier_phase_cycles.unwrap_or_default() * a.signal.wavelength_m()
                    - b.carrier_phase_cycles.unwrap_or_default() * b.signal.wavelength_m()
            };
            let limits = (settings.slip_threshold_m, settings.max_gap_s);
            let (a, b) = (both[0], both[1]);
            jumped |= slips.jumped(0, sat, t_s, gf(a.1, b.1), limits);
            jumped |= slips.jumped(1, sat, t_s, gf(a.2, b.2), limits);
        }
        let signals = (both.iter())
            .map(|&(signal, t, c)| {
                let lli = |r: &ObsRecord| r.phase_lli & LLI_LOSS_OF_LOCK != 0;
                SignalSd {
                    signal,
                    code_m: c.pseudorange_m.unwrap_or_default()
                        - t.pseudorange_m.unwrap_or_default(),
                    phase_cycles: c.carrier_phase_cycles.unwrap_or_default()
                        - t.carrier_phase_cycles.unwrap_or_default(),
                    slip: jumped || lli(t) || lli(c),
                }
            })
            .collect();
        out.push(SatPair {
            sat,
            at_target_m: vt.r_ecef_m,
            at_chaser_m: vc.r_ecef_m,
            clock_sd_m: C_MPS * (vc.clock_s - vt.clock_s),
            elevation_rad,
            signals,
        });
    }
    out
}
