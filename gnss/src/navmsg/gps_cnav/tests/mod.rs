//! Tests of the CNAV encoder and decoder: layouts and CRC (`layout`), the continuous FEC
//! and symbol timing (`coding`), schedule and TOW (`timing`), round trips through symbols
//! and the decoder (`roundtrip`), refusals (`errors`), the decoder under noise and
//! garbage (`decoder`).

mod coding;
mod decoder;
mod errors;
mod layout;
mod roundtrip;
mod timing;

use super::{CNAV_LEAD_IN_SYMBOLS, CnavAssembler, CnavEncoder, CnavMessage, CnavParams};
use super::{CNAV_MESSAGE_SYMBOLS, decode_message};
use hifitime::{Epoch, TimeScale};
use skyforge_orbits::ephemeris::{
    BroadcastEphemeris, ClockParams, HarmonicCorrections, KeplerElements, OrbitClass, SatId,
};

/// 2023-03-12 10:00:00 GPST (Sunday, the first day of GPS week 2253), on the 300 s grid.
fn epoch() -> Epoch {
    Epoch::from_gregorian_hms(2023, 3, 12, 10, 0, 0, TimeScale::GPST)
}

/// GPS week of [`epoch`].
const WEEK: u32 = 2253;
/// Messages per week.
const PER_WEEK: u64 = 100_800;

/// A hand-made GPS set with every term non-zero, values of LNAV resolution or finer (not
/// CNAV multiples): eccentricity, harmonics, rates, clock drift and drift rate, TGD;
/// toc 10 min after toe.
fn realistic(prn: u8, toe: Epoch) -> BroadcastEphemeris {
    let orbit = KeplerElements {
        sqrt_a: 5_153.612_345,
        e: 1.234_567e-2,
        i0: 0.958_431_2,
        omega0: -1.234_567_8,
        omega: 0.852_345_6,
        m0: 2.376_543_2,
        delta_n: 4.523_4e-9,
        idot: -2.134e-10,
        omega_dot: -8.123_9e-9,
    };
    let harmonics = HarmonicCorrections {
        cuc: -1.234e-6,
        cus: 8.765e-6,
        crc: 212.53,
        crs: -23.47,
        cic: 3.456e-8,
        cis: -5.678e-8,
    };
    let clock = ClockParams {
        af0: -1.234_567_8e-4,
        af1: -3.412e-12,
        af2: 1.3e-18,
        tgd_s: -1.117e-8,
        tgd2_s: 0.0,
    };
    BroadcastEphemeris {
        toc: toe + hifitime::Unit::Minute * 10,
        ..BroadcastEphemeris::from_elements(
            SatId::gps(prn),
            OrbitClass::Standard,
            toe,
            orbit,
            harmonics,
            clock,
            4.0 * 3600.0,
        )
    }
}

/// Hard symbols as soft ones (0 -> +1, 1 -> -1).
fn soft(symbols: &[u8]) -> Vec<f32> {
    symbols
        .iter()
        .map(|&s| if s == 0 { 1.0 } else { -1.0 })
        .collect()
}

/// The soft symbols `decode_message` takes for message `n` of `enc`'s stream: the lead-in
/// (erasures before symbol 0), the message, and as many symbols of the next message.
fn window(enc: &CnavEncoder, n: u64) -> Vec<f32> {
    let lead = CNAV_LEAD_IN_SYMBOLS as u64;
    let start = n * CNAV_MESSAGE_SYMBOLS as u64;
    let first = start.saturating_sub(lead);
    let mut out = vec![0.0; (lead - (start - first)) as usize];
    out.extend(soft(
        &enc.symbols(first, (start - first + 600 + lead) as usize),
    ));
    out
}

/// Decode messages `first..first + count` of `enc` from its symbol stream.
fn decode_messages(enc: &CnavEncoder, first: u64, count: u64) -> Vec<CnavMessage> {
    (first..first + count)
        .map(|n| decode_message(&window(enc, n)).expect("a clean message decodes"))
        .collect()
}

/// Feed messages to an assembler; the ephemerides it yields.
fn assemble(messages: &[CnavMessage]) -> Vec<super::CnavEphemeris> {
    let mut asm = CnavAssembler::new();
    messages.iter().filter_map(|m| asm.push(m)).collect()
}

fn encoder(eph: &BroadcastEphemeris) -> CnavEncoder {
    CnavEncoder::new(eph, &CnavParams::default(), WEEK).expect("encodable")
}

/// Bits to an unsigned integer, most significant first.
fn uint(bits: &[u8]) -> u64 {
    bits.iter().fold(0, |a, &b| (a << 1) | u64::from(b))
}
