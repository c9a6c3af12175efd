//! Real LNAV values for tests: a GPS broadcast ephemeris, the ionosphere and UTC
//! parameters of a real navigation file's header, and a published parity matrix. Used by this module's tests and, through
//! the `test-support` feature, by other crates' tests (the receiver's LNAV decoder).

use super::{IonoParams, UtcParams};
use hifitime::{Epoch, TimeScale};
use skyforge_orbits::ephemeris::{
    BroadcastEphemeris, ClockParams, HarmonicCorrections, KeplerElements, OrbitClass, SatId,
};

/// GPS PRN 1 of brdc0010.22n (IGS broadcast file, 2022-01-01 00:00 GPST, week 2190,
/// toe = 518400 s), as printed there: real LNAV values.
pub fn real_prn1() -> BroadcastEphemeris {
    let toe = Epoch::from_gregorian(2022, 1, 1, 0, 0, 0, 0, TimeScale::GPST);
    let orbit = KeplerElements {
        sqrt_a: 0.515367499542e4,
        e: 0.112181392033e-1,
        i0: 0.986418769490,
        omega0: -0.103661124009e1,
        omega: 0.884087601569,
        m0: -0.624294238235,
        delta_n: 0.398838041777e-8,
        idot: -0.377872882780e-9,
        omega_dot: -0.813355308085e-8,
    };
    let harmonics = HarmonicCorrections {
        cuc: -0.736303627491e-5,
        cus: 0.469572842121e-5,
        crc: 0.29975e3,
        crs: -0.141125e3,
        cic: -0.316649675369e-7,
        cis: 0.195577740669e-6,
    };
    let clock = ClockParams {
        af0: 0.469126738608e-3,
        af1: -0.100044417195e-10,
        af2: 0.0,
        tgd_s: 0.512227416039e-8,
        tgd2_s: 0.0,
    };
    BroadcastEphemeris {
        iode: 39,
        iodc: 39,
        ..BroadcastEphemeris::from_elements(
            SatId::gps(1),
            OrbitClass::Standard,
            toe,
            orbit,
            harmonics,
            clock,
            4.0 * 3600.0,
        )
    }
}

/// Header values of ESBC00DNK_R_20201770000_01D_MN (GPSA/GPSB lines), i.e. values decoded
/// from real LNAV page 18.
pub fn header_iono() -> IonoParams {
    IonoParams {
        alpha: [4.6566e-09, 1.4901e-08, -5.9605e-08, -1.1921e-07],
        beta: [8.1920e+04, 9.8304e+04, -6.5536e+04, -5.2429e+05],
    }
}

/// Header values of ESBC00DNK_R_20201770000_01D_MN (GPUT and LEAP SECONDS lines; WN_LSF,
/// DN: the 2016-12-31 event), with the file's reference week 2111.
pub fn header_utc() -> UtcParams {
    UtcParams {
        a0: 9.313_225_746_2e-10,
        a1: 2.664_535_259e-15,
        tot: 589_824,
        wnt: 2111,
        dt_ls: 18,
        wn_lsf: 1929,
        dn: 7,
        dt_lsf: 18,
    }
}

/// [`header_utc`] referred to week 2190, the week of [`real_prn1`].
pub fn utc_week_2190() -> UtcParams {
    UtcParams {
        wnt: 2190,
        ..header_utc()
    }
}

/// The LNAV parity matrix H printed in Tsui, "Fundamentals of GPS receivers" (eq. 5.3):
/// rows D25..D30 over d1..d24, a transcription of IS-GPS-200 table 20-XIV independent
/// of the encoder's and decoder's own.
pub const TSUI_PARITY_MATRIX: [&str; 6] = [
    "111011000111110011010010",
    "011101100011111001101001",
    "101110110001111100110100",
    "010111011000111110011010",
    "101011101100011111001101",
    "001011011110101000100111",
];
