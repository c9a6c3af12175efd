//! Figures of the attitude chain against the truth (`skyforge attitude`'s output compared
//! as `skyforge validate attitude` does): each baseline's N, E, D error and the yaw,
//! pitch and roll errors against time at the fixed epochs (thesis figures 5.4-1 to 5.4-6),
//! beside the standard deviations of thesis tables 5.4-4 and 5.4-5; and, when the chain
//! estimated the geometry offsets, their errors ([`super::geometry`]).

use super::chart::{Chart, Series};
use super::page::{Figure, Section};
use super::{ReportError, figure};
use skyforge_validate::attitude::{AttitudeValidation, OutputsComparison, compare_outputs};
use std::path::Path;

/// The attitude section: the chain's output in `attitude` against the truth in `truth`,
/// its integers also against the observations in `observations`.
pub fn section(truth: &Path, observations: &Path, attitude: &Path) -> Result<Section, ReportError> {
    let c = compare_outputs(truth, observations, attitude)
        .map_err(|e| ReportError::new(attitude, e.to_string()))?;
    let v = c.summary();
    let mut section = Section {
        heading: "Baselines and attitude".into(),
        paragraphs: vec![summary(&v)],
        ..Section::default()
    };
    let t: Vec<f64> = c.chain.fixed.iter().map(|e| e.t_s).collect();
    for b in &v.baselines {
        let k = b.baseline - 1;
        let mut chart = Chart::new(
            &format!(
                "Baseline {} ({} - {}) error",
                b.baseline, b.antenna, c.antennas[0].name
            ),
            "time (s)",
            "error (m)",
        );
        for (i, axis) in ["N", "E", "D"].iter().enumerate() {
            let values = c.chain.baseline_axis(k, i, true);
            chart
                .series
                .push(Series::line(*axis, t.iter().copied().zip(values).collect()));
        }
        let mut caption = format!(
            "Baseline {} error in the master's N, E, D frame at the fixed epochs: std {}.",
            b.baseline,
            stds(b.ned_m.axes().map(|a| a.std), 1e3, "mm")
        );
        if let Some(th) = b.thesis_ned_std_m {
            caption += &format!(
                " Thesis table 5.4-4: std {}.",
                stds([th.n, th.e, th.d].map(Some), 1e3, "mm")
            );
            chart.references = vec![("thesis D std".into(), th.d), (String::new(), -th.d)];
        }
        section.figures.push(figure(&chart, caption, attitude)?);
    }
    section.figures.push(attitude_figure(&c, &v, attitude)?);
    section
        .figures
        .extend(super::geometry::figures(&c, attitude)?);
    Ok(section)
}

fn attitude_figure(
    c: &OutputsComparison,
    v: &AttitudeValidation,
    attitude: &Path,
) -> Result<Figure, ReportError> {
    let mut chart = Chart::new("Attitude error", "time (s)", "error (deg)");
    let t: Vec<f64> = c
        .chain
        .fixed
        .iter()
        .filter(|e| e.attitude_deg.is_some())
        .map(|e| e.t_s)
        .collect();
    for (i, axis) in ["yaw", "pitch", "roll"].iter().enumerate() {
        let values = c.chain.attitude_axis(i);
        chart
            .series
            .push(Series::line(*axis, t.iter().copied().zip(values).collect()));
    }
    let th = v.thesis_attitude_std_deg;
    chart.references = vec![
        ("thesis roll std".into(), th.roll),
        (String::new(), -th.roll),
    ];
    let caption = format!(
        "Yaw, pitch and roll errors at the fixed epochs: std {}. Thesis table 5.4-5 \
         (real-time KF): std {}.",
        stds(v.attitude_deg.axes().map(|a| a.std), 1.0, "deg"),
        stds([th.yaw, th.pitch, th.roll].map(Some), 1.0, "deg")
    );
    figure(&chart, caption, attitude)
}

/// Three standard deviations scaled to `unit`, `-` where there is none.
fn stds(v: [Option<f64>; 3], scale: f64, unit: &str) -> String {
    let s: Vec<String> = v
        .iter()
        .map(|x| x.map_or_else(|| "-".into(), |x| format!("{:.3}", x * scale)))
        .collect();
    format!("{} {unit}", s.join(" / "))
}

fn summary(v: &AttitudeValidation) -> String {
    let first = v
        .first_fix_s
        .map_or_else(|| "never".into(), |t| format!("at {t:.0} s"));
    format!(
        "{} epochs; first fix {first}; {} of {} epochs fixed from then on ({:.1} %); \
         {} of {} fixed integers wrong.",
        v.epochs,
        v.fixed_epochs,
        v.epochs_from_first_fix,
        100.0 * v.fixed_fraction,
        v.integers.wrong,
        v.integers.checked
    )
}
