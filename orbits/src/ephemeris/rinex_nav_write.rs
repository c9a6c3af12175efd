//! Writing RINEX 3.04 mixed navigation files: GPS LNAV, Galileo I/NAV and F/NAV and
//! BeiDou D1/D2 records, with the record layout the reader in [`super::rinex_nav`] expects
//! (RINEX 3.04 tables A6, A8 and A14). The header date is the first record's toc, not the wall clock, so that the same
//! scenario writes the same bytes.

use super::broadcast::{BroadcastEphemeris, NavMessage};
use super::sat_id::System;
use std::io::{self, Write};

/// `x` in Fortran `Dw.d` style: mantissa in [1, 10) with `decimals` digits, a two-digit
/// exponent, right-aligned in `width` characters.
fn fortran(x: f64, decimals: usize, width: usize) -> String {
    let x = if x.is_finite() { x } else { 0.0 };
    let s = format!("{x:.decimals$E}");
    let (mantissa, exp) = s.split_once('E').unwrap_or((&s, "0"));
    let exp: i32 = exp.parse().unwrap_or(0);
    let sign = if exp < 0 { '-' } else { '+' };
    format!("{:>width$}", format!("{mantissa}E{sign}{:02}", exp.abs()))
}

/// A record value, `D19.12`.
fn d19(x: f64) -> String {
    fortran(x, 12, 19)
}

/// Galileo data sources (RINEX 3.05 Table A8): I/NAV E1-B and E5b-I with the E5b,E1 clock
/// (bits 0, 2, 9); F/NAV E5a-I with the E5a,E1 clock (bits 1, 8).
const GAL_SOURCES_INAV: f64 = 517.0;
const GAL_SOURCES_FNAV: f64 = 258.0;
/// The Galileo SISA field (m) SkyForge writes: 3.12 m, the value Galileo satellites
/// broadcast in nominal operation (seen in every record of the bundled 2020 and 2023 files).
const GAL_SISA_M: f64 = 3.12;

fn orbit_line(out: &mut impl Write, v: [f64; 4]) -> io::Result<()> {
    writeln!(
        out,
        "    {}{}{}{}",
        d19(v[0]),
        d19(v[1]),
        d19(v[2]),
        d19(v[3])
    )
}

/// A `TIME SYSTEM CORR` header line's polynomial: `a0 + a1 (t - t_ref)`, the reference
/// `t_ref` given as seconds of week and a continuous GPS week (RINEX 3.04 Table A5).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TimeSystemCorr {
    pub a0_s: f64,
    pub a1: f64,
    pub t_ref_sow: u32,
    pub week: u32,
}

/// What a navigation file's header carries besides its version line.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NavHeader<'a> {
    /// The writer, in `PGM / RUN BY / DATE`.
    pub program: &'a str,
    /// `IONOSPHERIC CORR` lines: (system, alpha, beta).
    pub iono: &'a [(System, [f64; 4], [f64; 4])],
    /// `TIME SYSTEM CORR` `GAGP`: GST - GPST as Galileo broadcasts it (A0G, A1G).
    pub gst_gps: Option<TimeSystemCorr>,
}

impl<'a> NavHeader<'a> {
    /// A header naming `program`, nothing else.
    pub fn new(program: &'a str) -> Self {
        Self {
            program,
            iono: &[],
            gst_gps: None,
        }
    }
}

/// Write `ephemerides` as a RINEX 3.04 navigation file with `header`'s program,
/// `IONOSPHERIC CORR` and `TIME SYSTEM CORR` lines.
pub fn write_nav(
    ephemerides: &[BroadcastEphemeris],
    header: &NavHeader<'_>,
    out: &mut impl Write,
) -> io::Result<()> {
    let (program, iono) = (header.program, header.iono);
    let systems: Vec<System> = ephemerides.iter().map(|e| e.sat.system).collect();
    let letter = match systems.first() {
        Some(&first) if systems.iter().all(|&s| s == first) => first.letter(),
        _ => 'M',
    };
    writeln!(
        out,
        "{:>9}{:11}{:<20}{:<20}RINEX VERSION / TYPE",
        "3.04", "", "N: GNSS NAV DATA", letter
    )?;
    let date = ephemerides
        .first()
        .map_or((1980, 1, 6, 0, 0, 0, 0), |e| e.toc.to_gregorian_utc());
    let stamp = format!(
        "{:04}{:02}{:02} {:02}{:02}{:02} UTC",
        date.0, date.1, date.2, date.3, date.4, date.5
    );
    writeln!(
        out,
        "{:<20}{:<20}{:<20}PGM / RUN BY / DATE",
        program, "", stamp
    )?;
    for (system, alpha, beta) in iono {
        let tag = match system {
            System::Gps => "GPS",
            System::Beidou => "BDS",
            System::Galileo => continue,
        };
        for (part, v) in [('A', alpha), ('B', beta)] {
            writeln!(
                out,
                "{tag}{part} {}{}{}{}       IONOSPHERIC CORR",
                fortran(v[0], 4, 12),
                fortran(v[1], 4, 12),
                fortran(v[2], 4, 12),
                fortran(v[3], 4, 12)
            )?;
        }
    }
    if let Some(c) = header.gst_gps {
        // A4, 1X, D17.10, D16.9, 1X, I6, 1X, I4 (RINEX 3.04 Table A5, as a PolaRx5 writes).
        let line = format!(
            "GAGP {}{} {:>6} {:>4}",
            fortran(c.a0_s, 10, 17),
            fortran(c.a1, 9, 16),
            c.t_ref_sow,
            c.week
        );
        writeln!(out, "{line:<60}TIME SYSTEM CORR")?;
    }
    writeln!(out, "{:60}END OF HEADER", "")?;
    for e in ephemerides {
        let (week, toe_sow) = e.sat.system.week_sow(e.toe);
        let (y, mo, d, h, mi, s, _) = e.toc.to_gregorian(e.sat.system.time_scale());
        writeln!(
            out,
            "{}{:02} {y:04} {mo:02} {d:02} {h:02} {mi:02} {s:02}{}{}{}",
            e.sat.system.letter(),
            e.sat.prn,
            d19(e.clock.af0),
            d19(e.clock.af1),
            d19(e.clock.af2)
        )?;
        let (o, h) = (&e.orbit, &e.harmonics);
        orbit_line(out, [f64::from(e.iode), h.crs, o.delta_n, o.m0])?;
        orbit_line(out, [h.cuc, o.e, h.cus, o.sqrt_a])?;
        orbit_line(out, [toe_sow, h.cic, o.omega0, h.cis])?;
        orbit_line(out, [o.i0, h.crc, o.omega, o.omega_dot])?;
        // Transmission time: taken as toc (the set is broadcast from then on in SkyForge).
        let (_, toc_sow) = e.sat.system.week_sow(e.toc);
        match e.sat.system {
            System::Gps => {
                orbit_line(out, [o.idot, 1.0, f64::from(week), 0.0])?;
                orbit_line(
                    out,
                    [2.0, f64::from(e.health), e.clock.tgd_s, f64::from(e.iodc)],
                )?;
                // Fit interval in hours: the set's own (the embedded nominal sets hold for
                // the whole run, so a reader must not drop them after the standard 4 h).
                orbit_line(out, [toc_sow, fit_hours(e.fit_interval_s), 0.0, 0.0])?;
            }
            System::Galileo => {
                let (sources, bgd_e5a, bgd_e5b) = match e.message {
                    NavMessage::GalileoFnav => (GAL_SOURCES_FNAV, e.clock.tgd_s, 0.0),
                    _ => (GAL_SOURCES_INAV, e.clock.tgd2_s, e.clock.tgd_s),
                };
                orbit_line(out, [o.idot, sources, f64::from(week), 0.0])?;
                orbit_line(out, [GAL_SISA_M, f64::from(e.health), bgd_e5a, bgd_e5b])?;
                orbit_line(out, [toc_sow, 0.0, 0.0, 0.0])?;
            }
            System::Beidou => {
                orbit_line(out, [o.idot, 0.0, f64::from(week), 0.0])?;
                orbit_line(out, [2.0, f64::from(e.health), e.clock.tgd_s, 0.0])?;
                orbit_line(out, [toc_sow, f64::from(e.iodc), 0.0, 0.0])?;
            }
        }
    }
    Ok(())
}

/// The RINEX GPS fit-interval field (hours) for a fit of `fit_s`: at least the standard
/// 4 h, which is what a reader assumes for a smaller value.
fn fit_hours(fit_s: f64) -> f64 {
    if fit_s.is_finite() {
        (fit_s / 3600.0).max(4.0)
    } else {
        4.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    use crate::ephemeris::NavMessage;
    use crate::ephemeris::config::BeidouSet;
    use crate::ephemeris::nominal;
    use crate::ephemeris::rinex_nav::parse_nav;
    use hifitime::Epoch;
    use hifitime::TimeScale;

    fn text_has_iono(buf: &[u8]) -> bool {
        let text = String::from_utf8_lossy(buf);
        text.lines().any(|l| {
            l.starts_with("GPSA   1.1176E-08") && l.len() == 76 && l.ends_with("IONOSPHERIC CORR")
        })
    }

    /// One nominal Galileo set of `message` as a RINEX 3.04 file.
    fn galileo_text(message: NavMessage) -> String {
        let start = Epoch::from_gregorian(2023, 3, 12, 0, 0, 0, 0, TimeScale::GST);
        let mut e = nominal::galileo(start).remove(0);
        e.message = message;
        let mut buf = Vec::new();
        write_nav(&[e], &NavHeader::new("skyforge"), &mut buf).unwrap();
        String::from_utf8(buf).unwrap()
    }

    #[test]
    fn galileo_records_name_their_message_by_the_data_sources() {
        let inav = galileo_text(NavMessage::GalileoInav);
        assert!(inav.contains(" 5.170000000000E+02"), "{inav}");
        assert!(inav.starts_with("     3.04           N: GNSS NAV DATA    E"));
        let fnav = galileo_text(NavMessage::GalileoFnav);
        assert!(fnav.contains(" 2.580000000000E+02"));
        let back = parse_nav(&fnav, "f.rnx").unwrap();
        assert_eq!(back[0].message, NavMessage::GalileoFnav);
        // The week is the GPS week (2253 on 2023-03-12), not the GST week (1229).
        assert!(fnav.contains(" 2.253000000000E+03"), "{fnav}");
        assert_eq!(
            back[0].toe,
            Epoch::from_gregorian(2023, 3, 12, 0, 0, 0, 0, TimeScale::GPST)
        );
        // A record claiming I/NAV and F/NAV at once is refused.
        let both = inav.replace(" 5.170000000000E+02", " 5.190000000000E+02");
        let err = parse_nav(&both, "both.rnx").unwrap_err().to_string();
        assert!(err.contains("both I/NAV"), "{err}");
        let neither = inav.replace(" 5.170000000000E+02", " 5.120000000000E+02");
        let err = parse_nav(&neither, "neither.rnx").unwrap_err().to_string();
        assert!(err.contains("neither"), "{err}");
    }

    #[test]
    fn d19_is_fortran_style() {
        assert_eq!(d19(-1.169201079756e-4), "-1.169201079756E-04");
        assert_eq!(d19(26559700.0), " 2.655970000000E+07");
        assert_eq!(d19(0.0), " 0.000000000000E+00");
        assert_eq!(d19(1.0), " 1.000000000000E+00");
    }

    #[test]
    fn a_gps_fit_longer_than_4_h_survives_a_round_trip() {
        // The embedded nominal sets hold for the whole run: a 15 h run read back from
        // nav.rnx must not lose them after 2 h.
        let start = Epoch::from_gregorian(2023, 3, 12, 0, 0, 0, 0, TimeScale::GPST);
        let mut ephs = nominal::gps(start);
        ephs[1].fit_interval_s = 6.0 * 3600.0;
        let mut buf = Vec::new();
        write_nav(&ephs, &NavHeader::new("skyforge"), &mut buf).unwrap();
        let back = parse_nav(&String::from_utf8(buf).unwrap(), "fit.rnx").unwrap();
        assert!(back[0].fit_interval_s >= 0.999_999 * nominal::NOMINAL_FIT_S);
        assert!((back[1].fit_interval_s - 6.0 * 3600.0).abs() < 1e-6);
        assert_eq!(fit_hours(3600.0), 4.0);
        assert_eq!(fit_hours(f64::INFINITY), 4.0);
    }

    #[test]
    fn nominal_gps_and_beidou_survive_a_round_trip() {
        let start = Epoch::from_gregorian(2023, 3, 12, 0, 0, 0, 0, TimeScale::GPST);
        let mut ephs = nominal::gps(start);
        ephs.extend(nominal::galileo(start));
        ephs.extend(nominal::beidou(BeidouSet::Bds3, start));
        for (k, e) in ephs.iter_mut().enumerate() {
            if e.sat.system == System::Galileo {
                // Both Galileo messages; I/NAV carries the second group delay.
                if k % 2 == 0 {
                    e.message = NavMessage::GalileoFnav;
                } else {
                    e.message = NavMessage::GalileoInav;
                    e.clock.tgd2_s = 2.7e-9;
                }
            }
            // Values as a message carries them: non-zero clocks and harmonics, IOD.
            e.clock.af0 = 1.234e-5;
            e.clock.af1 = -3.4e-12;
            e.harmonics.crs = 12.5;
            e.harmonics.cuc = 1.1e-6;
            e.clock.tgd_s = -5.1e-9;
            e.iode = 77;
            e.iodc = 77;
            e.fit_interval_s = if e.sat.system == System::Gps {
                4.0 * 3600.0
            } else {
                e.fit_interval_s
            };
        }
        let mut buf = Vec::new();
        let iono = [(
            System::Gps,
            [1.1176e-8, 0.0, -5.9605e-8, 1.1921e-7],
            [1.0e5, 0.0, -1.9661e5, 0.0],
        )];
        let header = NavHeader {
            iono: &iono,
            ..NavHeader::new("skyforge")
        };
        write_nav(&ephs, &header, &mut buf).unwrap();
        assert!(text_has_iono(&buf));
        let text = String::from_utf8(buf).unwrap();
        assert!(
            text.lines().all(|l| l.len() <= 80),
            "a line longer than 80 characters"
        );
        let back = parse_nav(&text, "round-trip.rnx").unwrap();
        assert_eq!(back.len(), ephs.len());
        for (a, b) in ephs.iter().zip(&back) {
            assert_eq!(
                (a.sat, a.class, a.toe, a.toc),
                (b.sat, b.class, b.toe, b.toc),
                "{}",
                a.sat
            );
            assert_eq!((a.iode, a.health, a.message), (b.iode, b.health, b.message));
            let values = |e: &BroadcastEphemeris| {
                [
                    e.orbit.sqrt_a,
                    e.orbit.e,
                    e.orbit.i0,
                    e.orbit.omega0,
                    e.orbit.omega,
                    e.orbit.m0,
                    e.orbit.omega_dot,
                    e.clock.af0,
                    e.clock.af1,
                    e.harmonics.crs,
                    e.harmonics.cuc,
                    e.clock.tgd_s,
                    e.clock.tgd2_s,
                ]
            };
            for (x, y) in values(a).into_iter().zip(values(b)) {
                assert!(
                    (x - y).abs() <= 1e-12 * x.abs().max(1e-30),
                    "{}: {x} vs {y}",
                    a.sat
                );
            }
        }
    }

    /// The GAGP line in the layout of a real receiver's file (ESBC00DNK, 2020 day 177,
    /// Septentrio PolaRx5: `GAGP  2.3574102670E-09 3.996802889E-15 345600 2111`).
    #[test]
    fn the_gst_gps_line_has_a_real_files_layout() {
        let mut buf = Vec::new();
        let header = NavHeader {
            gst_gps: Some(TimeSystemCorr {
                a0_s: 2.3574102670e-9,
                a1: 3.996802889e-15,
                t_ref_sow: 345_600,
                week: 2111,
            }),
            ..NavHeader::new("t")
        };
        write_nav(&[], &header, &mut buf).unwrap();
        let text = String::from_utf8(buf).unwrap();
        let expected = format!(
            "{:<60}TIME SYSTEM CORR",
            "GAGP  2.3574102670E-09 3.996802889E-15 345600 2111"
        );
        assert!(text.lines().any(|l| l == expected), "{text}");
        // The reader takes the file (the line is a header line it passes over).
        assert!(parse_nav(&text, "t.rnx").unwrap().is_empty());
    }
}
