//! Reading a `.sigmf-meta` document: the fields SkyForge takes from it, typed and checked,
//! with errors that name the field. What a reader does with them (defaults, command-line
//! overrides) is the reader's.

use super::datetime::parse_utc;
use super::keys;
use crate::antenna_name::check_antenna_name;
use crate::sample_format::SampleFormat;
use crate::signal::Signal;
use hifitime::Epoch;
use serde_json::{Map, Value};
use skyforge_orbits::time::{SUPPORTED_RANGE, in_supported_range};

/// How errors name the fields of a capture segment (`captures[] core:frequency`).
const CAPTURE_SECTION: &str = "captures[]";

/// Why a metadata document cannot be read.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum MetaError {
    /// The document does not have the SigMF shape.
    #[error("not SigMF metadata: {detail}")]
    NotSigmf {
        /// What is wrong, for people.
        detail: String,
    },
    /// A field has a value SkyForge cannot use.
    #[error("{field} is {found}; expected {expected}")]
    BadField {
        /// The field, with its section (`global core:sample_rate`).
        field: String,
        /// The value found, as JSON.
        found: String,
        /// What would have done.
        expected: String,
    },
    /// A `core:datatype` that names no [`SampleFormat`].
    #[error("unknown sample datatype {found:?}")]
    UnknownDatatype {
        /// The datatype found.
        found: String,
    },
}

/// The fields SkyForge reads of a capture segment.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Capture {
    /// Centre frequency (Hz; `core:frequency`).
    pub frequency_hz: Option<f64>,
    /// UTC time of the segment's first sample (`core:datetime`), in the supported range.
    pub datetime: Option<Epoch>,
    /// Index of the segment's first sample in the recorder's stream (`core:global_index`).
    pub global_index: Option<u64>,
    /// Index of the segment's first sample in the data file (`core:sample_start`).
    pub sample_start: Option<u64>,
    /// Non-sample bytes before the segment's samples (`core:header_bytes`).
    pub header_bytes: Option<u64>,
}

/// What a `.sigmf-meta` document says, as SkyForge reads it: one channel of samples read
/// as one stream from the first capture segment on (a later segment's header bytes and
/// several channels are refused).
#[derive(Debug, Clone, PartialEq)]
pub struct ParsedMeta {
    /// Sample container (`core:datatype`).
    pub format: Option<SampleFormat>,
    /// Samples per second (`core:sample_rate`).
    pub sample_rate_hz: Option<f64>,
    /// Non-sample bytes after the samples (`core:trailing_bytes`).
    pub trailing_bytes: Option<u64>,
    /// The antenna recorded (`skyforge:antenna`).
    pub antenna: Option<String>,
    /// Nominal antenna position in the body frame (m; `skyforge:antenna_position_body_m`).
    pub antenna_position_body_m: Option<[f64; 3]>,
    /// Intermediate frequency of the signal within the recording (Hz; `skyforge:if_hz`).
    pub if_hz: Option<f64>,
    /// The signals of a recording that carries several (`skyforge:signals`).
    pub signals: Option<Vec<Signal>>,
    /// The first capture segment (all fields absent when there is none).
    pub first_capture: Capture,
    /// Number of capture segments.
    pub capture_count: usize,
}

impl ParsedMeta {
    /// The fields of metadata document `json`, or the first error in reading order: the
    /// global datatype, rate and channels, the capture segments' shape, then the
    /// remaining fields.
    pub fn from_json(json: &Value) -> Result<Self, MetaError> {
        let g = Fields {
            section: keys::GLOBAL,
            obj: global(json)?,
        };
        let format = g.datatype()?;
        let sample_rate_hz = g.f64(keys::SAMPLE_RATE)?;
        g.single_channel()?;
        let captures = captures(json)?;
        let empty = Map::new();
        let c0 = capture_fields(captures.first(), &empty)?;
        for c in captures.iter().skip(1) {
            capture_fields(Some(c), &empty)?.no_header_bytes()?;
        }
        let frequency_hz = c0.f64(keys::FREQUENCY)?;
        let if_hz = g.f64(keys::IF_HZ)?;
        let antenna = g.antenna_name()?;
        let first_capture = c0.capture(frequency_hz)?;
        let trailing_bytes = g.u64(keys::TRAILING_BYTES)?;
        let antenna_position_body_m = g.vec3(keys::ANTENNA_POSITION_BODY_M)?;
        let signals = g.signals()?;
        Ok(Self {
            format,
            sample_rate_hz,
            trailing_bytes,
            antenna,
            antenna_position_body_m,
            if_hz,
            signals,
            first_capture,
            capture_count: captures.len(),
        })
    }
}

/// The JSON document `text`, refused ([`MetaError::NotSigmf`]) where it is not JSON or
/// where an object gives a key twice: JSON readers differ on which value wins (serde_json
/// keeps the last), so such a file says two things.
pub fn parse_json(text: &str) -> Result<Value, MetaError> {
    serde_json::from_str::<Strict>(text)
        .map(|s| s.0)
        .map_err(|e| not_sigmf(&format!("invalid JSON: {e}")))
}

/// A JSON value read with every object checked for repeated keys.
struct Strict(Value);

impl<'de> serde::Deserialize<'de> for Strict {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_any(StrictVisitor).map(Strict)
    }
}

/// Builds a [`Value`] as serde_json's own does, but an object's repeated key is an error.
struct StrictVisitor;

impl<'de> serde::de::Visitor<'de> for StrictVisitor {
    type Value = Value;

    fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        f.write_str("a JSON value")
    }
    fn visit_bool<E>(self, v: bool) -> Result<Value, E> {
        Ok(Value::Bool(v))
    }
    fn visit_i64<E>(self, v: i64) -> Result<Value, E> {
        Ok(v.into())
    }
    fn visit_u64<E>(self, v: u64) -> Result<Value, E> {
        Ok(v.into())
    }
    fn visit_f64<E>(self, v: f64) -> Result<Value, E> {
        Ok(v.into())
    }
    fn visit_str<E>(self, v: &str) -> Result<Value, E> {
        Ok(Value::String(v.to_owned()))
    }
    fn visit_unit<E>(self) -> Result<Value, E> {
        Ok(Value::Null)
    }
    fn visit_seq<A: serde::de::SeqAccess<'de>>(self, mut seq: A) -> Result<Value, A::Error> {
        let mut items = Vec::new();
        while let Some(Strict(v)) = seq.next_element()? {
            items.push(v);
        }
        Ok(Value::Array(items))
    }
    fn visit_map<A: serde::de::MapAccess<'de>>(self, mut map: A) -> Result<Value, A::Error> {
        let mut obj = Map::new();
        while let Some(key) = map.next_key::<String>()? {
            if obj.contains_key(&key) {
                return Err(serde::de::Error::custom(format!("key {key:?} given twice")));
            }
            let Strict(v) = map.next_value()?;
            obj.insert(key, v);
        }
        Ok(Value::Object(obj))
    }
}

/// A [`MetaError::NotSigmf`] saying `detail`.
fn not_sigmf(detail: &str) -> MetaError {
    MetaError::NotSigmf {
        detail: detail.to_owned(),
    }
}

/// The `global` object of `json`.
fn global(json: &Value) -> Result<&Map<String, Value>, MetaError> {
    json.get(keys::GLOBAL)
        .and_then(Value::as_object)
        .ok_or_else(|| not_sigmf(&format!("no \"{}\" object", keys::GLOBAL)))
}

/// The capture segments of `json` (none when it has no `captures` array).
fn captures(json: &Value) -> Result<&[Value], MetaError> {
    match json.get(keys::CAPTURES) {
        None => Ok(&[]),
        Some(Value::Array(a)) => Ok(a),
        Some(_) => Err(not_sigmf(&format!(
            "\"{}\" is not an array",
            keys::CAPTURES
        ))),
    }
}

/// The fields of capture segment `capture` (`empty` when there is none).
fn capture_fields<'a>(
    capture: Option<&'a Value>,
    empty: &'a Map<String, Value>,
) -> Result<Fields<'a>, MetaError> {
    let obj = match capture {
        None => empty,
        Some(c) => c
            .as_object()
            .ok_or_else(|| not_sigmf("a capture segment is not an object"))?,
    };
    Ok(Fields {
        section: CAPTURE_SECTION,
        obj,
    })
}

/// Typed access to one JSON object of a metadata document, with errors naming the field.
struct Fields<'a> {
    section: &'static str,
    obj: &'a Map<String, Value>,
}

impl Fields<'_> {
    /// The error for `key`'s value `v`, which is not `expected`.
    fn bad(&self, key: &str, v: &Value, expected: &str) -> MetaError {
        MetaError::BadField {
            field: format!("{} {key}", self.section),
            found: v.to_string(),
            expected: expected.to_owned(),
        }
    }

    /// The number `key`, if present.
    fn f64(&self, key: &str) -> Result<Option<f64>, MetaError> {
        self.obj
            .get(key)
            .map(|v| v.as_f64().ok_or_else(|| self.bad(key, v, "a number")))
            .transpose()
    }

    /// The non-negative integer `key`, if present.
    fn u64(&self, key: &str) -> Result<Option<u64>, MetaError> {
        self.obj
            .get(key)
            .map(|v| {
                v.as_u64()
                    .ok_or_else(|| self.bad(key, v, "a non-negative integer"))
            })
            .transpose()
    }

    /// The string `key`, if present.
    fn str(&self, key: &str) -> Result<Option<&str>, MetaError> {
        self.obj
            .get(key)
            .map(|v| v.as_str().ok_or_else(|| self.bad(key, v, "a string")))
            .transpose()
    }

    /// The antenna name (`skyforge:antenna`), if present: it names output files, so it
    /// keeps [`check_antenna_name`].
    fn antenna_name(&self) -> Result<Option<String>, MetaError> {
        let Some(v) = self.obj.get(keys::ANTENNA) else {
            return Ok(None);
        };
        let name = self.str(keys::ANTENNA)?.unwrap_or_default();
        check_antenna_name(name).map_err(|rule| {
            self.bad(keys::ANTENNA, v, &format!("an antenna name, which {rule}"))
        })?;
        Ok(Some(name.to_owned()))
    }

    /// The signals `skyforge:signals` names, if present: a non-empty array of distinct
    /// signal tags.
    fn signals(&self) -> Result<Option<Vec<Signal>>, MetaError> {
        let Some(v) = self.obj.get(keys::SIGNALS) else {
            return Ok(None);
        };
        let expected = "a non-empty array of distinct signal tags (\"gps-l1ca\", \"gal-e1\", ...)";
        let tags = v
            .as_array()
            .filter(|a| !a.is_empty())
            .ok_or_else(|| self.bad(keys::SIGNALS, v, expected))?;
        let mut signals = Vec::with_capacity(tags.len().min(Signal::ALL.len()));
        for t in tags {
            let signal = t
                .as_str()
                .and_then(|t| t.parse::<Signal>().ok())
                .filter(|s| !signals.contains(s))
                .ok_or_else(|| self.bad(keys::SIGNALS, v, expected))?;
            signals.push(signal);
        }
        Ok(Some(signals))
    }

    /// The container named by `core:datatype`.
    fn datatype(&self) -> Result<Option<SampleFormat>, MetaError> {
        self.str(keys::DATATYPE)?
            .map(|d| {
                SampleFormat::from_name(d).ok_or_else(|| MetaError::UnknownDatatype {
                    found: d.to_owned(),
                })
            })
            .transpose()
    }

    /// This capture segment's fields, its frequency `frequency_hz` already read.
    fn capture(&self, frequency_hz: Option<f64>) -> Result<Capture, MetaError> {
        let datetime = self.epoch(keys::DATETIME)?;
        let global_index = self.u64(keys::GLOBAL_INDEX)?;
        let sample_start = self.u64(keys::SAMPLE_START)?;
        let header_bytes = self.u64(keys::HEADER_BYTES)?;
        Ok(Capture {
            frequency_hz,
            datetime,
            global_index,
            sample_start,
            header_bytes,
        })
    }

    /// Refuses a `core:num_channels` other than 1.
    fn single_channel(&self) -> Result<(), MetaError> {
        match self.u64(keys::NUM_CHANNELS)? {
            Some(n) if n != 1 => Err(self.bad(
                keys::NUM_CHANNELS,
                &Value::from(n),
                "1 (multi-channel datasets are not supported: give one file per antenna)",
            )),
            _ => Ok(()),
        }
    }

    /// Refuses header bytes in a capture segment after the first.
    fn no_header_bytes(&self) -> Result<(), MetaError> {
        match self.u64(keys::HEADER_BYTES)? {
            Some(n) if n > 0 => Err(self.bad(
                keys::HEADER_BYTES,
                &Value::from(n),
                "0 after the first capture (header bytes between segments are not supported)",
            )),
            _ => Ok(()),
        }
    }

    /// A UTC time in the supported range (a recording dated 1900 or 9999 gave RINEX
    /// epochs in 1899: GPS weeks do not reach there).
    fn epoch(&self, key: &str) -> Result<Option<Epoch>, MetaError> {
        self.str(key)?
            .map(|s| {
                let epoch = parse_utc(s).ok_or_else(|| {
                    self.bad(
                        key,
                        &Value::from(s),
                        "an ISO-8601 UTC time such as 2023-03-12T00:00:00.000Z",
                    )
                })?;
                if !in_supported_range(epoch) {
                    return Err(self.bad(
                        key,
                        &Value::from(s),
                        &format!("a time {SUPPORTED_RANGE}"),
                    ));
                }
                Ok(epoch)
            })
            .transpose()
    }

    /// The three numbers `key`, if present.
    fn vec3(&self, key: &str) -> Result<Option<[f64; 3]>, MetaError> {
        self.obj
            .get(key)
            .map(|v| {
                let xs: Option<Vec<f64>> = v
                    .as_array()
                    .map(|a| a.iter().filter_map(Value::as_f64).collect());
                xs.and_then(|xs| <[f64; 3]>::try_from(xs).ok())
                    .ok_or_else(|| self.bad(key, v, "three numbers [x, y, z] in metres"))
            })
            .transpose()
    }
}
