//! What B-CNAV1 (B1C) and B-CNAV2 (B2a) share: the data blocks and parameters their ICDs
//! define identically (BDS-SIS-ICD-B1C-1.0 and BDS-SIS-ICD-B2a-1.0, §6.2.3 data blocks,
//! §7.3-7.15), the quantisation of an ephemeris onto them and the ephemeris they describe.
//!
//! The BDS CNAV orbit (Table 7-8, Table 7-9) is relative to a reference semi-major axis,
//! A0 = A_ref + Delta A (A_ref 27906100 m for MEO, 42162200 m for IGSO/GEO), with rates
//! A-dot and Delta n0-dot. SkyForge's [`BroadcastEphemeris`] is the GPS-style Keplerian
//! set, so the encoder sends A-dot = 0 and Delta n0-dot = 0, with which the CNAV user
//! algorithm and the Keplerian one coincide (sqrt A = sqrt(A_ref + Delta A), Delta n =
//! Delta n0). The ionosphere (BDGIM, Table 7-10), SISAI and SISMAI blocks are sent as
//! zeros; BDT-UTC carries only Delta t_LS = Delta t_LSF = 4 s (BDT - UTC since 2017).

use crate::navmsg::field::{Field, Fields, Lsb, OutOfRange, field};
use hifitime::Epoch;
use skyforge_orbits::ephemeris::{
    BroadcastEphemeris, ClockParams, HarmonicCorrections, KeplerElements, OrbitClass, SatId, System,
};

/// Table 7-8 note ***: reference semi-major axis of MEO satellites (m).
pub const A_REF_MEO_M: f64 = 27_906_100.0;
/// Table 7-8 note ***: reference semi-major axis of IGSO and GEO satellites (m).
pub const A_REF_IGSO_GEO_M: f64 = 42_162_200.0;
/// Semi-major axis above which a set is taken as IGSO (m), between the two references.
const IGSO_ABOVE_M: f64 = 35_000_000.0;
/// Table 7-8 note ****: SatType of IGSO and MEO satellites.
const SAT_TYPE_IGSO: i64 = 0b10;
const SAT_TYPE_MEO: i64 = 0b11;
/// Grid of toe and toc (s): their scale factor (Table 7-5, Table 7-8).
const T_REF_GRID_S: i128 = 300;
/// Fit interval given to decoded sets (s).
const FIT_INTERVAL_S: f64 = 3.0 * 3600.0;
/// BDT - UTC leap seconds sent as Delta t_LS and Delta t_LSF (s).
const BDT_UTC_LEAP_S: i64 = 4;
const NS: i128 = 1_000_000_000;
const WEEK_S: i128 = 604_800;

// Table 7-2: system time parameters.
pub(crate) const WN: Field = field("WN", 13, false, Lsb::Count);
// Table 7-3, Table 7-4: issue of data.
pub(crate) const IODE: Field = field("IODE", 8, false, Lsb::Count);
pub(crate) const IODC: Field = field("IODC", 10, false, Lsb::Count);

// Figure 6-11 / 6-12 (B2a), 6-12 / 6-13 (B1C), Table 7-8: ephemeris I and II.
pub(crate) const TOE: Field = field("toe", 11, false, Lsb::Value(300.0));
pub(crate) const SAT_TYPE: Field = field("SatType", 2, false, Lsb::Count);
pub(crate) const DELTA_A: Field = field("Delta A", 26, true, Lsb::Pow2(-9));
pub(crate) const A_DOT: Field = field("A dot", 25, true, Lsb::Pow2(-21));
pub(crate) const DELTA_N0: Field = field("Delta n0", 17, true, Lsb::Semi(-44));
pub(crate) const DELTA_N0_DOT: Field = field("Delta n0 dot", 23, true, Lsb::Semi(-57));
pub(crate) const M0: Field = field("M0", 33, true, Lsb::Semi(-32));
pub(crate) const E: Field = field("e", 33, false, Lsb::Pow2(-34));
pub(crate) const OMEGA: Field = field("omega", 33, true, Lsb::Semi(-32));
pub(crate) const OMEGA0: Field = field("Omega0", 33, true, Lsb::Semi(-32));
pub(crate) const I0: Field = field("i0", 33, true, Lsb::Semi(-32));
pub(crate) const OMEGA_DOT: Field = field("Omega dot", 19, true, Lsb::Semi(-44));
pub(crate) const IDOT: Field = field("i0 dot", 15, true, Lsb::Semi(-44));
pub(crate) const CIS: Field = field("Cis", 16, true, Lsb::Pow2(-30));
pub(crate) const CIC: Field = field("Cic", 16, true, Lsb::Pow2(-30));
pub(crate) const CRS: Field = field("Crs", 24, true, Lsb::Pow2(-8));
pub(crate) const CRC: Field = field("Crc", 24, true, Lsb::Pow2(-8));
pub(crate) const CUS: Field = field("Cus", 21, true, Lsb::Pow2(-30));
pub(crate) const CUC: Field = field("Cuc", 21, true, Lsb::Pow2(-30));

/// Ephemeris I (203 bits).
pub(crate) const EPHEMERIS_1: [Field; 9] = [
    TOE,
    SAT_TYPE,
    DELTA_A,
    A_DOT,
    DELTA_N0,
    DELTA_N0_DOT,
    M0,
    E,
    OMEGA,
];
/// Ephemeris II (222 bits).
pub(crate) const EPHEMERIS_2: [Field; 10] =
    [OMEGA0, I0, OMEGA_DOT, IDOT, CIS, CIC, CRS, CRC, CUS, CUC];

// Figure 6-13 (B2a) / 6-14 (B1C), Table 7-5: clock correction parameters (69 bits).
pub(crate) const TOC: Field = field("toc", 11, false, Lsb::Value(300.0));
pub(crate) const A0: Field = field("a0", 25, true, Lsb::Pow2(-34));
pub(crate) const A1: Field = field("a1", 22, true, Lsb::Pow2(-50));
pub(crate) const A2: Field = field("a2", 11, true, Lsb::Pow2(-66));
pub(crate) const CLOCK: [Field; 4] = [TOC, A0, A1, A2];

// Table 7-6: group delay differentials.
pub(crate) const TGD_B1CP: Field = field("TGD_B1Cp", 12, true, Lsb::Pow2(-34));
pub(crate) const TGD_B2AP: Field = field("TGD_B2ap", 12, true, Lsb::Pow2(-34));
pub(crate) const ISC_B1CD: Field = field("ISC_B1Cd", 12, true, Lsb::Pow2(-34));
pub(crate) const ISC_B2AD: Field = field("ISC_B2ad", 12, true, Lsb::Pow2(-34));

// §7.14-7.17: health, integrity flags, accuracy indices.
pub(crate) const HS: Field = field("HS", 2, false, Lsb::Count);
pub(crate) const SISMAI: Field = field("SISMAI", 4, false, Lsb::Count);
pub(crate) const SISAI_OE: Field = field("SISAIoe", 5, false, Lsb::Count);
/// Figure 6-14 (B2a) / 6-15 (B1C): t_op, SISAIocb, SISAIoc1, SISAIoc2 (22 bits, zeros).
pub(crate) const SISAI_OC: Field = field("SISAIoc", 22, false, Lsb::Count);
/// Table 7-23: DIF, SIF, AIF of B1C.
pub(crate) const FLAGS_B1C: [Field; 3] = [
    field("DIF(B1C)", 1, false, Lsb::Count),
    field("SIF(B1C)", 1, false, Lsb::Count),
    field("AIF(B1C)", 1, false, Lsb::Count),
];
/// Table 7-23: DIF, SIF, AIF of B2a.
pub(crate) const FLAGS_B2A: [Field; 3] = [
    field("DIF(B2a)", 1, false, Lsb::Count),
    field("SIF(B2a)", 1, false, Lsb::Count),
    field("AIF(B2a)", 1, false, Lsb::Count),
];

/// Table 7-10: BDGIM alpha1..alpha9 (74 bits, TECu, sent as zeros). The B2b ICD (Table
/// 7-8) gives alpha5 a negative scale, -2^-3, on its unsigned field (unchecked against
/// B1C's and B2a's own tables): to mind before sending coefficients.
pub(crate) const IONO: [Field; 9] = [
    field("alpha1", 10, false, Lsb::Pow2(-3)),
    field("alpha2", 8, true, Lsb::Pow2(-3)),
    field("alpha3", 8, false, Lsb::Pow2(-3)),
    field("alpha4", 8, false, Lsb::Pow2(-3)),
    field("alpha5", 8, false, Lsb::Pow2(-3)),
    field("alpha6", 8, true, Lsb::Pow2(-3)),
    field("alpha7", 8, true, Lsb::Pow2(-3)),
    field("alpha8", 8, true, Lsb::Pow2(-3)),
    field("alpha9", 8, true, Lsb::Pow2(-3)),
];

const DELTA_T_LS: Field = field("Delta tLS", 8, true, Lsb::Count);
const DELTA_T_LSF: Field = field("Delta tLSF", 8, true, Lsb::Count);
/// Figure 6-16 (B2a) / 6-17 (B1C), Table 7-20: BDT-UTC time offset parameters (97 bits).
pub(crate) const BDT_UTC: [Field; 9] = [
    field("A0UTC", 16, true, Lsb::Pow2(-35)),
    field("A1UTC", 13, true, Lsb::Pow2(-51)),
    field("A2UTC", 7, true, Lsb::Pow2(-68)),
    DELTA_T_LS,
    field("tot", 16, false, Lsb::Pow2(4)),
    field("WNot", 13, false, Lsb::Count),
    field("WNLSF", 13, false, Lsb::Count),
    field("DN", 3, false, Lsb::Count),
    DELTA_T_LSF,
];

/// A reserved field of `bits` bits (never set: always zeros).
pub(crate) const fn rev(bits: u32) -> Field {
    field("Rev", bits, false, Lsb::Count)
}

/// The group delays the B-CNAV messages carry besides the ephemeris (s). Default: zero.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct BdsCnavParams {
    /// TGD_B1Cp: B1C pilot minus B3I group delay.
    pub tgd_b1cp_s: f64,
    /// TGD_B2ap: B2a pilot minus B3I group delay.
    pub tgd_b2ap_s: f64,
    /// ISC_B1Cd: B1C data minus B1C pilot (B-CNAV1 only).
    pub isc_b1cd_s: f64,
    /// ISC_B2ad: B2a data minus B2a pilot (B-CNAV2 only).
    pub isc_b2ad_s: f64,
}

/// Why a B-CNAV message cannot be built.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum BdsCnavError {
    /// The ephemeris is not a BeiDou MEO/IGSO one.
    #[error("{sat}: B1C and B2a are broadcast by BeiDou MEO and IGSO satellites only")]
    NotMeoIgso { sat: String },
    /// A value does not fit its field.
    #[error("{sat}: {field} = {value:e} is outside the range B-CNAV carries [{min:e}, {max:e}]")]
    FieldOutOfRange {
        sat: String,
        field: &'static str,
        value: f64,
        min: f64,
        max: f64,
    },
    /// toe or toc is not on the 300 s grid.
    #[error("{sat}: {field} (BDT seconds of week {sow_s}) is not a multiple of 300 s")]
    OffGrid {
        sat: String,
        field: &'static str,
        sow_s: f64,
    },
}

/// The BDT week and seconds of week of a reference time on the 300 s grid.
fn on_grid(sat: &str, f: &Field, t: Epoch) -> Result<(u32, i64), BdsCnavError> {
    let ns = t.to_bdt_duration().total_nanoseconds();
    let (week, ns_of_week) = (ns.div_euclid(WEEK_S * NS), ns.rem_euclid(WEEK_S * NS));
    if ns_of_week % (T_REF_GRID_S * NS) == 0 && week >= 0 {
        Ok((week as u32, (ns_of_week / NS) as i64))
    } else {
        Err(BdsCnavError::OffGrid {
            sat: sat.to_string(),
            field: f.name,
            sow_s: ns_of_week as f64 * 1e-9,
        })
    }
}

/// The raw fields of `eph` and `params`: ephemeris I and II, clock, IODE, IODC (= IODE,
/// §7.4.3), HS, group delays and the constant blocks.
pub(crate) fn quantise(
    eph: &BroadcastEphemeris,
    params: &BdsCnavParams,
) -> Result<Fields, BdsCnavError> {
    let sat = eph.sat.to_string();
    if eph.sat.system != System::Beidou || eph.class != OrbitClass::Standard {
        return Err(BdsCnavError::NotMeoIgso { sat });
    }
    let err = |e: OutOfRange| BdsCnavError::FieldOutOfRange {
        sat: sat.clone(),
        field: e.field,
        value: e.value,
        min: e.min,
        max: e.max,
    };
    let (o, h, c) = (&eph.orbit, &eph.harmonics, &eph.clock);
    let a = o.sqrt_a * o.sqrt_a;
    let (sat_type, a_ref) = if a > IGSO_ABOVE_M {
        (SAT_TYPE_IGSO, A_REF_IGSO_GEO_M)
    } else {
        (SAT_TYPE_MEO, A_REF_MEO_M)
    };
    let mut f = Fields::default();
    let plain = [
        (&DELTA_A, a - a_ref),
        (&DELTA_N0, o.delta_n),
        (&E, o.e),
        (&OMEGA_DOT, o.omega_dot),
        (&IDOT, o.idot),
        (&CIS, h.cis),
        (&CIC, h.cic),
        (&CRS, h.crs),
        (&CRC, h.crc),
        (&CUS, h.cus),
        (&CUC, h.cuc),
        (&A0, c.af0),
        (&A1, c.af1),
        (&A2, c.af2),
        (&TGD_B1CP, params.tgd_b1cp_s),
        (&TGD_B2AP, params.tgd_b2ap_s),
        (&ISC_B1CD, params.isc_b1cd_s),
        (&ISC_B2AD, params.isc_b2ad_s),
    ];
    for (field, v) in plain {
        f.set(field, field.quantise(v).map_err(err)?);
    }
    for (field, v) in [
        (&M0, o.m0),
        (&OMEGA, o.omega),
        (&OMEGA0, o.omega0),
        (&I0, o.i0),
    ] {
        f.set(field, field.quantise_angle(v).map_err(err)?);
    }
    let (_, toe_sow) = on_grid(&sat, &TOE, eph.toe)?;
    let (_, toc_sow) = on_grid(&sat, &TOC, eph.toc)?;
    f.set(&TOE, toe_sow / 300);
    f.set(&TOC, toc_sow / 300);
    f.set(&SAT_TYPE, sat_type);
    let iode = i64::from(eph.iode % 256);
    f.set(&IODE, iode);
    f.set(&IODC, iode);
    f.set(&HS, i64::from(eph.health != 0));
    f.set(&DELTA_T_LS, BDT_UTC_LEAP_S);
    f.set(&DELTA_T_LSF, BDT_UTC_LEAP_S);
    Ok(f)
}

/// The ephemeris the raw fields describe, toe and toc at the given epochs, `tgd` the
/// group delay its `tgd_s` holds (the message's own pilot: TGD_B1Cp or TGD_B2ap).
/// Message: [`skyforge_orbits::ephemeris::NavMessage::BdsD1D2`], whose clock reference
/// (B3I, §7.6) B-CNAV shares.
pub(crate) fn to_ephemeris(
    f: &Fields,
    sat: SatId,
    toe: Epoch,
    toc: Epoch,
    tgd: &Field,
) -> BroadcastEphemeris {
    let si = |field: &Field| field.si_value(f.get(field));
    let a_ref = if f.get(&SAT_TYPE) == SAT_TYPE_IGSO {
        A_REF_IGSO_GEO_M
    } else {
        A_REF_MEO_M
    };
    let orbit = KeplerElements {
        sqrt_a: (a_ref + si(&DELTA_A)).sqrt(),
        e: si(&E),
        i0: si(&I0),
        omega0: si(&OMEGA0),
        omega: si(&OMEGA),
        m0: si(&M0),
        delta_n: si(&DELTA_N0),
        idot: si(&IDOT),
        omega_dot: si(&OMEGA_DOT),
    };
    let harmonics = HarmonicCorrections {
        cuc: si(&CUC),
        cus: si(&CUS),
        crc: si(&CRC),
        crs: si(&CRS),
        cic: si(&CIC),
        cis: si(&CIS),
    };
    let clock = ClockParams {
        af0: si(&A0),
        af1: si(&A1),
        af2: si(&A2),
        tgd_s: si(tgd),
        tgd2_s: 0.0,
    };
    BroadcastEphemeris {
        toc,
        iode: f.get(&IODE) as u32,
        iodc: f.get(&IODC) as u32,
        health: f.get(&HS) as u32,
        ..BroadcastEphemeris::from_elements(
            sat,
            OrbitClass::Standard,
            toe,
            orbit,
            harmonics,
            clock,
            FIT_INTERVAL_S,
        )
    }
}

/// The epoch of a reference time `ref_sow` (s of week) broadcast in BDT week `week` at
/// seconds of week `tx_sow`: the reference is at most half a week away (Table 7-9 **).
pub(crate) fn reference_epoch(week: u32, tx_sow: i64, ref_sow: i64) -> Epoch {
    let d = ref_sow - tx_sow;
    let week = if d > 302_400 {
        week.saturating_sub(1)
    } else if d < -302_400 {
        week + 1
    } else {
        week
    };
    skyforge_orbits::time::epoch_from_bdt(week, ref_sow as f64)
}

/// `count` channel symbols from stream symbol `first` on, frames of `frame_len` symbols
/// made by `frame(n)` (B-CNAV1's and B-CNAV2's symbol streams).
pub(crate) fn symbols_of_frames(
    frame_len: usize,
    first: u64,
    count: usize,
    frame: impl Fn(u64) -> Vec<u8>,
) -> Vec<u8> {
    let n_sym = frame_len as u64;
    let mut out = Vec::with_capacity(count);
    let mut k = first;
    while out.len() < count {
        let symbols = frame(k / n_sym);
        let from = (k % n_sym) as usize;
        let take = (frame_len - from).min(count - out.len());
        out.extend_from_slice(&symbols[from..from + take]);
        k += take as u64;
    }
    out
}
