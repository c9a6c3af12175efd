//! The transmitters of a constellation: each satellite's navigation-message encoder built
//! from its broadcast ephemeris (with the constellation's almanac, ionosphere and UTC
//! parameters), and its ranging code.

use super::transmitter::Transmitter;
use crate::errors::ionosphere::{IonoConfig, KlobucharCoeffs};
use hifitime::Epoch;
use skyforge_gnss::navmsg::bds_cnav1::BdsCnav1Encoder;
use skyforge_gnss::navmsg::bds_cnav2::BdsCnav2Encoder;
use skyforge_gnss::navmsg::galileo_fnav::{FnavEncoder, FnavError, GalileoParams};
use skyforge_gnss::navmsg::galileo_inav::{InavEncoder, InavError};
use skyforge_gnss::navmsg::gps_cnav::{CnavEncoder, CnavError, CnavParams};
use skyforge_gnss::navmsg::gps_lnav::{Almanac, IonoParams, LnavEncoder, LnavError, UtcParams};
use skyforge_gnss::navmsg::{BdsCnavError, BdsCnavParams, BdsNavEncoder, BdsNavError, Klobuchar};
use skyforge_gnss::signal::Signal;
use skyforge_orbits::ephemeris::{BroadcastEphemeris, OrbitClass, SatId, System};
use skyforge_orbits::time::{GST_WEEK0_IN_GPS_WEEKS, GstGpsOffset, TimeOrigin};

/// Why a constellation's transmitters could not be built.
#[derive(Debug, thiserror::Error)]
pub enum TransmitterError {
    #[error("GPS LNAV: {0}")]
    Lnav(#[from] LnavError),
    #[error("BeiDou D1/D2: {0}")]
    Bds(#[from] BdsNavError),
    #[error("Galileo F/NAV: {0}")]
    Fnav(#[from] FnavError),
    #[error("Galileo I/NAV: {0}")]
    Inav(#[from] InavError),
    #[error("{0}")]
    E1Codes(#[from] skyforge_gnss::codes::E1CodesError),
    #[error("GPS CNAV: {0}")]
    Cnav(#[from] CnavError),
    #[error("BeiDou B-CNAV1/B-CNAV2: {0}")]
    BdsCnav2(#[from] BdsCnavError),
    #[error(
        "{0}: none of the {1} BeiDou satellites is a BDS-3 MEO or IGSO one (PRN 19 and up, not GEO); \
         BDS-2 satellites and GEOs broadcast no {0} (choose embedded_set = \"bds3\")"
    )]
    NoBds3(Signal, usize),
    #[error("no ranging code, or a start before the time scale's epoch, for {0}")]
    NoSignal(SatId),
    #[error("{0} is not transmitted by SkyForge")]
    NotTransmitted(Signal),
}

/// The transmitters of `signal` for its constellation's ephemerides among `ephs`,
/// broadcasting the Klobuchar coefficients of `iono` where the message carries them and
/// Galileo's GST - GPST offset `gst_gps`.
pub fn transmitters(
    signal: Signal,
    ephs: &[BroadcastEphemeris],
    start: Epoch,
    iono: &IonoConfig,
    gst_gps: &GstGpsOffset,
) -> Result<Vec<Transmitter>, TransmitterError> {
    match signal {
        Signal::GpsL1Ca => gps_l1ca(ephs, start, &iono.gps),
        Signal::BdsB1I => bds_b1i(ephs, start, &iono.bds),
        Signal::GalE5a => gal_e5a(ephs, start, gst_gps),
        Signal::GalE1 => gal_e1(ephs, start, gst_gps),
        Signal::GpsL5 => gps_l5(ephs, start, &iono.gps),
        Signal::BdsB2a => bds_b2a(ephs, start),
        Signal::BdsB1C => bds_b1c(ephs, start),
        other => Err(TransmitterError::NotTransmitted(other)),
    }
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

/// Grid of Galileo toe and toc (s): their scale factor is 60 s (Galileo OS SIS ICD §5.1.1,
/// §5.1.3).
const GAL_TIME_GRID_S: f64 = 60.0;

/// Grid of CNAV toe and toc (s): their scale factor is 300 s (IS-GPS-705 Tables 20-I,
/// 20-III).
const CNAV_TIME_GRID_S: f64 = 300.0;

/// The `system` ephemerides among `ephs` with toe and toc on the `grid_s` grid of their
/// message: sets off it (the embedded constellations at any start) are re-expressed on it
/// without moving the orbit or the clock.
fn on_message_grid(
    ephs: &[BroadcastEphemeris],
    system: System,
    grid_s: f64,
) -> Vec<BroadcastEphemeris> {
    ephs.iter()
        .filter(|e| e.sat.system == system)
        .map(|e| {
            let on_grid = |t| system.on_grid(t, grid_s);
            e.reexpressed(on_grid(e.toe), on_grid(e.toc))
                .unwrap_or_else(|| e.clone())
        })
        .collect()
}

/// Leap seconds at `start`: GPST - UTC = TAI - UTC - 19 s (GST is aligned with GPST).
fn gps_utc_leap_s(start: Epoch) -> i32 {
    (start.leap_seconds(true).unwrap_or(19.0) - 19.0).round() as i32
}

/// GPS L5 transmitters (CNAV on I5, pilot on Q5) for the GPS ephemerides among `ephs`,
/// broadcasting the Klobuchar coefficients `coeffs` in message type 30 and zero
/// inter-signal corrections. Sets off the 300 s grid are re-expressed on it.
pub fn gps_l5(
    ephs: &[BroadcastEphemeris],
    start: Epoch,
    coeffs: &KlobucharCoeffs,
) -> Result<Vec<Transmitter>, TransmitterError> {
    let gps = on_message_grid(ephs, System::Gps, CNAV_TIME_GRID_S);
    let params = CnavParams {
        iono: IonoParams {
            alpha: coeffs.alpha,
            beta: coeffs.beta,
        },
        utc: UtcParams::from_leap_seconds(start)?,
        ..CnavParams::default()
    };
    // Symbols count from the GPS week before the start's, so that satellite times a light
    // time before a start on a week boundary still lie after symbol 0.
    let week = skyforge_orbits::time::gpst_week_sow(start)
        .0
        .saturating_sub(1);
    gps.iter()
        .map(|eph| {
            let nav = CnavEncoder::new(eph, &params, week)?;
            Transmitter::gps_l5(eph.sat, nav, start).ok_or(TransmitterError::NoSignal(eph.sat))
        })
        .collect()
}

/// Grid of B-CNAV1 and B-CNAV2 toe and toc (s): their scale factor is 300 s
/// (BDS-SIS-ICD-B2a-1.0 and BDS-SIS-ICD-B1C-1.0, Tables 7-8 and 7-9).
const BDS_CNAV_TIME_GRID_S: f64 = 300.0;

/// The first PRN of BeiDou-3: C19-C46 are the BDS-3 MEO and IGSO satellites, C01-C18
/// BDS-2, C59-C63 GEO (BDS-3 C59-C61 and BDS-2 GEOs transmit no B2a or B1C).
const BDS3_FIRST_PRN: u8 = 19;

/// Whether BeiDou satellite `eph` broadcasts B2a and B1C: BDS-3 MEO and IGSO only
/// (BDS-SIS-ICD-B2a-1.0 §1 and BDS-SIS-ICD-B1C-1.0 §1: open service signals of the BDS-3
/// MEO and IGSO satellites; BDS-2 satellites and the GEOs do not transmit them).
fn transmits_bds3_signals(eph: &BroadcastEphemeris) -> bool {
    eph.class == OrbitClass::Standard && eph.sat.prn >= BDS3_FIRST_PRN
}

/// BeiDou B2a transmitters (B-CNAV2 on B2a_d, pilot on B2a_p) for the BDS-3 MEO and IGSO
/// ephemerides among `ephs` ([`bds3`]). TGD_B2ap is the set's `tgd_s`, the one BeiDou
/// group delay SkyForge keeps (so a receiver using the D1 set of a B1I recording applies
/// the same delay), ISC_B2ad zero.
pub fn bds_b2a(
    ephs: &[BroadcastEphemeris],
    start: Epoch,
) -> Result<Vec<Transmitter>, TransmitterError> {
    bds3(ephs, start, Signal::BdsB2a, |eph, week| {
        let params = BdsCnavParams {
            tgd_b2ap_s: eph.clock.tgd_s,
            ..BdsCnavParams::default()
        };
        let nav = BdsCnav2Encoder::new(eph, &params, week)?;
        Transmitter::bds_b2a(eph.sat, nav, start).ok_or(TransmitterError::NoSignal(eph.sat))
    })
}

/// BeiDou B1C transmitters (B-CNAV1 on B1C_data, pilot on B1C_pilot) for the BDS-3 MEO
/// and IGSO ephemerides among `ephs` ([`bds3`]). TGD_B1Cp is the set's `tgd_s`, as
/// TGD_B2ap is B2a's; ISC_B1Cd zero (data and pilot leave together).
pub fn bds_b1c(
    ephs: &[BroadcastEphemeris],
    start: Epoch,
) -> Result<Vec<Transmitter>, TransmitterError> {
    bds3(ephs, start, Signal::BdsB1C, |eph, week| {
        let params = BdsCnavParams {
            tgd_b1cp_s: eph.clock.tgd_s,
            ..BdsCnavParams::default()
        };
        let nav = BdsCnav1Encoder::new(eph, &params, week)?;
        Transmitter::bds_b1c(eph.sat, nav, start).ok_or(TransmitterError::NoSignal(eph.sat))
    })
}

/// The transmitters `build` makes of each BDS-3 MEO and IGSO ephemeris among `ephs` (with
/// the BDT week the symbols count from); the BDS-2 satellites (PRN 1-18) and every GEO are
/// left out, as they broadcast neither B2a nor B1C ([`transmits_bds3_signals`]); a set
/// with BeiDou satellites but none of these is refused for `signal`. Sets off the 300 s
/// grid are re-expressed on it.
fn bds3(
    ephs: &[BroadcastEphemeris],
    start: Epoch,
    signal: Signal,
    build: impl Fn(&BroadcastEphemeris, u32) -> Result<Transmitter, TransmitterError>,
) -> Result<Vec<Transmitter>, TransmitterError> {
    let bds = on_message_grid(ephs, System::Beidou, BDS_CNAV_TIME_GRID_S);
    // Symbols count from the BDT week before the start's, so that satellite times a light
    // time before a start on a week boundary still lie after symbol 0.
    let week = skyforge_orbits::time::bdt_week_sow(start)
        .0
        .saturating_sub(1);
    if !bds.is_empty() && !bds.iter().any(transmits_bds3_signals) {
        return Err(TransmitterError::NoBds3(signal, bds.len()));
    }
    bds.iter()
        .filter(|eph| transmits_bds3_signals(eph))
        .map(|eph| build(eph, week))
        .collect()
}

/// Galileo E5a transmitters (F/NAV on E5a-I, pilot on E5a-Q) for the Galileo ephemerides
/// among `ephs` ([`galileo`]), broadcasting `gst_gps`.
pub fn gal_e5a(
    ephs: &[BroadcastEphemeris],
    start: Epoch,
    gst_gps: &GstGpsOffset,
) -> Result<Vec<Transmitter>, TransmitterError> {
    galileo(ephs, start, |eph, gal, leap_s, week| {
        let params = galileo_params(leap_s, start, gst_gps);
        let nav = FnavEncoder::new(eph, gal, &params, week)?;
        Transmitter::gal_e5a(eph.sat, nav, start).ok_or(TransmitterError::NoSignal(eph.sat))
    })
}

/// Galileo E1 transmitters (I/NAV on E1-B, pilot on E1-C, CBOC) for the Galileo
/// ephemerides among `ephs` ([`galileo`]); the codes come from the user's tables
/// (`skyforge_gnss::codes::e1_codes`), broadcasting `gst_gps`.
pub fn gal_e1(
    ephs: &[BroadcastEphemeris],
    start: Epoch,
    gst_gps: &GstGpsOffset,
) -> Result<Vec<Transmitter>, TransmitterError> {
    let codes = skyforge_gnss::codes::e1_codes()?;
    galileo(ephs, start, |eph, gal, leap_s, week| {
        let params = galileo_params(leap_s, start, gst_gps);
        let nav = InavEncoder::new(eph, gal, &params, week)?;
        Transmitter::gal_e1(eph.sat, nav, codes, start).ok_or(TransmitterError::NoSignal(eph.sat))
    })
}

/// I/NAV's and F/NAV's parameters: GST - UTC the leap seconds `leap_s` at `start`, GST - GPS
/// `gst_gps` with its reference time (§5.1.8), the rest zero.
fn galileo_params(leap_s: i32, start: Epoch, gst_gps: &GstGpsOffset) -> GalileoParams {
    let (t0g_s, week) = gst_gps.reference(&TimeOrigin::new(start));
    let wn0g = week.saturating_sub(GST_WEEK0_IN_GPS_WEEKS) % 64;
    GalileoParams {
        dt_ls_s: leap_s,
        dt_lsf_s: leap_s,
        a0g_s: gst_gps.a0_s,
        a1g_s_s: gst_gps.a1,
        t0g_s,
        wn0g,
        ..GalileoParams::default()
    }
}

/// The transmitters `build` makes of each Galileo ephemeris among `ephs` (with the
/// constellation for the almanac, the leap seconds at `start` and the GST week the
/// symbols count from). Sets off the 60 s grid (the embedded constellation at any start)
/// are re-expressed on it without moving the orbit or the clock. The symbols count in GST
/// as the satellite clock keeps it (GST - GPST, `[gnss.galileo] gst_gps_ns`, lies in the
/// clock truth: `truth::GeometryTruth::with_gst_gps`).
fn galileo(
    ephs: &[BroadcastEphemeris],
    start: Epoch,
    build: impl Fn(
        &BroadcastEphemeris,
        &[BroadcastEphemeris],
        i32,
        u32,
    ) -> Result<Transmitter, TransmitterError>,
) -> Result<Vec<Transmitter>, TransmitterError> {
    let gal = on_message_grid(ephs, System::Galileo, GAL_TIME_GRID_S);
    let leap_s = gps_utc_leap_s(start);
    // Symbols count from the GST week before the start's, so that satellite times a light
    // time before a start on a week boundary still lie after symbol 0.
    let week = skyforge_orbits::time::gpst_week_sow(start)
        .0
        .saturating_sub(GST_WEEK0_IN_GPS_WEEKS + 1);
    gal.iter()
        .map(|eph| build(eph, &gal, leap_s, week))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use hifitime::TimeScale;
    use skyforge_orbits::ephemeris::{BeidouSet, nominal};

    /// I/NAV and F/NAV carry GST - GPST with the reference of the hour at or before the
    /// start: 2023-03-12T00:40:00 GPST is 2400 s into GPS week 2253, GST week 1229.
    #[test]
    fn galileo_messages_carry_the_gst_gps_offset() {
        let start = Epoch::from_gregorian(2023, 3, 12, 0, 40, 0, 0, TimeScale::GPST);
        let g = GstGpsOffset::at_origin(50e-9, 2e-14, &TimeOrigin::new(start));
        let p = galileo_params(18, start, &g);
        assert_eq!((p.a0g_s, p.a1g_s_s), (50e-9, 2e-14));
        assert_eq!((p.t0g_s, p.wn0g), (0, 1229 % 64));
        assert_eq!((p.dt_ls_s, p.dt_lsf_s), (18, 18));
    }

    /// B2a from the BDS-3 MEO and IGSO satellites only: the BDS-3 set's GEOs are left out,
    /// and the BDS-2 set (PRN 1-16) has none to send it.
    #[test]
    fn b2a_is_transmitted_by_bds3_meo_and_igso_only() {
        let start = Epoch::from_gregorian(2023, 3, 12, 0, 0, 0, 0, TimeScale::GPST);
        let bds3 = nominal::beidou(BeidouSet::Bds3, start);
        let txs = bds_b2a(&bds3, start).expect("BDS-3 transmitters");
        let meo_igso = bds3
            .iter()
            .filter(|e| e.class == OrbitClass::Standard)
            .count();
        assert!(meo_igso > 20 && txs.len() == meo_igso, "{}", txs.len());
        assert!(
            txs.iter()
                .all(|t| t.signal == Signal::BdsB2a && (BDS3_FIRST_PRN..59).contains(&t.sat.prn))
        );
        let bds2 = nominal::beidou(BeidouSet::Bds2, start);
        let err = bds_b2a(&bds2, start).expect_err("refused");
        assert!(
            matches!(err, TransmitterError::NoBds3(Signal::BdsB2a, 15)),
            "{err}"
        );
        assert!(err.to_string().contains("bds3"), "{err}");
    }

    /// B1C likewise (BDS-SIS-ICD-B1C-1.0 §1): the same BDS-3 MEO and IGSO satellites as
    /// B2a, each with its B-CNAV1 ephemeris; the BDS-2 set is refused.
    #[test]
    fn b1c_is_transmitted_by_bds3_meo_and_igso_only() {
        let start = Epoch::from_gregorian(2023, 3, 12, 0, 0, 0, 0, TimeScale::GPST);
        let bds3 = nominal::beidou(BeidouSet::Bds3, start);
        let b1c = bds_b1c(&bds3, start).expect("BDS-3 transmitters");
        let b2a = bds_b2a(&bds3, start).expect("BDS-3 transmitters");
        assert_eq!(
            b1c.iter().map(|t| t.sat).collect::<Vec<_>>(),
            b2a.iter().map(|t| t.sat).collect::<Vec<_>>()
        );
        assert!(b1c.iter().all(|t| t.signal == Signal::BdsB1C));
        let err = bds_b1c(&nominal::beidou(BeidouSet::Bds2, start), start).expect_err("refused");
        assert!(
            matches!(err, TransmitterError::NoBds3(Signal::BdsB1C, 15)),
            "{err}"
        );
    }
}
