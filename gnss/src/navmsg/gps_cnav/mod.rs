//! The GPS L5 CNAV navigation message of the L5 I5 component (IS-GPS-705J §3.3.3.1,
//! §20.3), encoder and decoder.
//!
//! Timing: 50 bps, rate 1/2 FEC, 100 symbols/s (§3.3.3.1.1); a message is 300 bits, 600
//! symbols, 6 s (§20.3.3). Messages start at GPS TOW multiples of 6 s; the message TOW
//! count is the TOW of the start of the next message in 6 s units (§20.3.3). The FEC runs
//! continuously across message boundaries (§3.3.3.1.1), with the G1 symbol first in each
//! bit period, and the first symbol a message's first bit produces starts at the message's
//! 6 s epoch: symbol k lies at k / 100 s after the GPS week start, message n holds symbols
//! 600 n .. 600 n + 599, and its first two symbols already depend on the last six bits of
//! message n - 1 (the previous week's last message for n = 0).
//!
//! Schedule: types 10, 11, 30, 33 repeating, one cycle per 24 s, starting at each week's
//! start (100800 messages a week, a multiple of 4, so the cycle runs on across weeks). The
//! ICD's maximum broadcast intervals for L5 (§20.3.4.1, Table 20-XII) are 24 s for the
//! ephemeris (10, 11) and for a clock message (30-37), 144 s for type 30's ISC/iono data
//! and for type 33's UTC data: the cycle sends 10 and 11 every 24 s, a clock message at
//! most 18 s after the last, 30 and 33 every 24 s. SkyForge sends no almanac, EOP, GGTO or
//! text messages.
//!
//! [`CnavEncoder`] turns one ephemeris (plus [`CnavParams`]) into channel symbols;
//! [`decode_message`] and [`CnavAssembler`] turn received soft symbols back into messages
//! and an ephemeris. [`CnavEncoder::broadcast_ephemeris`] is the quantised ephemeris, the
//! one the signal must follow and a decoder recovers.

mod decode;
mod eph;
mod layout;
mod params;
mod quant;
#[cfg(test)]
mod tests;

pub use decode::{
    CNAV_LEAD_IN_SYMBOLS, CnavAssembler, CnavDecodeError, CnavEphemeris, CnavMessage,
    decode_message,
};
pub use eph::{A_REF_M, OMEGA_DOT_REF_SC};
pub use layout::{CNAV_PREAMBLE, MESSAGE_BITS as CNAV_MESSAGE_BITS};
pub use layout::{MESSAGE_SYMBOLS as CNAV_MESSAGE_SYMBOLS, layout as message_layout};
pub use params::CnavParams;
pub use quant::Field;

use super::gps_lnav::IonoParams;
use eph::Fields;
use hifitime::Epoch;
use quant::{self as q};
use skyforge_orbits::ephemeris::{BroadcastEphemeris, SatId, System};
use skyforge_orbits::time::epoch_from_gpst;
use std::sync::Mutex;

/// Channel symbol rate of L5 I5 (symbols/s).
pub const CNAV_SYMBOL_RATE_HZ: f64 = 100.0;
/// Message duration (s).
pub const CNAV_MESSAGE_S: u64 = 6;
/// The repeating message schedule, from each week's start.
pub const CNAV_SCHEDULE: [u8; 4] = [10, 11, 30, 33];
/// Seconds per GPS week.
const WEEK_S: i64 = 604_800;

/// Why a CNAV message cannot be built.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum CnavError {
    /// The ephemeris is not a GPS one.
    #[error("{sat}: not a GPS satellite; CNAV is a GPS message")]
    NotGps { sat: String },
    /// A value does not fit its field.
    #[error("{sat}: {field} = {value:e} is outside the range CNAV carries [{min:e}, {max:e}]")]
    FieldOutOfRange {
        sat: String,
        field: &'static str,
        value: f64,
        min: f64,
        max: f64,
    },
    /// toe or toc is not on the 300 s grid (re-express the set first, with
    /// `BroadcastEphemeris::reexpressed`).
    #[error("{sat}: {field} (GPS seconds of week {sow_s}) is not a multiple of {grid_s} s")]
    OffGrid {
        sat: String,
        field: &'static str,
        sow_s: f64,
        grid_s: f64,
    },
}

/// The channel symbols of one satellite's CNAV message, counted from the start of GPS
/// week [`Self::week`] (symbol 0 is the first symbol of a type 10 message).
#[derive(Debug)]
pub struct CnavEncoder {
    sat: SatId,
    week: u32,
    fields: Fields,
    toe: Epoch,
    toc: Epoch,
    /// The last message encoded, by index: `symbol` is called once per symbol.
    cache: Mutex<Option<(u64, Vec<u8>)>>,
}

impl Clone for CnavEncoder {
    fn clone(&self) -> Self {
        Self {
            sat: self.sat,
            week: self.week,
            fields: self.fields.clone(),
            toe: self.toe,
            toc: self.toc,
            cache: Mutex::new(None),
        }
    }
}

impl CnavEncoder {
    /// An encoder for GPS ephemeris `eph`, from the start of GPS week `gps_week`. toe and
    /// toc must be on the 300 s grid; every value must fit its field.
    pub fn new(
        eph: &BroadcastEphemeris,
        params: &CnavParams,
        gps_week: u32,
    ) -> Result<Self, CnavError> {
        let sat = eph.sat.to_string();
        if eph.sat.system != System::Gps {
            return Err(CnavError::NotGps { sat });
        }
        Ok(Self {
            sat: eph.sat,
            week: gps_week,
            fields: eph::quantise(eph, params, &sat)?,
            toe: eph.toe,
            toc: eph.toc,
            cache: Mutex::new(None),
        })
    }

    /// GPS week of symbol 0.
    pub fn week(&self) -> u32 {
        self.week
    }

    /// Start of GPS week [`Self::week`], where symbol 0 starts.
    pub fn week_start(&self) -> Epoch {
        epoch_from_gpst(self.week, 0.0)
    }

    /// The ephemeris the messages describe, in SI units: every field quantised and
    /// converted back (message GpsLnav, tgd_s = TGD, tgd2_s = 0, iode = iodc = 0, health
    /// = the three health bits, 3 h fit). The orbit and clock the signal must follow.
    pub fn broadcast_ephemeris(&self) -> BroadcastEphemeris {
        eph::to_ephemeris(&self.fields, self.sat, self.toe, self.toc)
    }

    /// The Klobuchar coefficients type 30 carries (quantised), the ones the signal must
    /// follow for a receiver's broadcast correction to match.
    pub fn iono(&self) -> IonoParams {
        let si = |f: &Field| f.si_value(self.fields.get(f));
        IonoParams {
            alpha: [
                si(&q::ALPHA[0]),
                si(&q::ALPHA[1]),
                si(&q::ALPHA[2]),
                si(&q::ALPHA[3]),
            ],
            beta: [
                si(&q::BETA[0]),
                si(&q::BETA[1]),
                si(&q::BETA[2]),
                si(&q::BETA[3]),
            ],
        }
    }

    /// Message type of message `n` (message 0 starts at [`Self::week_start`]).
    pub fn message_type(&self, n: u64) -> u8 {
        schedule(i64::try_from(n).unwrap_or(i64::MAX))
    }

    /// GPS week and TOW (s) at the start of message `n`.
    pub fn message_time(&self, n: u64) -> (u32, u32) {
        let (week, tow) = self.time_of(n as i64);
        (week as u32, tow as u32)
    }

    /// The 300 bits of message `n`.
    pub fn message_bits(&self, n: u64) -> [u8; CNAV_MESSAGE_BITS] {
        self.bits_at(n as i64)
    }

    /// The 600 channel symbols (0/1) of message `n`, the FEC continuing from message
    /// `n - 1`.
    pub fn message_symbols(&self, n: u64) -> Vec<u8> {
        let previous = self.bits_at(n as i64 - 1);
        layout::encode(&previous[CNAV_MESSAGE_BITS - 6..], &self.message_bits(n))
    }

    /// Channel symbol `k` (0/1) counted from [`Self::week_start`] (its message encoded
    /// once, then kept until another message is asked for).
    pub fn symbol(&self, k: u64) -> u8 {
        let n_sym = CNAV_MESSAGE_SYMBOLS as u64;
        let (n, j) = (k / n_sym, (k % n_sym) as usize);
        let Ok(mut cache) = self.cache.try_lock() else {
            return self.message_symbols(n)[j];
        };
        if cache.as_ref().is_some_and(|(m, _)| *m != n) {
            *cache = None;
        }
        cache.get_or_insert_with(|| (n, self.message_symbols(n))).1[j]
    }

    /// `count` channel symbols from symbol `first` on (each message encoded once).
    pub fn symbols(&self, first: u64, count: usize) -> Vec<u8> {
        let n_sym = CNAV_MESSAGE_SYMBOLS as u64;
        let mut out = Vec::with_capacity(count);
        let mut k = first;
        while out.len() < count {
            let message = self.message_symbols(k / n_sym);
            let from = (k % n_sym) as usize;
            let take = (CNAV_MESSAGE_SYMBOLS - from).min(count - out.len());
            out.extend_from_slice(&message[from..from + take]);
            k += take as u64;
        }
        out
    }

    /// GPS week and TOW (s) of the start of message `index` (negative: before the week).
    fn time_of(&self, index: i64) -> (i64, i64) {
        let s = i64::from(self.week) * WEEK_S + index * CNAV_MESSAGE_S as i64;
        (s.div_euclid(WEEK_S), s.rem_euclid(WEEK_S))
    }

    /// The bits of message `index` (negative: the messages before the week start).
    fn bits_at(&self, index: i64) -> [u8; CNAV_MESSAGE_BITS] {
        let msg_type = schedule(index);
        let (week, tow) = self.time_of(index);
        let next_tow = (tow + CNAV_MESSAGE_S as i64) % WEEK_S;
        let mut f = self.fields.clone();
        f.set(&q::PREAMBLE, i64::from(CNAV_PREAMBLE));
        f.set(&q::PRN, i64::from(self.sat.prn));
        f.set(&q::MSG_TYPE, i64::from(msg_type));
        f.set(&q::TOW, next_tow / CNAV_MESSAGE_S as i64);
        f.set(&q::WN, week.rem_euclid(1 << q::WN.bits));
        layout::pack(msg_type, &f.values_for(layout::all_fields(msg_type)))
    }
}

/// The message type of message `index` of the schedule.
fn schedule(index: i64) -> u8 {
    CNAV_SCHEDULE[index.rem_euclid(CNAV_SCHEDULE.len() as i64) as usize]
}
