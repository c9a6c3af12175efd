//! Tests of the I/NAV encoder and decoder: layouts and coding (`coding`), round trips
//! through symbols and the decoder (`roundtrip`), schedule and timing (`timing`), refusals
//! (`errors`), the decoder under noise and garbage (`decoder`), the almanac (`almanac`).

mod almanac;
mod coding;
mod decoder;
mod errors;
mod roundtrip;
mod timing;

use super::{InavAssembler, InavEncoder, InavEphemeris, InavPage, InavParams, decode_page};
use hifitime::{Epoch, TimeScale};
use skyforge_orbits::ephemeris::{
    BroadcastEphemeris, ClockParams, HarmonicCorrections, KeplerElements, NavMessage, OrbitClass,
    SatId,
};

/// 2023-03-12 10:00:00 GST (Sunday, GST week 1229 = GPS week 2253), a whole minute.
fn epoch() -> Epoch {
    Epoch::from_gregorian_hms(2023, 3, 12, 10, 0, 0, TimeScale::GST)
}

/// GST week of [`epoch`].
const WEEK: u32 = 1229;

/// A hand-made I/NAV set with every term non-zero: eccentricity, harmonics, rates, clock
/// drift and drift rate, both BGDs, E1-B and E5b health bits, IODnav.
fn realistic(prn: u8, toe: Epoch) -> BroadcastEphemeris {
    let orbit = KeplerElements {
        sqrt_a: 5_440.612_345,
        e: 2.345_678e-4,
        i0: 0.977_431_2,
        omega0: -1.234_567_8,
        omega: -0.523_456_7,
        m0: 2.876_543_2,
        delta_n: 3.123_4e-9,
        idot: -1.234e-10,
        omega_dot: -5.678_9e-9,
    };
    let harmonics = HarmonicCorrections {
        cuc: -1.234e-6,
        cus: 8.765e-6,
        crc: 187.53,
        crs: -23.47,
        cic: 3.456e-8,
        cis: -5.678e-8,
    };
    let clock = ClockParams {
        af0: -5.123_456_7e-4,
        af1: -8.123e-12,
        af2: 3.5e-18,
        tgd_s: 2.56e-9,
        tgd2_s: -1.7e-9,
    };
    BroadcastEphemeris {
        message: NavMessage::GalileoInav,
        toc: toe + hifitime::Unit::Minute * 10,
        iode: 97,
        iodc: 97,
        // E1-B DVS, E1-B HS 2, E5b HS 1 (E5b DVS 0).
        health: 1 | (2 << 1) | (1 << 7),
        ..BroadcastEphemeris::from_elements(
            SatId::galileo(prn),
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

/// Decode pages `first..first + count` of `enc` from its symbols.
fn decode_pages(enc: &InavEncoder, first: u64, count: u64) -> Vec<InavPage> {
    (first..first + count)
        .map(|n| decode_page(&soft(&enc.page_symbols(n))).expect("a clean page decodes"))
        .collect()
}

/// Feed pages to an assembler; the ephemerides it yields.
fn assemble(pages: &[InavPage]) -> Vec<InavEphemeris> {
    let mut asm = InavAssembler::new();
    pages.iter().filter_map(|p| asm.push(p)).collect()
}

/// The first page of the frame that holds `t` (frames start at GST 1 s modulo 720 s; page
/// n starts 2n - 1 s into the week).
fn frame_page_at(enc: &InavEncoder, t: Epoch) -> u64 {
    let s = (t - enc.week_start()).to_seconds() as u64;
    s.saturating_sub(1) / 720 * 360 + 1
}

fn encoder(eph: &BroadcastEphemeris) -> InavEncoder {
    InavEncoder::new(eph, &[], &InavParams::default(), WEEK).expect("encodable")
}
