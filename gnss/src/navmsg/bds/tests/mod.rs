//! Tests of the D1/D2 encoder against the independent decoder of `test_decoder` and the
//! broadcast test vectors of `real_words`.

mod accuracy;
mod broadcast;
mod structure;

use super::test_decoder::{Decoded, logical_bits};
use super::{BdsExtraFields, BdsNavEncoder, Klobuchar};
use skyforge_orbits::ephemeris::{
    BroadcastEphemeris, ClockParams, HarmonicCorrections, KeplerElements, OrbitClass, SatId,
};
use skyforge_orbits::time::epoch_from_bdt;

/// Subframe `index` of `enc`, in the ICD's layout, checking every codeword.
fn logical(enc: &BdsNavEncoder, index: u64) -> [u8; 300] {
    logical_bits(&enc.subframe(index)).unwrap_or_else(|e| panic!("subframe {index}: {e}"))
}

/// The ephemeris, ionosphere and extra fields a decoded message describes (toe, toc in
/// week `week`).
fn from_decoded(
    d: &Decoded,
    sat: SatId,
    class: OrbitClass,
    week: u32,
) -> (BroadcastEphemeris, Klobuchar, BdsExtraFields) {
    let orbit = KeplerElements {
        sqrt_a: d.sqrt_a,
        e: d.e,
        i0: d.i0,
        omega0: d.omega0,
        omega: d.omega,
        m0: d.m0,
        delta_n: d.delta_n,
        idot: d.idot,
        omega_dot: d.omega_dot,
    };
    let harmonics = HarmonicCorrections {
        cuc: d.cuc,
        cus: d.cus,
        crc: d.crc,
        crs: d.crs,
        cic: d.cic,
        cis: d.cis,
    };
    let clock = ClockParams {
        af0: d.a0,
        af1: d.a1,
        af2: d.a2,
        tgd_s: d.tgd1_s,
        tgd2_s: 0.0,
    };
    let toe = epoch_from_bdt(week, d.toe_s);
    let eph = BroadcastEphemeris {
        toc: epoch_from_bdt(week, d.toc_s),
        iode: d.aode as u32,
        iodc: d.aodc as u32,
        health: d.sat_h1 as u32,
        ..BroadcastEphemeris::from_elements(sat, class, toe, orbit, harmonics, clock, 6.0 * 3600.0)
    };
    let iono = Klobuchar {
        alpha: d.alpha,
        beta: d.beta,
    };
    let extra = BdsExtraFields {
        urai: d.urai as u8,
        tgd2_s: d.tgd2_s,
    };
    (eph, iono, extra)
}

/// |a - b| <= tol, with a readable failure.
#[track_caller]
fn assert_close(what: &str, a: f64, b: f64, tol: f64) {
    assert!(
        (a - b).abs() <= tol,
        "{what}: {a:e} vs {b:e} (tolerance {tol:e})"
    );
}
