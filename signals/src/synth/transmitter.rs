//! A transmitting satellite as the synthesiser sees it: ranging code, data bits and the
//! time scale its code and data are counted in.

use crate::codes::gps_ca::{GPS_CA_CHIP_RATE_HZ, gps_ca};
use crate::navmsg::gps_lnav::LnavEncoder;
use crate::signal::SignalId;
use hifitime::Epoch;
use skyforge_orbits::ephemeris::{BroadcastEphemeris, SatId};

/// Chips per LNAV data bit (20 C/A periods).
const GPS_CHIPS_PER_BIT: u64 = 20 * 1023;

/// Data modulating a signal.
#[derive(Debug, Clone)]
pub enum DataBits {
    /// GPS LNAV, 50 bps, bit b from 0.02 b s after the GPS epoch.
    GpsLnav(Box<LnavEncoder>),
}

/// One satellite's signal.
#[derive(Debug, Clone)]
pub struct Transmitter {
    pub sat: SatId,
    pub signal: SignalId,
    pub chip_rate_hz: f64,
    code: Vec<i8>,
    data: DataBits,
    /// Scenario start in the signal's time scale: whole seconds since its epoch.
    start_whole_s: u64,
    /// ... and the fraction (s).
    start_frac_s: f64,
}

impl Transmitter {
    /// GPS L1 C/A with LNAV; `start` is the scenario start epoch.
    pub fn gps_l1ca(sat: SatId, lnav: LnavEncoder, start: Epoch) -> Option<Self> {
        let code = gps_ca(sat.prn)?.to_vec();
        let since = start.to_gpst_duration();
        let ns = since.total_nanoseconds();
        if ns < 0 {
            return None;
        }
        let whole = (ns / 1_000_000_000) as u64;
        let frac = (ns % 1_000_000_000) as f64 * 1e-9;
        Some(Self {
            sat,
            signal: SignalId::GpsL1Ca,
            chip_rate_hz: GPS_CA_CHIP_RATE_HZ,
            code,
            data: DataBits::GpsLnav(Box::new(lnav)),
            start_whole_s: whole,
            start_frac_s: frac,
        })
    }

    /// The ephemeris the data broadcast (quantised as the message carries it): the orbit
    /// and clock the signal must follow so that a receiver's decoded ephemeris is exact.
    pub fn broadcast_ephemeris(&self) -> BroadcastEphemeris {
        match &self.data {
            DataBits::GpsLnav(lnav) => lnav.broadcast_ephemeris(),
        }
    }

    /// Absolute chip index (since the time-scale epoch) and code phase within it (chips) of
    /// satellite time `t_sv_s` (seconds since the scenario start).
    pub fn chip_at(&self, t_sv_s: f64) -> (u64, f64) {
        let chips = self.chip_rate_hz * (self.start_frac_s + t_sv_s);
        let whole = chips.floor();
        let base = self.start_whole_s * self.chip_rate_hz as u64;
        (base.wrapping_add_signed(whole as i64), chips - whole)
    }

    /// Append the signed chips `k0 .. k0 + count` (absolute indices, data bits applied) to
    /// `out`; the data bit is looked up once per bit, not per chip.
    pub fn chip_signs(&self, k0: u64, count: usize, out: &mut Vec<i8>) {
        let len = self.code.len() as u64;
        let mut k = k0;
        let end = k0 + count as u64;
        while k < end {
            let (bit, bit_end) = match &self.data {
                DataBits::GpsLnav(lnav) => {
                    let b = k / GPS_CHIPS_PER_BIT;
                    (lnav.bit(b), (b + 1) * GPS_CHIPS_PER_BIT)
                }
            };
            let stop = bit_end.min(end);
            let sign = if bit == 1 { -1 } else { 1 };
            out.extend((k..stop).map(|c| sign * self.code[(c % len) as usize]));
            k = stop;
        }
    }
}
