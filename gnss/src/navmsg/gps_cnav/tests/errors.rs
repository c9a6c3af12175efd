//! What the encoder refuses, and how it says so.

use super::super::{CnavEncoder, CnavError, CnavParams};
use super::{WEEK, epoch, realistic};
use hifitime::Unit;
use skyforge_orbits::ephemeris::{BroadcastEphemeris, SatId, System};

/// A change that puts one field out of its range.
type Spoil = fn(&mut BroadcastEphemeris);

fn refusal(eph: &BroadcastEphemeris, params: &CnavParams) -> CnavError {
    CnavEncoder::new(eph, params, WEEK).expect_err("refused")
}

fn out_of_range_field(err: &CnavError) -> &'static str {
    match err {
        CnavError::FieldOutOfRange { field, .. } => field,
        other => panic!("not a range error: {other}"),
    }
}

#[test]
fn a_non_gps_satellite_is_refused() {
    let mut e = realistic(5, epoch());
    e.sat = SatId::galileo(5);
    let err = refusal(&e, &CnavParams::default());
    assert!(matches!(err, CnavError::NotGps { .. }));
    assert!(err.to_string().contains("E05"), "{err}");
}

#[test]
fn values_outside_their_fields_are_refused_with_the_field_named() {
    let p = CnavParams::default();
    let mut e = realistic(5, epoch());
    // af0: 26 bits of 2^-35 s, at most (2^25 - 1) 2^-35 = 9.7656e-4 s.
    e.clock.af0 = 1e-3;
    let err = refusal(&e, &p);
    assert_eq!(out_of_range_field(&err), "af0-n");
    let text = err.to_string();
    assert!(text.contains("1e-3") && text.contains("9.7656"), "{text}");

    let cases: [(&str, Spoil); 6] = [
        // A 66 km above A_REF: Delta A holds +-2^25 2^-9 m = +-65.536 km.
        ("Delta A", |e| {
            e.orbit.sqrt_a = (26_559_710.0f64 + 66_000.0).sqrt()
        }),
        ("e-n", |e| e.orbit.e = 0.5),
        ("Delta OMEGAdot", |e| e.orbit.omega_dot = 1e-8),
        ("Cic-n", |e| e.harmonics.cic = 3.1e-5),
        ("af1-n", |e| e.clock.af1 = 1.9e-9),
        ("TGD", |e| e.clock.tgd_s = 1.2e-7),
    ];
    for (name, spoil) in cases {
        let mut e = realistic(5, epoch());
        spoil(&mut e);
        assert_eq!(out_of_range_field(&refusal(&e, &p)), name);
    }
    let e = realistic(5, epoch());
    let mut bad = [p; 4];
    bad[0].ura_ed_index = 16;
    bad[1].ura_ned1_index = 8;
    bad[2].isc_l5i5_s = Some(1.2e-7);
    bad[3].utc.dn = 16;
    for (name, params) in ["URA_ED index", "URA_NED1 index", "ISC_L5I5", "DN"]
        .iter()
        .zip(bad)
    {
        assert_eq!(out_of_range_field(&refusal(&e, &params)), *name);
    }
}

#[test]
fn toe_and_toc_off_the_300_s_grid_are_refused() {
    let mut e = realistic(5, epoch());
    e.toe += Unit::Second * 16;
    let err = refusal(&e, &CnavParams::default());
    assert!(
        matches!(err, CnavError::OffGrid { field: "toe", .. }),
        "{err}"
    );
    let mut e = realistic(5, epoch());
    e.toc += Unit::Millisecond * 1;
    let err = refusal(&e, &CnavParams::default());
    assert!(
        matches!(err, CnavError::OffGrid { field: "toc", .. }),
        "{err}"
    );
    assert!(err.to_string().contains("300 s"));
    // Re-expressed onto the grid, the same set is accepted.
    let mut e = realistic(5, epoch());
    e.toe += Unit::Second * 16;
    let on = System::Gps.on_grid(e.toe, 300.0);
    let fixed = e.reexpressed(on, e.toc).unwrap();
    assert!(CnavEncoder::new(&fixed, &CnavParams::default(), WEEK).is_ok());
}
