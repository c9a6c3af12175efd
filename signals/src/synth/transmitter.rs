//! A transmitting satellite as the synthesiser sees it: ranging code, data bits, an
//! optional pilot component, and the time scale its code and data are counted in.

use hifitime::{Duration, Epoch};
use skyforge_gnss::codes::{BDS_B1C_CHIP_RATE_HZ, bds_b1c_data};
use skyforge_gnss::codes::{BDS_B1I_CHIP_RATE_HZ, bds_b1i};
use skyforge_gnss::codes::{BDS_B2A_CHIP_RATE_HZ, bds_b2a_data};
use skyforge_gnss::codes::{E1Codes, GALILEO_E1_C_SECONDARY, GALILEO_E1_CHIP_RATE_HZ};
use skyforge_gnss::codes::{GALILEO_E5A_CHIP_RATE_HZ, galileo_e5a_i};
use skyforge_gnss::codes::{GPS_CA_CHIP_RATE_HZ, gps_ca};
use skyforge_gnss::codes::{GPS_L5_CHIP_RATE_HZ, gps_l5_i};
use skyforge_gnss::navmsg::bds_cnav1::BdsCnav1Encoder;
use skyforge_gnss::navmsg::bds_cnav2::BdsCnav2Encoder;
use skyforge_gnss::navmsg::galileo_fnav::FnavEncoder;
use skyforge_gnss::navmsg::galileo_inav::InavEncoder;
use skyforge_gnss::navmsg::gps_cnav::CnavEncoder;
use skyforge_gnss::navmsg::gps_lnav::LnavEncoder;
use skyforge_gnss::navmsg::{BdsNavEncoder, BdsNavFormat};
use skyforge_gnss::signal::{DataModulation, Signal};
use skyforge_gnss::subcarrier::{CBOC_SUBCHIPS, b1c_qmboc, e1_cboc};
use skyforge_orbits::ephemeris::{BroadcastEphemeris, SatId};

/// Data modulating a signal.
#[derive(Debug, Clone)]
pub enum DataBits {
    /// GPS LNAV, 50 bps (20 C/A periods per bit), bit b from 0.02 b s after the GPS epoch.
    GpsLnav(Box<LnavEncoder>),
    /// BeiDou D1 (50 bps, 20 B1I periods per bit, NH20 per period) or D2 (500 bps, 2
    /// periods per bit, no NH), bit 0 at the encoder's BDT week start.
    Bds(Box<BdsNavEncoder>),
    /// Galileo F/NAV on E5a-I: 50 symbols/s after its FEC, 20 E5a periods per symbol,
    /// CS20_1 per period (Galileo OS SIS ICD §3.4), symbol 0 at the encoder's GST week
    /// start.
    GalileoFnav(Box<FnavEncoder>),
    /// GPS CNAV on L5 I5: 100 symbols/s after its FEC, 10 L5 periods per symbol, the
    /// 10-chip Neumann-Hoffman code per period (IS-GPS-705 §3.3.2.2, §3.3.3.1.1), symbol 0
    /// at the encoder's GPS week start.
    GpsCnav(Box<CnavEncoder>),
    /// Galileo I/NAV on E1-B: 250 symbols/s after its FEC, one E1 period (4 ms) per
    /// symbol, no secondary code (Galileo OS SIS ICD §2.3.3, §4.3), symbol 0 at the
    /// encoder's GST week start.
    GalileoInav(Box<InavEncoder>),
    /// BeiDou B-CNAV2 on B2a_d: 200 symbols/s after its LDPC code, 5 B2a periods per
    /// symbol, the secondary code 00010 per period (BDS-SIS-ICD-B2a-1.0 §5.2.2, §6.2.1),
    /// symbol 0 at the encoder's BDT week start (frames on BDT multiples of 3 s).
    BdsCnav2(Box<BdsCnav2Encoder>),
    /// BeiDou B-CNAV1 on B1C_data: 100 symbols/s after its BCH and LDPC codes, one B1C
    /// period (10 ms) per symbol, no secondary code (BDS-SIS-ICD-B1C-1.0 §6.2.1), symbol 0
    /// at the encoder's BDT week start (18 s frames on BDT multiples of 18 s).
    BdsCnav1(Box<BdsCnav1Encoder>),
}

impl DataBits {
    /// How the data modulate the code ([`DataModulation`]: bit length, secondary code).
    fn modulation(&self) -> DataModulation {
        match self {
            DataBits::GpsLnav(_) => DataModulation::GpsLnav,
            DataBits::GalileoFnav(_) => DataModulation::GalFnav,
            DataBits::GpsCnav(_) => DataModulation::GpsCnav,
            DataBits::GalileoInav(_) => DataModulation::GalInav,
            DataBits::BdsCnav2(_) => DataModulation::BdsCnav2,
            DataBits::BdsCnav1(_) => DataModulation::BdsCnav1,
            DataBits::Bds(e) => match e.format() {
                BdsNavFormat::D1 => DataModulation::BdsD1,
                BdsNavFormat::D2 => DataModulation::BdsD2,
            },
        }
    }

    /// Code periods per data bit.
    fn periods_per_bit(&self) -> u64 {
        u64::from(self.modulation().periods_per_bit())
    }
    /// Data bit `b` (0 or 1).
    fn bit(&self, b: u64) -> u8 {
        match self {
            DataBits::GpsLnav(lnav) => lnav.bit(b),
            DataBits::Bds(e) => e.bits(b, 1).first().copied().unwrap_or(0),
            DataBits::GalileoFnav(e) => e.symbol(b),
            DataBits::GpsCnav(e) => e.symbol(b),
            DataBits::GalileoInav(e) => e.symbol(b),
            DataBits::BdsCnav2(e) => e.symbol(b),
            DataBits::BdsCnav1(e) => e.symbol(b),
        }
    }
    /// Secondary-code sign of code period `p` (+1/-1): the code restarts with every bit.
    fn secondary(&self, p: u64) -> i8 {
        self.modulation()
            .data_secondary_code()
            .map_or(1, |code| code[(p % code.len() as u64) as usize])
    }
}

/// A dataless pilot component, in quadrature with the data component (+90 deg) and with
/// half the signal's power; its primary code's chips align with the data code's.
#[derive(Debug, Clone)]
pub struct Pilot {
    code: Vec<i8>,
    /// One chip per primary period, period 0 at the time scale's epoch.
    secondary: Vec<i8>,
}

impl Pilot {
    /// The pilot of `signal`'s `prn` ([`Signal::pilot`]).
    fn of(signal: Signal, prn: u8) -> Option<Self> {
        let codes = signal.pilot(prn).ok()?;
        Some(Self {
            code: codes.primary,
            secondary: codes.secondary,
        })
    }
}

/// One satellite's signal.
#[derive(Debug, Clone)]
pub struct Transmitter {
    pub sat: SatId,
    pub signal: Signal,
    pub chip_rate_hz: f64,
    code: Vec<i8>,
    data: DataBits,
    pilot: Option<Pilot>,
    /// Scenario start in the signal's time scale: whole seconds since its epoch.
    start_whole_s: u64,
    /// ... and the fraction (s).
    start_frac_s: f64,
}

impl Transmitter {
    /// GPS L1 C/A with LNAV; `start` is the scenario start epoch.
    pub fn gps_l1ca(sat: SatId, lnav: LnavEncoder, start: Epoch) -> Option<Self> {
        let code = gps_ca(sat.prn)?.to_vec();
        let (start_whole_s, start_frac_s) = seconds_since(start.to_gpst_duration())?;
        Some(Self {
            sat,
            signal: Signal::GpsL1Ca,
            chip_rate_hz: GPS_CA_CHIP_RATE_HZ,
            code,
            data: DataBits::GpsLnav(Box::new(lnav)),
            pilot: None,
            start_whole_s,
            start_frac_s,
        })
    }

    /// BeiDou B1I with D1 or D2 data; chips and bits count from the encoder's BDT week
    /// start, which must not be after `start`.
    pub fn bds_b1i(sat: SatId, nav: BdsNavEncoder, start: Epoch) -> Option<Self> {
        let code = bds_b1i(sat.prn)?;
        let (start_whole_s, start_frac_s) = seconds_since(start - nav.week_start())?;
        Some(Self {
            sat,
            signal: Signal::BdsB1I,
            chip_rate_hz: BDS_B1I_CHIP_RATE_HZ,
            code,
            data: DataBits::Bds(Box::new(nav)),
            pilot: None,
            start_whole_s,
            start_frac_s,
        })
    }

    /// Galileo E5a: E5a-I with F/NAV and CS20_1, E5a-Q pilot with CS100_prn (Galileo OS
    /// SIS ICD §2.3, §3.4); chips and symbols count from the encoder's GST week start,
    /// which must not be after `start`.
    pub fn gal_e5a(sat: SatId, nav: FnavEncoder, start: Epoch) -> Option<Self> {
        let (start_whole_s, start_frac_s) = seconds_since(start - nav.week_start())?;
        Some(Self {
            sat,
            signal: Signal::GalE5a,
            chip_rate_hz: GALILEO_E5A_CHIP_RATE_HZ,
            code: galileo_e5a_i(sat.prn)?,
            data: DataBits::GalileoFnav(Box::new(nav)),
            pilot: Some(Pilot::of(Signal::GalE5a, sat.prn)?),
            start_whole_s,
            start_frac_s,
        })
    }

    /// GPS L5: I5 with CNAV and the 10-chip NH code, Q5 pilot with the 20-chip NH code
    /// (IS-GPS-705 §3.2.2, §3.3.2); chips and symbols count from the encoder's GPS week
    /// start, which must not be after `start`. Both NH codes restart at every week start
    /// (a whole number of their 10 and 20 ms cycles).
    pub fn gps_l5(sat: SatId, nav: CnavEncoder, start: Epoch) -> Option<Self> {
        let (start_whole_s, start_frac_s) = seconds_since(start - nav.week_start())?;
        Some(Self {
            sat,
            signal: Signal::GpsL5,
            chip_rate_hz: GPS_L5_CHIP_RATE_HZ,
            code: gps_l5_i(sat.prn)?,
            data: DataBits::GpsCnav(Box::new(nav)),
            pilot: Some(Pilot::of(Signal::GpsL5, sat.prn)?),
            start_whole_s,
            start_frac_s,
        })
    }

    /// BeiDou B2a: B2a_d with B-CNAV2 and the 5-chip secondary code, B2a_p pilot (+90 deg,
    /// BDS-SIS-ICD-B2a-1.0 §4.1 Table 4-1, §4.2) with the PRN's 100-chip secondary code
    /// (§5.2); chips and symbols count from the encoder's BDT week start, which must not
    /// be after `start`. The secondary codes (5 and 100 ms) and the 3 s frames all
    /// restart at every BDT week start, so each is aligned with BDT as the ICD requires.
    pub fn bds_b2a(sat: SatId, nav: BdsCnav2Encoder, start: Epoch) -> Option<Self> {
        let (start_whole_s, start_frac_s) = seconds_since(start - nav.week_start())?;
        Some(Self {
            sat,
            signal: Signal::BdsB2a,
            chip_rate_hz: BDS_B2A_CHIP_RATE_HZ,
            code: bds_b2a_data(sat.prn)?,
            data: DataBits::BdsCnav2(Box::new(nav)),
            pilot: Some(Pilot::of(Signal::BdsB2a, sat.prn)?),
            start_whole_s,
            start_frac_s,
        })
    }

    /// BeiDou B1C: B1C_data with B-CNAV1 (BOC(1,1), 1/4 of the power), B1C_pilot with the
    /// PRN's 1800-chip secondary code (QMBOC(6,1,4/33), 3/4), BDS-SIS-ICD-B1C-1.0 §4.2.2,
    /// §5.2; chips and symbols count from the encoder's BDT week start, which must not be
    /// after `start`. The 18 s secondary code and the 18 s frames both restart at every
    /// BDT week start (33600 of each a week), so the secondary code starts with each frame.
    pub fn bds_b1c(sat: SatId, nav: BdsCnav1Encoder, start: Epoch) -> Option<Self> {
        let (start_whole_s, start_frac_s) = seconds_since(start - nav.week_start())?;
        Some(Self {
            sat,
            signal: Signal::BdsB1C,
            chip_rate_hz: BDS_B1C_CHIP_RATE_HZ,
            code: bds_b1c_data(sat.prn)?,
            data: DataBits::BdsCnav1(Box::new(nav)),
            pilot: Some(Pilot::of(Signal::BdsB1C, sat.prn)?),
            start_whole_s,
            start_frac_s,
        })
    }

    /// Galileo E1: E1-B with I/NAV and E1-C pilot with CS25, in phase, each on its CBOC
    /// sub-carriers (Galileo OS SIS ICD §2.3.3, §3.4), the primary codes from `codes`;
    /// chips and symbols count from the encoder's GST week start, which must not be after
    /// `start`.
    pub fn gal_e1(sat: SatId, nav: InavEncoder, codes: &E1Codes, start: Epoch) -> Option<Self> {
        let (start_whole_s, start_frac_s) = seconds_since(start - nav.week_start())?;
        Some(Self {
            sat,
            signal: Signal::GalE1,
            chip_rate_hz: GALILEO_E1_CHIP_RATE_HZ,
            code: codes.data(sat.prn)?.to_vec(),
            data: DataBits::GalileoInav(Box::new(nav)),
            pilot: Some(Pilot {
                code: codes.pilot(sat.prn)?.to_vec(),
                secondary: GALILEO_E1_C_SECONDARY.to_vec(),
            }),
            start_whole_s,
            start_frac_s,
        })
    }

    /// Sub-chips per chip of the waveform: 12 for E1's CBOC ([`Self::cboc_levels_after`])
    /// and B1C's QMBOC ([`Self::qmboc_levels_after`]), 1 for the binary codes.
    pub fn subchips_per_chip(&self) -> usize {
        if matches!(self.signal, Signal::GalE1 | Signal::BdsB1C) {
            CBOC_SUBCHIPS
        } else {
            1
        }
    }

    /// Whether the signal has a pilot component ([`Self::pilot_chip_signs`]).
    pub fn has_pilot(&self) -> bool {
        self.pilot.is_some()
    }

    /// The ephemeris the data broadcast (quantised as the message carries it): the orbit
    /// and clock the signal must follow so that a receiver's decoded ephemeris is exact.
    pub fn broadcast_ephemeris(&self) -> BroadcastEphemeris {
        match &self.data {
            DataBits::GpsLnav(lnav) => lnav.broadcast_ephemeris(),
            DataBits::Bds(nav) => nav.broadcast_ephemeris(),
            DataBits::GalileoFnav(nav) => nav.broadcast_ephemeris(),
            DataBits::GpsCnav(nav) => nav.broadcast_ephemeris(),
            DataBits::GalileoInav(nav) => nav.broadcast_ephemeris(),
            DataBits::BdsCnav2(nav) => nav.broadcast_ephemeris(),
            DataBits::BdsCnav1(nav) => nav.broadcast_ephemeris(),
        }
    }

    /// The Klobuchar coefficients the data broadcast (as quantised in the message), when
    /// the message carries them (GPS LNAV, CNAV).
    pub fn broadcast_iono(&self) -> Option<([f64; 4], [f64; 4])> {
        match &self.data {
            DataBits::GpsLnav(lnav) => {
                let p = lnav.iono();
                Some((p.alpha, p.beta))
            }
            DataBits::GpsCnav(cnav) => {
                let p = cnav.iono();
                Some((p.alpha, p.beta))
            }
            DataBits::Bds(_)
            | DataBits::GalileoFnav(_)
            | DataBits::GalileoInav(_)
            | DataBits::BdsCnav2(_)
            | DataBits::BdsCnav1(_) => None,
        }
    }

    /// Absolute chip index (since the time-scale epoch) and code phase within it (chips) of
    /// satellite time `t_sv_s` (seconds since the scenario start).
    pub fn chip_at(&self, t_sv_s: f64) -> (u64, f64) {
        self.count_at(self.chip_rate_hz, t_sv_s)
    }

    /// [`Self::chip_at`] in sub-chips ([`Self::subchips_per_chip`]).
    pub fn subchip_at(&self, t_sv_s: f64) -> (u64, f64) {
        self.count_at(self.chip_rate_hz * self.subchips_per_chip() as f64, t_sv_s)
    }

    /// Whole and fractional counts at `rate` (an integer number per second) since the time
    /// scale's epoch of satellite time `t_sv_s`.
    fn count_at(&self, rate: f64, t_sv_s: f64) -> (u64, f64) {
        let counts = rate * (self.start_frac_s + t_sv_s);
        let whole = counts.floor();
        let base = self.start_whole_s * rate as u64;
        (base.wrapping_add_signed(whole as i64), counts - whole)
    }

    /// Append the E1 CBOC waveform over sub-chips `s0 .. s0 + count` (absolute indices,
    /// [`Self::subchip_at`]) to `out`: per chip the data chip (E1-B code x I/NAV symbol)
    /// and the pilot chip (E1-C code x CS25) weight the sub-carriers
    /// ([`skyforge_gnss::subcarrier::e1_cboc`]); `cached` as in [`Self::chip_signs_after`].
    pub fn cboc_levels_after(
        &self,
        s0: u64,
        count: usize,
        out: &mut Vec<f32>,
        cached: &mut Option<(u64, u8)>,
    ) {
        // The four waveforms of a chip, by (data, pilot) sign.
        let table = [
            e1_cboc(1, 1),
            e1_cboc(1, -1),
            e1_cboc(-1, 1),
            e1_cboc(-1, -1),
        ];
        out.reserve(count);
        self.subchip_spans(s0, count, cached, |row, span| {
            out.extend_from_slice(&table[row][span]);
        });
    }

    /// Append the B1C QMBOC waveform over sub-chips `s0 .. s0 + count` to `out_i` (data
    /// and the pilot's BOC(6,1) part) and `out_q` (the pilot's BOC(1,1) part), per chip
    /// from the data chip (B1C_data code x B-CNAV1 symbol) and the pilot chip (B1C_pilot
    /// code x secondary chip) ([`skyforge_gnss::subcarrier::b1c_qmboc`]); `cached` as in
    /// [`Self::chip_signs_after`].
    pub fn qmboc_levels_after(
        &self,
        s0: u64,
        count: usize,
        (out_i, out_q): (&mut Vec<f32>, &mut Vec<f32>),
        cached: &mut Option<(u64, u8)>,
    ) {
        let table = [
            b1c_qmboc(1, 1),
            b1c_qmboc(1, -1),
            b1c_qmboc(-1, 1),
            b1c_qmboc(-1, -1),
        ];
        out_i.reserve(count);
        out_q.reserve(count);
        self.subchip_spans(s0, count, cached, |row, span| {
            out_i.extend_from_slice(&table[row].0[span.clone()]);
            out_q.extend_from_slice(&table[row].1[span]);
        });
    }

    /// For each chip touched by sub-chips `s0 .. s0 + count`, in order: `emit(row, span)`
    /// with `row` = 2 (data < 0) + (pilot < 0) and the chip's sub-chips inside the span.
    fn subchip_spans(
        &self,
        s0: u64,
        count: usize,
        cached: &mut Option<(u64, u8)>,
        mut emit: impl FnMut(usize, std::ops::Range<usize>),
    ) {
        if count == 0 {
            return;
        }
        let sub = CBOC_SUBCHIPS as u64;
        let (c0, c1) = (s0 / sub, (s0 + count as u64 - 1) / sub + 1);
        let (mut data, mut pilot) = (Vec::new(), Vec::new());
        self.chip_signs_after(c0, (c1 - c0) as usize, &mut data, cached);
        self.pilot_chip_signs(c0, (c1 - c0) as usize, &mut pilot);
        let end = s0 + count as u64;
        for (j, (&d, &p)) in data.iter().zip(&pilot).enumerate() {
            let first = (c0 + j as u64) * sub;
            let (from, to) = (s0.max(first) - first, end.min(first + sub) - first);
            emit(
                2 * usize::from(d < 0) + usize::from(p < 0),
                from as usize..to as usize,
            );
        }
    }

    /// Append the signed chips `k0 .. k0 + count` (absolute indices, data bits and any
    /// secondary code applied) to `out`; data and secondary code are looked up once per
    /// code period, not per chip.
    pub fn chip_signs(&self, k0: u64, count: usize, out: &mut Vec<i8>) {
        self.chip_signs_after(k0, count, out, &mut None);
    }

    /// [`Self::chip_signs`] with the last data bit looked up (`(bit index, bit)`) kept in
    /// `cached` between calls: a caller going through consecutive blocks encodes each
    /// navigation subframe once per bit, not once per block.
    pub fn chip_signs_after(
        &self,
        k0: u64,
        count: usize,
        out: &mut Vec<i8>,
        cached: &mut Option<(u64, u8)>,
    ) {
        let per_bit = self.data.periods_per_bit();
        spread_periods(&self.code, k0, count, out, |period| {
            let b = period / per_bit;
            let bit = match *cached {
                Some((cb, v)) if cb == b => v,
                _ => {
                    let v = self.data.bit(b);
                    *cached = Some((b, v));
                    v
                }
            };
            let data_sign: i8 = if bit == 1 { -1 } else { 1 };
            data_sign * self.data.secondary(period)
        });
    }

    /// Append the pilot's signed chips `k0 .. k0 + count` (secondary code applied) to
    /// `out`; nothing when the signal has no pilot.
    pub fn pilot_chip_signs(&self, k0: u64, count: usize, out: &mut Vec<i8>) {
        let Some(pilot) = &self.pilot else { return };
        let secondary = &pilot.secondary;
        spread_periods(&pilot.code, k0, count, out, |period| {
            secondary[(period % secondary.len() as u64) as usize]
        });
    }
}

/// A non-negative span as whole seconds and the fraction of a second; `None` before
/// the time scale's epoch or the encoder's week start.
fn seconds_since(span: Duration) -> Option<(u64, f64)> {
    let ns = span.total_nanoseconds();
    (ns >= 0).then_some((
        (ns / 1_000_000_000) as u64,
        (ns % 1_000_000_000) as f64 * 1e-9,
    ))
}

/// Append chips `k0 .. k0 + count` (absolute indices) of the repeating primary `code` to
/// `out`, each code period `p` multiplied by `sign_of(p)`, looked up once per period.
fn spread_periods(
    code: &[i8],
    k0: u64,
    count: usize,
    out: &mut Vec<i8>,
    mut sign_of: impl FnMut(u64) -> i8,
) {
    let len = code.len() as u64;
    let (mut k, end) = (k0, k0 + count as u64);
    while k < end {
        let period = k / len;
        let sign = sign_of(period);
        let stop = ((period + 1) * len).min(end);
        let (from, to) = ((k - period * len) as usize, (stop - period * len) as usize);
        out.extend(code[from..to].iter().map(|&c| sign * c));
        k = stop;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use hifitime::{Epoch, TimeScale};
    use skyforge_gnss::codes::{GPS_L5_I_NH10, GPS_L5_Q_NH20, gps_l5_q};
    use skyforge_gnss::navmsg::gps_cnav::CnavParams;
    use skyforge_orbits::ephemeris::{System, nominal};

    /// GPS L5 chips against a direct evaluation of IS-GPS-705 §3.3.2: I5 chip k of the
    /// week is I5[k mod 10230] x NH10[period mod 10] x the CNAV symbol of its 10 ms, Q5
    /// chip k is Q5[k mod 10230] x NH20[period mod 20]; the first symbol of a message is
    /// the encoder's first symbol of that message.
    #[test]
    fn gps_l5_chips_follow_the_codes_the_nh_codes_and_the_cnav_symbols() {
        let start = Epoch::from_gregorian(2023, 3, 12, 0, 0, 0, 0, TimeScale::GPST);
        let eph = nominal::gps(start)
            .into_iter()
            .map(|e| {
                let grid = |t| System::Gps.on_grid(t, 300.0);
                e.reexpressed(grid(e.toe), grid(e.toc)).expect("on grid")
            })
            .next()
            .expect("a GPS set");
        let week = skyforge_orbits::time::gpst_week_sow(start).0 - 1;
        let nav = CnavEncoder::new(&eph, &CnavParams::default(), week).expect("encoder");
        let symbols = nav.clone();
        let tx = Transmitter::gps_l5(eph.sat, nav, start).expect("L5");
        assert!(tx.has_pilot() && Signal::GpsL5.has_pilot());
        let (i5, q5) = (
            gps_l5_i(eph.sat.prn).unwrap(),
            gps_l5_q(eph.sat.prn).unwrap(),
        );
        let len = i5.len() as u64;
        // The scenario start is one week (604800 s) after symbol 0.
        let (k_start, phase) = tx.chip_at(0.0);
        assert_eq!((k_start, phase), (604_800 * 10_230_000, 0.0));
        // Spans across symbol, NH and message edges (a message is 6 s, 600 symbols).
        for k0 in [
            k_start,
            k_start + 6 * 10_230_000 - 5_000,
            k_start + 123_456_789,
        ] {
            let count = 3 * len as usize;
            let (mut data, mut pilot) = (Vec::new(), Vec::new());
            tx.chip_signs(k0, count, &mut data);
            tx.pilot_chip_signs(k0, count, &mut pilot);
            for (j, (&d, &p)) in data.iter().zip(&pilot).enumerate() {
                let k = k0 + j as u64;
                let period = k / len;
                let symbol = symbols.symbol(period / 10);
                let expect_d = i5[(k % len) as usize]
                    * GPS_L5_I_NH10[(period % 10) as usize]
                    * (1 - 2 * symbol as i8);
                let expect_p = q5[(k % len) as usize] * GPS_L5_Q_NH20[(period % 20) as usize];
                assert_eq!((d, p), (expect_d, expect_p), "chip {k}");
            }
        }
        let n = 604_800 / 6 + 1;
        assert_eq!(symbols.symbol(600 * n), symbols.message_symbols(n)[0]);
        assert_eq!(tx.broadcast_ephemeris(), symbols.broadcast_ephemeris());
        assert_eq!(
            tx.broadcast_iono(),
            Some((symbols.iono().alpha, symbols.iono().beta))
        );
    }

    /// BeiDou B2a chips against a direct evaluation of BDS-SIS-ICD-B2a-1.0 §5.2 and §6.2.1:
    /// B2a_d chip k of the BDT week is data[k mod 10230] x 00010[period mod 5] x the
    /// B-CNAV2 symbol of its 5 ms, B2a_p chip k is pilot[k mod 10230] x the PRN's 100-chip
    /// secondary code[period mod 100]; a frame's preamble starts on a BDT multiple of 3 s
    /// (its SOW) and despreads from the data chips there.
    #[test]
    fn bds_b2a_chips_follow_the_codes_the_secondary_codes_and_the_cnav2_symbols() {
        use skyforge_gnss::codes::{
            BDS_B2A_DATA_SECONDARY, bds_b2a_pilot, bds_b2a_pilot_secondary,
        };
        use skyforge_gnss::navmsg::BdsCnavParams;
        use skyforge_gnss::navmsg::bds_cnav2::CNAV2_PREAMBLE;
        use skyforge_orbits::ephemeris::BeidouSet;
        let start = Epoch::from_gregorian(2023, 3, 12, 0, 0, 0, 0, TimeScale::GPST);
        let eph = nominal::beidou(BeidouSet::Bds3, start)
            .into_iter()
            .find(|e| e.sat.prn == 19)
            .map(|e| {
                let grid = |t| System::Beidou.on_grid(t, 300.0);
                e.reexpressed(grid(e.toe), grid(e.toc)).expect("on grid")
            })
            .expect("C19");
        let week = skyforge_orbits::time::bdt_week_sow(start).0 - 1;
        let nav = BdsCnav2Encoder::new(&eph, &BdsCnavParams::default(), week).expect("encoder");
        let symbols = nav.clone();
        let tx = Transmitter::bds_b2a(eph.sat, nav, start).expect("B2a");
        assert!(tx.has_pilot() && tx.signal == Signal::BdsB2a);
        let (data, pilot) = (
            bds_b2a_data(eph.sat.prn).unwrap(),
            bds_b2a_pilot(eph.sat.prn).unwrap(),
        );
        let secondary = bds_b2a_pilot_secondary(eph.sat.prn).unwrap();
        let len = data.len() as u64;
        // 2023-03-12 00:00 GPST is 23:59:46 BDT on the 11th, 14 s before a BDT week's
        // end; symbol 0 is one BDT week earlier still.
        let start_s = 2 * 604_800 - 14;
        let (k_start, phase) = tx.chip_at(0.0);
        assert_eq!((k_start, phase), (start_s * 10_230_000, 0.0));
        // Spans across symbol (5 ms), pilot secondary (100 ms) and frame (3 s) edges.
        for k0 in [
            k_start,
            k_start + 3 * 10_230_000 - 5_000,
            k_start + 123_456_789,
        ] {
            let count = 3 * len as usize;
            let (mut d, mut p) = (Vec::new(), Vec::new());
            tx.chip_signs(k0, count, &mut d);
            tx.pilot_chip_signs(k0, count, &mut p);
            // One symbol looked up per period (each look-up encodes its frame).
            let mut symbol_of = (u64::MAX, 0u8);
            for (j, (&d, &p)) in d.iter().zip(&p).enumerate() {
                let k = k0 + j as u64;
                let period = k / len;
                if symbol_of.0 != period / 5 {
                    symbol_of = (period / 5, symbols.symbol(period / 5));
                }
                let symbol = symbol_of.1;
                let expect_d = data[(k % len) as usize]
                    * BDS_B2A_DATA_SECONDARY[(period % 5) as usize]
                    * (1 - 2 * symbol as i8);
                let expect_p = pilot[(k % len) as usize] * secondary[(period % 100) as usize];
                assert_eq!((d, p), (expect_d, expect_p), "chip {k}");
            }
        }
        // The first frame after the start: at BDT SOW 604788 (2 s after the start's
        // 604786, the next multiple of 3), its 24 preamble symbols despread from the data
        // chips.
        let n = start_s.div_ceil(3);
        assert_eq!(symbols.frame_time(n), (week + 1, 604_788));
        let first_chip = n * 3 * 10_230_000;
        let mut chips = Vec::new();
        tx.chip_signs(first_chip, 24 * 5 * len as usize, &mut chips);
        let despread: u32 = chips
            .chunks(len as usize)
            .enumerate()
            .map(|(period, c)| {
                let sum: i64 = c.iter().zip(&data).map(|(&a, &b)| i64::from(a * b)).sum();
                sum * i64::from(BDS_B2A_DATA_SECONDARY[period % 5])
            })
            .collect::<Vec<_>>()
            .chunks(5)
            .fold(0, |acc, s| {
                assert!(s.iter().all(|&x| x == s[0] && x.abs() == len as i64));
                (acc << 1) | u32::from(s[0] < 0)
            });
        assert_eq!(despread, CNAV2_PREAMBLE);
        assert_eq!(tx.broadcast_ephemeris(), symbols.broadcast_ephemeris());
        assert_eq!(tx.broadcast_iono(), None);
    }

    /// A B1C transmitter for C30 of the BDS-3 set at 2023-03-12 00:00 GPST, its encoder.
    fn b1c_c30() -> (Transmitter, BdsCnav1Encoder) {
        use skyforge_gnss::navmsg::BdsCnavParams;
        use skyforge_orbits::ephemeris::BeidouSet;
        let start = Epoch::from_gregorian(2023, 3, 12, 0, 0, 0, 0, TimeScale::GPST);
        let eph = nominal::beidou(BeidouSet::Bds3, start)
            .into_iter()
            .find(|e| e.sat.prn == 30)
            .map(|e| {
                let grid = |t| System::Beidou.on_grid(t, 300.0);
                e.reexpressed(grid(e.toe), grid(e.toc)).expect("on grid")
            })
            .expect("C30");
        let week = skyforge_orbits::time::bdt_week_sow(start).0 - 1;
        let nav = BdsCnav1Encoder::new(&eph, &BdsCnavParams::default(), week).expect("encoder");
        let tx = Transmitter::bds_b1c(eph.sat, nav.clone(), start).expect("B1C");
        (tx, nav)
    }

    /// BeiDou B1C chips against BDS-SIS-ICD-B1C-1.0 §5.2 and §6.2.1: B1C_data chip k of
    /// the BDT week is data[k mod 10230] x the B-CNAV1 symbol of its 10 ms period, B1C_pilot
    /// chip k is pilot[k mod 10230] x secondary[period mod 1800]; the frame starting at the
    /// first BDT multiple of 18 s after the start, despread from the data chips, decodes
    /// (BCH, LDPC, CRC) to the transmitter's ephemeris and that SOW.
    #[test]
    fn bds_b1c_chips_follow_the_codes_the_secondary_code_and_the_cnav1_frames() {
        use skyforge_gnss::codes::{bds_b1c_pilot, bds_b1c_pilot_secondary};
        use skyforge_gnss::navmsg::bds_cnav1::decode_frame;
        let (tx, nav) = b1c_c30();
        assert!(tx.has_pilot() && tx.subchips_per_chip() == 12);
        let prn = tx.sat.prn;
        let (data, pilot) = (bds_b1c_data(prn).unwrap(), bds_b1c_pilot(prn).unwrap());
        let secondary = bds_b1c_pilot_secondary(prn).unwrap();
        let len = data.len() as u64;
        // The start, 23:59:46 BDT on the 11th, is 14 s before a BDT week's end, and symbol
        // 0 one BDT week earlier still.
        let start_s = 2 * 604_800 - 14;
        assert_eq!(tx.chip_at(0.0), (start_s * 1_023_000, 0.0));
        for k0 in [start_s * 1_023_000, 604_800 * 1_023_000 - 7_000] {
            let count = 3 * len as usize;
            let (mut d, mut p) = (Vec::new(), Vec::new());
            tx.chip_signs(k0, count, &mut d);
            tx.pilot_chip_signs(k0, count, &mut p);
            for (j, (&d, &p)) in d.iter().zip(&p).enumerate() {
                let k = k0 + j as u64;
                let period = k / len;
                let symbol = nav.symbol(period);
                let expect_d = data[(k % len) as usize] * (1 - 2 * symbol as i8);
                let expect_p = pilot[(k % len) as usize] * secondary[(period % 1800) as usize];
                assert_eq!((d, p), (expect_d, expect_p), "chip {k}");
            }
        }
        // The frame at BDT SOW 0 of the next week (its first symbol 14 s after the start).
        let n = start_s.div_ceil(18);
        assert_eq!(nav.frame_time(n), (nav.week() + 2, 0));
        let mut chips = Vec::new();
        tx.chip_signs(n * 18 * 1_023_000, 1800 * len as usize, &mut chips);
        let soft: Vec<f32> = chips
            .chunks(len as usize)
            .map(|c| c.iter().zip(&data).map(|(&a, &b)| f32::from(a * b)).sum())
            .collect();
        let frame = decode_frame(&soft, prn).expect("a frame");
        assert_eq!(frame.time(), Some(nav.frame_time(n)));
        assert_eq!(frame.ephemeris(tx.sat), Some(tx.broadcast_ephemeris()));
    }

    /// B1C's QMBOC sub-chips: for each sub-chip, the ICD's `I = d sc_a / 2 + sqrt(1/11) p
    /// sc_b` and `Q = sqrt(29/44) p sc_a` from the transmitter's own data and pilot chips
    /// (BDS-SIS-ICD-B1C-1.0 §4.2.2), sub-carriers from the sub-chip's middle.
    #[test]
    fn bds_b1c_sub_chips_follow_the_qmboc_definition() {
        let (tx, _) = b1c_c30();
        let (s_start, _) = tx.subchip_at(0.0);
        let s0 = s_start + 7;
        let count = 2 * 122_760 + 5;
        let (mut i, mut q) = (Vec::new(), Vec::new());
        tx.qmboc_levels_after(s0, count, (&mut i, &mut q), &mut None);
        assert_eq!((i.len(), q.len()), (count, count));
        let c0 = s0 / 12;
        let chips = (s0 + count as u64).div_ceil(12) - c0;
        let (mut d, mut p) = (Vec::new(), Vec::new());
        tx.chip_signs(c0, chips as usize, &mut d);
        tx.pilot_chip_signs(c0, chips as usize, &mut p);
        let sign = |x: f64| if x > 0.0 { 1.0 } else { -1.0 };
        for (n, (&li, &lq)) in i.iter().zip(&q).enumerate() {
            let s = s0 + n as u64;
            let j = (s / 12 - c0) as usize;
            let t = ((s % 12) as f64 + 0.5) / 12.0;
            let a = sign((std::f64::consts::TAU * t).sin());
            let b = sign((std::f64::consts::TAU * 6.0 * t).sin());
            let (dj, pj) = (f64::from(d[j]), f64::from(p[j]));
            let ei = 0.5 * dj * a + (1.0f64 / 11.0).sqrt() * pj * b;
            let eq = (29.0f64 / 44.0).sqrt() * pj * a;
            assert!((f64::from(li) - ei).abs() < 1e-6, "I sub-chip {s}");
            assert!((f64::from(lq) - eq).abs() < 1e-6, "Q sub-chip {s}");
        }
    }

    /// Made-up E1 code tables (pseudo-random, not the ICD's) read back unchecked.
    fn made_up_e1_codes() -> E1Codes {
        let dir = tempfile::tempdir().expect("tempdir");
        let mut x: u32 = 7;
        for name in ["galileo_e1b.txt", "galileo_e1c.txt"] {
            let mut text = String::new();
            for n in 1..=50 {
                let digits: String = (0..1023)
                    .map(|_| {
                        x = x.wrapping_mul(1_103_515_245).wrapping_add(12345);
                        char::from_digit((x >> 16) & 15, 16).unwrap()
                    })
                    .collect();
                text.push_str(&format!("{n} {digits}\n"));
            }
            std::fs::write(dir.path().join(name), text).expect("table");
        }
        E1Codes::from_dir(dir.path(), false).expect("made-up tables")
    }

    /// Galileo E1 sub-chips against a direct evaluation of the ICD's E1 signal (§2.3.3):
    /// sub-chip s of the week lies in chip j = s / 12 of period p = j / 4092, and is
    /// (1/sqrt 2) [d (alpha a + beta b) - c (alpha a - beta b)] with d = E1-B[j mod 4092] x
    /// the I/NAV symbol of period p, c = E1-C[j mod 4092] x CS25[p mod 25], a and b the
    /// signs of sin(2 pi f t) at the sub-chip's middle for f = 1.023 and 6.138 MHz.
    #[test]
    fn galileo_e1_sub_chips_follow_the_cboc_definition() {
        let start = Epoch::from_gregorian(2023, 3, 12, 0, 0, 0, 0, TimeScale::GPST);
        let codes = made_up_e1_codes();
        let eph = nominal::galileo(start)
            .into_iter()
            .map(|e| {
                let grid = |t| System::Galileo.on_grid(t, 60.0);
                e.reexpressed(grid(e.toe), grid(e.toc)).expect("on grid")
            })
            .next()
            .expect("a Galileo set");
        let week = skyforge_orbits::time::gpst_week_sow(start).0
            - skyforge_orbits::time::GST_WEEK0_IN_GPS_WEEKS
            - 1;
        let nav = InavEncoder::new(
            &eph,
            std::slice::from_ref(&eph),
            &skyforge_gnss::navmsg::galileo_inav::InavParams::default(),
            week,
        )
        .expect("encoder");
        let tx = Transmitter::gal_e1(eph.sat, nav.clone(), &codes, start).expect("E1");
        assert_eq!(tx.subchips_per_chip(), 12);
        let (b, c) = (
            codes.data(eph.sat.prn).unwrap(),
            codes.pilot(eph.sat.prn).unwrap(),
        );
        let (alpha, beta) = ((10.0f64 / 11.0).sqrt(), (1.0f64 / 11.0).sqrt());
        let sign = |x: f64| if x > 0.0 { 1.0 } else { -1.0 };
        let (s_start, phase) = tx.subchip_at(0.0);
        assert_eq!((s_start, phase), (604_800 * 12_276_000, 0.0));
        // Spans across symbol (4 ms) and CS25 (100 ms) edges.
        for s0 in [s_start, s_start + 100 * 49_104 - 777, s_start + 1_234_567] {
            let mut levels = Vec::new();
            tx.cboc_levels_after(s0, 3 * 49_104, &mut levels, &mut None);
            for (n, &level) in levels.iter().enumerate() {
                let s = s0 + n as u64;
                let (j, k) = (s / 12, (s % 12) as f64);
                let (p, i) = (j / 4092, (j % 4092) as usize);
                let d = f64::from(b[i]) * (1.0 - 2.0 * f64::from(nav.symbol(p)));
                let pl = f64::from(c[i]) * f64::from(GALILEO_E1_C_SECONDARY[(p % 25) as usize]);
                let t = (k + 0.5) / 12.0;
                let a = sign((std::f64::consts::TAU * t).sin());
                let bb = sign((std::f64::consts::TAU * 6.0 * t).sin());
                let expect = (d * (alpha * a + beta * bb) - pl * (alpha * a - beta * bb))
                    / std::f64::consts::SQRT_2;
                assert!((f64::from(level) - expect).abs() < 1e-6, "sub-chip {s}");
            }
        }
        assert_eq!(tx.broadcast_ephemeris(), nav.broadcast_ephemeris());
    }
}
