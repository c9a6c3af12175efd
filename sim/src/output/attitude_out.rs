//! The outputs of `skyforge attitude`: one [`EpochValues`] per master epoch, written as a
//! row of `attitude.csv` and of `attitude.h5` (schema in docs/attitude.md), and the fixed
//! integers as rows of `ambiguities.csv`.

use crate::output::h5_datasets::{append_rows, create_epoch_file, create_rows};
use hifitime::Epoch;
use skyforge_navigation::relative::AmbiguityStatus;
use skyforge_navigation::relative::files::EpochOutcome;
use std::path::Path;

/// A fixed baseline in the master's NED frame and its standard deviations (m).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NedBaseline {
    pub ned_m: [f64; 3],
    pub sigma_m: [f64; 3],
}

/// The attitude stage's state: yaw, pitch, roll (deg), standard deviations, rates.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AttitudeValues {
    pub angles_deg: [f64; 3],
    pub std_deg: [f64; 3],
    /// Filters only.
    pub rates_dps: Option<[f64; 3]>,
}

/// What one epoch gave, as numbers.
#[derive(Debug, Clone, PartialEq)]
pub struct EpochValues {
    pub time: Epoch,
    /// `none`, `float`, `partial` or `fixed`.
    pub status: &'static str,
    pub ambiguities: usize,
    pub fixed_combinations: usize,
    pub held: usize,
    pub ratio: Option<f64>,
    pub success_rate: Option<f64>,
    /// Per baseline: ECEF x, y, z (fixed; float when not fixed).
    pub ecef_m: Vec<[f64; 3]>,
    /// Per baseline: fixed N, E, D and their standard deviations.
    pub ned_m: Option<Vec<NedBaseline>>,
    pub attitude: Option<AttitudeValues>,
    /// Why there is no solution, or why the attitude stage skipped the epoch.
    pub note: String,
}

/// Status codes of `attitude.h5`'s `status` dataset.
const STATUS_CODES: [&str; 4] = ["none", "float", "partial", "fixed"];

impl EpochValues {
    /// The values of `o` for `m` baselines.
    pub fn of(o: &EpochOutcome, m: usize) -> Self {
        let mut v = Self {
            time: o.time,
            status: "none",
            ambiguities: 0,
            fixed_combinations: 0,
            held: 0,
            ratio: None,
            success_rate: None,
            ecef_m: Vec::new(),
            ned_m: None,
            attitude: None,
            note: String::new(),
        };
        let e = match &o.result {
            Ok(e) => e,
            Err(why) => {
                v.note = why.clone();
                return v;
            }
        };
        let r = &e.resolution;
        (v.status, v.fixed_combinations) = match r.status {
            AmbiguityStatus::Float => ("float", 0),
            AmbiguityStatus::Partial { combinations } => ("partial", combinations),
            AmbiguityStatus::Fixed => ("fixed", e.float.ambiguities.len()),
        };
        v.ambiguities = e.float.ambiguities.len();
        v.held = r.held;
        v.ratio = r.ratio;
        v.success_rate = Some(r.success_rate);
        let baselines = e
            .fixed
            .as_ref()
            .map_or(&e.float.baselines, |x| &x.baselines);
        v.ecef_m = (0..m)
            .map(|k| {
                let c = baselines.column(k);
                [c[0], c[1], c[2]]
            })
            .collect();
        v.ned_m = e.fixed_ned.as_ref().map(|ned| {
            let q = ned.covariance();
            (0..m)
                .map(|k| {
                    let b = ned.baselines()[k];
                    let s = |i: usize| q[(3 * k + i, 3 * k + i)].sqrt();
                    NedBaseline {
                        ned_m: [b.x, b.y, b.z],
                        sigma_m: [s(0), s(1), s(2)],
                    }
                })
                .collect()
        });
        v.attitude = e.attitude.as_ref().map(|s| {
            let a = [s.angles.yaw_rad, s.angles.pitch_rad, s.angles.roll_rad];
            AttitudeValues {
                angles_deg: a.map(f64::to_degrees),
                std_deg: [0, 1, 2].map(|i| s.covariance[(i, i)].sqrt().to_degrees()),
                rates_dps: s
                    .rates_rad_s
                    .map(|r| [r[0], r[1], r[2]].map(f64::to_degrees)),
            }
        });
        v.note = e.attitude_skipped.clone().unwrap_or_default();
        v
    }
}

/// The CSV header for `m` baselines.
pub fn csv_header(m: usize) -> String {
    let mut cols: Vec<String> = [
        "time_gpst",
        "status",
        "ambiguities",
        "fixed_combinations",
        "held",
        "ratio",
        "success_rate",
    ]
    .map(String::from)
    .to_vec();
    for k in 1..=m {
        for c in [
            "x_m", "y_m", "z_m", "n_m", "e_m", "d_m", "sn_m", "se_m", "sd_m",
        ] {
            cols.push(format!("b{k}_{c}"));
        }
    }
    for suffix in ["deg", "std_deg", "rate_dps"] {
        for c in ["yaw", "pitch", "roll"] {
            cols.push(format!("{c}_{suffix}"));
        }
    }
    cols.push("note".into());
    cols.join(",")
}

/// One CSV row of `v` for `m` baselines (empty fields for what the epoch did not give).
pub fn csv_row(v: &EpochValues, m: usize) -> String {
    let fmt = |x: &[f64], digits: usize| x.iter().map(|v| format!("{v:.digits$}")).collect();
    let blank = |n: usize| vec![String::new(); n];
    let mut f = vec![v.time.to_string(), v.status.to_string()];
    if v.success_rate.is_none() {
        f.extend(blank(5 + 9 * m + 9));
    } else {
        f.push(v.ambiguities.to_string());
        f.push(v.fixed_combinations.to_string());
        f.push(v.held.to_string());
        f.push(v.ratio.map_or(String::new(), |r| format!("{r:.3}")));
        f.push(v.success_rate.map_or(String::new(), |s| format!("{s:.6}")));
        for k in 0..m {
            f.extend::<Vec<String>>(fmt(&v.ecef_m[k], 4));
            match &v.ned_m {
                Some(ned) => {
                    f.extend::<Vec<String>>(fmt(&ned[k].ned_m, 4));
                    f.extend::<Vec<String>>(fmt(&ned[k].sigma_m, 5));
                }
                None => f.extend(blank(6)),
            }
        }
        match &v.attitude {
            Some(a) => {
                f.extend::<Vec<String>>(fmt(&a.angles_deg, 5));
                f.extend::<Vec<String>>(fmt(&a.std_deg, 5));
                match a.rates_dps {
                    Some(r) => f.extend::<Vec<String>>(fmt(&r, 5)),
                    None => f.extend(blank(3)),
                }
            }
            None => f.extend(blank(9)),
        }
    }
    f.push(v.note.replace(',', ";"));
    f.join(",")
}

/// The fixed integers of an epoch, one CSV row each (baselines numbered from 1).
pub fn integer_rows(o: &EpochOutcome) -> String {
    let Ok(e) = &o.result else {
        return String::new();
    };
    let ids: Vec<_> = e.float.model.layout.ambiguity_ids().collect();
    let mut out = String::new();
    for (i, value) in e.resolution.integers.iter().enumerate() {
        if let Some(v) = value {
            let (signal, sat, reference) = ids[i % ids.len()];
            out += &format!(
                "{},{},{},{sat},{reference},{v}\n",
                o.time,
                i / ids.len() + 1,
                signal.tag()
            );
        }
    }
    out
}

/// `attitude.h5`: every epoch's values as columns (NaN where the epoch gave none).
pub fn write_h5(path: &Path, epochs: &[EpochValues], m: usize) -> hdf5::Result<()> {
    let start = epochs.first().map(|v| v.time);
    let file = create_epoch_file(path, "skyforge attitude.h5 version 1", start)?;
    let root: &hdf5::Group = &file;
    let n = epochs.len();
    let chunk = n.clamp(1, 4096);
    let column = |name: &str, width: usize, unit: &str, what: &str, data: Vec<f64>| {
        let ds = create_rows::<f64>(root, name, width, chunk, unit, what)?;
        append_rows(&ds, 0, &data, width)
    };
    let per = |f: &dyn Fn(&EpochValues) -> Vec<f64>| epochs.iter().flat_map(f).collect();
    let nan = f64::NAN;
    column(
        "t_s",
        0,
        "s",
        "epoch time since start_gpst",
        per(&|v| vec![start.map_or(0.0, |s| (v.time - s).to_seconds())]),
    )?;
    let codes: Vec<u8> = epochs
        .iter()
        .map(|v| {
            STATUS_CODES
                .iter()
                .position(|s| *s == v.status)
                .unwrap_or(0) as u8
        })
        .collect();
    let ds = create_rows::<u8>(
        root,
        "status",
        0,
        chunk,
        "-",
        "0 no solution, 1 float, 2 partial, 3 fixed",
    )?;
    append_rows(&ds, 0, &codes, 0)?;
    column(
        "ratio",
        0,
        "-",
        "second-best over best score of the integer search",
        per(&|v| vec![v.ratio.unwrap_or(nan)]),
    )?;
    column(
        "success_rate",
        0,
        "-",
        "bootstrapped success rate of the free ambiguities",
        per(&|v| vec![v.success_rate.unwrap_or(nan)]),
    )?;
    column(
        "baseline_ecef_m",
        3 * m,
        "m",
        "baselines (antenna k+1 minus the master), x y z per baseline; fixed, float when not",
        per(&|v| {
            let mut row: Vec<f64> = v.ecef_m.iter().flatten().copied().collect();
            row.resize(3 * m, nan);
            row
        }),
    )?;
    let ned = |pick: fn(&NedBaseline) -> [f64; 3]| {
        per(&move |v: &EpochValues| match &v.ned_m {
            Some(b) => b.iter().flat_map(pick).collect(),
            None => vec![nan; 3 * m],
        })
    };
    column(
        "baseline_ned_m",
        3 * m,
        "m",
        "fixed baselines in the master's NED frame, n e d per baseline",
        ned(|b| b.ned_m),
    )?;
    column(
        "baseline_ned_sigma_m",
        3 * m,
        "m",
        "standard deviations of baseline_ned_m",
        ned(|b| b.sigma_m),
    )?;
    let attitude = |pick: fn(&AttitudeValues) -> Option<[f64; 3]>| {
        per(&move |v: &EpochValues| {
            v.attitude
                .as_ref()
                .and_then(pick)
                .unwrap_or([nan; 3])
                .to_vec()
        })
    };
    column(
        "attitude_deg",
        3,
        "deg",
        "yaw, pitch, roll from the master's NED frame (3-2-1)",
        attitude(|a| Some(a.angles_deg)),
    )?;
    column(
        "attitude_std_deg",
        3,
        "deg",
        "standard deviations of attitude_deg",
        attitude(|a| Some(a.std_deg)),
    )?;
    column(
        "attitude_rate_dps",
        3,
        "deg/s",
        "yaw, pitch, roll rates (filters only)",
        attitude(|a| a.rates_dps),
    )?;
    file.close()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn values(t_s: f64, fixed: bool) -> EpochValues {
        let time = Epoch::from_gpst_seconds(1.0e9 + t_s);
        EpochValues {
            time,
            status: if fixed { "fixed" } else { "float" },
            ambiguities: 20,
            fixed_combinations: if fixed { 20 } else { 0 },
            held: 0,
            ratio: Some(4.5),
            success_rate: Some(0.9999),
            ecef_m: vec![[1.0, 2.0, 3.0], [4.0, 5.0, 6.0]],
            ned_m: fixed.then(|| {
                vec![
                    NedBaseline {
                        ned_m: [0.1, 0.2, 0.3],
                        sigma_m: [1e-3; 3],
                    };
                    2
                ]
            }),
            attitude: fixed.then_some(AttitudeValues {
                angles_deg: [10.0, 2.0, -1.0],
                std_deg: [0.01; 3],
                rates_dps: None,
            }),
            note: String::new(),
        }
    }

    #[test]
    fn h5_columns_hold_every_epoch_with_nan_where_none() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("attitude.h5");
        let epochs = [values(0.0, false), values(1.0, true)];
        write_h5(&path, &epochs, 2).unwrap();
        let f = hdf5::File::open(&path).unwrap();
        let t: Vec<f64> = f.dataset("t_s").unwrap().read_raw().unwrap();
        assert_eq!(t, [0.0, 1.0]);
        let status: Vec<u8> = f.dataset("status").unwrap().read_raw().unwrap();
        assert_eq!(status, [1, 3]);
        let ecef: Vec<f64> = f.dataset("baseline_ecef_m").unwrap().read_raw().unwrap();
        assert_eq!(ecef.len(), 12);
        assert_eq!(ecef[6..], [1.0, 2.0, 3.0, 4.0, 5.0, 6.0]);
        let ned: Vec<f64> = f.dataset("baseline_ned_m").unwrap().read_raw().unwrap();
        assert!(ned[..6].iter().all(|v| v.is_nan()));
        assert_eq!(ned[6..9], [0.1, 0.2, 0.3]);
        let att: Vec<f64> = f.dataset("attitude_deg").unwrap().read_raw().unwrap();
        assert!(att[..3].iter().all(|v| v.is_nan()));
        assert_eq!(att[3..], [10.0, 2.0, -1.0]);
        let rates: Vec<f64> = f.dataset("attitude_rate_dps").unwrap().read_raw().unwrap();
        assert!(rates.iter().all(|v| v.is_nan()));
    }

    #[test]
    fn csv_row_has_a_field_per_header_column() {
        let header = csv_header(2);
        for v in [values(0.0, false), values(1.0, true)] {
            let row = csv_row(&v, 2);
            assert_eq!(row.split(',').count(), header.split(',').count(), "{row}");
        }
    }
}
