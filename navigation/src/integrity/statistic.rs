//! The four statistics the monitor compares across stations.

use serde::{Deserialize, Serialize};

/// A test statistic of one station's track of one satellite (paper 002 figures 4-7).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Statistic {
    /// Change of the virtual pseudorange since the track began (m).
    Code,
    /// Change of the carrier-smoothed virtual pseudorange since the Hatch filter settled
    /// (one time constant into the track) (m).
    SmoothedCode,
    /// Change of the virtual carrier phase since the track began (cycles).
    Carrier,
    /// Code-carrier divergence rate (m/s).
    Divergence,
}

impl Statistic {
    /// Every statistic, in output order.
    pub const ALL: [Statistic; 4] = [
        Statistic::Code,
        Statistic::SmoothedCode,
        Statistic::Carrier,
        Statistic::Divergence,
    ];

    /// Position in [`Self::ALL`].
    pub const fn index(self) -> usize {
        self as usize
    }

    /// Name in outputs and configuration.
    pub fn name(self) -> &'static str {
        match self {
            Statistic::Code => "code",
            Statistic::SmoothedCode => "smoothed-code",
            Statistic::Carrier => "carrier",
            Statistic::Divergence => "divergence",
        }
    }

    /// Column key in `monitor.csv` (`smoothed_code` for `smoothed-code`).
    pub fn key(self) -> &'static str {
        match self {
            Statistic::Code => "code",
            Statistic::SmoothedCode => "smoothed_code",
            Statistic::Carrier => "carrier",
            Statistic::Divergence => "divergence",
        }
    }

    /// Unit of the statistic and its B value.
    pub fn unit(self) -> &'static str {
        match self {
            Statistic::Code | Statistic::SmoothedCode => "m",
            Statistic::Carrier => "cycles",
            Statistic::Divergence => "m/s",
        }
    }
}

/// One value per statistic, in the order of [`Statistic::ALL`].
pub type PerStatistic<T> = [T; 4];
