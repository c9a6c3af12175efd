//! The transmitters of a constellation: each satellite's navigation-message encoder built
//! from its broadcast ephemeris (with the constellation's almanac, ionosphere and UTC
//! parameters), and its ranging code.

use super::transmitter::Transmitter;
use crate::errors::ionosphere::KlobucharCoeffs;
use hifitime::Epoch;
use skyforge_gnss::navmsg::gps_lnav::{Almanac, IonoParams, LnavEncoder, LnavError, UtcParams};
use skyforge_gnss::navmsg::{BdsNavEncoder, BdsNavError, Klobuchar};
use skyforge_orbits::ephemeris::{BroadcastEphemeris, SatId, System};

/// Why a constellation's transmitters could not be built.
#[derive(Debug, thiserror::Error)]
pub enum TransmitterError {
    #[error("GPS LNAV: {0}")]
    Lnav(#[from] LnavError),
    #[error("BeiDou D1/D2: {0}")]
    Bds(#[from] BdsNavError),
    #[error("no ranging code, or a start before the time scale's epoch, for {0}")]
    NoSignal(SatId),
}

/// GPS L1 C/A transmitters for the GPS ephemerides among `ephs`, broadcasting the
/// Klobuchar coefficients `coeffs`.
pub fn gps_l1ca(
    ephs: &[BroadcastEphemeris],
    start: Epoch,
    coeffs: &KlobucharCoeffs,
) -> Result<Vec<Transmitter>, TransmitterError> {
    let gps: Vec<&BroadcastEphemeris> = ephs
        .iter()
        .filter(|e| e.sat.system == System::Gps)
        .collect();
    let owned: Vec<BroadcastEphemeris> = gps.iter().map(|e| (*e).clone()).collect();
    let almanac = Almanac::from_ephemerides(&owned, start)?;
    let iono = IonoParams {
        alpha: coeffs.alpha,
        beta: coeffs.beta,
    };
    let utc = UtcParams::from_leap_seconds(start)?;
    gps.iter()
        .map(|eph| {
            let lnav = LnavEncoder::new(eph, &almanac, &iono, &utc, 0)?;
            Transmitter::gps_l1ca(eph.sat, lnav, start).ok_or(TransmitterError::NoSignal(eph.sat))
        })
        .collect()
}

/// BeiDou B1I transmitters (D1 for MEO/IGSO, D2 for GEO) for the BeiDou ephemerides among
/// `ephs`, broadcasting the Klobuchar coefficients `coeffs`.
pub fn bds_b1i(
    ephs: &[BroadcastEphemeris],
    start: Epoch,
    coeffs: &KlobucharCoeffs,
) -> Result<Vec<Transmitter>, TransmitterError> {
    let bds: Vec<BroadcastEphemeris> = ephs
        .iter()
        .filter(|e| e.sat.system == System::Beidou)
        .cloned()
        .collect();
    let iono = Klobuchar {
        alpha: coeffs.alpha,
        beta: coeffs.beta,
    };
    let (week, _) = skyforge_orbits::time::bdt_week_sow(start);
    bds.iter()
        .map(|eph| {
            let nav = BdsNavEncoder::new(eph, &iono, &bds, week)?;
            Transmitter::bds_b1i(eph.sat, nav, start).ok_or(TransmitterError::NoSignal(eph.sat))
        })
        .collect()
}
