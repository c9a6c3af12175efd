//! How a run on files starts the INS: aligned at rest, or in motion on the GNSS track.
//!
//! At rest ([`StaticAlignment`]): the IMU still for the first `span_s`, its attitude from
//! the means of the increments (coarse alignment, `ins::coarse_alignment`) and, if asked,
//! refined by a fine alignment through the same increments (zero-velocity updates,
//! `ins::fine_alignment`), its position the surveyed antenna's or the mean of the fixes
//! meanwhile. Gyrocompassing needs gyros well below the Earth's rate.
//!
//! In motion ([`TrackAlignment`]): at the first fix whose horizontal speed reaches
//! `min_speed_mps`, the body's x axis along the fix's velocity (heading and pitch from
//! the track, as for a vehicle that does not slip sideways; Groves 2013 sec. 5.6.2,
//! attitude initialisation from the trajectory), roll zero, position and velocity the
//! fix's less the lever arm. Any grade of IMU starts so; the filter's initial attitude
//! sigmas must cover the sideslip, the road's camber and the velocity's own error.

use super::config::InsRunError;
use super::fix::GnssFix;
use crate::ins::{
    FineAlignment, FineAlignmentConfig, InsState, coarse_alignment, fine_alignment, static_means,
};
use hifitime::{Duration, Epoch};
use skyforge_gnss::imu::ImuIncrement;
use skyforge_orbits::frames::{YawPitchRoll, c_ecef_ned, ecef_to_geodetic};
use skyforge_orbits::{Mat3, Vec3};

/// How a run aligns on its static start.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StaticAlignment {
    /// The static start's length from the first IMU record (s).
    pub span_s: f64,
    /// `Some`: after the coarse alignment, a fine alignment through the same increments
    /// from the coarse attitude at the start's beginning; `None`: coarse only.
    pub fine: Option<FineAlignmentConfig>,
}

/// How a run aligns in motion.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TrackAlignment {
    /// The horizontal speed from which a fix's velocity gives the heading (m/s).
    pub min_speed_mps: f64,
}

/// How a run on files starts.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Alignment {
    /// At rest.
    Static(StaticAlignment),
    /// In motion, from the track.
    Track(TrackAlignment),
}

impl Alignment {
    /// Coarse alignment at rest over `span_s`.
    pub fn coarse(span_s: f64) -> Self {
        Self::Static(StaticAlignment { span_s, fine: None })
    }
}

/// The INS aligned: its state, how many increments lie before it, and the fine
/// alignment's diagnostics where one ran.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Aligned {
    pub state: InsState,
    pub records: usize,
    pub fine: Option<FineAlignment>,
}

/// How many of `increments` fall in the static start of `span_s`, and its end.
pub(crate) fn alignment_span(
    increments: &[ImuIncrement],
    span_s: f64,
) -> Result<(usize, Epoch), InsRunError> {
    let start = first_instant(increments)?;
    let end = start + Duration::from_seconds(span_s);
    match increments.iter().take_while(|i| i.t_end <= end).count() {
        0 => Err(InsRunError::Input(format!(
            "no IMU record in the {span_s} s alignment from {start}"
        ))),
        n => Ok((n, end)),
    }
}

/// The instant the first increment begins.
fn first_instant(increments: &[ImuIncrement]) -> Result<Epoch, InsRunError> {
    (increments.first())
        .map(|i| i.t_end - Duration::from_seconds(i.dt_s))
        .ok_or_else(|| InsRunError::Input("the IMU file holds no record".into()))
}

/// The INS aligned as `alignment` says, with its antenna `lever` away (body axes); at
/// rest at `antenna` or, without, at the mean of the `fixes` meanwhile; in motion at the
/// first of the `fixes` fast enough (then `antenna` must be `None`).
pub(crate) fn align(
    increments: &[ImuIncrement],
    alignment: &Alignment,
    lever: &Vec3,
    antenna: Option<Vec3>,
    fixes: &[GnssFix],
) -> Result<Aligned, InsRunError> {
    match (alignment, antenna) {
        (Alignment::Static(a), _) => align_at_rest(increments, a, lever, antenna, fixes),
        (Alignment::Track(a), None) => align_on_track(increments, a, lever, fixes),
        (Alignment::Track(_), Some(_)) => Err(InsRunError::Input(
            "a surveyed start is a static start: align at rest".into(),
        )),
    }
}

/// [`align`] at rest.
fn align_at_rest(
    increments: &[ImuIncrement],
    alignment: &StaticAlignment,
    lever: &Vec3,
    antenna: Option<Vec3>,
    fixes: &[GnssFix],
) -> Result<Aligned, InsRunError> {
    let span_s = alignment.span_s;
    let (n, end) = alignment_span(increments, span_s)?;
    let during: Vec<Vec3> = (fixes.iter())
        .filter(|f| f.t <= end)
        .map(|f| f.r_ecef_m)
        .collect();
    let antenna = match antenna {
        Some(a) => a,
        None if during.is_empty() => {
            return Err(InsRunError::Input(format!(
                "no GNSS fix in the {span_s} s alignment to {end}"
            )));
        }
        None => during.iter().sum::<Vec3>() / during.len() as f64,
    };
    let still = &increments[..n];
    let means = static_means(still)?;
    let c = coarse_alignment(
        &means.f_body_mps2,
        &means.w_body_rps,
        &ecef_to_geodetic(&antenna),
    )?;
    let at = |t| InsState::at_rest(t, antenna - c * lever, c);
    let (state, fine) = match &alignment.fine {
        None => (at(still[n - 1].t_end), None),
        Some(cfg) => {
            let out = fine_alignment(&at(first_instant(still)?), still, cfg)?;
            (out.state, Some(out))
        }
    };
    Ok(Aligned {
        state,
        records: n,
        fine,
    })
}

/// [`align`] in motion: at the first fix with a velocity whose horizontal speed reaches
/// the threshold and an IMU record ending within half an interval of it.
fn align_on_track(
    increments: &[ImuIncrement],
    alignment: &TrackAlignment,
    lever: &Vec3,
    fixes: &[GnssFix],
) -> Result<Aligned, InsRunError> {
    let begins = first_instant(increments)?;
    let fast = |f: &&GnssFix| {
        let (v, _) = f.v_ecef_mps?;
        let g = ecef_to_geodetic(&f.r_ecef_m);
        let v_ned = c_ecef_ned(g.lat_rad, g.lon_rad) * v;
        (f.t > begins && v_ned.x.hypot(v_ned.y) >= alignment.min_speed_mps).then_some(())
    };
    for fix in fixes.iter().filter(|f| fast(f).is_some()) {
        let records = increments.partition_point(|i| i.t_end <= fix.t);
        let nearest = [records.checked_sub(1), Some(records)]
            .into_iter()
            .flatten()
            .filter(|&k| k < increments.len())
            .min_by(|&a, &b| gap_s(&increments[a], fix).total_cmp(&gap_s(&increments[b], fix)));
        let Some(k) = nearest.filter(|&k| gap_s(&increments[k], fix) <= increments[k].dt_s) else {
            continue;
        };
        let Some((v, _)) = fix.v_ecef_mps else {
            continue;
        };
        let c = along_track(&fix.r_ecef_m, &v);
        let state = InsState {
            t: increments[k].t_end,
            r_ecef_m: fix.r_ecef_m - c * lever,
            v_ecef_mps: v,
            c_body_ecef: c,
        };
        return Ok(Aligned {
            state,
            records: k + 1,
            fine: None,
        });
    }
    Err(InsRunError::Input(format!(
        "no GNSS fix with a horizontal speed of {} m/s or more to align on",
        alignment.min_speed_mps
    )))
}

/// Seconds between the end of `inc` and `fix`.
fn gap_s(inc: &ImuIncrement, fix: &GnssFix) -> f64 {
    (inc.t_end - fix.t).to_seconds().abs()
}

/// The body-to-ECEF attitude whose x axis lies along `v` (heading and pitch of the
/// track) with no roll, at `r`.
fn along_track(r: &Vec3, v: &Vec3) -> Mat3 {
    let g = ecef_to_geodetic(r);
    let c_ecef_to_ned = c_ecef_ned(g.lat_rad, g.lon_rad);
    let v_ned = c_ecef_to_ned * v;
    let yaw = v_ned.y.atan2(v_ned.x);
    let pitch = (-v_ned.z).atan2(v_ned.x.hypot(v_ned.y));
    let c_body_ned = YawPitchRoll::new(yaw, pitch, 0.0).c_body_ref();
    c_ecef_to_ned.transpose() * c_body_ned
}

#[cfg(test)]
mod tests {
    use super::*;
    use skyforge_orbits::frames::{Geodetic, geodetic_to_ecef};

    /// A fix at `t_s` seconds with the NED velocity `v_ned` at 30 N 114 E.
    fn fix(t_s: f64, v_ned: Vec3) -> GnssFix {
        let g = Geodetic::from_degrees(30.0, 114.0, 20.0);
        let c_ned_ecef = c_ecef_ned(g.lat_rad, g.lon_rad).transpose();
        GnssFix {
            t: Epoch::from_gpst_seconds(t_s),
            r_ecef_m: geodetic_to_ecef(&g),
            r_cov_m2: Mat3::identity(),
            v_ecef_mps: Some((c_ned_ecef * v_ned, Mat3::identity())),
        }
    }

    /// IMU records of 10 ms from 0 to `end_s`.
    fn records(end_s: f64) -> Vec<ImuIncrement> {
        let n = (end_s / 0.01).round() as usize;
        (1..=n)
            .map(|k| ImuIncrement {
                t_end: Epoch::from_gpst_seconds(k as f64 * 0.01),
                dt_s: 0.01,
                dtheta_rad: Vec3::zeros(),
                dv_mps: Vec3::zeros(),
            })
            .collect()
    }

    /// The first fix at the threshold speed or above starts the INS: the body's x axis
    /// along its velocity (heading 30 deg, climbing 2 deg), no roll, the lever arm taken
    /// off, at the IMU record of the fix's time.
    #[test]
    fn the_track_gives_heading_and_pitch() {
        let climb = 2f64.to_radians();
        let (h, v) = (30f64.to_radians(), 10.0);
        let along = Vec3::new(h.cos() * climb.cos(), h.sin() * climb.cos(), -climb.sin());
        let fixes = [fix(1.0, Vec3::new(3.0, 0.0, 0.0)), fix(2.0, along * v)];
        let lever = Vec3::new(0.0, 0.0, -1.0);
        let track = Alignment::Track(TrackAlignment { min_speed_mps: 5.0 });
        let out = align(&records(5.0), &track, &lever, None, &fixes).unwrap();
        assert_eq!(out.records, 200);
        assert_eq!(out.state.t, Epoch::from_gpst_seconds(2.0));
        let a = out.state.attitude_ned();
        // 1e-8 rad: the attitude read at the IMU, 3.5 cm north-east of the antenna's
        // vertical, where north and down have turned by 5e-9 rad.
        let off = [a.yaw_rad - h, a.pitch_rad - climb, a.roll_rad];
        assert!(off.iter().all(|e| e.abs() < 1e-8), "{a:?}");
        let antenna = out.state.r_ecef_m + out.state.c_body_ecef * lever;
        assert!((antenna - fixes[1].r_ecef_m).norm() < 1e-9);
        assert_eq!(out.state.v_ecef_mps, fixes[1].v_ecef_mps.unwrap().0);
    }

    /// Too slow a track, or a track beside a surveyed start, is refused with the reason.
    #[test]
    fn a_slow_track_or_a_surveyed_one_is_refused() {
        let track = Alignment::Track(TrackAlignment { min_speed_mps: 5.0 });
        let slow = [fix(1.0, Vec3::new(3.0, 3.0, 0.0))];
        let zero = Vec3::zeros();
        let e = align(&records(5.0), &track, &zero, None, &slow).unwrap_err();
        assert!(e.to_string().contains("5 m/s"), "{e}");
        let e = align(&records(5.0), &track, &zero, Some(zero), &[]).unwrap_err();
        assert!(e.to_string().contains("static start"), "{e}");
    }
}
