//! The broadcast Klobuchar coefficients of a RINEX navigation file: RINEX 2 `ION ALPHA` /
//! `ION BETA`, RINEX 3 `IONOSPHERIC CORR` header lines (`GPSA`, `GPSB`, `BDSA`, `BDSB`),
//! RINEX 4 `> ION` records (`G.. LNAV`, `C.. D1D2`; the first of each system).

use super::NavError;
use super::klobuchar::KlobucharCoeffs;
use super::nav_text::read_text_maybe_gz;
use std::path::Path;

/// The ionosphere coefficients a navigation file carries.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct BroadcastIono {
    pub gps: Option<KlobucharCoeffs>,
    pub bds: Option<KlobucharCoeffs>,
}

/// Read the Klobuchar coefficients of a RINEX 2/3/4 navigation file (gzip or plain).
pub fn read_iono_file(path: &Path) -> Result<BroadcastIono, NavError> {
    let text = read_text_maybe_gz(path)?;
    parse_iono(&text, &path.display().to_string())
}

/// `text` with `D` exponents as `E` and a space before every sign that follows a digit
/// (RINEX numbers may touch: "...e-07-1.2e-07").
fn split_touching(text: &str) -> String {
    let mut spaced = String::with_capacity(text.len() + 8);
    let mut prev = ' ';
    for ch in text.replace(['D', 'd'], "E").chars() {
        if ch == '-' && (prev.is_ascii_digit() || prev == '.') {
            spaced.push(' ');
        }
        spaced.push(ch);
        prev = ch;
    }
    spaced
}

/// Four Fortran-style numbers (`D` or `E` exponents) from `fields`.
fn four(fields: &str, source: &str, line: usize) -> Result<[f64; 4], NavError> {
    let spaced = split_touching(fields);
    let values: Vec<f64> = spaced
        .split_whitespace()
        .map(str::parse)
        .collect::<Result<_, _>>()
        .map_err(|e| NavError::Format {
            path: source.into(),
            line,
            message: format!("ionosphere coefficients {fields:?}: {e}"),
        })?;
    values.try_into().map_err(|v: Vec<f64>| NavError::Format {
        path: source.into(),
        line,
        message: format!("{} ionosphere coefficients, 4 expected", v.len()),
    })
}

/// Parse the text of a navigation file; `source` names it in errors.
pub fn parse_iono(text: &str, source: &str) -> Result<BroadcastIono, NavError> {
    let lines: Vec<&str> = text.lines().map(|l| l.trim_end_matches('\r')).collect();
    let mut alpha_beta: [[Option<[f64; 4]>; 2]; 2] = [[None; 2]; 2];
    // The first value of each (system, alpha/beta) wins.
    fn put(slots: &mut [[Option<[f64; 4]>; 2]; 2], sys: usize, part: usize, v: [f64; 4]) {
        slots[sys][part].get_or_insert(v);
    }
    let mut in_header = true;
    for (i, line) in lines.iter().enumerate() {
        let label = crate::rinex_header::label(line);
        if in_header {
            match label {
                "END OF HEADER" => in_header = false,
                "ION ALPHA" => put(&mut alpha_beta, 0, 0, four(&line[..60], source, i + 1)?),
                "ION BETA" => put(&mut alpha_beta, 0, 1, four(&line[..60], source, i + 1)?),
                "IONOSPHERIC CORR" => {
                    let tag = line.get(..4).unwrap_or("");
                    let slot = match tag {
                        "GPSA" => Some((0, 0)),
                        "GPSB" => Some((0, 1)),
                        "BDSA" => Some((1, 0)),
                        "BDSB" => Some((1, 1)),
                        _ => None,
                    };
                    if let Some((sys, part)) = slot {
                        put(
                            &mut alpha_beta,
                            sys,
                            part,
                            four(line.get(5..53).unwrap_or(""), source, i + 1)?,
                        );
                    }
                }
                _ => {}
            }
            continue;
        }
        // RINEX 4: "> ION G12 LNAV" then the epoch and alpha0-2, alpha3 beta0-2, beta3.
        let sys = if line.starts_with("> ION G") && line.trim_end().ends_with("LNAV") {
            0
        } else if line.starts_with("> ION C") && line.trim_end().ends_with("D1D2") {
            1
        } else {
            continue;
        };
        if alpha_beta[sys][0].is_some() {
            continue;
        }
        let body: Vec<&str> = lines.iter().skip(i + 1).take(3).copied().collect();
        if body.len() < 3 {
            return Err(NavError::Format {
                path: source.into(),
                line: i + 1,
                message: "ION record cut short".into(),
            });
        }
        // Epoch in columns 5-23, then 19-character fields.
        let values = format!(
            "{} {} {}",
            body[0].get(23..).unwrap_or(""),
            body[1].get(4..).unwrap_or(""),
            body[2]
                .get(4..)
                .unwrap_or("")
                .split_whitespace()
                .next()
                .unwrap_or("")
        );
        let nums = four_plus_four(&values, source, i + 2)?;
        put(
            &mut alpha_beta,
            sys,
            0,
            [nums[0], nums[1], nums[2], nums[3]],
        );
        put(
            &mut alpha_beta,
            sys,
            1,
            [nums[4], nums[5], nums[6], nums[7]],
        );
    }
    let coeffs = |sys: usize| match alpha_beta[sys] {
        [Some(alpha), Some(beta)] => Some(KlobucharCoeffs { alpha, beta }),
        _ => None,
    };
    Ok(BroadcastIono {
        gps: coeffs(0),
        bds: coeffs(1),
    })
}

/// Eight numbers of a RINEX 4 ION record.
fn four_plus_four(text: &str, source: &str, line: usize) -> Result<[f64; 8], NavError> {
    let spaced = split_touching(text);
    let parts: Vec<&str> = spaced.split_whitespace().collect();
    let (a, b) = (
        four(
            &parts.iter().take(4).copied().collect::<Vec<_>>().join(" "),
            source,
            line,
        )?,
        four(
            &parts.iter().skip(4).copied().collect::<Vec<_>>().join(" "),
            source,
            line,
        )?,
    );
    Ok([a[0], a[1], a[2], a[3], b[0], b[1], b[2], b[3]])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_the_three_rinex_generations() {
        let v2 = "     2              NAVIGATION DATA                         RINEX VERSION / TYPE\n    0.1211D-07 -0.7451D-08 -0.5960D-07  0.1192D-06          ION ALPHA           \n    0.1167D+06 -0.2458D+06 -0.6554D+05  0.1114D+07          ION BETA            \n                                                            END OF HEADER\n";
        let g = parse_iono(v2, "v2").unwrap().gps.unwrap();
        assert_eq!(g.alpha, [0.1211e-7, -0.7451e-8, -0.5960e-7, 0.1192e-6]);
        assert_eq!(g.beta, [0.1167e6, -0.2458e6, -0.6554e5, 0.1114e7]);
        let v3 = "     3.04           N: GNSS NAV DATA    M                   RINEX VERSION / TYPE\nGPSA   4.6566e-09  1.4901e-08 -5.9605e-08 -1.1921E-07       IONOSPHERIC CORR    \nGPSB   8.1920e+04  9.8304e+04 -6.5536e+04 -5.2429E+05       IONOSPHERIC CORR    \nBDSA   1.1176E-08  2.9802E-08 -4.1723E-07  6.5565E-07       IONOSPHERIC CORR    \nBDSB   1.4131E+05 -5.2429E+05  1.6384E+06 -4.5875E+05       IONOSPHERIC CORR    \n                                                            END OF HEADER\n";
        let i = parse_iono(v3, "v3").unwrap();
        assert_eq!(i.gps.unwrap().alpha[3], -1.1921e-7);
        assert_eq!(
            i.bds.unwrap().beta,
            [1.4131e5, -5.2429e5, 1.6384e6, -4.5875e5]
        );
        let v4 = "     4.00           NAVIGATION DATA     M                   RINEX VERSION / TYPE\n                                                            END OF HEADER\n> ION G12 LNAV\n    2023 03 12 00 08 54 3.259629011154e-08 7.450580596924e-09-1.788139343262e-07\n     0.000000000000e+00 1.351680000000e+05 0.000000000000e+00-2.621440000000e+05\n     1.310720000000e+05\n";
        let g = parse_iono(v4, "v4").unwrap().gps.unwrap();
        assert_eq!(
            g.alpha,
            [
                3.259629011154e-08,
                7.450580596924e-09,
                -1.788139343262e-07,
                0.0
            ]
        );
        assert_eq!(g.beta, [1.35168e5, 0.0, -2.62144e5, 1.31072e5]);
    }

    #[test]
    fn what_the_writer_writes_reads_back() {
        let mut out = Vec::new();
        let (a, b) = (
            [1.1176e-8, 2.9802e-8, -4.1723e-7, 6.5565e-7],
            [1.4131e5, -5.2429e5, 1.6384e6, -4.5875e5],
        );
        let iono = [(crate::ephemeris::System::Beidou, a, b)];
        let header = crate::ephemeris::NavHeader {
            iono: &iono,
            ..crate::ephemeris::NavHeader::new("t")
        };
        crate::ephemeris::rinex_nav_write::write_nav(&[], &header, &mut out).unwrap();
        let i = parse_iono(&String::from_utf8(out).unwrap(), "w").unwrap();
        assert_eq!(i.bds, Some(KlobucharCoeffs { alpha: a, beta: b }));
        assert_eq!(i.gps, None);
    }
}
