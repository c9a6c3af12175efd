//! The in-memory view of a RINEX observation file (`observation::as_written`) against the
//! real thing: random epochs of GPS and BeiDou records written by the one writer and read
//! back by the one reader equal what `epoch_as_written` says the file keeps, value for
//! value and bit for bit (rounding to F14.3 and 100 ns, blanks, phase wrap, loss-of-lock
//! digits).

use hifitime::{Duration, Epoch, TimeScale};
use proptest::prelude::*;
use skyforge_gnss::observation::epoch_as_written;
use skyforge_gnss::observation::{ObsEpoch, ObsRecord, parse_obs_text};
use skyforge_gnss::observation::{ObsHeader, ObsWriter, RECEIVER_TYPE, calendar_gpst};
use skyforge_gnss::signal::Signal;
use skyforge_orbits::ephemeris::SatId;

/// A value of one field: often ordinary, sometimes missing, not finite or too wide.
fn value(ordinary: std::ops::Range<f64>) -> impl Strategy<Value = Option<f64>> {
    value_near(ordinary, [1e9 - 0.0004, -0.0004])
}

/// [`value`] with two values at the edges of the field's rounding (the reader refuses
/// pseudoranges and Dopplers outside their physical ranges, issue #33).
fn value_near(
    ordinary: std::ops::Range<f64>,
    [a, b]: [f64; 2],
) -> impl Strategy<Value = Option<f64>> {
    prop_oneof![
        6 => ordinary.prop_map(Some),
        1 => Just(None),
        1 => Just(Some(f64::NAN)),
        1 => prop_oneof![Just(1e12), Just(-2.5e11), Just(a), Just(b)].prop_map(Some),
    ]
}

fn record() -> impl Strategy<Value = ObsRecord> {
    (
        (any::<bool>(), 1u8..=37),
        value_near(1.9e7..4.2e7, [1e9 - 0.0004, 1e6 - 0.0004]),
        prop_oneof![value(-2e9..2e9), (-3e11..3e11f64).prop_map(Some)],
        value_near(-6e3..6e3, [1e5 - 0.0004, -0.0004]),
        value(-5.0..70.0),
        0u8..=12,
    )
        .prop_map(
            |((bds, prn), pseudorange_m, carrier_phase_cycles, doppler_hz, cn0_dbhz, lli)| {
                let sat = if bds {
                    SatId::beidou(prn)
                } else {
                    SatId::gps(prn.min(32))
                };
                ObsRecord {
                    sat,
                    signal: Signal::of_system(sat.system),
                    pseudorange_m,
                    carrier_phase_cycles,
                    doppler_hz,
                    cn0_dbhz,
                    phase_lli: lli,
                }
            },
        )
}

/// Epochs a tenth of a second apart with a random fraction of a nanosecond-resolution
/// offset, starting at random instants (some a few nanoseconds before midnight, where the
/// rounding carries through the calendar).
fn epochs() -> impl Strategy<Value = Vec<(Epoch, Vec<ObsRecord>)>> {
    let start = (
        0u32..4000,
        prop_oneof![0i64..86_400_000_000_000, Just(86_399_999_999_951)],
    );
    (
        start,
        prop::collection::vec(
            (0i64..100_000_000, prop::collection::vec(record(), 1..8)),
            1..6,
        ),
    )
        .prop_map(|((day, ns), list)| {
            let t0 = Epoch::from_gregorian(2020, 1, 1, 0, 0, 0, 0, TimeScale::GPST)
                + Duration::from_days(f64::from(day))
                + Duration::from_total_nanoseconds(i128::from(ns));
            list.into_iter()
                .enumerate()
                .map(|(k, (jitter, records))| {
                    let at = t0
                        + Duration::from_total_nanoseconds(i128::from(
                            k as i64 * 1_000_000_000 + jitter,
                        ));
                    (at, records)
                })
                .collect()
        })
}

/// The epochs written by the writer and read by the reader.
fn written_and_read(epochs: &[(Epoch, Vec<ObsRecord>)]) -> Vec<ObsEpoch> {
    let signals = [Signal::GpsL1Ca, Signal::BdsB1I];
    let header = ObsHeader {
        marker: "ant1",
        receiver_type: RECEIVER_TYPE,
        antenna_type: "SKYFORGE",
        approx_ecef_m: None,
        first: calendar_gpst(epochs[0].0),
        interval_s: 1.0,
        signals: &signals,
    };
    let mut w = ObsWriter::with_header(Vec::new(), &header).unwrap();
    for (at, records) in epochs {
        w.epoch(calendar_gpst(*at), records).unwrap();
    }
    let text = String::from_utf8(w.finish().unwrap()).unwrap();
    parse_obs_text(&text, "test").unwrap().epochs
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    #[test]
    fn the_file_keeps_what_as_written_says(epochs in epochs()) {
        let read = written_and_read(&epochs);
        let kept: Vec<ObsEpoch> = epochs
            .iter()
            .map(|(at, records)| epoch_as_written(*at, records).unwrap())
            .collect();
        prop_assert_eq!(read.len(), kept.len());
        for (r, k) in read.iter().zip(&kept) {
            prop_assert_eq!(r.time, k.time);
            prop_assert_eq!(r.time.to_string(), k.time.to_string());
            prop_assert_eq!(r.sats.len(), k.sats.len(), "{:?}\nvs\n{:?}", r.sats, k.sats);
            for (a, b) in r.sats.iter().zip(&k.sats) {
                // Bit for bit: NaN never appears (a value that is not finite is blank).
                let bits = |v: Option<f64>| v.map(f64::to_bits);
                prop_assert_eq!((a.sat, a.signal, a.phase_lli), (b.sat, b.signal, b.phase_lli));
                prop_assert_eq!(bits(a.pseudorange_m), bits(b.pseudorange_m));
                prop_assert_eq!(bits(a.carrier_phase_cycles), bits(b.carrier_phase_cycles), "{:?} {:?}", a, b);
                prop_assert_eq!(bits(a.doppler_hz), bits(b.doppler_hz));
                prop_assert_eq!(bits(a.cn0_dbhz), bits(b.cn0_dbhz));
            }
        }
    }
}
