//! Thesis figures 3.3-7 to 3.3-11, 4.3-2, 4.3-3, 4.3-6 to 4.3-10 and 5.5-2 to 5.5-5 from
//! `curves.json` (`skyforge validate thesis --out`):
//! the data of the figures the validation tables compute on their registered seeds
//! ([`skyforge_validate::thesis::curves`]), one figure per curve, each caption giving SkyForge's
//! numbers beside the thesis's where it prints any.

use super::chart::{Chart, Series};
use super::page::Section;
use super::{ReportError, figure, read_text};
use skyforge_validate::thesis::curves::{Curve, CurvesFile, Mark, Value};
use std::path::Path;

/// Largest `curves.json` read (bytes): a whole thesis run writes about 300 kB.
const MAX_BYTES: u64 = 16 << 20;

/// The section of the thesis figures in `path` (a `curves.json`).
pub fn section(path: &Path) -> Result<Section, ReportError> {
    let err = |m: String| ReportError::new(path, m);
    let text = read_text(path, MAX_BYTES)?;
    let file = CurvesFile::parse(&text).map_err(|e| {
        err(format!(
            "line {}, column {}: {e} (expected the curves `skyforge validate thesis --out` writes)",
            e.line(),
            e.column()
        ))
    })?;
    let figures = file
        .curves
        .iter()
        .map(|c| figure(&chart(c), caption(c), path))
        .collect::<Result<_, _>>()?;
    Ok(Section {
        heading: "Thesis figures of the validation".into(),
        paragraphs: vec![format!(
            "{} figures the validation tables compute, each on its table's registered seeds \
             (also when validate thesis ran over seeds).",
            file.curves.len()
        )],
        figures,
        tables: Vec::new(),
    })
}

fn chart(c: &Curve) -> Chart {
    let mut chart = Chart::new(
        &format!("Figure {}: {}", c.number(), c.title),
        &c.x_label,
        &c.y_label,
    );
    chart.series = c
        .series
        .iter()
        .map(|s| {
            let (name, points) = (s.name.as_str(), s.points.clone());
            match s.mark {
                Mark::Line => Series::line(name, points),
                Mark::Dots => Series::dots(name, points),
                Mark::Companion => Series::companion(name, points),
            }
        })
        .collect();
    chart.references = c
        .references
        .iter()
        .map(|r| (r.label.clone(), r.value))
        .collect();
    chart
}

/// "Thesis figure N: title." and each value, SkyForge's beside the thesis's.
fn caption(c: &Curve) -> String {
    let mut text = format!("Thesis figure {}: {}.", c.number(), c.title);
    for v in &c.values {
        text.push(' ');
        text.push_str(&value_text(v));
    }
    if c.values.iter().all(|v| v.thesis.is_none()) {
        text.push_str(" The thesis prints no number for this figure.");
    }
    text
}

/// "What: SkyForge x unit, thesis y unit." (`-`: no unit).
fn value_text(v: &Value) -> String {
    let mut chars = v.what.chars();
    let what: String = chars
        .next()
        .map(|c| c.to_uppercase().chain(chars).collect())
        .unwrap_or_default();
    let unit = if v.unit == "-" {
        String::new()
    } else {
        format!(" {}", v.unit)
    };
    let ours = v.ours.map_or_else(
        || "none".to_string(),
        |x| format!("{}{unit}", significant(x)),
    );
    match v.thesis {
        Some(t) => format!("{what}: SkyForge {ours}, thesis {}{unit}.", printed(t)),
        None => format!("{what}: SkyForge {ours}."),
    }
}

/// `x` to four significant digits.
fn significant(x: f64) -> String {
    let a = x.abs();
    if a == 0.0 {
        "0".into()
    } else if (1e-3..1e5).contains(&a) {
        let decimals = (3 - a.log10().floor() as i32).max(0) as usize;
        format!("{x:.decimals$}")
    } else {
        format!("{x:.3e}")
    }
}

/// A thesis value with all its digits (the tiny ones as `1e-9`).
fn printed(x: f64) -> String {
    if x != 0.0 && !(1e-5..1e5).contains(&x.abs()) {
        format!("{x:e}")
    } else {
        format!("{x}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use skyforge_validate::thesis::curves::{CurveSeries, Reference};

    fn curve() -> Curve {
        Curve {
            figure: "3.3-8".into(),
            panels: "(a)".into(),
            title: "R_f against delta, L = 64".into(),
            x_label: "delta".into(),
            y_label: "R_f".into(),
            series: vec![
                CurveSeries::new("Monte Carlo", Mark::Dots, vec![(0.0, 1.02), (0.5, 1.04)]),
                CurveSeries::new("eq. 3.3-55", Mark::Companion, vec![(0.0, 1.01), (0.5, 1.4)]),
            ],
            references: vec![Reference {
                label: "thesis".into(),
                value: 1.0902,
            }],
            values: vec![
                Value::new("largest R_f", "-", 1.079_631, Some(1.0902)),
                Value::new("convergence", "s", f64::NAN, None),
                Value::new("NMSE", "-", 3.543e-10, Some(1e-9)),
            ],
        }
    }

    #[test]
    fn captions_put_skyforge_beside_the_thesis() {
        let c = curve();
        assert_eq!(
            caption(&c),
            "Thesis figure 3.3-8 (a): R_f against delta, L = 64. Largest R_f: SkyForge \
             1.080, thesis 1.0902. Convergence: SkyForge none. NMSE: SkyForge 3.543e-10, \
             thesis 1e-9."
        );
        let none = Curve {
            values: vec![Value::new("bias", "bin", 0.00231, None)],
            ..c.clone()
        };
        assert!(caption(&none).ends_with(
            "Bias: SkyForge 0.002310 bin. The thesis prints no number for this figure."
        ));
        let svg = figure(&chart(&c), caption(&c), Path::new("curves.json"))
            .unwrap()
            .svg;
        for needle in ["Figure 3.3-8 (a)", "Monte Carlo", "eq. 3.3-55", "<circle"] {
            assert!(svg.contains(needle), "{needle}");
        }
        assert_eq!(
            [significant(-155.463), printed(233.1055), printed(0.0005)],
            ["-155.5", "233.1055", "0.0005"]
        );
    }

    #[test]
    fn a_broken_or_oversized_file_is_named_with_its_line() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("curves.json");
        std::fs::write(&path, "{\n  \"curves\": [\n    {\"figure\": 1}\n  ]\n}\n").unwrap();
        let e = section(&path).unwrap_err().to_string();
        assert!(e.contains("curves.json") && e.contains("line 3"), "{e}");

        let file = CurvesFile {
            curves: vec![curve()],
        };
        std::fs::write(&path, file.to_json().unwrap()).unwrap();
        let s = section(&path).unwrap();
        assert_eq!(s.figures.len(), 1);
        assert!(s.figures[0].caption.starts_with("Thesis figure 3.3-8 (a):"));

        std::fs::File::create(&path)
            .unwrap()
            .set_len(MAX_BYTES + 1)
            .unwrap();
        let e = section(&path).unwrap_err().to_string();
        assert!(e.contains("at most"), "{e}");
    }
}
