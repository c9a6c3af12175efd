//! Ionospheric (Klobuchar) and UTC parameters of subframe 4 page 18
//! (IS-GPS-200 20.3.3.5.1.6-7, table 20-X, figure 20-1 sheet 8).

use super::LnavError;
use super::scale::{self, Scale};
use super::words::DataWords;
use hifitime::Epoch;
use hifitime::leap_seconds::LatestLeapSeconds;

/// TAI - GPST (s): GPS time was set to UTC at the GPS epoch, when TAI - UTC was 19 s.
const TAI_MINUS_GPST_S: f64 = 19.0;
/// Whole days from 1900-01-01 to the GPS epoch 1980-01-06 (hifitime's leap-second
/// timestamps count calendar seconds from 1900-01-01).
const DAYS_1900_TO_GPS_EPOCH: i64 = 29_224;
/// Largest tot / toa value the ICD allows (147 x 4096 s, table 20-X).
const MAX_REFERENCE_TIME_S: u32 = 602_112;

/// Klobuchar coefficients (IS-GPS-200 20.3.3.5.2.5), in the ICD's units because the
/// model itself works in semicircles: `alpha[n]` in s/semicircle^n, `beta[n]` in
/// s/semicircle^n.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct IonoParams {
    /// Amplitude coefficients alpha0..alpha3.
    pub alpha: [f64; 4],
    /// Period coefficients beta0..beta3.
    pub beta: [f64; 4],
}

/// UTC parameters (IS-GPS-200 20.3.3.5.2.4): GPS - UTC = dt_ls + A0 + A1 (t - tot +
/// 604800 (WN - WNt)) before the leap second at the end of day `dn` of week `wn_lsf`,
/// dt_lsf after it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct UtcParams {
    /// A0 (s).
    pub a0: f64,
    /// A1 (s/s).
    pub a1: f64,
    /// Reference time of the UTC data, seconds of week `wnt` (a multiple of 4096 s, at
    /// most 602112 s).
    pub tot: u32,
    /// Week of `tot` (full GPS week; its 8 LSBs are broadcast).
    pub wnt: u32,
    /// Leap seconds GPS - UTC before the event (s).
    pub dt_ls: i32,
    /// Week of the leap-second event (full GPS week; its 8 LSBs are broadcast).
    pub wn_lsf: u32,
    /// Day of week `wn_lsf` at whose end the leap second takes effect (1 = Sunday .. 7).
    pub dn: u8,
    /// Leap seconds GPS - UTC after the event (s).
    pub dt_lsf: i32,
}

impl UtcParams {
    /// GPS - UTC from the leap-second table (hifitime's IERS list) at `reference`: A0 =
    /// A1 = 0, dt_ls = dt_lsf = TAI - UTC - 19 s, and the most recent leap-second event
    /// (the UTC day before it took effect) as (wn_lsf, dn); tot/wnt at the 4096-s step
    /// at or before `reference`.
    pub fn from_leap_seconds(reference: Epoch) -> Result<Self, LnavError> {
        let before_gps = || LnavError::BeforeGpsEpoch {
            epoch: reference.to_string(),
        };
        let tai_s = reference.to_tai_duration().to_seconds();
        let last = LatestLeapSeconds::default()
            .rev()
            .find(|ls| ls.announced_by_iers && ls.timestamp_tai_s <= tai_s)
            .ok_or_else(before_gps)?;
        let event_day =
            (last.timestamp_tai_s / 86_400.0).round() as i64 - DAYS_1900_TO_GPS_EPOCH - 1;
        let gps_s = super::gps_ns(reference).div_euclid(super::NS_PER_S) as i64;
        if event_day < 0 || gps_s < 0 {
            return Err(before_gps());
        }
        let (week, sow) = super::week_and_sow(gps_s);
        let dt_ls = (last.delta_at - TAI_MINUS_GPST_S).round() as i32;
        Ok(Self {
            a0: 0.0,
            a1: 0.0,
            tot: ((sow / 4096 * 4096) as u32).min(MAX_REFERENCE_TIME_S),
            wnt: week as u32,
            dt_ls,
            wn_lsf: (event_day / 7) as u32,
            dn: (event_day % 7 + 1) as u8,
            dt_lsf: dt_ls,
        })
    }

    /// The parameters as broadcast (A0, A1 quantised per table 20-X).
    pub fn quantised(&self) -> Result<Self, LnavError> {
        RawUtc::new(self).map(|r| r.to_params())
    }
}

impl IonoParams {
    /// The coefficients as broadcast (quantised per table 20-X).
    pub fn quantised(&self) -> Result<Self, LnavError> {
        RawIono::new(self).map(|r| r.to_params())
    }
}

/// Broadcast integers of the Klobuchar coefficients.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct RawIono {
    alpha: [i64; 4],
    beta: [i64; 4],
}

impl RawIono {
    pub fn new(p: &IonoParams) -> Result<Self, LnavError> {
        let q = |scales: &[Scale; 4], v: &[f64; 4]| -> Result<[i64; 4], LnavError> {
            let mut out = [0; 4];
            for ((o, s), &x) in out.iter_mut().zip(scales).zip(v) {
                *o = s.quantise(x, "ionosphere")?;
            }
            Ok(out)
        };
        Ok(Self {
            alpha: q(&scale::ALPHA, &p.alpha)?,
            beta: q(&scale::BETA, &p.beta)?,
        })
    }

    pub fn to_params(self) -> IonoParams {
        let v = |scales: &[Scale; 4], n: &[i64; 4]| std::array::from_fn(|k| scales[k].value(n[k]));
        IonoParams {
            alpha: v(&scale::ALPHA, &self.alpha),
            beta: v(&scale::BETA, &self.beta),
        }
    }
}

/// Broadcast integers of the UTC parameters.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct RawUtc {
    a0: i64,
    a1: i64,
    params: UtcParams,
}

/// An integer that must lie in `lo..=hi`.
fn check_range(
    what: &str,
    value: i64,
    lo: i64,
    hi: i64,
    allowed: &'static str,
) -> Result<(), LnavError> {
    if (lo..=hi).contains(&value) {
        Ok(())
    } else {
        Err(LnavError::BadValue {
            what: format!("UTC {what}"),
            value,
            allowed,
        })
    }
}

impl RawUtc {
    pub fn new(p: &UtcParams) -> Result<Self, LnavError> {
        check_range(
            "dt_ls",
            i64::from(p.dt_ls),
            -128,
            127,
            "8-bit two's complement seconds",
        )?;
        check_range(
            "dt_lsf",
            i64::from(p.dt_lsf),
            -128,
            127,
            "8-bit two's complement seconds",
        )?;
        check_range("dn", i64::from(p.dn), 1, 7, "day 1-7 of the week")?;
        if !p.tot.is_multiple_of(4096) || p.tot > MAX_REFERENCE_TIME_S {
            return Err(LnavError::BadValue {
                what: "UTC tot".into(),
                value: i64::from(p.tot),
                allowed: "a multiple of 4096 s up to 602112 s",
            });
        }
        Ok(Self {
            a0: scale::UTC_A0.quantise(p.a0, "UTC")?,
            a1: scale::UTC_A1.quantise(p.a1, "UTC")?,
            params: *p,
        })
    }

    pub fn to_params(self) -> UtcParams {
        UtcParams {
            a0: scale::UTC_A0.value(self.a0),
            a1: scale::UTC_A1.value(self.a1),
            ..self.params
        }
    }
}

/// Words 3-10 of subframe 4 page 18, after the data ID and SV ID (figure 20-1 sheet 8);
/// bits 9-22 of word 10 are reserved (alternating ones and zeros).
pub(crate) fn page18(d: &mut DataWords, iono: &RawIono, utc: &RawUtc) {
    let a = &scale::ALPHA;
    let b = &scale::BETA;
    d.put_field(3, 9, &a[0], iono.alpha[0]);
    d.put_field(3, 17, &a[1], iono.alpha[1]);
    d.put_field(4, 1, &a[2], iono.alpha[2]);
    d.put_field(4, 9, &a[3], iono.alpha[3]);
    d.put_field(4, 17, &b[0], iono.beta[0]);
    d.put_field(5, 1, &b[1], iono.beta[1]);
    d.put_field(5, 9, &b[2], iono.beta[2]);
    d.put_field(5, 17, &b[3], iono.beta[3]);
    d.put_field(6, 1, &scale::UTC_A1, utc.a1);
    let a0 = scale::UTC_A0.bits_of(utc.a0);
    d.put(7, 1, 24, a0 >> 8);
    d.put(8, 1, 8, a0 & 0xFF);
    let p = &utc.params;
    d.put_field(8, 9, &scale::UTC_TOT, i64::from(p.tot / 4096));
    d.put(8, 17, 8, p.wnt & 0xFF);
    d.put(9, 1, 8, p.dt_ls as u32 & 0xFF);
    d.put(9, 9, 8, p.wn_lsf & 0xFF);
    d.put(9, 17, 8, u32::from(p.dn));
    d.put(10, 1, 8, p.dt_lsf as u32 & 0xFF);
    d.put_alternating(10, 9, 14);
}

#[cfg(test)]
mod tests {
    use super::super::fixtures::{header_iono, header_utc};
    use super::*;
    use hifitime::TimeScale;

    #[test]
    fn leap_seconds_of_2020_match_the_2016_12_31_event() {
        // IERS Bulletin C: a leap second was inserted at the end of 2016-12-31 (Saturday),
        // bringing TAI - UTC to 37 s, i.e. GPS - UTC = 18 s. 2017-01-01 is the first day of
        // GPS week 1930 (1930 x 7 days after 1980-01-06), so the event is at the end of
        // day 7 of week 1929.
        let e = Epoch::from_gregorian(2020, 6, 25, 0, 0, 0, 0, TimeScale::GPST);
        let u = UtcParams::from_leap_seconds(e).unwrap_or_else(|err| panic!("{err}"));
        assert_eq!((u.dt_ls, u.dt_lsf, u.wn_lsf, u.dn), (18, 18, 1929, 7));
        assert_eq!((u.wnt, u.tot), (2111, 344_064)); // 345600 s floored to 84 x 4096
        // Before that event: 2016-06-01 had GPS - UTC = 17 s, last event end of 2015-06-30
        // (a Tuesday: day 3 of GPS week 1851).
        let e = Epoch::from_gregorian(2016, 6, 1, 0, 0, 0, 0, TimeScale::GPST);
        let u = UtcParams::from_leap_seconds(e).unwrap_or_else(|err| panic!("{err}"));
        assert_eq!((u.dt_ls, u.wn_lsf, u.dn), (17, 1851, 3));
    }

    #[test]
    fn rinex_header_values_are_on_the_icd_grid() {
        // Header of ESBC00DNK_R_20201770000_01D_MN (GPSA/GPSB/GPUT lines), i.e. values
        // decoded from real LNAV page 18: quantising them must return them unchanged.
        let iono = header_iono();
        let q = iono.quantised().unwrap_or_else(|e| panic!("{e}"));
        for (x, y) in iono
            .alpha
            .iter()
            .chain(&iono.beta)
            .zip(q.alpha.iter().chain(&q.beta))
        {
            assert!((x - y).abs() <= 1e-4 * x.abs(), "{x} -> {y}");
        }
        let utc = header_utc();
        let q = utc.quantised().unwrap_or_else(|e| panic!("{e}"));
        assert!((q.a0 - utc.a0).abs() < 1e-20 && (q.a1 - utc.a1).abs() < 1e-24);
        assert!(UtcParams { dn: 8, ..utc }.quantised().is_err());
        assert!(UtcParams { tot: 4095, ..utc }.quantised().is_err());
    }
}
