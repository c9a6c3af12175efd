//! `receiver.h5`: the receiver's observations and fixes.
//!
//! - root attributes `schema_version`, `generator`, `time_system` ("GPST, receiver clock")
//!   and, from the first epoch on, `gps_week`: the GPS week whose start all `t_rx_gpst_s`
//!   count from (also an attribute of every `t_rx_gpst_s`);
//! - `/observations/<antenna>/<sat>` (e.g. `G07`), one row per epoch the satellite was
//!   observed: `t_rx_gpst_s`, `pseudorange_m`, `carrier_phase_cycles` (RINEX sign),
//!   `doppler_hz`, `cn0_dbhz`, `lock_time_s`, `loss_of_lock` (u8, 1 = lock lost since the
//!   previous epoch);
//! - `/pvt/<antenna>`, one row per fix: `t_rx_gpst_s`, `r_ecef_m` (N x 3), `clock_bias_m`,
//!   `v_ecef_mps` (N x 3, NaN without a velocity fix), `clock_drift_mps` (NaN likewise),
//!   `pdop`, `sats_used` (u16), `hpl_m`, `vpl_m` (the residual test's protection levels,
//!   NaN without RAIM; docs/raim.md).
//!
//! Rows wait in memory per dataset and are appended to the resizable, chunked datasets
//! [`FLUSH_ROWS`] at a time, so memory stays bounded by satellites x `FLUSH_ROWS` rows
//! however long the run.

use crate::h5::{append_rows, create_group, create_rows, create_versioned_file, text_attr};
use hdf5::{Dataset, Group, H5Type, Location};
use hifitime::Epoch;
use skyforge_navigation::pvt::{Fix, VelocityFix};
use skyforge_orbits::ephemeris::SatId;
use skyforge_orbits::time::{epoch_from_gpst, gpst_week_sow};
use skyforge_receiver::observables::Observation;
use skyforge_receiver::pipeline::EpochReport;
use std::collections::BTreeMap;
use std::path::Path;

/// Schema version written to the root attribute `schema_version`.
pub const SCHEMA_VERSION: &str = "1";

/// Rows buffered per dataset before they are appended; also the HDF5 chunk length.
const FLUSH_ROWS: usize = 1024;

fn week_attr(loc: &Location, week: u32) -> hdf5::Result<()> {
    loc.new_attr::<u32>()
        .create("gps_week")?
        .write_scalar(&week)
}

/// A resizable dataset (1-D when `width` is 0, else `[row, width]`) and its rows waiting
/// to be appended.
#[derive(Debug)]
struct Column<T> {
    ds: Dataset,
    width: usize,
    rows: usize,
    pending: Vec<T>,
}

impl<T: H5Type + Copy> Column<T> {
    fn create(
        group: &Group,
        name: &str,
        width: usize,
        unit: &str,
        description: &str,
    ) -> hdf5::Result<Self> {
        let ds = create_rows::<T>(group, name, width, FLUSH_ROWS, unit, description)?;
        Ok(Self {
            ds,
            width,
            rows: 0,
            pending: Vec::with_capacity(FLUSH_ROWS * width.max(1)),
        })
    }

    /// Append the waiting rows.
    fn flush(&mut self) -> hdf5::Result<()> {
        let n = self.pending.len() / self.width.max(1);
        if n == 0 {
            return Ok(());
        }
        append_rows(&self.ds, self.rows, &self.pending, self.width)?;
        self.rows += n;
        self.pending.clear();
        Ok(())
    }
}

/// The datasets of one antenna and satellite.
#[derive(Debug)]
struct ObsSeries {
    /// `t_rx_gpst_s`, `pseudorange_m`, `carrier_phase_cycles`, `doppler_hz`, `cn0_dbhz`,
    /// `lock_time_s`.
    values: [Column<f64>; 6],
    loss_of_lock: Column<u8>,
}

impl ObsSeries {
    fn create(g: &Group, week: u32) -> hdf5::Result<Self> {
        let values = [
            Column::create(
                g,
                "t_rx_gpst_s",
                0,
                "s",
                "receiver time tag since the start of GPS week gps_week",
            )?,
            Column::create(
                g,
                "pseudorange_m",
                0,
                "m",
                "c (receiver time - transmit time)",
            )?,
            Column::create(
                g,
                "carrier_phase_cycles",
                0,
                "cycles",
                "accumulated carrier phase, RINEX sign (grows with the range)",
            )?,
            Column::create(
                g,
                "doppler_hz",
                0,
                "Hz",
                "Doppler, RINEX sign (positive approaching)",
            )?,
            Column::create(g, "cn0_dbhz", 0, "dB-Hz", "estimated C/N0")?,
            Column::create(
                g,
                "lock_time_s",
                0,
                "s",
                "continuous tracking time up to the epoch",
            )?,
        ];
        week_attr(&values[0].ds, week)?;
        Ok(Self {
            values,
            loss_of_lock: Column::create(
                g,
                "loss_of_lock",
                0,
                "1",
                "1 when lock was lost since the previous epoch (RINEX LLI bit 0)",
            )?,
        })
    }

    fn push(&mut self, t_s: f64, o: &Observation) {
        let row = [
            t_s,
            o.pseudorange_m,
            o.carrier_phase_cycles,
            o.doppler_hz,
            o.cn0_dbhz,
            o.lock_time_s,
        ];
        for (c, v) in self.values.iter_mut().zip(row) {
            c.pending.push(v);
        }
        self.loss_of_lock.pending.push(u8::from(o.loss_of_lock));
    }

    fn flush(&mut self) -> hdf5::Result<()> {
        for c in &mut self.values {
            c.flush()?;
        }
        self.loss_of_lock.flush()
    }

    fn waiting(&self) -> usize {
        self.values[0].pending.len()
    }
}

/// The fix datasets of one antenna.
#[derive(Debug)]
struct PvtSeries {
    /// `t_rx_gpst_s`, `clock_bias_m`, `clock_drift_mps`, `pdop`, `hpl_m`, `vpl_m`.
    scalars: [Column<f64>; 6],
    r_ecef_m: Column<f64>,
    v_ecef_mps: Column<f64>,
    sats_used: Column<u16>,
}

impl PvtSeries {
    fn create(g: &Group, week: u32) -> hdf5::Result<Self> {
        let scalars = [
            Column::create(
                g,
                "t_rx_gpst_s",
                0,
                "s",
                "receiver time tag since the start of GPS week gps_week; the fix's GPST is t_rx_gpst_s - clock_bias_m / c",
            )?,
            Column::create(
                g,
                "clock_bias_m",
                0,
                "m",
                "c x receiver clock offset against GPST",
            )?,
            Column::create(
                g,
                "clock_drift_mps",
                0,
                "m/s",
                "c x receiver clock drift, NaN without a velocity fix",
            )?,
            Column::create(g, "pdop", 0, "1", "position dilution of precision")?,
            Column::create(
                g,
                "hpl_m",
                0,
                "m",
                "horizontal protection level of the residual test, NaN without RAIM",
            )?,
            Column::create(
                g,
                "vpl_m",
                0,
                "m",
                "vertical protection level of the residual test, NaN without RAIM",
            )?,
        ];
        week_attr(&scalars[0].ds, week)?;
        Ok(Self {
            scalars,
            r_ecef_m: Column::create(g, "r_ecef_m", 3, "m", "antenna position, ECEF (WGS-84)")?,
            v_ecef_mps: Column::create(
                g,
                "v_ecef_mps",
                3,
                "m/s",
                "antenna velocity, ECEF, NaN without a velocity fix",
            )?,
            sats_used: Column::create(g, "sats_used", 0, "1", "satellites in the fix")?,
        })
    }

    fn push(&mut self, t_s: f64, fix: &Fix, velocity: Option<&VelocityFix>) {
        let row = [
            t_s,
            fix.clock_bias_m,
            velocity.map_or(f64::NAN, |v| v.clock_drift_mps),
            fix.dop.pdop,
            fix.protection.as_ref().map_or(f64::NAN, |p| p.hpl_m),
            fix.protection.as_ref().map_or(f64::NAN, |p| p.vpl_m),
        ];
        for (c, v) in self.scalars.iter_mut().zip(row) {
            c.pending.push(v);
        }
        self.r_ecef_m.pending.extend(fix.r_ecef_m.iter());
        match velocity {
            Some(v) => self.v_ecef_mps.pending.extend(v.v_ecef_mps.iter()),
            None => self.v_ecef_mps.pending.extend([f64::NAN; 3]),
        }
        self.sats_used
            .pending
            .push(u16::try_from(fix.used.len()).unwrap_or(u16::MAX));
    }

    fn flush(&mut self) -> hdf5::Result<()> {
        for c in &mut self.scalars {
            c.flush()?;
        }
        self.r_ecef_m.flush()?;
        self.v_ecef_mps.flush()?;
        self.sats_used.flush()
    }

    fn waiting(&self) -> usize {
        self.scalars[0].pending.len()
    }
}

/// `receiver.h5` being written.
#[derive(Debug)]
pub(super) struct ReceiverH5 {
    file: hdf5::File,
    /// `/observations/<antenna>` and `/pvt` groups.
    obs_groups: Vec<Group>,
    pvt_group: Group,
    names: Vec<String>,
    /// GPS week of the first epoch and its start.
    week: Option<(u32, Epoch)>,
    obs: BTreeMap<(usize, SatId), ObsSeries>,
    pvt: Vec<Option<PvtSeries>>,
}

impl ReceiverH5 {
    /// Create the file, its root attributes and a group per antenna.
    pub(super) fn create(path: &Path, names: &[String]) -> hdf5::Result<Self> {
        let file = create_versioned_file(
            path,
            SCHEMA_VERSION,
            concat!("skyforge receive ", env!("CARGO_PKG_VERSION")),
        )?;
        text_attr(&file, "time_system", "GPST, receiver clock")?;
        let observations = create_group(&file, "observations")?;
        let obs_groups = names
            .iter()
            .map(|n| create_group(&observations, n))
            .collect::<hdf5::Result<Vec<_>>>()?;
        let pvt_group = create_group(&file, "pvt")?;
        Ok(Self {
            file,
            obs_groups,
            pvt_group,
            names: names.to_vec(),
            week: None,
            obs: BTreeMap::new(),
            pvt: names.iter().map(|_| None).collect(),
        })
    }

    /// Buffer (and append when due) the observations and fixes of `report`.
    pub(super) fn write_epoch(&mut self, report: &EpochReport) -> hdf5::Result<()> {
        let (week, week_start) = match self.week {
            Some(w) => w,
            None => {
                let week = gpst_week_sow(report.t_rx).0;
                week_attr(&self.file, week)?;
                *self.week.insert((week, epoch_from_gpst(week, 0.0)))
            }
        };
        let t_s = (report.t_rx - week_start).to_seconds();
        for o in &report.observations {
            let series = match self.obs.entry((o.antenna, o.sat)) {
                std::collections::btree_map::Entry::Occupied(e) => e.into_mut(),
                std::collections::btree_map::Entry::Vacant(e) => {
                    let g = create_group(&self.obs_groups[o.antenna], o.sat.to_string().as_str())?;
                    e.insert(ObsSeries::create(&g, week)?)
                }
            };
            series.push(t_s, o);
            if series.waiting() >= FLUSH_ROWS {
                series.flush()?;
            }
        }
        for af in &report.fixes {
            let Ok(fix) = &af.fix else {
                continue;
            };
            let series = match &mut self.pvt[af.antenna] {
                Some(s) => s,
                empty => {
                    let g = create_group(&self.pvt_group, self.names[af.antenna].as_str())?;
                    empty.insert(PvtSeries::create(&g, week)?)
                }
            };
            series.push(t_s, fix, af.velocity.as_ref());
            if series.waiting() >= FLUSH_ROWS {
                series.flush()?;
            }
        }
        Ok(())
    }

    /// Append what waits and close the file.
    pub(super) fn finish(mut self) -> hdf5::Result<()> {
        for s in self.obs.values_mut() {
            s.flush()?;
        }
        for s in self.pvt.iter_mut().flatten() {
            s.flush()?;
        }
        drop(self.obs);
        drop(self.pvt);
        drop(self.obs_groups);
        drop(self.pvt_group);
        self.file.flush()?;
        self.file.close()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use skyforge_receiver::pipeline::fixtures::report;

    fn read_f64(file: &hdf5::File, path: &str) -> Vec<f64> {
        file.dataset(path).unwrap().read_raw::<f64>().unwrap()
    }

    #[test]
    fn datasets_hold_every_row_across_chunks() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("receiver.h5");
        let names = vec!["ant1".to_string(), "ant2".to_string()];
        let mut h5 = ReceiverH5::create(&path, &names).unwrap();
        let n = FLUSH_ROWS + 5;
        for k in 0..n {
            h5.write_epoch(&report(k)).unwrap();
        }
        h5.finish().unwrap();

        let file = hdf5::File::open(&path).unwrap();
        let week: u32 = file.attr("gps_week").unwrap().read_scalar().unwrap();
        // 2022-01-01 (the reports' day) is in GPS week 2190.
        assert_eq!(week, 2190);
        let mut sats = file
            .group("observations/ant1")
            .unwrap()
            .member_names()
            .unwrap();
        sats.sort();
        assert_eq!(sats, ["C19", "G07", "G12", "G19"]);
        assert_eq!(
            file.group("observations/ant2")
                .unwrap()
                .member_names()
                .unwrap(),
            ["G07"]
        );
        let t = read_f64(&file, "observations/ant1/G12/t_rx_gpst_s");
        assert_eq!(t.len(), n);
        // Saturday 00:00:30.0000001 GPST = 6 days + 30 s into the week, then 10 Hz.
        assert!(
            (t[0] - (6.0 * 86400.0 + 30.000_000_1)).abs() < 1e-9,
            "{}",
            t[0]
        );
        assert!((t[n - 1] - t[0] - 0.1 * (n - 1) as f64).abs() < 1e-6);
        let t_week: u32 = file
            .dataset("observations/ant1/G12/t_rx_gpst_s")
            .unwrap()
            .attr("gps_week")
            .unwrap()
            .read_scalar()
            .unwrap();
        assert_eq!(t_week, 2190);
        let pr = read_f64(&file, "observations/ant1/G12/pseudorange_m");
        assert_eq!(pr[n - 1], 2.0e7 + 12_000.0 + 100.0 * (n - 1) as f64);
        let lli = file
            .dataset("observations/ant1/G12/loss_of_lock")
            .unwrap()
            .read_raw::<u8>()
            .unwrap();
        assert_eq!(lli.len(), n);
        assert_eq!(lli.iter().map(|&x| usize::from(x)).sum::<usize>(), 2);
        assert_eq!((lli[0], lli[1], lli[2]), (1, 0, 1));
        for name in [
            "carrier_phase_cycles",
            "doppler_hz",
            "cn0_dbhz",
            "lock_time_s",
        ] {
            assert_eq!(
                read_f64(&file, &format!("observations/ant2/G07/{name}")).len(),
                n
            );
        }

        // Fixes from epoch 1 on, velocity from epoch 2 on; antenna 2 never fixes.
        let r = file.dataset("pvt/ant1/r_ecef_m").unwrap();
        assert_eq!(r.shape(), [n - 1, 3]);
        let r = r.read_2d::<f64>().unwrap();
        assert_eq!(r[[n - 2, 1]], 5_009_154.0);
        let v = file
            .dataset("pvt/ant1/v_ecef_mps")
            .unwrap()
            .read_2d::<f64>()
            .unwrap();
        assert!(v.row(0).iter().all(|x| x.is_nan()));
        assert_eq!(v.row(1).to_vec(), [1.0, -2.0, 0.5]);
        let drift = read_f64(&file, "pvt/ant1/clock_drift_mps");
        assert!(drift[0].is_nan() && drift[1] == 0.25);
        assert_eq!(read_f64(&file, "pvt/ant1/pdop")[0], 2.1);
        // The fixtures' fixes carry no protection: NaN protection levels.
        for name in ["hpl_m", "vpl_m"] {
            let pl = read_f64(&file, &format!("pvt/ant1/{name}"));
            assert!(pl.len() == n - 1 && pl.iter().all(|x| x.is_nan()));
        }
        assert_eq!(read_f64(&file, "pvt/ant1/clock_bias_m").len(), n - 1);
        let used = file
            .dataset("pvt/ant1/sats_used")
            .unwrap()
            .read_raw::<u16>()
            .unwrap();
        assert!(used.len() == n - 1 && used.iter().all(|&u| u == 4));
        assert!(file.group("pvt/ant2").is_err());
    }
}
