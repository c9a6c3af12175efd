//! RINEX 3.04 observation files of the signal truth: pseudorange, carrier phase, Doppler
//! and C/N0 per satellite at whole seconds, one file per antenna (RINEX 3.04 section 5 and
//! table A2; GPS L1 C/A observation codes 1C, BeiDou B1I 2I).

use skyforge_orbits::Vec3;
use skyforge_orbits::ephemeris::{SatId, System};
use std::io::{self, Write};

/// One satellite's observations at one epoch.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ObsRecord {
    pub sat: SatId,
    pub pseudorange_m: f64,
    pub carrier_phase_cycles: f64,
    pub doppler_hz: f64,
    pub cn0_dbhz: f64,
}

/// Streams epochs of observations into a RINEX 3.04 observation file.
#[derive(Debug)]
pub struct ObsWriter<W: Write> {
    out: W,
}

/// Calendar fields (GPS time) of an epoch.
pub type Calendar = (i32, u8, u8, u8, u8, f64);

impl<W: Write> ObsWriter<W> {
    /// Write the header: marker `name` at `approx_ecef_m`, first epoch `first` (GPS time),
    /// `interval_s`, and which systems are present.
    pub fn new(
        mut out: W,
        name: &str,
        approx_ecef_m: &Vec3,
        first: Calendar,
        interval_s: f64,
        systems: &[System],
    ) -> io::Result<Self> {
        let letter = match systems {
            [System::Gps] => 'G',
            [System::Beidou] => 'C',
            _ => 'M',
        };
        writeln!(
            out,
            "{:>9}{:11}{:<20}{:<20}RINEX VERSION / TYPE",
            "3.04", "", "OBSERVATION DATA", letter
        )?;
        writeln!(
            out,
            "{:<20}{:<20}{:<20}PGM / RUN BY / DATE",
            "skyforge",
            "",
            format!(
                "{:04}{:02}{:02} {:02}{:02}{:02} GPS",
                first.0, first.1, first.2, first.3, first.4, first.5 as u32
            )
        )?;
        writeln!(out, "{:<60}MARKER NAME", name)?;
        writeln!(out, "{:<60}MARKER TYPE", "NON_GEODETIC")?;
        writeln!(
            out,
            "{:<20}{:<40}OBSERVER / AGENCY",
            "skyforge", "simulation"
        )?;
        writeln!(
            out,
            "{:<20}{:<20}{:<20}REC # / TYPE / VERS",
            "0",
            "SKYFORGE TRUTH",
            env!("CARGO_PKG_VERSION")
        )?;
        writeln!(out, "{:<20}{:<20}{:<20}ANT # / TYPE", "0", "SKYFORGE", "")?;
        writeln!(
            out,
            "{:14.4}{:14.4}{:14.4}{:18}APPROX POSITION XYZ",
            approx_ecef_m.x, approx_ecef_m.y, approx_ecef_m.z, ""
        )?;
        writeln!(
            out,
            "{:14.4}{:14.4}{:14.4}{:18}ANTENNA: DELTA H/E/N",
            0.0, 0.0, 0.0, ""
        )?;
        for system in systems {
            let (c, band) = match system {
                System::Gps => ('G', "1C"),
                System::Beidou => ('C', "2I"),
            };
            let types = format!(" C{band} L{band} D{band} S{band}");
            writeln!(out, "{c}  {:>3}{:<54}SYS / # / OBS TYPES", 4, types)?;
        }
        writeln!(out, "{:10.3}{:50}INTERVAL", interval_s, "")?;
        writeln!(
            out,
            "  {:04}    {:02}    {:02}    {:02}    {:02}   {:10.7}     GPS{:9}TIME OF FIRST OBS",
            first.0, first.1, first.2, first.3, first.4, first.5, ""
        )?;
        writeln!(out, "{:60}END OF HEADER", "")?;
        Ok(Self { out })
    }

    /// Append one epoch (GPS time `at`) of observations.
    pub fn epoch(&mut self, at: Calendar, records: &[ObsRecord]) -> io::Result<()> {
        writeln!(
            self.out,
            "> {:04} {:02} {:02} {:02} {:02}{:11.7}  0{:3}",
            at.0,
            at.1,
            at.2,
            at.3,
            at.4,
            at.5,
            records.len()
        )?;
        for r in records {
            writeln!(
                self.out,
                "{}{:14.3}  {:14.3}  {:14.3}  {:14.3}  ",
                r.sat, r.pseudorange_m, r.carrier_phase_cycles, r.doppler_hz, r.cn0_dbhz
            )?;
        }
        Ok(())
    }

    /// Flush and hand back the writer.
    pub fn finish(mut self) -> io::Result<W> {
        self.out.flush()?;
        Ok(self.out)
    }
}
