//! Helpers shared by the GPS and BeiDou navigation-decoder round trips: soft bits, the
//! events of one kind, and the field-by-field comparison in LSB.

use skyforge_orbits::ephemeris::BroadcastEphemeris;
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

/// A broadcast field: its name, how to read it and its LSB.
pub type Field = (&'static str, fn(&BroadcastEphemeris) -> f64, f64);

/// Asserts |decoded - reference| <= `tol_lsb` x LSB for every field of `fields`.
pub fn assert_within_lsb(
    decoded: &BroadcastEphemeris,
    reference: &BroadcastEphemeris,
    fields: &[Field],
    tol_lsb: f64,
) {
    for &(name, field, lsb) in fields {
        let (a, b) = (field(decoded), field(reference));
        assert!(
            (a - b).abs() <= tol_lsb * lsb,
            "{} {name}: decoded {a:e}, reference {b:e}, {:.3e} LSB apart",
            reference.sat,
            (a - b).abs() / lsb
        );
    }
}

/// Asserts that the decoded toe and toc are the reference's.
pub fn assert_same_toe_toc(decoded: &BroadcastEphemeris, reference: &BroadcastEphemeris) {
    assert_eq!(decoded.toe, reference.toe, "toe");
    assert_eq!(decoded.toc, reference.toc, "toc");
}
