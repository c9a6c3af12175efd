//! Thesis figures 3.2-4 to 3.2-23: the carrier loop's dynamic stress error and total
//! 1-sigma phase error against time, for the most dynamic GPS satellite of a run's truth,
//! one figure for each of the thesis's 20 loop settings (order, Bn, sigma_A; C/N0
//! 39 dB-Hz, 1 ms; [`figure_settings`]), with the 15 deg lock threshold. The error terms
//! are `skyforge_receiver::tracking::error_budget`'s:
//! - thesis eq. 3.2-1: 2nd-order dynamic stress theta_e2 = 0.2809 * 360 * |fd'| / Bn^2;
//! - thesis eq. 3.2-2: 3rd-order dynamic stress theta_e3 = 0.4828 * 360 * |fd''| / Bn^3;
//! - thesis eqs. 3.2-3 to 3.2-5: thermal jitter sigma_iPLL and Allan jitter theta_A;
//! - thesis eq. 3.2-6: total sigma_PLL = sqrt(sigma_iPLL^2 + theta_A^2 + sigma_v^2) +
//!   theta_e / 3, with sigma_v = 2 deg.

use super::chart::{Chart, Series};
use super::page::Figure;
use super::{ReportError, figure};
use skyforge_formats::truth::VisibleLinks;
use skyforge_receiver::tracking::error_budget::{Budget, DopplerDynamics, LOCK_THRESHOLD_DEG};
use skyforge_validate::thesis::{LoopFigure, figure_settings};
use std::path::Path;

/// The pass the figures follow: the satellite column and, at each of its epochs, the
/// time and the Doppler dynamics.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Pass {
    id: String,
    t_s: Vec<f64>,
    dynamics: Vec<DopplerDynamics>,
}

impl Pass {
    /// The most dynamic GPS satellite's pass, as the thesis plotted one: the GPS satellite
    /// (ID starting with `G`) with the largest |Doppler rate| |fd'| over its visible
    /// links (the ranking of table T-3.2), and of its links the run of consecutive
    /// epochs that holds that peak. `rate_hzps` and `accel_hzps2` hold fd' and fd'' per
    /// link of `links`; `None` when no GPS satellite is in view.
    pub(super) fn most_dynamic(
        links: &VisibleLinks,
        t_s: &[f64],
        ids: &[String],
        rate_hzps: &[f64],
        accel_hzps2: &[f64],
    ) -> Option<Pass> {
        let peak = (0..links.sat.len())
            .filter(|&l| ids[usize::from(links.sat[l])].starts_with('G'))
            .filter(|&l| rate_hzps[l].is_finite())
            .max_by(|&a, &b| rate_hzps[a].abs().total_cmp(&rate_hzps[b].abs()))?;
        let sat = links.sat[peak];
        let own: Vec<usize> = (0..links.sat.len())
            .filter(|&l| links.sat[l] == sat)
            .collect();
        let at = own.iter().position(|&l| l == peak)?;
        let next = |a: usize, b: usize| links.epoch[b] == links.epoch[a] + 1;
        let mut first = at;
        while first > 0 && next(own[first - 1], own[first]) {
            first -= 1;
        }
        let mut last = at;
        while last + 1 < own.len() && next(own[last], own[last + 1]) {
            last += 1;
        }
        let pass = &own[first..=last];
        Some(Pass {
            id: ids[usize::from(sat)].clone(),
            t_s: pass.iter().map(|&l| t_s[links.epoch[l] as usize]).collect(),
            dynamics: pass
                .iter()
                .map(|&l| DopplerDynamics {
                    rate_hzps: rate_hzps[l].abs(),
                    accel_hzps2: accel_hzps2[l].abs(),
                })
                .collect(),
        })
    }

    /// The budget of `fig`'s loop at each epoch of the pass (thesis eqs. 3.2-1 to 3.2-6).
    fn budgets(&self, fig: &LoopFigure) -> Vec<Budget> {
        self.dynamics
            .iter()
            .map(|&d| fig.setting.budget(d))
            .collect()
    }
}

/// The paragraph introducing the figures and the 20 figures, one per thesis loop setting;
/// with no GPS satellite in view of `antenna` (`pass` `None`), a paragraph saying so and
/// no figure. `path` is the truth file, named by errors.
pub(super) fn figures(
    path: &Path,
    antenna: &str,
    pass: Option<&Pass>,
) -> Result<(String, Vec<Figure>), ReportError> {
    let Some(pass) = pass else {
        return Ok((
            format!(
                "No GPS satellite is in view of antenna {antenna}: thesis figures 3.2-4 to \
                 3.2-23 (carrier-loop errors for the most dynamic GPS satellite) are not drawn."
            ),
            Vec::new(),
        ));
    };
    let (t0, t1) = (
        pass.t_s.first().copied().unwrap_or(0.0),
        pass.t_s.last().copied().unwrap_or(0.0),
    );
    let peak = pass
        .dynamics
        .iter()
        .fold(DopplerDynamics::default(), |p, d| DopplerDynamics {
            rate_hzps: p.rate_hzps.max(d.rate_hzps),
            accel_hzps2: p.accel_hzps2.max(d.accel_hzps2),
        });
    let paragraph = format!(
        "Thesis figures 3.2-4 to 3.2-23: the carrier loop's errors (thesis eqs. 3.2-1 to \
         3.2-6) along the pass of the most dynamic GPS satellite in view of antenna \
         {antenna} (largest |fd'|), {} from {t0:.0} s to {t1:.0} s: peak |fd'| {:.2} Hz/s, \
         |fd''| {:.4} Hz/s^2. The loop settings are the thesis's, whatever the run's.",
        pass.id, peak.rate_hzps, peak.accel_hzps2
    );
    let mut out = Vec::new();
    for fig in figure_settings() {
        let s = &fig.setting;
        let setting = format!(
            "{} loop, Bn = {} Hz, sigma_A = {:.0e}",
            s.order.label(),
            s.bn_hz,
            s.sigma_allan
        );
        let budgets = pass.budgets(&fig);
        let mut chart = Chart::new(
            &format!("Figure 3.2-{}: {setting}", fig.number),
            "time (s)",
            "phase error (deg)",
        );
        chart.y_from_zero = true;
        let along = |f: fn(&Budget) -> f64| -> Vec<(f64, f64)> {
            pass.t_s
                .iter()
                .zip(&budgets)
                .map(|(&t, b)| (t, f(b)))
                .collect()
        };
        chart.series.push(Series::line(
            "dynamic stress theta_e (3 sigma)",
            along(|b| b.dynamic_deg),
        ));
        chart.series.push(Series::line(
            "total sigma_PLL (1 sigma)",
            along(|b| b.total_deg),
        ));
        chart.references = vec![("lock threshold".into(), LOCK_THRESHOLD_DEG)];
        let ours = budgets.iter().map(|b| b.total_deg).fold(0.0, f64::max);
        let thesis = match fig.thesis_max_total_deg {
            Some(t) => format!("{t} deg"),
            None => "only \"fail\"".into(),
        };
        let caption = format!(
            "Thesis figure 3.2-{}: dynamic stress error and total 1-sigma phase error \
             (eq. 3.2-6) of a {setting}, C/N0 {} dB-Hz, T {} ms, for {} against time; \
             {LOCK_THRESHOLD_DEG} deg lock threshold. Maximum total: SkyForge {ours:.2} deg \
             ({}), thesis {thesis}.",
            fig.number,
            s.cn0_dbhz,
            1e3 * s.t_coh_s,
            pass.id,
            if ours <= LOCK_THRESHOLD_DEG {
                "lock"
            } else {
                "fail"
            },
        );
        out.push(figure(&chart, caption, path)?);
    }
    Ok((paragraph, out))
}

#[cfg(test)]
mod tests {
    use super::*;
    use skyforge_receiver::tracking::error_budget::{
        LoopOrder, allan_jitter_deg, dynamic_stress_2nd_deg, dynamic_stress_3rd_deg,
        thermal_jitter_deg,
    };

    fn ids(names: &[&str]) -> Vec<String> {
        names.iter().map(|s| s.to_string()).collect()
    }

    /// Links of (epoch, satellite) in truth order, 1 s epochs.
    fn links(pairs: &[(u32, u16)]) -> VisibleLinks {
        VisibleLinks {
            epoch: pairs.iter().map(|p| p.0).collect(),
            sat: pairs.iter().map(|p| p.1).collect(),
        }
    }

    #[test]
    fn the_pass_is_the_gps_satellite_of_largest_doppler_rate_around_its_peak() {
        let ids = ids(&["G01", "C02", "G03"]);
        let t_s: Vec<f64> = (0..8).map(f64::from).collect();
        // G01 at -30 Hz/s all along; the BeiDou one faster, not GPS; G03 in two passes
        // (epochs 0-2 and 5-7) reaching -40 Hz/s at epoch 6.
        let mut pairs = Vec::new();
        let mut rate = Vec::new();
        for e in 0..8u32 {
            pairs.push((e, 0));
            rate.push(-30.0);
            pairs.push((e, 1));
            rate.push(100.0);
            if !(3..5).contains(&e) {
                pairs.push((e, 2));
                rate.push(if e == 6 { -40.0 } else { 1.0 });
            }
        }
        let accel: Vec<f64> = rate.iter().map(|r| r / 100.0).collect();
        let pass = Pass::most_dynamic(&links(&pairs), &t_s, &ids, &rate, &accel).unwrap();
        assert_eq!(pass.id, "G03");
        assert_eq!(pass.t_s, vec![5.0, 6.0, 7.0]);
        let rates: Vec<f64> = pass.dynamics.iter().map(|d| d.rate_hzps).collect();
        assert_eq!(rates, vec![1.0, 40.0, 1.0]);
        assert_eq!(pass.dynamics[1].accel_hzps2, 0.4);

        // Without GPS links there is no pass, and no figure.
        let bds = links(&[(0, 1), (1, 1)]);
        assert_eq!(
            Pass::most_dynamic(&bds, &t_s, &ids, &[5.0, 6.0], &[0.0, 0.0]),
            None
        );
        let (text, figs) = figures(Path::new("truth.h5"), "ant1", None).unwrap();
        assert!(figs.is_empty());
        assert!(text.contains("No GPS satellite"), "{text}");
    }

    #[test]
    fn constant_dynamics_give_flat_errors_of_the_thesis_equations() {
        let (rate, accel) = (12.5, 0.05);
        let n = 5u32;
        let pairs: Vec<(u32, u16)> = (0..n).map(|e| (e, 0)).collect();
        let t_s: Vec<f64> = (0..n).map(|e| 10.0 * f64::from(e)).collect();
        let pass = Pass::most_dynamic(
            &links(&pairs),
            &t_s,
            &ids(&["G07"]),
            &vec![rate; n as usize],
            &vec![-accel; n as usize],
        )
        .unwrap();
        for fig in figure_settings() {
            let s = fig.setting;
            let dynamic = match s.order {
                LoopOrder::Second => dynamic_stress_2nd_deg(rate, s.bn_hz),
                LoopOrder::Third => dynamic_stress_3rd_deg(accel, s.bn_hz),
            };
            // Thesis eq. 3.2-6.
            let total = (thermal_jitter_deg(s.bn_hz, s.cn0_dbhz, s.t_coh_s).powi(2)
                + allan_jitter_deg(s.order, s.sigma_allan, s.carrier_hz, s.bn_hz).powi(2)
                + s.sigma_vibration_deg.powi(2))
            .sqrt()
                + dynamic / 3.0;
            for b in pass.budgets(&fig) {
                assert!((b.dynamic_deg - dynamic).abs() < 1e-12, "{}", fig.number);
                assert!((b.total_deg - total).abs() < 1e-12, "{}", fig.number);
            }
        }
    }

    #[test]
    fn twenty_figures_in_the_thesis_order_with_its_printed_maxima() {
        let settings = figure_settings();
        let numbers: Vec<usize> = settings.iter().map(|f| f.number).collect();
        assert_eq!(numbers, (4..=23).collect::<Vec<_>>());
        // The thesis's list of figures: 3.2-9 is the 3rd-order loop at 1e-10 and 10 Hz,
        // 3.2-14 the 2nd-order one at 1e-9 and 10 Hz, 3.2-23 the 3rd-order at 1e-9, 200 Hz.
        let key = |f: &LoopFigure| (f.setting.order, f.setting.sigma_allan, f.setting.bn_hz);
        assert_eq!(key(&settings[5]), (LoopOrder::Third, 1e-10, 10.0));
        assert_eq!(key(&settings[10]), (LoopOrder::Second, 1e-9, 10.0));
        assert_eq!(key(&settings[19]), (LoopOrder::Third, 1e-9, 200.0));

        let pairs: Vec<(u32, u16)> = (0..3).map(|e| (e, 0)).collect();
        let pass = Pass::most_dynamic(
            &links(&pairs),
            &[0.0, 1.0, 2.0],
            &ids(&["G07"]),
            &[10.0, 20.0, 10.0],
            &[0.01, 0.0, -0.01],
        )
        .unwrap();
        let (text, figs) = figures(Path::new("truth.h5"), "ant1", Some(&pass)).unwrap();
        assert!(
            text.contains("G07") && text.contains("20.00 Hz/s"),
            "{text}"
        );
        assert_eq!(figs.len(), settings.len());
        for (f, s) in figs.iter().zip(&settings) {
            let n = s.number;
            assert!(
                f.caption.starts_with(&format!("Thesis figure 3.2-{n}:")),
                "{}",
                f.caption
            );
            let ours = s
                .setting
                .budget(DopplerDynamics {
                    rate_hzps: 20.0,
                    accel_hzps2: 0.01,
                })
                .total_deg;
            assert!(f.caption.contains(&format!("SkyForge {ours:.2} deg")));
            if let Some(t) = s.thesis_max_total_deg {
                assert!(f.caption.contains(&format!("thesis {t} deg")), "{n}");
            }
            assert!(f.svg.contains("lock threshold") && f.svg.contains("<polyline"));
        }
    }
}
