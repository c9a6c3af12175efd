//! Physical and system constants (SI). Values from the cited ICDs and standards.

/// Speed of light in vacuum (m/s), IS-GPS-200 and BDS ICD.
pub const C_MPS: f64 = 299_792_458.0;
/// WGS-84 Earth gravitational constant used by GPS (m^3/s^2), IS-GPS-200 20.3.3.4.3.
pub const GM_GPS: f64 = 3.986_005e14;
/// CGCS2000 Earth gravitational constant used by BeiDou (m^3/s^2), BDS-SIS-ICD.
pub const GM_BDS: f64 = 3.986_004_418e14;
/// WGS-84 Earth rotation rate (rad/s), IS-GPS-200.
pub const OMEGA_E_GPS: f64 = 7.292_115_146_7e-5;
/// CGCS2000 Earth rotation rate (rad/s), BDS-SIS-ICD.
pub const OMEGA_E_BDS: f64 = 7.292_115e-5;
/// Earth gravitational constant of the Galileo user algorithm (m^3/s^2), Galileo OS SIS
/// ICD Issue 2.1 §5.1.1 (GTRF).
pub const GM_GAL: f64 = 3.986_004_418e14;
/// Earth rotation rate of the Galileo user algorithm (rad/s), Galileo OS SIS ICD §5.1.1.
pub const OMEGA_E_GAL: f64 = 7.292_115_146_7e-5;
/// WGS-84 semi-major axis (m).
pub const WGS84_A_M: f64 = 6_378_137.0;
/// WGS-84 flattening.
pub const WGS84_F: f64 = 1.0 / 298.257_223_563;
/// EGM-96 / EGM-2008 unnormalised zonal harmonic J2.
pub const J2: f64 = 1.082_626_683_55e-3;
/// GPS L1 carrier frequency (Hz).
pub const F_GPS_L1_HZ: f64 = 1_575.42e6;
/// GPS L2 carrier frequency (Hz): 120 x 10.23 MHz (IS-GPS-200 §3.3.1.1).
pub const F_GPS_L2_HZ: f64 = 1_227.60e6;
/// GPS L5 carrier frequency (Hz): 115 x 10.23 MHz (IS-GPS-705 §3.3.1.1).
pub const F_GPS_L5_HZ: f64 = 1_176.45e6;
/// Galileo E1 carrier frequency (Hz): 154 x 10.23 MHz (Galileo OS SIS ICD §2.3.1).
pub const F_GAL_E1_HZ: f64 = 1_575.42e6;
/// Galileo E5a carrier frequency (Hz): 115 x 10.23 MHz (Galileo OS SIS ICD §2.3.1).
pub const F_GAL_E5A_HZ: f64 = 1_176.45e6;
/// BeiDou B1I carrier frequency (Hz).
pub const F_BDS_B1I_HZ: f64 = 1_561.098e6;
/// BeiDou B2I carrier frequency (Hz): 1180 x 1.023 MHz (BDS-SIS-ICD-B2I-1.0 §4.2.1).
pub const F_BDS_B2I_HZ: f64 = 1_207.14e6;
/// BeiDou B3I carrier frequency (Hz): 1240 x 1.023 MHz (BDS-SIS-ICD-B3I-1.0 §4.2.1).
pub const F_BDS_B3I_HZ: f64 = 1_268.52e6;
