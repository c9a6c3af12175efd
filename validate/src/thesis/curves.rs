//! The data of the thesis's figures that the validation tables compute (`curves.json` of
//! `skyforge validate thesis --out DIR`, drawn by `skyforge report DIR`): for each figure,
//! its axes, its series of points and the numbers a caption puts beside the thesis's.
//! A non-finite number is written as `null` and read back as NaN (a gap in a curve).

use serde::{Deserialize, Deserializer, Serialize};

/// The file a `validate thesis --out DIR` run writes the curves to, in DIR.
pub const CURVES_FILE: &str = "curves.json";

/// One figure (or some panels of one) of the thesis.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Curve {
    /// The thesis figure's number, e.g. `3.3-8`.
    pub figure: String,
    /// The thesis figure's panels this one draws, e.g. `(a), (c)`; empty for all of it.
    pub panels: String,
    pub title: String,
    /// Axis labels with their units.
    pub x_label: String,
    pub y_label: String,
    pub series: Vec<CurveSeries>,
    /// Horizontal reference lines (a bound, a thesis value).
    pub references: Vec<Reference>,
    /// SkyForge's numbers beside the thesis's, for the caption.
    pub values: Vec<Value>,
}

/// One series of a figure.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CurveSeries {
    pub name: String,
    pub mark: Mark,
    /// (x, y) in the units of the figure's axes.
    #[serde(deserialize_with = "points_with_gaps")]
    pub points: Vec<(f64, f64)>,
}

/// How a series is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Mark {
    /// A curve.
    Line,
    /// Separate points (Monte Carlo estimates).
    Dots,
    /// A thin curve in the colour of the series before it (a theory beside its Monte
    /// Carlo points).
    Companion,
}

/// A horizontal line across a figure.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Reference {
    pub label: String,
    #[serde(deserialize_with = "number_or_gap")]
    pub value: f64,
}

/// One number of a figure: SkyForge's, and the thesis's where it prints one.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Value {
    pub what: String,
    pub unit: String,
    pub ours: Option<f64>,
    pub thesis: Option<f64>,
}

impl Curve {
    /// "3.3-8 (a)": the figure's number and panels.
    pub fn number(&self) -> String {
        if self.panels.is_empty() {
            self.figure.clone()
        } else {
            format!("{} {}", self.figure, self.panels)
        }
    }
}

impl CurveSeries {
    pub fn new(name: impl Into<String>, mark: Mark, points: Vec<(f64, f64)>) -> Self {
        CurveSeries {
            name: name.into(),
            mark,
            points,
        }
    }
}

impl Value {
    /// SkyForge's `ours` (NaN: none) beside the thesis's `thesis`.
    pub fn new(what: impl Into<String>, unit: &str, ours: f64, thesis: Option<f64>) -> Self {
        Value {
            what: what.into(),
            unit: unit.into(),
            ours: ours.is_finite().then_some(ours),
            thesis,
        }
    }
}

/// Most points a series of a long run keeps in `curves.json`: as many as a chart of the
/// report draws, so the page thins it no further.
pub const MAX_POINTS: usize = 1500;

/// Time series of a long run thinned for the page: every `step`-th point of each (the
/// first kept), the statistics of its figure being those of the whole series.
#[derive(Debug, Clone, PartialEq)]
pub struct Decimated {
    pub series: Vec<CurveSeries>,
    /// One point kept in `step`.
    pub step: usize,
    /// Points of the longest series before thinning.
    pub longest: usize,
}

impl Decimated {
    /// Each of `series` (name, points) as a line, with the smallest common step that
    /// leaves each at most [`MAX_POINTS`] points.
    pub fn lines(series: Vec<(String, Vec<(f64, f64)>)>) -> Self {
        let longest = series.iter().map(|(_, p)| p.len()).max().unwrap_or(0);
        let step = longest.div_ceil(MAX_POINTS).max(1);
        Decimated {
            series: series
                .into_iter()
                .map(|(name, points)| {
                    let kept = points.into_iter().step_by(step).collect();
                    CurveSeries::new(name, Mark::Line, kept)
                })
                .collect(),
            step,
            longest,
        }
    }

    /// What a title says of the thinning: `every 21st of 30247 updates`, or `all 600
    /// epochs` (`what`: what a point is).
    pub fn note(&self, what: &str) -> String {
        let k = self.step;
        let suffix = match (k % 10, k % 100) {
            (_, 11..=13) => "th",
            (1, _) => "st",
            (2, _) => "nd",
            (3, _) => "rd",
            _ => "th",
        };
        if k == 1 {
            format!("all {} {what}", self.longest)
        } else {
            format!("every {k}{suffix} of {} {what}", self.longest)
        }
    }
}

/// The contents of `curves.json`: the figures of the tables run, each computed on the
/// table's registered seeds (also in a `--seeds` run).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CurvesFile {
    pub curves: Vec<Curve>,
}

impl CurvesFile {
    /// As `curves.json` holds it: compact (thousands of points).
    pub fn to_json(&self) -> serde_json::Result<String> {
        serde_json::to_string(self).map(|t| t + "\n")
    }

    /// A `curves.json`; errors carry their line and column.
    pub fn parse(text: &str) -> serde_json::Result<Self> {
        serde_json::from_str(text)
    }
}

fn number_or_gap<'de, D: Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
    Ok(Option::<f64>::deserialize(d)?.unwrap_or(f64::NAN))
}

fn points_with_gaps<'de, D: Deserializer<'de>>(d: D) -> Result<Vec<(f64, f64)>, D::Error> {
    let points = Vec::<(Option<f64>, Option<f64>)>::deserialize(d)?;
    let gap = |v: Option<f64>| v.unwrap_or(f64::NAN);
    Ok(points.into_iter().map(|(x, y)| (gap(x), gap(y))).collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn long_series_keep_every_step_th_point() {
        let long: Vec<(f64, f64)> = (0..30_247).map(|k| (k as f64, -(k as f64))).collect();
        let d = Decimated::lines(vec![
            ("a".into(), long.clone()),
            ("b".into(), long[..100].to_vec()),
        ]);
        assert_eq!((d.step, d.longest), (21, 30_247));
        assert_eq!(d.series[0].points.len(), 1441);
        assert!(d.series.iter().all(|s| s.points.len() <= MAX_POINTS));
        assert_eq!(d.series[0].points[1], (21.0, -21.0));
        assert_eq!(d.series[1].points.len(), 5);
        assert_eq!(d.note("updates"), "every 21st of 30247 updates");
        let note = |step| Decimated { step, ..d.clone() }.note("epochs");
        assert_eq!(
            [2, 3, 4, 11, 12, 13, 22, 111].map(note),
            ["2nd", "3rd", "4th", "11th", "12th", "13th", "22nd", "111th"]
                .map(|k| format!("every {k} of 30247 epochs"))
        );
        let short = Decimated::lines(vec![("a".into(), long[..600].to_vec())]);
        assert_eq!((short.step, short.series[0].points.len()), (1, 600));
        assert_eq!(short.note("epochs"), "all 600 epochs");
        assert_eq!(Decimated::lines(Vec::new()).step, 1);
    }

    #[test]
    fn curves_json_round_trips_with_gaps_as_null() {
        let file = CurvesFile {
            curves: vec![Curve {
                figure: "3.3-9".into(),
                panels: String::new(),
                title: "NMSE".into(),
                x_label: "fd Tc".into(),
                y_label: "NMSE".into(),
                series: vec![CurveSeries::new(
                    "Monte Carlo",
                    Mark::Dots,
                    vec![(-0.5, 1e-9), (0.0, f64::NAN)],
                )],
                references: vec![Reference {
                    label: "MCRB".into(),
                    value: 1.4e-10,
                }],
                values: vec![Value::new("max", "-", f64::NAN, Some(1e-9))],
            }],
        };
        let text = file.to_json().unwrap();
        assert!(text.contains("null") && text.contains("\"dots\""), "{text}");
        let back = CurvesFile::parse(&text).unwrap();
        let (c, b) = (&file.curves[0], &back.curves[0]);
        assert_eq!(b.series[0].points[0], c.series[0].points[0]);
        assert!(b.series[0].points[1].1.is_nan());
        assert_eq!(b.references, c.references);
        assert_eq!(b.values, c.values);
        assert_eq!(b.values[0].ours, None);
        let e = CurvesFile::parse("{\n \"curves\": 1\n}").unwrap_err();
        assert_eq!(e.line(), 2);
    }
}
