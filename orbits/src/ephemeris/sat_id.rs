//! Satellite identifiers, and the constants of each system's user algorithm.

use crate::constants::{GM_BDS, GM_GAL, GM_GPS, OMEGA_E_BDS, OMEGA_E_GAL, OMEGA_E_GPS};
use hifitime::TimeScale;

/// A GNSS.
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, serde::Serialize, serde::Deserialize,
)]
pub enum System {
    Gps,
    Beidou,
    /// Galileo, opt-in in scenarios (`[gnss.galileo]`).
    Galileo,
}

impl System {
    /// The time scale the system's messages (toe, toc, week numbers) are expressed in.
    pub fn time_scale(self) -> hifitime::TimeScale {
        match self {
            System::Gps => hifitime::TimeScale::GPST,
            System::Beidou => hifitime::TimeScale::BDT,
            System::Galileo => hifitime::TimeScale::GST,
        }
    }

    /// Earth rotation rate of the frame the system's ephemerides are expressed in (rad/s):
    /// WGS-84 (GPS), CGCS2000 (BeiDou), GTRF (Galileo).
    pub fn earth_rotation_rad_s(self) -> f64 {
        system_constants(self).omega_e
    }

    /// Week and seconds of week of `epoch` as the system's navigation files count them:
    /// GPS and Galileo in continuous GPS weeks (GST's seconds of week are GPST's; RINEX
    /// 3.05 §6.12), BeiDou in BDT weeks.
    pub fn week_sow(self, epoch: hifitime::Epoch) -> (u32, f64) {
        match self {
            System::Gps | System::Galileo => crate::time::gpst_week_sow(epoch),
            System::Beidou => crate::time::bdt_week_sow(epoch),
        }
    }

    /// The epoch at `week`, `sow` counted as [`Self::week_sow`] counts them.
    pub fn epoch_at(self, week: u32, sow: f64) -> hifitime::Epoch {
        match self {
            System::Gps | System::Galileo => crate::time::epoch_from_gpst(week, sow),
            System::Beidou => crate::time::epoch_from_bdt(week, sow),
        }
    }

    /// `t` moved to the nearest multiple of `grid_s` seconds of the system's week: where a
    /// message's reference times (toe, toc) may lie (BeiDou 8 s, Galileo 60 s).
    pub fn on_grid(self, t: hifitime::Epoch, grid_s: f64) -> hifitime::Epoch {
        let (week, sow) = self.week_sow(t);
        self.epoch_at(week, grid_s * (sow / grid_s).round())
    }

    /// The name users know the system by: `GPS`, `BeiDou`, `Galileo`.
    pub fn name(self) -> &'static str {
        match self {
            System::Gps => "GPS",
            System::Beidou => "BeiDou",
            System::Galileo => "Galileo",
        }
    }

    /// The RINEX system letter (`G`, `C`, `E`).
    pub fn letter(self) -> char {
        match self {
            System::Gps => 'G',
            System::Beidou => 'C',
            System::Galileo => 'E',
        }
    }

    /// The system of a RINEX system letter, if SkyForge supports it.
    pub fn from_letter(letter: char) -> Option<System> {
        match letter {
            'G' => Some(System::Gps),
            'C' => Some(System::Beidou),
            'E' => Some(System::Galileo),
            _ => None,
        }
    }

    /// Highest PRN number the system's signals define (GPS 1..=32, BeiDou 1..=63, Galileo
    /// 1..=36: the SVIDs RINEX 3/4 gives Galileo, RINEX 3.05 §5.1).
    pub fn max_prn(self) -> u8 {
        match self {
            System::Gps => 32,
            System::Beidou => 63,
            System::Galileo => 36,
        }
    }
}

/// A satellite: system and PRN (1-based). Displayed RINEX-style: `G05`, `C19`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct SatId {
    pub system: System,
    pub prn: u8,
}

impl SatId {
    /// A GPS satellite.
    pub fn gps(prn: u8) -> Self {
        Self {
            system: System::Gps,
            prn,
        }
    }

    /// A BeiDou satellite.
    pub fn beidou(prn: u8) -> Self {
        Self {
            system: System::Beidou,
            prn,
        }
    }

    /// A Galileo satellite.
    pub fn galileo(prn: u8) -> Self {
        Self {
            system: System::Galileo,
            prn,
        }
    }
}

impl std::fmt::Display for SatId {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}{:02}", self.system.letter(), self.prn)
    }
}

/// Error parsing a satellite identifier.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("not a GPS/BeiDou/Galileo satellite id {text:?} (expected e.g. G05, C19, E11, \"G 5\")")]
pub struct SatIdError {
    /// The text that failed to parse.
    pub text: String,
}

impl std::str::FromStr for SatId {
    type Err = SatIdError;

    /// Parse `G05`, `C19`, `G5` or the RINEX 2/3 blank-padded form `G 5`. The PRN must be in
    /// `1..=System::max_prn()`.
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let err = || SatIdError {
            text: s.to_string(),
        };
        let trimmed = s.trim();
        let mut chars = trimmed.chars();
        let system = chars
            .next()
            .and_then(|c| System::from_letter(c.to_ascii_uppercase()))
            .ok_or_else(err)?;
        let digits = chars.as_str().trim_start();
        if digits.is_empty() || digits.len() > 2 || !digits.bytes().all(|b| b.is_ascii_digit()) {
            return Err(err());
        }
        let prn: u8 = digits.parse().map_err(|_| err())?;
        if prn == 0 || prn > system.max_prn() {
            return Err(err());
        }
        Ok(SatId { system, prn })
    }
}

/// Relativistic clock constant F = -2 sqrt(mu) / c^2 (s/m^1/2), IS-GPS-200 20.3.3.3.3.1.
const F_REL_GPS: f64 = -4.442_807_633e-10;
/// Relativistic clock constant F = -2 sqrt(mu) / c^2 (s/m^1/2) with the CGCS2000 mu,
/// BDS-SIS-ICD-B1I-3.0 5.2.4 (clock correction).
const F_REL_BDS: f64 = -4.442_807_309e-10;
/// Relativistic clock constant F = -2 sqrt(mu) / c^2 (s/m^1/2), Galileo OS SIS ICD §5.1.4.
const F_REL_GAL: f64 = -4.442_807_309e-10;

/// The constants of a system's user algorithm.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct SystemConstants {
    /// Earth gravitational constant (m^3/s^2).
    pub gm: f64,
    /// Earth rotation rate (rad/s).
    pub omega_e: f64,
    /// Relativistic clock constant F (s/m^1/2).
    pub f_rel: f64,
    /// The time scale of toe, toc and the week.
    pub scale: TimeScale,
}

/// The user-algorithm constants of `system` (IS-GPS-200 20.3.3.4.3, BDS-SIS-ICD 5.2.4,
/// Galileo OS SIS ICD §5.1.1).
pub(crate) fn system_constants(system: System) -> SystemConstants {
    let (gm, omega_e, f_rel) = match system {
        System::Gps => (GM_GPS, OMEGA_E_GPS, F_REL_GPS),
        System::Beidou => (GM_BDS, OMEGA_E_BDS, F_REL_BDS),
        System::Galileo => (GM_GAL, OMEGA_E_GAL, F_REL_GAL),
    };
    SystemConstants {
        gm,
        omega_e,
        f_rel,
        scale: system.time_scale(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    #[test]
    fn relativistic_constants_match_minus_two_sqrt_mu_over_c2() {
        let c = crate::constants::C_MPS;
        for (gm, f) in [
            (GM_GPS, F_REL_GPS),
            (GM_BDS, F_REL_BDS),
            (GM_GAL, F_REL_GAL),
        ] {
            let expect = -2.0 * gm.sqrt() / (c * c);
            assert!((expect - f).abs() < 1e-18, "{expect:e} vs {f:e}");
        }
    }

    #[test]
    fn parses_rinex_forms() {
        assert_eq!("G05".parse::<SatId>(), Ok(SatId::gps(5)));
        assert_eq!("C19".parse::<SatId>(), Ok(SatId::beidou(19)));
        assert_eq!("G 5".parse::<SatId>(), Ok(SatId::gps(5)));
        assert_eq!("g7".parse::<SatId>(), Ok(SatId::gps(7)));
        assert_eq!(" C63 ".parse::<SatId>(), Ok(SatId::beidou(63)));
        assert_eq!("E36".parse::<SatId>(), Ok(SatId::galileo(36)));
    }

    #[test]
    fn rejects_bad_ids() {
        for bad in [
            "", "G", "G00", "G33", "C64", "E37", "E00", "R01", "G123", "G-1", "5", "G 0x",
        ] {
            assert!(bad.parse::<SatId>().is_err(), "{bad:?} accepted");
        }
    }

    proptest! {
        #[test]
        fn display_round_trips(gps in any::<bool>(), prn in 1u8..=32) {
            let sat = if gps { SatId::gps(prn) } else { SatId::beidou(prn) };
            prop_assert_eq!(sat.to_string().parse::<SatId>(), Ok(sat));
        }

        #[test]
        fn never_panics(text in ".{0,6}") {
            let _ = text.parse::<SatId>();
        }
    }
}
