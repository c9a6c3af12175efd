//! Line charts rendered to SVG text by plotters: series of (x, y) points, each with an
//! optional confidence band, and horizontal reference lines (thesis values).

use plotters::coord::Shift;
use plotters::coord::ranged1d::ValueFormatter;
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;
use std::ops::Range;

/// Most points a series keeps (longer ones are thinned evenly): enough for a 760-pixel
/// plot, small enough that a page of figures stays light.
const MAX_POINTS: usize = 1500;

/// One curve of a chart.
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    pub name: String,
    pub points: Vec<(f64, f64)>,
    /// (x, low, high) of a band drawn under the curve.
    pub band: Vec<(f64, f64, f64)>,
    /// Drawn thin in the colour of the curve before it (e.g. a percentile beside a mean).
    pub companion: bool,
    /// Drawn as dots, not joined.
    pub dots: bool,
    /// A colour of its own (RGB) instead of the next one in turn.
    pub colour: Option<(u8, u8, u8)>,
}

impl Series {
    /// A curve without a band.
    pub fn line(name: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Series {
            name: name.into(),
            points,
            band: Vec::new(),
            companion: false,
            dots: false,
            colour: None,
        }
    }

    /// Dots, not joined (values of separate rows).
    pub fn dots(name: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Series {
            dots: true,
            ..Series::line(name, points)
        }
    }

    /// A thin curve in the colour of the one before it.
    pub fn companion(name: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Series {
            companion: true,
            ..Series::line(name, points)
        }
    }
}

/// A chart: axes, curves and horizontal reference lines (label, value; an empty label
/// stays out of the legend).
#[derive(Debug, Clone, PartialEq)]
pub struct Chart {
    pub title: String,
    pub x_label: String,
    pub y_label: String,
    pub series: Vec<Series>,
    pub references: Vec<(String, f64)>,
    /// The y axis reaches down (or up) to zero (counts, rates).
    pub y_from_zero: bool,
}

/// Why a chart could not be drawn.
#[derive(Debug, thiserror::Error)]
#[error("chart \"{title}\": {reason}")]
pub struct ChartError {
    title: String,
    reason: String,
}

impl Chart {
    /// A chart with no curves yet.
    pub fn new(title: &str, x_label: &str, y_label: &str) -> Self {
        Chart {
            title: title.into(),
            x_label: x_label.into(),
            y_label: y_label.into(),
            series: Vec::new(),
            references: Vec::new(),
            y_from_zero: false,
        }
    }

    /// The chart as an `<svg>` element (760 x 380 pixels).
    pub fn to_svg(&self) -> Result<String, ChartError> {
        let fail = |reason: String| ChartError {
            title: self.title.clone(),
            reason,
        };
        let (x, y) = self
            .ranges()
            .ok_or_else(|| fail("no finite point".into()))?;
        let mut svg = String::new();
        {
            let root = SVGBackend::with_string(&mut svg, (760, 380)).into_drawing_area();
            self.draw(&root, x, y).map_err(|e| fail(e.to_string()))?;
            root.present().map_err(|e| fail(e.to_string()))?;
        }
        Ok(svg)
    }

    fn draw(
        &self,
        root: &DrawingArea<SVGBackend<'_>, Shift>,
        x: Range<f64>,
        y: Range<f64>,
    ) -> Result<(), Box<dyn std::error::Error + '_>> {
        root.fill(&WHITE)?;
        let mut chart = ChartBuilder::on(root)
            .caption(&self.title, ("sans-serif", 18))
            .margin(12)
            .x_label_area_size(42)
            .y_label_area_size(64)
            .build_cartesian_2d(x.clone(), y)?;
        chart
            .configure_mesh()
            .x_desc(&self.x_label)
            .y_desc(&self.y_label)
            .x_label_formatter(&tick)
            .y_label_formatter(&tick)
            .light_line_style(WHITE.mix(0.0))
            .draw()?;
        let mut k: usize = 0;
        for s in &self.series {
            if !s.companion {
                k += 1;
            }
            let colour = match s.colour {
                Some((r, g, b)) => RGBColor(r, g, b).to_rgba(),
                None => colour(k.saturating_sub(1)),
            };
            let width = if s.companion { 1 } else { 2 };
            let band = thin(&s.band);
            if !band.is_empty() {
                let outline: Vec<(f64, f64)> = band
                    .iter()
                    .map(|&(x, lo, _)| (x, lo))
                    .chain(band.iter().rev().map(|&(x, _, hi)| (x, hi)))
                    .filter(|p| p.0.is_finite() && p.1.is_finite())
                    .collect();
                chart.draw_series(std::iter::once(Polygon::new(outline, colour.mix(0.2))))?;
            }
            let points: Vec<(f64, f64)> = thin(&s.points)
                .into_iter()
                .filter(|p| p.0.is_finite() && p.1.is_finite())
                .collect();
            let drawn = if s.dots {
                chart.draw_series(
                    points
                        .into_iter()
                        .map(|p| Circle::new(p, 4, colour.filled())),
                )?
            } else {
                chart.draw_series(LineSeries::new(points, colour.stroke_width(width)))?
            };
            if !s.name.is_empty() {
                drawn
                    .label(s.name.as_str())
                    .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], colour));
            }
        }
        for (label, value) in &self.references {
            let line = vec![(x.start, *value), (x.end, *value)];
            let drawn = chart.draw_series(LineSeries::new(line, BLACK.stroke_width(1)))?;
            if !label.is_empty() {
                drawn
                    .label(label.as_str())
                    .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 18, y)], BLACK));
            }
        }
        let named = self.series.iter().filter(|s| !s.name.is_empty()).count();
        if named > 1 || !self.references.is_empty() {
            chart
                .configure_series_labels()
                .background_style(WHITE.mix(0.85))
                .border_style(BLACK.mix(0.4))
                .draw()?;
        }
        Ok(())
    }

    /// Axis ranges covering every finite point, band and the reference, with a margin.
    fn ranges(&self) -> Option<(Range<f64>, Range<f64>)> {
        let points = self.series.iter().flat_map(|s| {
            s.points
                .iter()
                .copied()
                .chain(s.band.iter().flat_map(|&(x, lo, hi)| [(x, lo), (x, hi)]))
        });
        let reference = self.references.iter().map(|r| (f64::NAN, r.1));
        let (mut x, mut y) = (Bounds::default(), Bounds::default());
        for (px, py) in points.chain(reference) {
            x.add(px);
            y.add(py);
        }
        if self.y_from_zero {
            y.add(0.0);
        }
        Some((x.range(0.0)?, y.range(0.05)?))
    }
}

/// Running minimum and maximum of finite values.
#[derive(Debug, Clone, Copy)]
struct Bounds {
    lo: f64,
    hi: f64,
}

impl Default for Bounds {
    fn default() -> Self {
        Bounds {
            lo: f64::INFINITY,
            hi: f64::NEG_INFINITY,
        }
    }
}

impl Bounds {
    fn add(&mut self, v: f64) {
        if v.is_finite() {
            self.lo = self.lo.min(v);
            self.hi = self.hi.max(v);
        }
    }

    /// The range widened by `margin` of its span (a flat range by one unit).
    fn range(self, margin: f64) -> Option<Range<f64>> {
        if self.lo > self.hi {
            return None;
        }
        let span = self.hi - self.lo;
        let pad = if span > 0.0 {
            span * margin
        } else {
            self.lo.abs().max(1.0) * 0.5
        };
        Some(self.lo - pad..self.hi + pad)
    }
}

/// An axis label: plotters' own (at most five decimals), or three significant digits in
/// scientific notation below 1e-3, which five decimals would round away (an NMSE of 1e-10
/// reads 0.0).
fn tick(v: &f64) -> String {
    if *v == 0.0 || v.abs() >= 1e-3 {
        return RangedCoordf64::format(v);
    }
    let text = format!("{v:.2e}");
    match text.split_once('e') {
        Some((mantissa, exponent)) if mantissa.contains('.') => {
            let mantissa = mantissa.trim_end_matches('0').trim_end_matches('.');
            format!("{mantissa}e{exponent}")
        }
        _ => text,
    }
}

/// Curve colour `k`: the ten of Tableau 10 in turn (distinct, readable on white).
fn colour(k: usize) -> RGBAColor {
    const TABLEAU: [(u8, u8, u8); 10] = [
        (31, 119, 180),
        (255, 127, 14),
        (44, 160, 44),
        (214, 39, 40),
        (148, 103, 189),
        (140, 86, 75),
        (227, 119, 194),
        (127, 127, 127),
        (188, 189, 34),
        (23, 190, 207),
    ];
    let (r, g, b) = TABLEAU[k % TABLEAU.len()];
    RGBColor(r, g, b).to_rgba()
}

/// At most `MAX_POINTS` of `v`, evenly spaced, the last one kept.
fn thin<T: Copy>(v: &[T]) -> Vec<T> {
    if v.len() <= MAX_POINTS {
        return v.to_vec();
    }
    let step = v.len().div_ceil(MAX_POINTS);
    let mut out: Vec<T> = v.iter().step_by(step).copied().collect();
    if !(v.len() - 1).is_multiple_of(step) {
        out.extend(v.last().copied());
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn draws_curves_bands_and_the_reference_as_svg() {
        let mut c = Chart::new("fix rate", "C/N0 (dB-Hz)", "fix rate");
        c.series.push(Series {
            name: "mean".into(),
            points: vec![(35.0, 0.03), (40.0, 0.58), (45.0, 1.0)],
            band: vec![(35.0, 0.02, 0.04), (40.0, 0.5, 0.6), (45.0, 0.99, 1.0)],
            companion: false,
            dots: false,
            colour: None,
        });
        c.series.push(Series::dots("rows", vec![(36.0, 0.5)]));
        c.series
            .push(Series::companion("p95", vec![(35.0, 0.05), (45.0, 1.0)]));
        c.references = vec![("thesis".into(), 0.9), (String::new(), 0.1)];
        let svg = c.to_svg().unwrap();
        assert!(svg.starts_with("<svg"));
        for needle in [
            "fix rate",
            "C/N0 (dB-Hz)",
            "thesis",
            "<polyline",
            "<polygon",
            "<circle",
        ] {
            assert!(svg.contains(needle), "{needle}");
        }
    }

    #[test]
    fn small_ticks_keep_their_digits() {
        assert_eq!(tick(&1.5e-10), "1.5e-10");
        assert_eq!(tick(&-2.5e-4), "-2.5e-4");
        assert_eq!(tick(&5e-5), "5e-5");
        assert_eq!(tick(&0.0), RangedCoordf64::format(&0.0));
        assert_eq!(tick(&12.5), RangedCoordf64::format(&12.5));
    }

    #[test]
    fn a_chart_without_finite_points_is_an_error() {
        let mut c = Chart::new("empty", "x", "y");
        c.series.push(Series::line("nan", vec![(f64::NAN, 1.0)]));
        let e = c.to_svg().unwrap_err().to_string();
        assert!(e.contains("empty") && e.contains("no finite point"), "{e}");
    }

    #[test]
    fn long_series_are_thinned_to_the_limit_keeping_both_ends() {
        let v: Vec<usize> = (0..10_001).collect();
        let t = thin(&v);
        assert!(t.len() <= MAX_POINTS + 1);
        assert_eq!((t[0], *t.last().unwrap()), (0, 10_000));
        assert_eq!(thin(&v[..10]), v[..10].to_vec());
    }
}
