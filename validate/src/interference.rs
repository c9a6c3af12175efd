//! `skyforge validate interference`: a jamming monitor's verdicts (`interference.csv`)
//! against the truth's jammers (`truth.h5` group `jammers`): for every span in which a
//! jammer transmits, how long after its start the first alarm came (or none before its
//! end); and the alarms outside every span and its grace period (false alarms), against
//! the number of such clean epochs.

use serde::Serialize;
use skyforge_formats::truth::JammerTruth;
use skyforge_navigation::interference::JammingEpoch;

/// Seconds after a span's end during which an alarm is not false: the receiver's C/N0
/// estimates still hold the jammed prompts. # assumed: 2 s, twice the bundled
/// receiver's 1-s C/N0 window.
pub const GRACE_S: f64 = 2.0;

/// One span in which some jammer transmits.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct JammedSpan {
    /// Its start and end (s since the truth's start epoch).
    pub start_s: f64,
    pub end_s: f64,
    /// The first alarm within it, in seconds after its start; `None`: not detected.
    pub detected_after_s: Option<f64>,
}

/// The score.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct JammingScore {
    pub spans: Vec<JammedSpan>,
    /// Epochs outside every span and grace period, and those among them with an alarm.
    pub clean_epochs: usize,
    pub false_alarms: usize,
}

/// The spans of `truth` in which any jammer transmits, from its epochs (each span closes
/// at the first epoch with none on).
fn spans(truth: &JammerTruth) -> Vec<(f64, f64)> {
    let mut out = Vec::new();
    let mut open: Option<f64> = None;
    for (t, on) in truth.t_s.iter().zip(&truth.on) {
        match (open, on.iter().any(|o| *o)) {
            (None, true) => open = Some(*t),
            (Some(start), false) => {
                out.push((start, *t));
                open = None;
            }
            _ => {}
        }
    }
    if let (Some(start), Some(last)) = (open, truth.t_s.last()) {
        out.push((start, *last));
    }
    out
}

/// Scores `epochs` against `truth`; `since_start(t)` gives an epoch's seconds since the
/// truth's start epoch.
pub fn score_jamming(
    epochs: &[JammingEpoch],
    truth: &JammerTruth,
    since_start: impl Fn(&JammingEpoch) -> f64,
) -> JammingScore {
    let jammed = spans(truth);
    let spans = (jammed.iter())
        .map(|&(start_s, end_s)| JammedSpan {
            start_s,
            end_s,
            detected_after_s: (epochs.iter())
                .map(|e| (since_start(e), e.alarm))
                .find(|&(t, alarm)| alarm && t >= start_s && t < end_s)
                .map(|(t, _)| t - start_s),
        })
        .collect();
    let clean: Vec<&JammingEpoch> = (epochs.iter())
        .filter(|e| {
            let t = since_start(e);
            !jammed.iter().any(|&(s, end)| t >= s && t < end + GRACE_S)
        })
        .collect();
    JammingScore {
        spans,
        clean_epochs: clean.len(),
        false_alarms: clean.iter().filter(|e| e.alarm).count(),
    }
}

/// The score as text.
pub fn print_jamming(s: &JammingScore, out: &mut impl std::io::Write) -> std::io::Result<()> {
    for span in &s.spans {
        match span.detected_after_s {
            Some(d) => writeln!(
                out,
                "jammed     {:.1}-{:.1} s: detected {d:.1} s after its start",
                span.start_s, span.end_s
            )?,
            None => writeln!(
                out,
                "jammed     {:.1}-{:.1} s: not detected",
                span.start_s, span.end_s
            )?,
        }
    }
    writeln!(
        out,
        "clean      {} epochs, {} false alarms",
        s.clean_epochs, s.false_alarms
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use hifitime::Epoch;

    /// A jammer on from 10 to 20 s: detected at 11 s; an alarm at 21 s is within the
    /// grace, one at 30 s is false.
    #[test]
    fn spans_detections_and_false_alarms_are_counted() {
        let t_s: Vec<f64> = (0..40).map(f64::from).collect();
        let on = t_s.iter().map(|t| vec![(10.0..20.0).contains(t)]).collect();
        let truth = JammerTruth {
            names: vec!["j".into()],
            antennas: vec!["ant1".into()],
            t_s: t_s.clone(),
            on,
            range_m: Vec::new(),
            jn0_dbhz: Vec::new(),
            azimuth_deg: Vec::new(),
            elevation_deg: Vec::new(),
        };
        let epochs: Vec<JammingEpoch> = (t_s.iter())
            .map(|&t| JammingEpoch {
                t: Epoch::from_gpst_seconds(t),
                tracked: 8,
                referenced: 8,
                change_db: 0.0,
                threshold_db: -1.0,
                alarm: [11.0, 12.0, 21.0, 30.0].contains(&t),
            })
            .collect();
        let s = score_jamming(&epochs, &truth, |e| e.t.to_gpst_seconds());
        assert_eq!(s.spans.len(), 1);
        assert_eq!((s.spans[0].start_s, s.spans[0].end_s), (10.0, 20.0));
        assert_eq!(s.spans[0].detected_after_s, Some(1.0));
        assert_eq!((s.clean_epochs, s.false_alarms), (40 - 12, 1));
    }
}
