//! Satellite identifiers.

/// A GNSS.
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, serde::Serialize, serde::Deserialize,
)]
pub enum System {
    Gps,
    Beidou,
}

/// A satellite: system and PRN (1-based). Displayed RINEX-style: `G05`, `C19`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct SatId {
    pub system: System,
    pub prn: u8,
}

impl std::fmt::Display for SatId {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let letter = match self.system {
            System::Gps => 'G',
            System::Beidou => 'C',
        };
        write!(f, "{letter}{:02}", self.prn)
    }
}
