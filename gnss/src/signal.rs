//! The GNSS signals SkyForge transmits and receives, one identifier through truth, samples
//! and observables: carrier, ranging code, chip rate, data modulation per PRN, and the
//! names users and files give them.

use crate::codes::bds_b1c;
use crate::codes::bds_b1i;
use crate::codes::bds_b2a;
use crate::codes::galileo_e1;
use crate::codes::galileo_e5a;
use crate::codes::gps_ca;
use crate::codes::gps_l5;
use skyforge_orbits::constants::{
    F_BDS_B1I_HZ, F_BDS_B2I_HZ, F_BDS_B3I_HZ, F_GAL_E1_HZ, F_GAL_E5A_HZ, F_GPS_L1_HZ, F_GPS_L2_HZ,
    F_GPS_L5_HZ,
};
use skyforge_orbits::ephemeris::{BroadcastEphemeris, NavMessage};
use std::str::FromStr;

/// A GNSS signal.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Signal {
    /// GPS L1 C/A: 1023 chips at 1.023 Mchip/s on 1575.42 MHz (IS-GPS-200 §3.3).
    GpsL1Ca,
    /// BeiDou B1I: 2046 chips at 2.046 Mchip/s on 1561.098 MHz (BDS-SIS-ICD-B1I-3.0 §4).
    BdsB1I,
    /// GPS L2 on 1227.60 MHz, as real geodetic receivers record it (phase `L2`, P(Y) code
    /// `P2` tracked semi-codelessly or L2C code `C2`): observed only. SkyForge neither
    /// synthesises nor receives it ([`Signal::RECEIVED`]); it is read from other
    /// receivers' RINEX files and used by the relative-positioning chain.
    GpsL2,
    /// GPS L5 on 1176.45 MHz, 10230 chips at 10.23 Mchip/s (IS-GPS-705 §3.3): I5 with
    /// CNAV and Q5 pilot, transmitted when a scenario chooses it
    /// ([`Signal::TRANSMITTED`]) and received by the bundled receiver.
    GpsL5,
    /// BeiDou B2I on 1207.14 MHz, 2046 chips at 2.046 Mchip/s (BDS-SIS-ICD-B2I-1.0 §4):
    /// observed only.
    BdsB2I,
    /// BeiDou B3I on 1268.52 MHz, 10230 chips at 10.23 Mchip/s (BDS-SIS-ICD-B3I-1.0 §4):
    /// observed only.
    BdsB3I,
    /// Galileo E1 (E1-B data with I/NAV, E1-C pilot with CS25, in phase) on 1575.42 MHz,
    /// 4092 chips at 1.023 Mchip/s, CBOC(6,1,1/11) (Galileo OS SIS ICD §2.3, §3.4):
    /// transmitted when a scenario chooses it ([`Signal::TRANSMITTED`]) and received by the
    /// bundled receiver (on its BOC(1,1) part, [`Signal::replica_boc11`]).
    GalE1,
    /// Galileo E5a (E5a-I data with F/NAV, E5a-Q pilot) on 1176.45 MHz, 10230 chips at
    /// 10.23 Mchip/s (Galileo OS SIS ICD §2.3, §3.4): Galileo's transmitted signal
    /// ([`Signal::TRANSMITTED`]) and received by the bundled receiver.
    GalE5a,
    /// BeiDou B2a (B2a_d data with B-CNAV2, B2a_p pilot) on 1176.45 MHz, 10230 chips at
    /// 10.23 Mchip/s, QPSK(10) (BDS-SIS-ICD-B2a-1.0 §4, §5): broadcast by the BDS-3 MEO
    /// and IGSO satellites, transmitted when a scenario chooses it
    /// ([`Signal::TRANSMITTED`]) and received by the bundled receiver.
    BdsB2a,
    /// BeiDou B1C (B1C_data with B-CNAV1, BOC(1,1), 1/4 of the power; B1C_pilot with the
    /// 1800-chip secondary code, QMBOC(6,1,4/33), 3/4) on 1575.42 MHz, 10230 chips at
    /// 1.023 Mchip/s (BDS-SIS-ICD-B1C-1.0 §4, §5): broadcast by the BDS-3 MEO and IGSO
    /// satellites, transmitted when a scenario chooses it ([`Signal::TRANSMITTED`]) and
    /// received by the bundled receiver (on the pilot's BOC(1,1) part).
    BdsB1C,
}

/// How navigation data (and any secondary code) modulate the ranging code.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum DataModulation {
    /// GPS LNAV: 50 bit/s, bit edges on code epochs, 20 code periods per bit
    /// (IS-GPS-200 §3.3.2.4).
    GpsLnav,
    /// BeiDou D1 (MEO/IGSO): 50 bit/s, each bit spread by the 20-chip Neumann-Hoffman code
    /// (BDS-SIS-ICD-B1I-3.0 §5.2.1).
    BdsD1,
    /// BeiDou D2 (GEO, PRN 1-5 and 59-63): 500 bit/s, 2 code periods per bit, no secondary
    /// code (BDS-SIS-ICD-B1I-3.0 §5.3).
    BdsD2,
    /// GPS L5 I5: CNAV at 100 symbol/s, each symbol spread by the 10-chip Neuman-Hofman
    /// code; the Q5 pilot carries the 20-chip one (IS-GPS-705 §3.3.2.2, §3.3.3.1).
    GpsCnav,
    /// Galileo E5a-I: F/NAV at 50 symbol/s, each symbol spread by the 20-chip secondary
    /// code CS20; the E5a-Q pilot carries the satellite's 100-chip CS100 (Galileo OS SIS ICD
    /// §3.4.2, Table 19).
    GalFnav,
    /// Galileo E1-B: I/NAV at 250 symbol/s, one symbol per 4 ms code period, no secondary
    /// code; the E1-C pilot carries CS25 (Galileo OS SIS ICD §2.3.3, §3.4.2).
    GalInav,
    /// BeiDou B2a_d: B-CNAV2 at 200 symbol/s, 5 primary periods per symbol, each symbol
    /// spread by the 5-chip secondary code 00010; the B2a_p pilot carries the satellite's
    /// 100-chip Weil secondary code (BDS-SIS-ICD-B2a-1.0 §5.2.2, §6.2.1).
    BdsCnav2,
    /// BeiDou B1C_data: B-CNAV1 at 100 symbol/s, one symbol per 10 ms primary period, no
    /// secondary code on the data; the pilot carries the satellite's 1800-chip secondary
    /// code, one 18 s frame long (BDS-SIS-ICD-B1C-1.0 §5.2.2, §6.2.1).
    BdsCnav1,
}

impl DataModulation {
    /// Code periods per data bit.
    pub fn periods_per_bit(self) -> u32 {
        match self {
            DataModulation::GpsLnav | DataModulation::BdsD1 | DataModulation::GalFnav => 20,
            DataModulation::GpsCnav => 10,
            DataModulation::BdsCnav2 => 5,
            DataModulation::BdsD2 => 2,
            DataModulation::GalInav | DataModulation::BdsCnav1 => 1,
        }
    }

    /// Whether every message frame starts with the pilot's secondary code, which lasts one
    /// frame: B-CNAV1's 18 s frames and B1C's 1800-chip code (BDS-SIS-ICD-B1C-1.0 §5.2.2,
    /// §6.2.1), so a receiver that found the code's start knows the frame's.
    pub fn frame_is_pilot_secondary(self) -> bool {
        self == DataModulation::BdsCnav1
    }

    /// The secondary code on the data component, one chip per code period, restarting
    /// with every bit or symbol; `None` where there is none.
    pub fn data_secondary_code(self) -> Option<&'static [i8]> {
        match self {
            DataModulation::BdsD1 => Some(&crate::codes::neumann_hoffman::NH20),
            DataModulation::GpsCnav => Some(&gps_l5::GPS_L5_I_NH10),
            DataModulation::GalFnav => Some(&galileo_e5a::GALILEO_E5A_I_SECONDARY),
            DataModulation::BdsCnav2 => Some(&bds_b2a::BDS_B2A_DATA_SECONDARY),
            DataModulation::GpsLnav
            | DataModulation::BdsD2
            | DataModulation::GalInav
            | DataModulation::BdsCnav1 => None,
        }
    }
}

/// A pilot component's codes ([`Signal::pilot`]), as signal levels (+1/-1).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct PilotCodes {
    /// One period of the primary code, chip 0 first.
    pub primary: Vec<i8>,
    /// The secondary code, one chip per primary period.
    pub secondary: Vec<i8>,
}

/// A PRN without a ranging code for the signal.
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
#[error("PRN {prn} has no {signal} ranging code (allowed: 1..={max})")]
pub struct UnknownPrn {
    pub signal: Signal,
    pub prn: u8,
    pub max: u8,
}

/// A signal name that is not one of [`Signal::ALL`]'s tags.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error(
    "unknown signal {0:?}: allowed gps-l1ca, bds-b1i, gps-l2, gps-l5, bds-b2i, bds-b3i, gal-e1, gal-e5a, bds-b2a, bds-b1c"
)]
pub struct UnknownSignal(pub String);

/// P-code chipping rate (chip/s), 10.23 MHz (IS-GPS-200 §3.3.1.1).
const P_CODE_CHIP_RATE_HZ: f64 = 10.23e6;
/// P-code chips in its one-week period (IS-GPS-200 §3.3.2.2).
const P_CODE_WEEK_CHIPS: usize = 10_230_000 * 604_800;
/// Chips of the 1 ms codes at 10.23 Mchip/s: GPS L5 (IS-GPS-705 §3.2.1.1), BeiDou B3I
/// (BDS-SIS-ICD-B3I-1.0 §4.3.2).
const CODE_10230: usize = 10_230;
/// Galileo E1-B/C primary code: 4092 chips at 1.023 Mchip/s, 4 ms (Galileo OS SIS ICD §3.4,
/// Table 18).
const GAL_E1_CODE_LENGTH: usize = 4092;
/// Galileo E1 chip rate (chip/s), Galileo OS SIS ICD Table 18.
const GAL_E1_CHIP_RATE_HZ: f64 = 1.023e6;

/// BeiDou B2a carrier frequency (Hz): 1150 x 1.023 MHz (BDS-SIS-ICD-B2a-1.0 §4.1).
const F_BDS_B2A_HZ: f64 = 1_176.45e6;
/// BeiDou B1C carrier frequency (Hz): 1540 x 1.023 MHz (BDS-SIS-ICD-B1C-1.0 §4.1), GPS
/// L1's and Galileo E1's.
const F_BDS_B1C_HZ: f64 = 1_575.42e6;
/// The BOC(6,1) sub-carrier rate of Galileo E1's CBOC and BeiDou B1C's QMBOC, in chips
/// of 1.023 Mchip/s (Galileo OS SIS ICD §2.3.3, BDS-SIS-ICD-B1C-1.0 §4.2.2).
const BOC61_RATE_CHIPS: f64 = 6.0;

/// Largest difference (Hz) between a recording's stated carrier (centre + IF) and a
/// signal's nominal carrier for the two to be taken as the same.
pub const CARRIER_MATCH_TOLERANCE_HZ: f64 = 1e3;

impl Signal {
    /// Every signal: those SkyForge synthesises and tracks, and those it only reads from
    /// other receivers' observation files.
    pub const ALL: [Signal; 10] = [
        Signal::GpsL1Ca,
        Signal::BdsB1I,
        Signal::GpsL2,
        Signal::GpsL5,
        Signal::BdsB2I,
        Signal::BdsB3I,
        Signal::GalE1,
        Signal::GalE5a,
        Signal::BdsB2a,
        Signal::BdsB1C,
    ];

    /// Each constellation's legacy civil signal, what single-frequency fixes and the
    /// observation level use unless a scenario or configuration says otherwise.
    pub const DEFAULT_FIX: [Signal; 2] = [Signal::GpsL1Ca, Signal::BdsB1I];

    /// Whether the signal is one of [`Signal::DEFAULT_FIX`].
    pub fn is_default_fix(self) -> bool {
        Self::DEFAULT_FIX.contains(&self)
    }

    /// The signals the bundled receiver acquires, tracks and decodes from samples: the
    /// legacy ones and the pilot signals GPS L5, Galileo E5a and E1, and BeiDou B2a and B1C
    /// (tracked on the pilot, the message read from the data component).
    pub const RECEIVED: [Signal; 7] = [
        Signal::GpsL1Ca,
        Signal::BdsB1I,
        Signal::GpsL5,
        Signal::GalE5a,
        Signal::GalE1,
        Signal::BdsB2a,
        Signal::BdsB1C,
    ];

    /// Whether the bundled receiver takes recordings of the signal ([`Signal::RECEIVED`]).
    pub fn is_received(self) -> bool {
        Self::RECEIVED.contains(&self)
    }

    /// The signals SkyForge can transmit at the sample level, those the bundled receiver
    /// takes ([`Signal::RECEIVED`]). A scenario's `[signal] signals` chooses among them.
    pub const TRANSMITTED: [Signal; 7] = [
        Signal::GpsL1Ca,
        Signal::BdsB1I,
        Signal::GalE5a,
        Signal::GpsL5,
        Signal::GalE1,
        Signal::BdsB2a,
        Signal::BdsB1C,
    ];

    /// Whether SkyForge can transmit the signal ([`Signal::TRANSMITTED`]).
    pub fn is_transmitted(self) -> bool {
        Self::TRANSMITTED.contains(&self)
    }

    /// The group delay (s) the navigation message `eph` broadcasts for this signal: the
    /// signal's own clock is the broadcast polynomial minus it.
    /// - GPS L1 C/A: TGD (IS-GPS-200 20.3.3.3.3.2: (dt_SV)L1 = dt_SV - TGD).
    /// - GPS L5 I5: TGD - ISC_L5I5 (IS-GPS-705, the inter-signal corrections of message
    ///   type 30); SkyForge's CNAV broadcasts ISC_L5I5 = 0, so TGD.
    /// - BeiDou B1I: TGD1 (BDS-SIS-ICD-B1I-3.0 5.2.4.10).
    /// - Galileo E5a: (f_E1 / f_E5a)^2 BGD(E1,E5a) (Galileo OS SIS ICD §5.1.5), from F/NAV's
    ///   `tgd_s` or I/NAV's `tgd2_s`.
    /// - Galileo E1: `tgd_s`, I/NAV's BGD(E1,E5b) or F/NAV's BGD(E1,E5a).
    /// - BeiDou B2a (pilot): `tgd_s`, B-CNAV2's TGD_B2ap (BDS-SIS-ICD-B2a-1.0 §7.6:
    ///   the B2a pilot's clock is the B3I-referenced polynomial minus TGD_B2ap). SkyForge
    ///   keeps one BeiDou group delay per satellite, so its B-CNAV2 broadcasts the set's
    ///   `tgd_s` as TGD_B2ap and a D1 set read for B2a gives the same delay.
    /// - BeiDou B1C (pilot): `tgd_s`, B-CNAV1's TGD_B1Cp (BDS-SIS-ICD-B1C-1.0 §7.6.2: the
    ///   B1C pilot's clock is the B3I-referenced polynomial minus TGD_B1Cp; the data
    ///   component's also minus ISC_B1Cd, which SkyForge broadcasts as 0), likewise the
    ///   set's one group delay.
    ///
    /// 0 for a signal of another system than `eph`'s, and for the observed-only signals.
    pub fn broadcast_group_delay_s(self, eph: &BroadcastEphemeris) -> f64 {
        if eph.sat.system != self.system() {
            return 0.0;
        }
        let c = &eph.clock;
        match self {
            // Galileo E1: BGD(E1,E5b) of an I/NAV ephemeris, BGD(E1,E5a) of an F/NAV one,
            // each the E1 user's delay against its message's clock (Galileo OS SIS ICD §5.1.5).
            Signal::GpsL1Ca
            | Signal::GpsL5
            | Signal::BdsB1I
            | Signal::GalE1
            | Signal::BdsB2a
            | Signal::BdsB1C => c.tgd_s,
            Signal::GalE5a => {
                let bgd = match eph.message {
                    NavMessage::GalileoInav => c.tgd2_s,
                    _ => c.tgd_s,
                };
                (F_GAL_E1_HZ / F_GAL_E5A_HZ).powi(2) * bgd
            }
            Signal::GpsL2 | Signal::BdsB2I | Signal::BdsB3I => 0.0,
        }
    }

    /// Whether the signal has a dataless pilot component beside its data component (GPS
    /// L5's Q5, Galileo E1-C and E5a-Q, BeiDou B2a_p and B1C_pilot).
    pub fn has_pilot(self) -> bool {
        matches!(
            self,
            Signal::GpsL5 | Signal::GalE1 | Signal::GalE5a | Signal::BdsB2a | Signal::BdsB1C
        )
    }

    /// Whether the pilot is in quadrature with the data component, 90 degrees ahead of it
    /// (L5's Q5, IS-GPS-705 §3.3.1.1; E5a-Q, Galileo OS SIS ICD §2.3.3; B2a's pilot,
    /// BDS-SIS-ICD-B2a Table 4-1; B1C's pilot BOC(1,1) part, the one a receiver tracks,
    /// BDS-SIS-ICD-B1C-1.0 §4.2.2: `s = s_data + j s_pilot`); Galileo E1's
    /// E1-C is in phase with E1-B, with the opposite sign: `e_B - e_C` (ICD §2.3.3, as
    /// `subcarrier::e1_cboc` sums them).
    pub fn pilot_in_quadrature(self) -> bool {
        matches!(
            self,
            Signal::GpsL5 | Signal::GalE5a | Signal::BdsB2a | Signal::BdsB1C
        )
    }

    /// Whether a receiver correlates with a BOC(1,1) replica: each chip as its two
    /// half-chips `+c, -c` (Galileo E1's CBOC(6,1,1/11) without the BOC(6,1) part, which
    /// carries 1/11 of the power: 0.41 dB lost, Galileo OS SIS ICD §2.3.3), and BeiDou
    /// B1C, whose data component is BOC(1,1) and whose pilot's BOC(1,1) part carries 29/33
    /// of the pilot's power (the BOC(6,1) part 4/33, BDS-SIS-ICD-B1C-1.0 §4.2.2).
    pub fn replica_boc11(self) -> bool {
        matches!(self, Signal::GalE1 | Signal::BdsB1C)
    }

    /// Whether a recording's carrier (or band) alone names the signal: not for Galileo E1
    /// and BeiDou B1C, whose carrier is GPS L1's (a recording at 1575.42 MHz is L1 C/A
    /// unless its file name or the command line says `gal-e1` or `bds-b1c`).
    fn named_by_carrier(self) -> bool {
        !matches!(self, Signal::GalE1 | Signal::BdsB1C)
    }

    /// Name for people, as in SigMF descriptions and messages: `GPS L1 C/A`, `BDS B1I`.
    pub fn name(self) -> &'static str {
        match self {
            Signal::GpsL1Ca => "GPS L1 C/A",
            Signal::BdsB1I => "BDS B1I",
            Signal::GpsL2 => "GPS L2",
            Signal::GpsL5 => "GPS L5",
            Signal::BdsB2I => "BDS B2I",
            Signal::BdsB3I => "BDS B3I",
            Signal::GalE1 => "GAL E1",
            Signal::GalE5a => "GAL E5a",
            Signal::BdsB2a => "BDS B2a",
            Signal::BdsB1C => "BDS B1C",
        }
    }

    /// The system's first signal, the one a scenario transmits unless `[signal] signals`
    /// says otherwise: GPS L1 C/A, BeiDou B1I, Galileo E5a (whose codes SkyForge
    /// generates; E1's memory codes it does not ship, docs/signals.md).
    pub fn of_system(system: skyforge_orbits::ephemeris::System) -> Self {
        match system {
            skyforge_orbits::ephemeris::System::Gps => Self::GpsL1Ca,
            skyforge_orbits::ephemeris::System::Beidou => Self::BdsB1I,
            skyforge_orbits::ephemeris::System::Galileo => Self::GalE5a,
        }
    }

    /// The constellation that transmits the signal.
    pub fn system(self) -> skyforge_orbits::ephemeris::System {
        match self {
            Self::GpsL1Ca | Self::GpsL2 | Self::GpsL5 => skyforge_orbits::ephemeris::System::Gps,
            Self::BdsB1I | Self::BdsB2I | Self::BdsB3I | Self::BdsB2a | Self::BdsB1C => {
                skyforge_orbits::ephemeris::System::Beidou
            }
            Self::GalE1 | Self::GalE5a => skyforge_orbits::ephemeris::System::Galileo,
        }
    }

    /// Command-line and file-name tag (`gps-l1ca`, `bds-b1i`), as in SkyForge's
    /// `<antenna>.<tag>.sigmf-meta` file names.
    pub fn tag(self) -> &'static str {
        match self {
            Signal::GpsL1Ca => "gps-l1ca",
            Signal::BdsB1I => "bds-b1i",
            Signal::GpsL2 => "gps-l2",
            Signal::GpsL5 => "gps-l5",
            Signal::BdsB2I => "bds-b2i",
            Signal::BdsB3I => "bds-b3i",
            Signal::GalE1 => "gal-e1",
            Signal::GalE5a => "gal-e5a",
            Signal::BdsB2a => "bds-b2a",
            Signal::BdsB1C => "bds-b1c",
        }
    }

    /// Nominal carrier frequency (Hz): IS-GPS-200 §3.3.1.1 (L1 = 154 x 10.23 MHz,
    /// L2 = 120 x 10.23 MHz), IS-GPS-705 (L5 = 115 x 10.23 MHz); the BeiDou ICDs
    /// (B1I 1561.098, B2I 1207.14, B3I 1268.52 MHz), the Galileo OS SIS ICD (E1 = 154 x
    /// 10.23 MHz, E5a = 115 x 10.23 MHz), BDS-SIS-ICD-B2a-1.0 §4.2 (B2a 1176.45 MHz),
    /// BDS-SIS-ICD-B1C-1.0 §4.1 (B1C 1575.42 MHz).
    pub fn carrier_hz(self) -> f64 {
        match self {
            Signal::GpsL1Ca => F_GPS_L1_HZ,
            Signal::BdsB1I => F_BDS_B1I_HZ,
            Signal::GpsL2 => F_GPS_L2_HZ,
            Signal::GpsL5 => F_GPS_L5_HZ,
            Signal::BdsB2I => F_BDS_B2I_HZ,
            Signal::BdsB3I => F_BDS_B3I_HZ,
            Signal::GalE1 => F_GAL_E1_HZ,
            Signal::GalE5a => F_GAL_E5A_HZ,
            Signal::BdsB2a => F_BDS_B2A_HZ,
            Signal::BdsB1C => F_BDS_B1C_HZ,
        }
    }

    /// Nominal carrier wavelength (m): c / carrier.
    pub fn wavelength_m(self) -> f64 {
        skyforge_orbits::constants::C_MPS / self.carrier_hz()
    }

    /// Chipping rate (chip/s); for GPS L2 that of the P(Y) code a geodetic receiver's `P2`
    /// measures, 10.23 Mchip/s (IS-GPS-200 §3.3.1.1).
    pub fn chip_rate_hz(self) -> f64 {
        match self {
            Signal::GpsL1Ca => gps_ca::GPS_CA_CHIP_RATE_HZ,
            Signal::GpsL2 | Signal::GpsL5 | Signal::BdsB3I => P_CODE_CHIP_RATE_HZ,
            Signal::BdsB1I | Signal::BdsB2I => bds_b1i::BDS_B1I_CHIP_RATE_HZ,
            Signal::GalE1 => GAL_E1_CHIP_RATE_HZ,
            Signal::GalE5a => galileo_e5a::GALILEO_E5A_CHIP_RATE_HZ,
            Signal::BdsB2a => bds_b2a::BDS_B2A_CHIP_RATE_HZ,
            Signal::BdsB1C => bds_b1c::BDS_B1C_CHIP_RATE_HZ,
        }
    }

    /// The outermost null of the signal's main lobes about its carrier (Hz), what a
    /// recording must hold: the chip rate for BPSK; for Galileo E1's CBOC(6,1,1/11) the
    /// BOC(6,1) lobe's, 6.138 + 1.023 MHz (Galileo OS SIS ICD §2.3.3; that lobe carries
    /// 1/11 of the power), and likewise for BeiDou B1C's QMBOC(6,1,4/33), whose pilot's
    /// BOC(6,1) part also carries 1/11 of the signal's power (BDS-SIS-ICD-B1C-1.0 §4.2.2).
    pub fn main_lobe_half_width_hz(self) -> f64 {
        match self {
            Signal::GalE1 | Signal::BdsB1C => (BOC61_RATE_CHIPS + 1.0) * self.chip_rate_hz(),
            _ => self.chip_rate_hz(),
        }
    }

    /// Chips per code period; for GPS L2 the P code's week (IS-GPS-200 §3.3.2.2).
    pub fn code_length(self) -> usize {
        match self {
            Signal::GpsL1Ca => gps_ca::GPS_CA_CODE_LENGTH,
            Signal::GpsL2 => P_CODE_WEEK_CHIPS,
            Signal::BdsB1I | Signal::BdsB2I => bds_b1i::BDS_B1I_CODE_LENGTH,
            Signal::GpsL5 | Signal::BdsB3I => CODE_10230,
            Signal::GalE1 => GAL_E1_CODE_LENGTH,
            Signal::GalE5a => galileo_e5a::GALILEO_E5A_CODE_LENGTH,
            Signal::BdsB2a => bds_b2a::BDS_B2A_CODE_LENGTH,
            Signal::BdsB1C => bds_b1c::BDS_B1C_CODE_LENGTH,
        }
    }

    /// Code period (s): 1 ms for the synthesised signals, 4 ms for Galileo E1, 10 ms for
    /// BeiDou B1C (a week for the P code of L2).
    pub fn code_period_s(self) -> f64 {
        self.code_length() as f64 / self.chip_rate_hz()
    }

    /// One code period of `prn` as signal levels (+1/-1), chip 0 first; an error for a
    /// signal SkyForge does not synthesise (no PRN has a code SkyForge generates).
    pub fn code(self, prn: u8) -> Result<Vec<i8>, UnknownPrn> {
        let (code, max) = match self {
            Signal::GpsL1Ca => (gps_ca::gps_ca(prn).map(Vec::from), gps_ca::GPS_CA_PRN_MAX),
            Signal::BdsB1I => (bds_b1i::bds_b1i(prn), bds_b1i::BDS_B1I_PRN_MAX),
            Signal::GpsL5 => (gps_l5::gps_l5_i(prn), gps_l5::GPS_L5_PRN_MAX),
            Signal::GalE5a => (
                galileo_e5a::galileo_e5a_i(prn),
                galileo_e5a::GALILEO_E5A_PRN_MAX,
            ),
            Signal::GalE1 => (galileo_e1::galileo_e1b(prn), galileo_e1::GALILEO_E1_PRN_MAX),
            Signal::BdsB2a => (bds_b2a::bds_b2a_data(prn), bds_b2a::BDS_B2A_PRN_MAX),
            Signal::BdsB1C => (bds_b1c::bds_b1c_data(prn), bds_b1c::BDS_B1C_PRN_MAX),
            Signal::GpsL2 | Signal::BdsB2I | Signal::BdsB3I => (None, 0),
        };
        code.ok_or(UnknownPrn {
            signal: self,
            prn,
            max,
        })
    }

    /// The pilot of `prn` ([`Signal::has_pilot`]): one period of its primary code and its
    /// secondary code (one chip per primary period, restarting every secondary period),
    /// as signal levels; an error for a signal without a pilot SkyForge generates.
    pub fn pilot(self, prn: u8) -> Result<PilotCodes, UnknownPrn> {
        let (codes, max) = match self {
            Signal::GpsL5 => (
                gps_l5::gps_l5_q(prn).map(|primary| PilotCodes {
                    primary,
                    secondary: gps_l5::GPS_L5_Q_NH20.to_vec(),
                }),
                gps_l5::GPS_L5_PRN_MAX,
            ),
            Signal::GalE5a => (
                galileo_e5a::galileo_e5a_q(prn)
                    .zip(galileo_e5a::galileo_e5a_q_secondary(prn))
                    .map(|(primary, secondary)| PilotCodes { primary, secondary }),
                galileo_e5a::GALILEO_E5A_PRN_MAX,
            ),
            Signal::GalE1 => (
                galileo_e1::galileo_e1c(prn).map(|primary| PilotCodes {
                    primary,
                    secondary: galileo_e1::GALILEO_E1_C_SECONDARY.to_vec(),
                }),
                galileo_e1::GALILEO_E1_PRN_MAX,
            ),
            Signal::BdsB2a => (
                bds_b2a::bds_b2a_pilot(prn)
                    .zip(bds_b2a::bds_b2a_pilot_secondary(prn))
                    .map(|(primary, secondary)| PilotCodes { primary, secondary }),
                bds_b2a::BDS_B2A_PRN_MAX,
            ),
            Signal::BdsB1C => (
                bds_b1c::bds_b1c_pilot(prn)
                    .zip(bds_b1c::bds_b1c_pilot_secondary(prn))
                    .map(|(primary, secondary)| PilotCodes { primary, secondary }),
                bds_b1c::BDS_B1C_PRN_MAX,
            ),
            _ => (None, 0),
        };
        codes.ok_or(UnknownPrn {
            signal: self,
            prn,
            max,
        })
    }

    /// The data modulation of `prn`: BeiDou GEO satellites (PRN 1-5 and 59-63) broadcast
    /// D2, the others D1, on B1I, B2I and B3I alike (BDS-SIS-ICD-B1I-3.0 §5.1); L1 C/A and
    /// L2 P(Y) carry LNAV, L5 CNAV, E5a F/NAV, E1 I/NAV, B2a B-CNAV2 and B1C B-CNAV1 (which
    /// only the BDS-3 MEO and IGSO satellites broadcast, BDS-SIS-ICD-B2a-1.0 §1,
    /// BDS-SIS-ICD-B1C-1.0 §1).
    pub fn data_modulation(self, prn: u8) -> Option<DataModulation> {
        match self {
            Signal::GpsL1Ca | Signal::GpsL2 => Some(DataModulation::GpsLnav),
            Signal::GpsL5 => Some(DataModulation::GpsCnav),
            Signal::GalE5a => Some(DataModulation::GalFnav),
            Signal::GalE1 => Some(DataModulation::GalInav),
            Signal::BdsB2a => Some(DataModulation::BdsCnav2),
            Signal::BdsB1C => Some(DataModulation::BdsCnav1),
            Signal::BdsB1I | Signal::BdsB2I | Signal::BdsB3I if prn <= 5 || prn >= 59 => {
                Some(DataModulation::BdsD2)
            }
            Signal::BdsB1I | Signal::BdsB2I | Signal::BdsB3I => Some(DataModulation::BdsD1),
        }
    }

    /// The only received signal ([`Signal::RECEIVED`]) whose carrier is within
    /// [`CARRIER_MATCH_TOLERANCE_HZ`] of `carrier_hz` (a recording's signal); `None` when
    /// none or several are (GPS L5, Galileo E5a and BeiDou B2a share 1176.45 MHz). Galileo E1
    /// and BeiDou B1C are never named by their carrier, GPS L1 C/A's.
    pub fn from_carrier_hz(carrier_hz: f64) -> Option<Self> {
        only(Self::RECEIVED.into_iter().filter(|s| {
            s.named_by_carrier()
                && (s.carrier_hz() - carrier_hz).abs() <= CARRIER_MATCH_TOLERANCE_HZ
        }))
    }

    /// The only received signal whose carrier lies inside the band recorded about
    /// `centre_hz` (complex: `|carrier - centre| < fs / 2`), or `None` when none or several
    /// do (Galileo E1 and BeiDou B1C aside, as for [`Signal::from_carrier_hz`]).
    pub fn in_band(centre_hz: f64, sample_rate_hz: f64) -> Option<Self> {
        only(Self::RECEIVED.into_iter().filter(|s| {
            s.named_by_carrier() && (s.carrier_hz() - centre_hz).abs() < sample_rate_hz / 2.0
        }))
    }

    /// The received signal named by a `.<tag>` component of a recording's file name
    /// (`ant1.gps-l1ca.sigmf-meta`).
    pub fn from_file_name(name: &str) -> Option<Self> {
        Self::named_in(name, Self::RECEIVED)
    }

    /// Any signal of [`Signal::ALL`] named by a `.<tag>` component of `name`, received or
    /// not (to say which signal a recording holds that the receiver cannot take).
    pub fn any_from_file_name(name: &str) -> Option<Self> {
        Self::named_in(name, Self::ALL)
    }

    /// The first of `signals` whose tag is a `.`-separated component of `name`.
    fn named_in(name: &str, signals: impl IntoIterator<Item = Self>) -> Option<Self> {
        signals
            .into_iter()
            .find(|s| name.split('.').any(|part| part == s.tag()))
    }
}

/// The only item of `items`, `None` for none or several.
fn only(mut items: impl Iterator<Item = Signal>) -> Option<Signal> {
    match (items.next(), items.next()) {
        (Some(s), None) => Some(s),
        _ => None,
    }
}

impl std::fmt::Display for Signal {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// A signal in a configuration file is its tag (`"gps-l1ca"`, any case).
impl<'de> serde::Deserialize<'de> for Signal {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let name = String::deserialize(d)?;
        name.parse().map_err(serde::de::Error::custom)
    }
}

impl FromStr for Signal {
    type Err = UnknownSignal;
    /// A command-line `--signal` value (the tag, any case).
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Self::ALL
            .into_iter()
            .find(|b| b.tag().eq_ignore_ascii_case(s.trim()))
            .ok_or_else(|| UnknownSignal(s.to_owned()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn codes_carriers_and_periods_follow_the_icds() {
        assert_eq!(Signal::GpsL1Ca.code(1).unwrap().len(), 1023);
        assert_eq!(Signal::BdsB1I.code(1).unwrap().len(), 2046);
        for s in Signal::DEFAULT_FIX {
            assert!((s.code_period_s() - 1e-3).abs() < 1e-15);
        }
        assert!(Signal::GpsL2.code(1).is_err());
        assert_eq!(Signal::GpsL1Ca.code(0).unwrap_err().prn, 0);
        assert!(Signal::BdsB1I.code(64).is_err());
        // GPS: 154 f0 with f0 = 10.23 MHz; BeiDou B1I: 1526 x 1.023 MHz.
        assert_eq!(Signal::GpsL1Ca.carrier_hz(), 154.0 * 10.23e6);
        assert!((Signal::BdsB1I.carrier_hz() - 1526.0 * 1.023e6).abs() < 1e-3);
    }

    #[test]
    fn geo_prns_carry_d2() {
        for prn in [1, 5, 59, 63] {
            assert_eq!(
                Signal::BdsB1I.data_modulation(prn),
                Some(DataModulation::BdsD2)
            );
        }
        for prn in [6, 19, 58] {
            assert_eq!(
                Signal::BdsB1I.data_modulation(prn),
                Some(DataModulation::BdsD1)
            );
        }
        assert_eq!(DataModulation::BdsD2.periods_per_bit(), 2);
    }

    #[test]
    fn identified_by_carrier_band_file_name_and_tag() {
        assert_eq!(
            Signal::from_carrier_hz(1575.42e6 - 400.0),
            Some(Signal::GpsL1Ca)
        );
        assert_eq!(Signal::from_carrier_hz(1575.0e6), None);
        assert_eq!(
            Signal::in_band(1561.098e6 - 1.0e6, 4e6),
            Some(Signal::BdsB1I)
        );
        assert_eq!(Signal::in_band(1568.0e6, 40e6), None);
        assert_eq!(
            Signal::from_file_name("ant2.bds-b1i.sigmf-meta"),
            Some(Signal::BdsB1I)
        );
        assert_eq!(Signal::from_file_name("ant2.sigmf-meta"), None);
        assert_eq!("GPS-L1CA".parse::<Signal>(), Ok(Signal::GpsL1Ca));
        assert!("l5".parse::<Signal>().is_err());
        assert_eq!("gps-l5".parse::<Signal>(), Ok(Signal::GpsL5));
        assert_eq!("BDS-B3I".parse::<Signal>(), Ok(Signal::BdsB3I));
        assert_eq!("gps-l2".parse::<Signal>(), Ok(Signal::GpsL2));
    }

    /// The observed-only signals' carriers, wavelengths and codes: the ICDs' multiples of
    /// 10.23 and 1.023 MHz; none has a code SkyForge generates.
    #[test]
    fn observed_only_signals_follow_the_icds() {
        assert_eq!(Signal::GpsL5.carrier_hz(), 115.0 * 10.23e6);
        assert!((Signal::BdsB2I.carrier_hz() - 1180.0 * 1.023e6).abs() < 1e-3);
        assert!((Signal::BdsB3I.carrier_hz() - 1240.0 * 1.023e6).abs() < 1e-3);
        assert!((Signal::GpsL5.wavelength_m() - 0.254_828).abs() < 1e-6);
        for s in [Signal::GpsL5, Signal::BdsB2I, Signal::BdsB3I] {
            assert!(!s.is_default_fix());
            assert!((s.code_period_s() - 1e-3).abs() < 1e-15, "{s}");
            assert_eq!(Signal::from_carrier_hz(s.carrier_hz()), None);
        }
        for s in [Signal::BdsB2I, Signal::BdsB3I] {
            assert!(s.code(6).is_err() && !s.is_received());
        }
        assert_eq!(
            Signal::BdsB3I.system(),
            skyforge_orbits::ephemeris::System::Beidou
        );
        assert_eq!(
            Signal::GalE1.data_modulation(1),
            Some(DataModulation::GalInav)
        );
        assert_eq!(
            Signal::BdsB2I.data_modulation(3),
            Some(DataModulation::BdsD2)
        );
    }

    /// The pilot signals: data codes, pilot codes and secondary codes from the gnss code
    /// tables; L5 and E5a share a carrier, so only a file name tells them apart.
    #[test]
    fn pilot_signals_have_their_codes_and_share_a_carrier() {
        for s in [Signal::GpsL5, Signal::GalE5a, Signal::BdsB2a] {
            assert!(s.has_pilot() && s.is_received() && s.is_transmitted());
            assert_eq!(s.code(1).unwrap().len(), 10_230);
            let pilot = s.pilot(1).unwrap();
            assert_eq!(pilot.primary.len(), 10_230);
            assert_ne!(pilot.primary, s.code(1).unwrap());
            let m = s.data_modulation(1).unwrap();
            let data_secondary = m.data_secondary_code().unwrap();
            assert_eq!(data_secondary.len() as u32, m.periods_per_bit());
            assert_eq!(pilot.secondary.len() % data_secondary.len(), 0);
        }
        assert_eq!(Signal::GpsL5.pilot(1).unwrap().secondary.len(), 20);
        assert_eq!(Signal::GalE5a.pilot(1).unwrap().secondary.len(), 100);
        assert_ne!(
            Signal::GalE5a.pilot(1).unwrap().secondary,
            Signal::GalE5a.pilot(2).unwrap().secondary
        );
        assert!(Signal::GalE5a.pilot(51).is_err() && Signal::GpsL1Ca.pilot(1).is_err());
        assert_eq!(Signal::from_carrier_hz(1176.45e6), None);
        assert_eq!(Signal::in_band(1176.45e6, 20.46e6), None);
        assert_eq!(
            Signal::from_file_name("ant1.gal-e5a.sigmf-meta"),
            Some(Signal::GalE5a)
        );
        assert_eq!(DataModulation::GpsLnav.data_secondary_code(), None);
    }

    /// Galileo E1 is received, its pilot in phase, its replica BOC(1,1); its carrier is
    /// L1's, so a recording's carrier or band names L1 C/A and only its file name E1.
    #[test]
    fn galileo_e1_is_received_beside_l1_ca_on_one_carrier() {
        assert!(Signal::GalE1.is_received() && Signal::GalE1.has_pilot());
        assert!(!Signal::GalE1.pilot_in_quadrature() && Signal::GalE1.replica_boc11());
        for s in [Signal::GpsL5, Signal::GalE5a, Signal::BdsB2a] {
            assert!(s.pilot_in_quadrature() && !s.replica_boc11());
        }
        assert!(!Signal::GpsL1Ca.pilot_in_quadrature() && !Signal::GpsL1Ca.replica_boc11());
        assert_eq!(
            Signal::from_carrier_hz(Signal::GalE1.carrier_hz()),
            Some(Signal::GpsL1Ca)
        );
        assert_eq!(Signal::in_band(1575.42e6, 15e6), Some(Signal::GpsL1Ca));
        assert_eq!(
            Signal::from_file_name("ant1.gal-e1.sigmf-meta"),
            Some(Signal::GalE1)
        );
    }

    /// BeiDou B2a (BDS-SIS-ICD-B2a-1.0 §4, §5): 1176.45 MHz, 10230 chips in 1 ms, 200
    /// symbol/s B-CNAV2 with 00010 on the data, a 100-chip secondary code per PRN on the
    /// pilot, PRN 1-63; named and tagged as the other signals.
    #[test]
    fn bds_b2a_follows_the_icd() {
        let s = Signal::BdsB2a;
        assert_eq!(s.carrier_hz(), 115.0 * 10.23e6);
        assert!((s.code_period_s() - 1e-3).abs() < 1e-15);
        assert_eq!(s.system(), skyforge_orbits::ephemeris::System::Beidou);
        let m = s.data_modulation(19).unwrap();
        assert_eq!(m, DataModulation::BdsCnav2);
        assert_eq!(m.data_secondary_code(), Some(&[1i8, 1, 1, -1, 1][..]));
        assert_eq!(
            f64::from(m.periods_per_bit()) * s.code_period_s(),
            1.0 / 200.0
        );
        assert_eq!(s.pilot(19).unwrap().secondary.len(), 100);
        assert_ne!(
            s.pilot(19).unwrap().secondary,
            s.pilot(20).unwrap().secondary
        );
        assert!(s.code(64).is_err() && s.pilot(0).is_err());
        assert_eq!("BDS-B2A".parse::<Signal>(), Ok(s));
        assert_eq!((s.tag(), s.name()), ("bds-b2a", "BDS B2a"));
        assert_eq!(
            Signal::from_file_name("ant1.bds-b2a.sigmf-meta"),
            Some(Signal::BdsB2a)
        );
    }

    /// BeiDou B1C (BDS-SIS-ICD-B1C-1.0 §4, §5): 1575.42 MHz (L1's, so only a file name
    /// names it), 10230 chips in 10 ms, 100 symbol/s B-CNAV1 without a data secondary code,
    /// an 1800-chip (18 s) secondary code per PRN on the pilot, BOC(1,1) replicas on a
    /// pilot in quadrature, the QMBOC's BOC(6,1) lobe in the band, PRN 1-63.
    #[test]
    fn bds_b1c_follows_the_icd() {
        let s = Signal::BdsB1C;
        assert_eq!(s.carrier_hz(), 1540.0 * 1.023e6);
        assert!((s.code_period_s() - 10e-3).abs() < 1e-15);
        assert_eq!(s.system(), skyforge_orbits::ephemeris::System::Beidou);
        let m = s.data_modulation(30).unwrap();
        assert_eq!((m, m.periods_per_bit()), (DataModulation::BdsCnav1, 1));
        assert!(
            m.frame_is_pilot_secondary() && !DataModulation::BdsCnav2.frame_is_pilot_secondary()
        );
        assert_eq!(m.data_secondary_code(), None);
        let pilot = s.pilot(30).unwrap();
        assert_eq!((pilot.primary.len(), pilot.secondary.len()), (10_230, 1800));
        assert_ne!(pilot.primary, s.code(30).unwrap());
        assert!(s.has_pilot() && s.pilot_in_quadrature() && s.replica_boc11());
        assert!(s.is_received() && s.is_transmitted() && !s.is_default_fix());
        assert_eq!(s.main_lobe_half_width_hz(), 7.161e6);
        assert!(s.code(64).is_err() && s.pilot(0).is_err());
        assert_eq!(("BDS-B1C".parse::<Signal>(), s.name()), (Ok(s), "BDS B1C"));
        assert_eq!(Signal::from_carrier_hz(1575.42e6), Some(Signal::GpsL1Ca));
        assert_eq!(Signal::in_band(1575.42e6, 15e6), Some(Signal::GpsL1Ca));
        assert_eq!(
            Signal::from_file_name("ant1.bds-b1c.sigmf-meta"),
            Some(Signal::BdsB1C)
        );
    }

    /// L2 is read from files, never synthesised: no recording is identified as L2.
    #[test]
    fn gps_l2_is_observed_only() {
        assert!(!Signal::GpsL2.is_default_fix());
        assert!(Signal::DEFAULT_FIX.iter().all(|s| s.is_default_fix()));
        assert!(
            Signal::RECEIVED
                .iter()
                .all(|s| s.is_received() && s.is_transmitted())
        );
        assert_eq!(Signal::GpsL2.carrier_hz(), 120.0 * 10.23e6);
        assert!((Signal::GpsL2.wavelength_m() - 0.244_210).abs() < 1e-6);
        assert_eq!(
            Signal::GpsL2.system(),
            skyforge_orbits::ephemeris::System::Gps
        );
        assert_eq!(Signal::from_carrier_hz(1227.60e6), None);
        assert_eq!(Signal::in_band(1227.60e6, 4e6), None);
        assert_eq!(Signal::from_file_name("ant1.gps-l2.sigmf-meta"), None);
    }
    /// Each signal's group delay from its message's fields: GPS and BeiDou take TGD / TGD1
    /// as broadcast; Galileo E5a scales BGD(E1,E5a) by (1575.42 / 1176.45)^2 = 1.79327,
    /// from F/NAV's first group delay or I/NAV's second; another system's set gives 0.
    #[test]
    fn group_delays_follow_each_message() {
        use skyforge_orbits::ephemeris::nominal;
        let start = hifitime::Epoch::from_gregorian_utc_at_midnight(2023, 3, 12);
        let mut gps = nominal::gps(start).remove(0);
        gps.clock.tgd_s = -4.0e-9;
        assert_eq!(Signal::GpsL1Ca.broadcast_group_delay_s(&gps), -4.0e-9);
        assert_eq!(Signal::GpsL5.broadcast_group_delay_s(&gps), -4.0e-9);
        assert_eq!(Signal::BdsB1I.broadcast_group_delay_s(&gps), 0.0);
        let mut gal = nominal::galileo(start).remove(0);
        gal.clock.tgd_s = 2.0e-9;
        gal.clock.tgd2_s = 3.0e-9;
        let ratio = (154.0f64 / 115.0).powi(2);
        gal.message = NavMessage::GalileoFnav;
        let fnav = Signal::GalE5a.broadcast_group_delay_s(&gal);
        assert!((fnav - ratio * 2.0e-9).abs() < 1e-20, "{fnav}");
        gal.message = NavMessage::GalileoInav;
        let inav = Signal::GalE5a.broadcast_group_delay_s(&gal);
        assert!((inav - ratio * 3.0e-9).abs() < 1e-20, "{inav}");
        // E1: the I/NAV BGD(E1,E5b) in tgd_s.
        assert_eq!(Signal::GalE1.broadcast_group_delay_s(&gal), 2.0e-9);
        // B2a: TGD_B2ap in tgd_s; nothing for another system's set.
        let mut bds = nominal::beidou(skyforge_orbits::ephemeris::BeidouSet::Bds3, start).remove(0);
        bds.clock.tgd_s = -1.5e-9;
        assert_eq!(Signal::BdsB2a.broadcast_group_delay_s(&bds), -1.5e-9);
        // B1C: TGD_B1Cp in tgd_s.
        assert_eq!(Signal::BdsB1C.broadcast_group_delay_s(&bds), -1.5e-9);
        assert_eq!(Signal::BdsB1C.broadcast_group_delay_s(&gps), 0.0);
        assert_eq!(Signal::BdsB2a.broadcast_group_delay_s(&gal), 0.0);
    }
}
