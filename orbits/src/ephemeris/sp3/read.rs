//! The SP3 reader.

use super::{CLOCK_MISSING_US, Sp3Record, Sp3State};
use crate::Vec3;
use crate::ephemeris::{NavError, nav_text::read_text_maybe_gz, sat_id::SatId};
use hifitime::{Epoch, TimeScale};
use std::path::Path;

/// Read the GPS, BeiDou and Galileo position records of an SP3 file.
pub fn read_sp3(path: &Path) -> Result<Vec<Sp3Record>, NavError> {
    let text = read_text_maybe_gz(path)?;
    parse_sp3(&text, &path.display().to_string())
}

/// Parse the text of an SP3-c/d file: the position records of the GNSS satellites
/// SkyForge knows. `source` names the file in errors.
pub fn parse_sp3(text: &str, source: &str) -> Result<Vec<Sp3Record>, NavError> {
    let mut out = Vec::new();
    parse_lines(text, source, |line| {
        if let Sp3Line::Position { epoch, id, state } = line
            && let Ok(sat) = id.parse::<SatId>()
        {
            out.push(Sp3Record {
                epoch,
                sat,
                r_ecef_m: state.r_ecef_m,
                clock_s: state.clock_s,
            });
        }
    })?;
    Ok(out)
}

/// Read the states (positions, and velocities where the file has them) of the vehicle
/// `id` (3 characters as the file writes them, e.g. `L01` for a LEO) in an SP3 file.
pub fn read_sp3_vehicle(path: &Path, id: &str) -> Result<Vec<Sp3State>, NavError> {
    let text = read_text_maybe_gz(path)?;
    parse_sp3_vehicle(&text, &path.display().to_string(), id)
}

/// [`read_sp3_vehicle`] on a file's text.
pub fn parse_sp3_vehicle(text: &str, source: &str, id: &str) -> Result<Vec<Sp3State>, NavError> {
    let mut out: Vec<Sp3State> = Vec::new();
    parse_lines(text, source, |line| match line {
        Sp3Line::Position { id: i, state, .. } if i == id => out.push(state),
        Sp3Line::Velocity {
            epoch,
            id: i,
            v_ecef_mps,
        } if i == id => {
            if let Some(last) = out.last_mut().filter(|s| s.epoch == epoch) {
                last.v_ecef_mps = Some(v_ecef_mps);
            }
        }
        _ => {}
    })?;
    Ok(out)
}

/// One data line of an SP3 file, with the epoch it belongs to.
enum Sp3Line<'a> {
    Position {
        epoch: Epoch,
        id: &'a str,
        state: Sp3State,
    },
    Velocity {
        epoch: Epoch,
        id: &'a str,
        v_ecef_mps: Vec3,
    },
}

/// Every position (`P`) and velocity (`V`) line of an SP3-c/d file, in file order; bad
/// or absent positions (all zero) left out.
fn parse_lines<'a>(
    text: &'a str,
    source: &str,
    mut each: impl FnMut(Sp3Line<'a>),
) -> Result<(), NavError> {
    let err = |line: usize, message: &str| NavError::Format {
        path: source.to_string(),
        line,
        message: message.to_string(),
    };
    let mut lines = text.lines().map(|l| l.trim_end_matches('\r')).enumerate();
    let first = lines.next().map(|(_, l)| l).unwrap_or("");
    if !(first.starts_with("#c") || first.starts_with("#d")) {
        return Err(err(
            1,
            "not an SP3-c/d file (line 1 must start with #c or #d)",
        ));
    }
    let mut scale = None;
    let mut epoch = None;
    for (i, line) in lines {
        let n = i + 1;
        if line.starts_with("%c") && scale.is_none() {
            let code = line.get(9..12).unwrap_or("").trim();
            scale = Some(match code {
                "GPS" | "" | "ccc" => TimeScale::GPST,
                "BDT" | "BDS" => TimeScale::BDT,
                "GAL" | "GST" => TimeScale::GST,
                "TAI" => TimeScale::TAI,
                "UTC" | "GLO" => TimeScale::UTC,
                _ => return Err(err(n, "unknown SP3 time system")),
            });
        } else if let Some(rest) = line.strip_prefix('*') {
            let ts = scale.unwrap_or(TimeScale::GPST);
            epoch = Some(parse_epoch(rest, ts).ok_or_else(|| err(n, "bad epoch line"))?);
        } else if line.starts_with('P') || line.starts_with('V') {
            let Some(id) = line.get(1..4) else {
                return Err(err(n, "a data line without a vehicle identifier"));
            };
            let t = epoch.ok_or_else(|| err(n, "data before the first epoch line"))?;
            let num = |a: usize, b: usize| -> Result<Option<f64>, NavError> {
                match line.get(a..b.min(line.len())).map(str::trim) {
                    None => Err(err(n, "non-ASCII text in a numeric field")),
                    Some("") => Ok(None),
                    Some(s) => match s.parse::<f64>() {
                        Ok(x) if x.is_finite() => Ok(Some(x)),
                        _ => Err(err(n, "bad number")),
                    },
                }
            };
            let xyz = [num(4, 18)?, num(18, 32)?, num(32, 46)?];
            let [Some(x), Some(y), Some(z)] = xyz else {
                return Err(err(n, "data line without x, y, z"));
            };
            if line.starts_with('V') {
                // Velocities in dm/s.
                each(Sp3Line::Velocity {
                    epoch: t,
                    id,
                    v_ecef_mps: Vec3::new(x, y, z) * 0.1,
                });
                continue;
            }
            if x == 0.0 && y == 0.0 && z == 0.0 {
                continue; // bad or absent position
            }
            let clock_s = num(46, 60)?
                .filter(|c| c.abs() < CLOCK_MISSING_US)
                .map(|c| c * 1e-6);
            each(Sp3Line::Position {
                epoch: t,
                id,
                state: Sp3State {
                    epoch: t,
                    r_ecef_m: Vec3::new(x, y, z) * 1e3,
                    v_ecef_mps: None,
                    clock_s,
                },
            });
        }
    }
    Ok(())
}

/// `  2020  6 25  0  0  0.00000000` in `scale`.
pub(super) fn parse_epoch(rest: &str, scale: TimeScale) -> Option<Epoch> {
    let t: Vec<&str> = rest.split_whitespace().collect();
    if t.len() != 6 {
        return None;
    }
    let int = |s: &str| s.parse::<u8>().ok();
    let sec: f64 = t[5].parse().ok()?;
    if !(0.0..61.0).contains(&sec) {
        return None;
    }
    let whole = sec.floor();
    let nanos = (((sec - whole) * 1e9).round() as u32).min(999_999_999);
    Epoch::maybe_from_gregorian(
        t[0].parse().ok()?,
        int(t[1])?,
        int(t[2])?,
        int(t[3])?,
        int(t[4])?,
        whole as u8,
        nanos,
        scale,
    )
    .ok()
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// Header and first epoch lines in the layout of GRG0MGXFIN_20201770000 (values from
    /// that file; one GPS clock set to the missing sentinel, one position zeroed).
    const SP3: &str = "#cP2020  6 25  0  0  0.00000000      96 TRACK IGb14 FIT GRGS
## 2111 345600.00000000   900.00000000 59025 0.0000000000000
+    4   E01G01G02G03  0  0  0  0  0  0  0  0  0  0  0  0  0
%c M  cc GPS ccc cccc cccc cccc cccc ccccc ccccc ccccc ccccc
%c cc cc ccc ccc cccc cccc cccc cccc ccccc ccccc ccccc ccccc
/* comment
*  2020  6 25  0  0  0.00000000
PE01 -11562.163582  14053.114306  23345.128269   -884.707516
PG01 -10814.532184  19731.805009 -14065.684961     15.943802
PG02  21815.313784 -13786.051880  -5530.292407 999999.999999
PG 3      0.000000      0.000000      0.000000 999999.999999
*  2020  6 25  0 15  0.00000000
PG 1 -11000.000000  19000.000000 -15000.000000
EOF
";

    #[test]
    fn reads_positions_clocks_and_epochs() {
        let all = parse_sp3(SP3, "t.sp3").unwrap();
        assert_eq!(all.len(), 4);
        assert_eq!(all[0].sat, SatId::galileo(1));
        assert!((all[0].r_ecef_m.x + 11_562_163.582).abs() < 1e-6);
        let recs = &all[1..];
        let t0 = Epoch::from_gregorian(2020, 6, 25, 0, 0, 0, 0, TimeScale::GPST);
        assert_eq!(recs[0].sat, SatId::gps(1));
        assert_eq!(recs[0].epoch, t0);
        let expect = Vec3::new(-10_814_532.184, 19_731_805.009, -14_065_684.961);
        assert!((recs[0].r_ecef_m - expect).norm() < 1e-6);
        let c = recs[0].clock_s.unwrap();
        assert!((c - 15.943802e-6).abs() < 1e-15);
        assert_eq!(recs[1].clock_s, None);
        assert_eq!(recs[2].sat, SatId::gps(1));
        assert_eq!(recs[2].epoch, t0 + hifitime::Unit::Minute * 15);
        assert_eq!(recs[2].clock_s, None);
    }

    #[test]
    fn rejects_non_sp3_and_bad_lines() {
        assert!(parse_sp3("#aP2020", "t").is_err());
        let bad = SP3.replace("19731.805009", "19731.8O5009");
        assert!(matches!(
            parse_sp3(&bad, "t"),
            Err(NavError::Format { line: 9, .. })
        ));
        let no_epoch = "#dP2020\nPG01 1.0 2.0 3.0\n";
        assert!(parse_sp3(no_epoch, "t").is_err());
    }

    proptest! {
        #[test]
        fn never_panics(lines in proptest::collection::vec(
            prop_oneof![".{0,70}", "[PG*0-9 .-]{0,62}"], 0..20)) {
            let _ = parse_sp3(&format!("#cP2020\n{}", lines.join("\n")), "t");
        }
    }
}
