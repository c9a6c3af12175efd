//! What one antenna's sample file holds: from its SigMF metadata (SigMF 1.0 `core`
//! fields plus SkyForge's `skyforge:` extension, read by [`skyforge_gnss::sigmf`]) merged
//! with what the command line gives, or from raw-file parameters given on the command line.

use super::error::{Finding, InputError};
use super::format::SampleFormat;
use hifitime::Epoch;
use serde_json::Value;
use skyforge_gnss::sigmf::{ParsedMeta, keys, parse_json};
use skyforge_gnss::signal::Signal;
use skyforge_orbits::bounded_read::read_text;
use std::path::{Path, PathBuf};

/// Largest SigMF metadata file read (annotations included).
const META_MAX_BYTES: u64 = 16 << 20;

/// Command-line description of sample files (`--format`, `--fs`, `--if`, `--signal`):
/// required (format and rate) for raw files; for SigMF recordings, what is given fills in
/// or overrides the metadata (an override that changes a value is reported).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct InputParams {
    /// `--format`.
    pub format: Option<SampleFormat>,
    /// Sample rate (Hz; real samples per second for `ri8`).
    pub sample_rate_hz: Option<f64>,
    /// Where the signal's carrier sits in the recording (Hz): the real IF for `ri8`, the
    /// offset from the centre for complex samples (0: baseband).
    pub if_hz: Option<f64>,
    /// `--signal`.
    pub signal: Option<Signal>,
}

/// One antenna's recording, as described by its metadata or the command line.
#[derive(Debug, Clone, PartialEq)]
pub struct Recording {
    /// Antenna name (`skyforge:antenna`, else the file name without its extension).
    pub antenna: String,
    /// The sample file.
    pub data_path: PathBuf,
    /// The `.sigmf-meta` file, if any.
    pub meta_path: Option<PathBuf>,
    /// Sample container.
    pub format: SampleFormat,
    /// Sample rate (Hz).
    pub sample_rate_hz: f64,
    /// Where the carrier sits in the recording (Hz): see [`InputParams::if_hz`].
    pub if_hz: f64,
    /// Centre frequency of the recorded band (Hz; SigMF capture `core:frequency`).
    pub centre_frequency_hz: Option<f64>,
    /// The signal recorded, when the metadata or the command line tells; `None` for a
    /// recording of several signals read for all of them ([`Self::carried`]).
    pub signal: Option<Signal>,
    /// Every signal of a recording that carries several (`skyforge:signals`); empty for
    /// one of a single signal.
    pub carried: Vec<Signal>,
    /// UTC time of the first sample (`core:datetime` of the first capture).
    pub start_utc: Option<Epoch>,
    /// Index of the first sample in the recorder's sample stream (`core:global_index`).
    pub global_index: Option<u64>,
    /// Samples to skip at the start of the data (the first capture's `core:sample_start`).
    pub first_sample: u64,
    /// Non-sample bytes before the samples (`core:header_bytes`) and after them
    /// (`core:trailing_bytes`).
    pub header_bytes: u64,
    pub trailing_bytes: u64,
    /// Nominal antenna position in the body frame (m; `skyforge:antenna_position_body_m`).
    pub antenna_position_body_m: Option<[f64; 3]>,
    /// What the metadata reading found worth reporting.
    pub findings: Vec<Finding>,
}

/// Whether `path` names a SigMF recording (`.sigmf-meta` or `.sigmf-data`).
pub fn is_sigmf(path: &Path) -> bool {
    path.extension()
        .is_some_and(|e| e == "sigmf-meta" || e == "sigmf-data")
}

/// File name without its last extension.
fn stem(path: &Path) -> String {
    path.file_stem().map_or_else(
        || path.display().to_string(),
        |s| s.to_string_lossy().into_owned(),
    )
}

/// Metadata values merged with command-line values: the findings of the overrides.
struct Merge<'a> {
    meta_path: &'a Path,
    findings: Vec<Finding>,
}

impl Merge<'_> {
    /// `given` when there is one (reported when it replaces a different `meta`), else
    /// `meta`.
    fn pick<T: ToString>(&mut self, field: &str, meta: Option<T>, given: Option<T>) -> Option<T> {
        if let (Some(meta), Some(given)) = (&meta, &given) {
            let (metadata, given) = (meta.to_string(), given.to_string());
            if metadata != given {
                self.findings.push(Finding::Overridden {
                    path: self.meta_path.to_owned(),
                    field: field.to_owned(),
                    metadata,
                    given,
                });
            }
        }
        given.or(meta)
    }

    /// The error for a global field `key` that neither the metadata nor the command line
    /// gives (`why` the receiver needs it).
    fn missing(&self, key: &str, why: &'static str) -> InputError {
        InputError::MissingField {
            path: self.meta_path.to_owned(),
            field: format!("{} {key}", keys::GLOBAL),
            why,
        }
    }

    /// The signal recorded: the command line's, else the metadata's (the one whose carrier
    /// is the centre frequency plus `skyforge:if_hz`, else the one in the band recorded,
    /// else the one the file name names; a file name naming another signal of that carrier,
    /// Galileo E1 beside GPS L1 C/A, wins). A recording of several signals has none unless
    /// the command line picks one of them.
    fn signal(
        &mut self,
        meta: &ParsedMeta,
        sample_rate_hz: f64,
        given: Option<Signal>,
    ) -> Option<Signal> {
        if let Some(carried) = &meta.signals {
            return match given {
                Some(g) if !carried.contains(&g) => {
                    let tags: Vec<&str> = carried.iter().map(|s| s.tag()).collect();
                    self.pick("the signal", Some(tags.join("+")), Some(g.tag().to_owned()));
                    Some(g)
                }
                given => given,
            };
        }
        let centre = meta.first_capture.frequency_hz;
        let by_carrier = centre
            .zip(meta.if_hz)
            .and_then(|(c, f_if)| Signal::from_carrier_hz(c + f_if));
        let named = Signal::from_file_name(&file_name(self.meta_path));
        let meta_signal = by_carrier
            .or_else(|| centre.and_then(|c| Signal::in_band(c, sample_rate_hz)))
            // Galileo E1 shares GPS L1 C/A's carrier: the file name tells them apart.
            .map(|s| {
                named
                    .filter(|n| n.carrier_hz() == s.carrier_hz())
                    .unwrap_or(s)
            })
            .or(named);
        self.pick("the signal", meta_signal, given)
    }
}

/// The last component of `path`, or nothing.
fn file_name(path: &Path) -> String {
    path.file_name()
        .map_or_else(String::new, |n| n.to_string_lossy().into_owned())
}

impl Recording {
    /// The recording at `path`: SigMF when it ends in `.sigmf-meta` or `.sigmf-data` (the
    /// other file of the pair next to it), raw samples described by `params` otherwise.
    pub fn open(path: &Path, params: &InputParams) -> Result<Self, InputError> {
        let rec = if is_sigmf(path) {
            Self::from_sigmf(path, params)?
        } else {
            Self::raw(path, params)?
        };
        rec.check()?;
        Ok(rec)
    }

    /// A raw sample file: `params` must give the format and the sample rate; the IF
    /// defaults to 0 and the signal to unknown.
    pub fn raw(path: &Path, params: &InputParams) -> Result<Self, InputError> {
        let (Some(format), Some(sample_rate_hz)) = (params.format, params.sample_rate_hz) else {
            return Err(InputError::RawParametersNeeded {
                path: path.to_owned(),
            });
        };
        let if_hz = params.if_hz.unwrap_or(0.0);
        Ok(Self {
            antenna: stem(path),
            data_path: path.to_owned(),
            meta_path: None,
            format,
            sample_rate_hz,
            if_hz,
            centre_frequency_hz: params.signal.map(|s| s.carrier_hz() - if_hz),
            signal: params.signal,
            carried: Vec::new(),
            start_utc: None,
            global_index: None,
            first_sample: 0,
            header_bytes: 0,
            trailing_bytes: 0,
            antenna_position_body_m: None,
            findings: Vec::new(),
        })
    }

    /// A SigMF recording named by its `.sigmf-meta` or `.sigmf-data` file.
    pub fn from_sigmf(path: &Path, params: &InputParams) -> Result<Self, InputError> {
        let meta_path = path.with_extension("sigmf-meta");
        let text =
            read_text(&meta_path, META_MAX_BYTES, "SigMF metadata file").map_err(|e| {
                match e.kind() {
                    std::io::ErrorKind::InvalidData => InputError::NotSigmf {
                        path: meta_path.clone(),
                        detail: "not UTF-8 text".into(),
                    },
                    _ => InputError::io(&meta_path, e),
                }
            })?;
        let json = parse_json(&text).map_err(|e| InputError::meta(&meta_path, e))?;
        Self::from_sigmf_json(&meta_path, &json, params)
    }

    /// A SigMF recording from its parsed metadata `json` (read from `meta_path`; the
    /// samples are in the `.sigmf-data` file beside it).
    pub fn from_sigmf_json(
        meta_path: &Path,
        json: &Value,
        params: &InputParams,
    ) -> Result<Self, InputError> {
        let meta = ParsedMeta::from_json(json).map_err(|e| InputError::meta(meta_path, e))?;
        let mut merge = Merge {
            meta_path,
            findings: Vec::new(),
        };
        let format = merge
            .pick(keys::DATATYPE, meta.format, params.format)
            .ok_or_else(|| merge.missing(keys::DATATYPE, "the sample format; or give --format"))?;
        let sample_rate_hz = merge
            .pick(
                keys::SAMPLE_RATE,
                meta.sample_rate_hz,
                params.sample_rate_hz,
            )
            .ok_or_else(|| {
                merge.missing(
                    keys::SAMPLE_RATE,
                    "the receiver needs the sample rate; or give --fs",
                )
            })?;
        if meta.capture_count > 1 {
            merge.findings.push(Finding::SeveralCaptures {
                path: meta_path.to_owned(),
                count: meta.capture_count,
            });
        }
        let signal = merge.signal(&meta, sample_rate_hz, params.signal);
        let c0 = &meta.first_capture;
        let carrier_offset = signal.zip(c0.frequency_hz).map(|(s, c)| s.carrier_hz() - c);
        let if_hz = merge
            .pick("the IF", meta.if_hz.or(carrier_offset), params.if_hz)
            .unwrap_or(0.0);
        let antenna = meta.antenna.clone().unwrap_or_else(|| {
            file_name(meta_path)
                .trim_end_matches(".sigmf-meta")
                .to_owned()
        });
        Ok(Self {
            antenna,
            data_path: meta_path.with_extension("sigmf-data"),
            meta_path: Some(meta_path.to_owned()),
            format,
            sample_rate_hz,
            if_hz,
            centre_frequency_hz: c0.frequency_hz,
            signal,
            carried: meta.signals.clone().unwrap_or_default(),
            start_utc: c0.datetime,
            global_index: c0.global_index,
            first_sample: c0.sample_start.unwrap_or(0),
            header_bytes: c0.header_bytes.unwrap_or(0),
            trailing_bytes: meta.trailing_bytes.unwrap_or(0),
            antenna_position_body_m: meta.antenna_position_body_m,
            findings: merge.findings,
        })
    }

    /// The file this description came from (the metadata, else the samples).
    pub fn source_path(&self) -> &Path {
        self.meta_path.as_deref().unwrap_or(&self.data_path)
    }

    /// Checks that the rate and IF can be processed: a positive finite rate; `|IF| < fs/2`;
    /// a real (`ri8`) recording needs `0 < IF < fs/2` (at IF 0 the image would fall on
    /// the signal).
    pub fn check(&self) -> Result<(), InputError> {
        let bad = |field: &str, found: f64, expected: String| InputError::BadField {
            path: self.source_path().to_owned(),
            field: field.to_owned(),
            found: found.to_string(),
            expected,
        };
        let fs = self.sample_rate_hz;
        if !(fs.is_finite() && fs > 0.0) {
            return Err(bad(
                &format!("the sample rate ({} or --fs)", keys::SAMPLE_RATE),
                fs,
                "a positive number of samples per second".into(),
            ));
        }
        let nyquist = fs / 2.0;
        let if_field = || {
            format!(
                "the IF ({}, carrier - {}, or --if)",
                keys::IF_HZ,
                keys::FREQUENCY
            )
        };
        if !(self.if_hz.is_finite() && self.if_hz.abs() < nyquist) {
            return Err(bad(
                &if_field(),
                self.if_hz,
                format!("|IF| < fs / 2 = {nyquist} Hz"),
            ));
        }
        if !self.format.is_complex() && self.if_hz <= 0.0 {
            return Err(bad(
                &if_field(),
                self.if_hz,
                format!("0 < IF < {nyquist} Hz for real (ri8) samples: give --if"),
            ));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    fn foreign(centre_hz: f64) -> Value {
        // A SigMF recording of another tool: no skyforge fields.
        json!({
            "global": {"core:datatype": "cf32_le", "core:sample_rate": 5e6, "core:version": "1.0.0"},
            "captures": [
                {"core:sample_start": 0, "core:frequency": centre_hz,
                 "core:datetime": "2020-06-25T12:00:00Z", "core:global_index": 1000},
                {"core:sample_start": 500, "core:frequency": centre_hz}
            ],
        })
    }

    #[test]
    fn the_if_of_a_foreign_recording_is_the_carrier_minus_the_centre() {
        let p = Path::new("/data/rx.sigmf-meta");
        let r =
            Recording::from_sigmf_json(p, &foreign(1561.098e6 - 250e3), &InputParams::default())
                .unwrap();
        assert_eq!(r.signal, Some(Signal::BdsB1I));
        assert!((r.if_hz - 250e3).abs() < 1e-6, "{}", r.if_hz);
        assert_eq!(r.antenna, "rx");
        assert_eq!(r.data_path, Path::new("/data/rx.sigmf-data"));
        assert_eq!(r.global_index, Some(1000));
        assert_eq!(
            r.findings,
            [Finding::SeveralCaptures {
                path: p.to_owned(),
                count: 2
            }]
        );
        // Centred between the bands at a wide rate: ambiguous, so unknown and IF 0.
        let mut wide = foreign(1568e6);
        wide["global"]["core:sample_rate"] = json!(40e6);
        let r = Recording::from_sigmf_json(p, &wide, &InputParams::default()).unwrap();
        assert_eq!((r.signal, r.if_hz), (None, 0.0));
    }

    #[test]
    fn command_line_values_override_the_metadata_and_say_so() {
        let p = Path::new("ant.sigmf-meta");
        let params = InputParams {
            sample_rate_hz: Some(5e6),
            if_hz: Some(1e3),
            ..InputParams::default()
        };
        let r = Recording::from_sigmf_json(p, &foreign(1575.42e6), &params).unwrap();
        assert_eq!((r.sample_rate_hz, r.if_hz), (5e6, 1e3));
        // The same rate is no override; the IF (0 from the carrier) is.
        assert_eq!(
            r.findings[1].to_string(),
            "ant.sigmf-meta: the IF 1000 from the command line replaces 0 of the metadata"
        );
        assert_eq!(r.findings.len(), 2);
    }
}
