//! What the encoder refuses, and how it says so.

use super::super::{InavEncoder, InavError, InavParams};
use super::{WEEK, epoch, realistic};
use hifitime::Unit;
use skyforge_orbits::ephemeris::{BroadcastEphemeris, SatId};

/// A change that puts one field out of its range.
type Spoil = fn(&mut BroadcastEphemeris);

fn refusal(eph: &BroadcastEphemeris, params: &InavParams) -> InavError {
    InavEncoder::new(eph, &[], params, WEEK).expect_err("refused")
}

fn out_of_range_field(err: &InavError) -> &'static str {
    match err {
        InavError::FieldOutOfRange { field, .. } => field,
        other => panic!("not a range error: {other}"),
    }
}

#[test]
fn a_non_galileo_satellite_is_refused() {
    let mut e = realistic(5, epoch());
    e.sat = SatId::gps(5);
    let err = refusal(&e, &InavParams::default());
    assert!(matches!(err, InavError::NotGalileo { .. }));
    assert!(err.to_string().contains("G05") && err.to_string().contains("I/NAV"));
}

#[test]
fn values_outside_their_fields_are_refused_with_the_field_named() {
    let p = InavParams::default();
    let mut e = realistic(5, epoch());
    e.clock.af0 = 0.07;
    let err = refusal(&e, &p);
    assert_eq!(out_of_range_field(&err), "af0");
    let text = err.to_string();
    assert!(text.contains("af0") && text.contains("7e-2"), "{text}");

    let cases: [(&str, Spoil); 6] = [
        ("IODnav", |e| e.iode = 1024),
        ("e", |e| e.orbit.e = 0.6),
        ("sqrtA", |e| e.orbit.sqrt_a = -1.0),
        ("Cis", |e| e.harmonics.cis = 1e-4),
        ("BGD(E1,E5a)", |e| e.clock.tgd2_s = 2e-7),
        ("BGD(E1,E5b)", |e| e.clock.tgd_s = -2e-7),
    ];
    for (name, spoil) in cases {
        let mut e = realistic(5, epoch());
        spoil(&mut e);
        assert_eq!(out_of_range_field(&refusal(&e, &p)), name);
    }
    let e = realistic(5, epoch());
    let params: [(&str, InavParams); 4] = [
        ("ai2", InavParams { ai2: 0.3, ..p }),
        (
            "A1G",
            InavParams {
                a1g_s_s: 1e-12,
                ..p
            },
        ),
        ("WNLSF", InavParams { wn_lsf: 256, ..p }),
        ("WN0G", InavParams { wn0g: 64, ..p }),
    ];
    for (name, bad) in params {
        assert_eq!(out_of_range_field(&refusal(&e, &bad)), name);
    }
}

#[test]
fn toe_and_toc_off_the_minute_grid_are_refused() {
    let mut e = realistic(5, epoch());
    e.toe += Unit::Second * 30;
    let err = refusal(&e, &InavParams::default());
    assert!(
        matches!(err, InavError::OffGrid { field: "t0e", .. }),
        "{err}"
    );
    let mut e = realistic(5, epoch());
    e.toc += Unit::Millisecond * 1;
    let err = refusal(&e, &InavParams::default());
    assert!(
        matches!(err, InavError::OffGrid { field: "t0c", .. }),
        "{err}"
    );
    assert!(err.to_string().contains("60 s"));
}
