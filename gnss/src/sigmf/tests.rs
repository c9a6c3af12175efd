//! The writer's bytes, and what the reader reads back of them.

use super::datetime::{format_utc, parse_utc};
use super::{Capture, MetaError, ParsedMeta, RecordingMeta};
use crate::sample_format::SampleFormat;
use crate::signal::Signal;
use hifitime::Epoch;
use proptest::prelude::*;

/// A recording as `skyforge synth` describes one.
fn plain() -> RecordingMeta {
    RecordingMeta {
        format: SampleFormat::Ci8,
        sample_rate_hz: 4.092e6,
        centre_frequency_hz: 1575.42e6,
        if_hz: 0.0,
        datetime_utc: "2023-03-12T00:00:00.000000000Z".into(),
        antenna_name: "ant1".into(),
        antenna_position_body_m: [0.0, 1.0, 0.0],
        scenario: "thesis-leo".into(),
        seed: 3,
        vehicle: None,
        description: "test".into(),
        signals: Vec::new(),
    }
}

/// A recording with names and numbers that JSON must escape or spell out.
fn odd() -> RecordingMeta {
    RecordingMeta {
        format: SampleFormat::Cf32,
        sample_rate_hz: 2.6e6,
        centre_frequency_hz: 1561.098e6 - 250e3,
        if_hz: 250e3,
        datetime_utc: "2024-02-29T23:59:59.999999999Z".into(),
        antenna_name: "left \"wing\" #1".into(),
        antenna_position_body_m: [-0.125, 0.3, 1e-9],
        scenario: "odd/scénario".into(),
        seed: u64::MAX,
        vehicle: None,
        description: "two\nlines\t\\".into(),
        signals: Vec::new(),
    }
}

/// `plain()`'s file as the writer in `skyforge_signals` `synth::sigmf` wrote it before the
/// format moved here.
const PLAIN_TEXT: &str = r#"{
  "annotations": [],
  "captures": [
    {
      "core:datetime": "2023-03-12T00:00:00.000000000Z",
      "core:frequency": 1575420000.0,
      "core:sample_start": 0
    }
  ],
  "global": {
    "core:datatype": "ci8",
    "core:description": "test",
    "core:extensions": [
      {
        "name": "skyforge",
        "optional": true,
        "version": "1.0.0"
      }
    ],
    "core:num_channels": 1,
    "core:recorder": "skyforge 0.1.0",
    "core:sample_rate": 4092000.0,
    "core:version": "1.0.0",
    "skyforge:antenna": "ant1",
    "skyforge:antenna_position_body_m": [
      0.0,
      1.0,
      0.0
    ],
    "skyforge:if_hz": 0.0,
    "skyforge:scenario": "thesis-leo",
    "skyforge:seed": 3
  }
}
"#;

/// `odd()`'s file, likewise.
const ODD_TEXT: &str = r#"{
  "annotations": [],
  "captures": [
    {
      "core:datetime": "2024-02-29T23:59:59.999999999Z",
      "core:frequency": 1560848000.0,
      "core:sample_start": 0
    }
  ],
  "global": {
    "core:datatype": "cf32_le",
    "core:description": "two\nlines\t\\",
    "core:extensions": [
      {
        "name": "skyforge",
        "optional": true,
        "version": "1.0.0"
      }
    ],
    "core:num_channels": 1,
    "core:recorder": "skyforge 0.1.0",
    "core:sample_rate": 2600000.0,
    "core:version": "1.0.0",
    "skyforge:antenna": "left \"wing\" #1",
    "skyforge:antenna_position_body_m": [
      -0.125,
      0.3,
      1e-9
    ],
    "skyforge:if_hz": 250000.0,
    "skyforge:scenario": "odd/scénario",
    "skyforge:seed": 18446744073709551615
  }
}
"#;

/// A captured text with the recorder of this build (captured at version 0.1.0).
fn this_version(text: &str) -> String {
    text.replace("\"skyforge 0.1.0\"", &format!("\"{}\"", super::RECORDER))
}

#[test]
fn a_vehicle_is_named_where_there_is_one() {
    let meta = RecordingMeta {
        vehicle: Some("chaser".into()),
        ..plain()
    };
    let want = this_version(PLAIN_TEXT).replace(
        "\"skyforge:seed\": 3\n",
        "\"skyforge:seed\": 3,\n    \"skyforge:vehicle\": \"chaser\"\n",
    );
    assert_eq!(meta.to_text(), want);
}

#[test]
fn writes_the_bytes_it_always_wrote() {
    assert_eq!(plain().to_text(), this_version(PLAIN_TEXT));
    assert_eq!(odd().to_text(), this_version(ODD_TEXT));
}

#[test]
fn has_the_core_fields_sigmf_readers_need() {
    let v = plain().to_json();
    assert_eq!(v["global"]["core:datatype"], "ci8");
    assert_eq!(v["global"]["core:sample_rate"], 4.092e6);
    assert_eq!(v["captures"][0]["core:frequency"], 1575.42e6);
    assert_eq!(v["captures"][0]["core:sample_start"], 0);
    assert!(v["annotations"].as_array().unwrap().is_empty());
    // Every non-core global key belongs to a declared extension.
    let declared: Vec<&str> = v["global"]["core:extensions"]
        .as_array()
        .unwrap()
        .iter()
        .map(|e| e["name"].as_str().unwrap())
        .collect();
    for key in v["global"].as_object().unwrap().keys() {
        let ns = key.split(':').next().unwrap();
        assert!(ns == "core" || declared.contains(&ns), "{key}");
    }
}

/// What the reader takes from `text`.
fn read_back(text: &str) -> ParsedMeta {
    let json = serde_json::from_str(text).unwrap();
    ParsedMeta::from_json(&json).unwrap()
}

/// What the reader should take from `meta`'s file.
fn expected(meta: &RecordingMeta) -> ParsedMeta {
    ParsedMeta {
        format: Some(meta.format),
        sample_rate_hz: Some(meta.sample_rate_hz),
        trailing_bytes: None,
        antenna: Some(meta.antenna_name.clone()),
        antenna_position_body_m: Some(meta.antenna_position_body_m),
        if_hz: Some(meta.if_hz),
        signals: (meta.signals.len() > 1).then(|| meta.signals.clone()),
        first_capture: Capture {
            frequency_hz: Some(meta.centre_frequency_hz),
            datetime: parse_utc(&meta.datetime_utc),
            global_index: None,
            sample_start: Some(0),
            header_bytes: None,
        },
        capture_count: 1,
    }
}

#[test]
fn reads_back_what_it_writes() {
    for meta in [plain(), odd()] {
        assert_eq!(read_back(&meta.to_text()), expected(&meta));
    }
    assert_eq!(
        read_back(PLAIN_TEXT).first_capture.datetime,
        Some(Epoch::from_gregorian_utc_at_midnight(2023, 3, 12))
    );
}

/// A recording of one band carrying several signals names them; one of a single signal
/// names none (its carrier does), so the files written before stay as they were.
#[test]
fn a_recording_of_several_signals_names_them() {
    let two = RecordingMeta {
        signals: vec![Signal::GpsL1Ca, Signal::GalE1],
        ..plain()
    };
    let text = two.to_text();
    assert!(text.contains("\"skyforge:signals\": [\n      \"gps-l1ca\",\n      \"gal-e1\"\n    ]"));
    assert_eq!(read_back(&text), expected(&two));
    let one = RecordingMeta {
        signals: vec![Signal::GpsL1Ca],
        ..plain()
    };
    assert_eq!(one.to_text(), plain().to_text());
    assert_eq!(read_back(&one.to_text()).signals, None);
}

#[test]
fn refuses_what_it_cannot_read_naming_the_field() {
    let bad = |field: &str, found: &str, expected: &str| MetaError::BadField {
        field: field.into(),
        found: found.into(),
        expected: expected.into(),
    };
    let read = |edit: &dyn Fn(&mut serde_json::Value)| {
        let mut json = plain().to_json();
        edit(&mut json);
        ParsedMeta::from_json(&json).unwrap_err()
    };
    assert_eq!(
        read(&|j| j["global"] = 3.into()),
        MetaError::NotSigmf {
            detail: "no \"global\" object".into()
        }
    );
    assert_eq!(
        read(&|j| j["global"]["core:datatype"] = "ci16_be".into()),
        MetaError::UnknownDatatype {
            found: "ci16_be".into()
        }
    );
    assert_eq!(
        read(&|j| j["global"]["core:num_channels"] = 2.into()),
        bad(
            "global core:num_channels",
            "2",
            "1 (multi-channel datasets are not supported: give one file per antenna)"
        )
    );
    let later_header = |j: &mut serde_json::Value| {
        let later = serde_json::json!({"core:sample_start": 9, "core:header_bytes": 4});
        j["captures"].as_array_mut().unwrap().push(later);
    };
    assert_eq!(
        read(&later_header),
        bad(
            "captures[] core:header_bytes",
            "4",
            "0 after the first capture (header bytes between segments are not supported)"
        )
    );
    assert_eq!(
        read(&|j| j["captures"][0]["core:datetime"] = "1979-12-31T00:00:00Z".into()),
        bad(
            "captures[] core:datetime",
            "\"1979-12-31T00:00:00Z\"",
            &format!("a time {}", skyforge_orbits::time::SUPPORTED_RANGE)
        )
    );
    let signals = "a non-empty array of distinct signal tags (\"gps-l1ca\", \"gal-e1\", ...)";
    for (value, found) in [
        (serde_json::json!([]), "[]"),
        (serde_json::json!("gps-l1ca"), "\"gps-l1ca\""),
        (
            serde_json::json!(["gps-l1ca", "gps-l9"]),
            "[\"gps-l1ca\",\"gps-l9\"]",
        ),
        (
            serde_json::json!(["gal-e1", "gal-e1"]),
            "[\"gal-e1\",\"gal-e1\"]",
        ),
    ] {
        assert_eq!(
            read(&|j| j["global"]["skyforge:signals"] = value.clone()),
            bad("global skyforge:signals", found, signals)
        );
    }
}

/// A finite number of any magnitude and sign.
fn finite() -> impl Strategy<Value = f64> + Clone {
    prop::num::f64::NORMAL | prop::num::f64::SUBNORMAL | prop::num::f64::ZERO
}

/// A number as people and SkyForge write them: up to 13 significant digits, a short
/// decimal exponent.
fn decimal() -> impl Strategy<Value = f64> + Clone {
    (-1_000_000_000_000i64..=1_000_000_000_000, 0i32..=9)
        .prop_map(|(digits, places)| digits as f64 / 10f64.powi(places))
}

/// A time in the supported range, to the nanosecond.
fn epoch() -> impl Strategy<Value = Epoch> {
    (
        1981i32..2100,
        1u8..=12,
        1u8..=28,
        0u8..24,
        0u8..60,
        0u8..60,
        0u32..1_000_000_000,
    )
        .prop_map(|(y, mo, d, h, mi, s, ns)| Epoch::from_gregorian_utc(y, mo, d, h, mi, s, ns))
}

/// An antenna name as `crate::antenna_name::check_antenna_name` allows: 1 to 60 printable ASCII characters
/// but `/` and `\`, no leading or trailing space, not `.` or `..`.
fn antenna_name() -> impl Strategy<Value = String> {
    "[!-.0-\\[\\]-~]([ !-.0-\\[\\]-~]{0,58}[!-.0-\\[\\]-~])?"
        .prop_filter("not . or ..", |n| n != "." && n != "..")
}

/// A recording's metadata, its numbers drawn from `number`.
fn any_meta(number: impl Strategy<Value = f64> + Clone) -> impl Strategy<Value = RecordingMeta> {
    let frequencies = [number.clone(), number.clone(), number.clone()];
    let position = [number.clone(), number.clone(), number];
    let texts = (antenna_name(), any::<String>(), any::<String>());
    let format = prop::sample::select(SampleFormat::ALL.to_vec());
    (format, frequencies, epoch(), position, texts, any::<u64>()).prop_map(
        |(format, [sample_rate_hz, centre_frequency_hz, if_hz], start, position, texts, seed)| {
            let (antenna_name, scenario, description) = texts;
            RecordingMeta {
                format,
                sample_rate_hz,
                centre_frequency_hz,
                if_hz,
                datetime_utc: format_utc(start),
                antenna_name,
                antenna_position_body_m: position,
                scenario,
                seed,
                vehicle: None,
                description,
                signals: Vec::new(),
            }
        },
    )
}

/// A name that would become a path or break the RINEX MARKER NAME is refused where the
/// metadata is read, naming the key.
#[test]
fn an_antenna_name_outside_the_rule_is_refused() {
    for name in [
        "../../evil",
        "/abs",
        "a/b",
        "",
        ".",
        "left \"wing\" ü",
        " a",
    ] {
        let mut meta = odd();
        meta.antenna_name = name.into();
        let e = ParsedMeta::from_json(&meta.to_json()).unwrap_err();
        assert!(
            matches!(&e, MetaError::BadField { field, .. } if field == "global skyforge:antenna"),
            "{name:?}: {e}"
        );
    }
    for name in ["ant1", "left \"wing\" #1", &"a".repeat(60)] {
        let mut meta = odd();
        meta.antenna_name = name.into();
        assert!(ParsedMeta::from_json(&meta.to_json()).is_ok(), "{name:?}");
    }
}

proptest! {
    #[test]
    fn any_document_reads_back_as_written(meta in any_meta(finite())) {
        prop_assert_eq!(ParsedMeta::from_json(&meta.to_json()), Ok(expected(&meta)));
    }

    /// Through the file's text too. (serde_json, without its `float_roundtrip` feature,
    /// may read a 17-digit number a few units in the last place off: not what SkyForge
    /// writes.)
    #[test]
    fn any_file_reads_back_as_written(meta in any_meta(decimal())) {
        prop_assert_eq!(read_back(&meta.to_text()), expected(&meta));
    }
}
