//! Helpers shared by the GPS and BeiDou navigation-decoder round trips: soft bits, the
//! events of one kind, and the field-by-field comparison in LSB.

use skyforge_orbits::ephemeris::{BroadcastEphemeris, SatId};
use skyforge_receiver::navdecode::{DecodedEphemeris, NavEvent, SubframeInfo};

/// Soft values (+1 for logic 0, -1 for logic 1), negated if `invert`.
pub fn soft(bits: &[u8], invert: bool) -> Vec<f32> {
    let s = if invert { -1.0 } else { 1.0 };
    bits.iter().map(|&b| if b == 0 { s } else { -s }).collect()
}

/// The decoded ephemerides among `events`, in order.
pub fn ephemerides(events: &[NavEvent]) -> Vec<&DecodedEphemeris> {
    events
        .iter()
        .filter_map(|e| match e {
            NavEvent::Ephemeris(d) => Some(&**d),
            _ => None,
        })
        .collect()
}

/// The decoded subframes among `events`, in order.
pub fn subframes(events: &[NavEvent]) -> Vec<SubframeInfo> {
    events
        .iter()
        .filter_map(|e| match e {
            NavEvent::Subframe(s) => Some(*s),
            _ => None,
        })
        .collect()
}

/// Asserts |decoded - reference| <= `tol_lsb` x lsb for every `(name, decoded, reference,
/// lsb)` of satellite `sat`.
pub fn assert_within_lsb(sat: SatId, fields: &[(&str, f64, f64, f64)], tol_lsb: f64) {
    for &(name, a, b, lsb) in fields {
        assert!(
            (a - b).abs() <= tol_lsb * lsb,
            "{sat} {name}: decoded {a:e}, reference {b:e}, {:.3e} LSB apart",
            (a - b).abs() / lsb
        );
    }
}

/// Asserts that the decoded toe and toc are the reference's.
pub fn assert_same_toe_toc(decoded: &BroadcastEphemeris, reference: &BroadcastEphemeris) {
    assert_eq!(decoded.toe, reference.toe, "toe");
    assert_eq!(decoded.toc, reference.toc, "toc");
}
