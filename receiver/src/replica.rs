//! The ranging codes a channel correlates with, and the chips of their replicas.
//!
//! A BPSK signal's replica is its code. BeiDou B1C's data is BOC(1,1) and its pilot
//! QMBOC(6,1,4/33), whose BOC(1,1) part (29/33 of the pilot) the receiver tracks with the
//! same half-chip replicas as E1's. Galileo E1 is CBOC(6,1,1/11); the receiver
//! correlates with its BOC(1,1) part only ([`Signal::replica_boc11`]): each chip `c` as two
//! half-chips `+c, -c` at twice the chip rate (the BOC(1,1) sub-carrier starts a chip
//! positive, `gnss::subcarrier::boc11`). The BOC(6,1) part carries 1/11 of the power and is
//! orthogonal to the BOC(1,1) replica at zero offset (each half-chip holds three of its
//! periods), so the correlation keeps 10/11 of the power: 0.41 dB lost (Galileo OS SIS ICD
//! §2.3.3). Code phases and rates stay in chips of the 1.023 Mchip/s code everywhere
//! outside the correlation kernels.

use skyforge_gnss::codes::{E1Codes, GALILEO_E1_C_SECONDARY, GALILEO_E1_PRN_MAX};
use skyforge_gnss::signal::{PilotCodes, Signal, UnknownPrn};

/// 10 log10(11/10): the CBOC power a BOC(1,1) replica does not see (dB).
pub const BOC61_SHARE_DB: f64 = 0.413_926_851_582_250_4;
/// 10 log10(44/29): the B1C power outside its pilot's BOC(1,1) part, the part tracked (the
/// data's 1/4 and the pilot's BOC(6,1) 1/11, BDS-SIS-ICD-B1C-1.0 §4.2.2) (dB).
pub const B1C_PILOT_BOC11_SHARE_DB: f64 = 1.810_546_785_872_313;

/// One PRN's codes: the data component's primary code and, for a signal with a pilot,
/// the pilot's primary and secondary codes (signal levels, one period each).
#[derive(Debug, Clone, PartialEq)]
pub struct SignalCodes {
    /// The data (or only) component's primary code.
    pub data: Vec<i8>,
    /// The pilot's codes, for a signal with one ([`Signal::has_pilot`]).
    pub pilot: Option<PilotCodes>,
}

impl SignalCodes {
    /// The codes of `signal`'s `prn` as SkyForge generates or reads them (Galileo E1's from
    /// the tables `SKYFORGE_GALILEO_E1_CODES` names).
    pub fn of(signal: Signal, prn: u8) -> Result<Self, UnknownPrn> {
        Ok(Self {
            data: signal.code(prn)?,
            pilot: if signal.has_pilot() {
                Some(signal.pilot(prn)?)
            } else {
                None
            },
        })
    }

    /// Galileo E1's codes of `prn` from tables the caller read ([`E1Codes::from_dir`]).
    pub fn galileo_e1(tables: &E1Codes, prn: u8) -> Result<Self, UnknownPrn> {
        let unknown = UnknownPrn {
            signal: Signal::GalE1,
            prn,
            max: GALILEO_E1_PRN_MAX,
        };
        let (data, pilot) = tables.data(prn).zip(tables.pilot(prn)).ok_or(unknown)?;
        Ok(Self {
            data: data.to_vec(),
            pilot: Some(PilotCodes {
                primary: pilot.to_vec(),
                secondary: GALILEO_E1_C_SECONDARY.to_vec(),
            }),
        })
    }
}

/// Replica chips per code chip: 2 for a BOC(1,1) replica, else 1.
pub fn subchips(signal: Signal) -> usize {
    if signal.replica_boc11() { 2 } else { 1 }
}

/// The replica of one period of `code` for `signal`: the code itself, or for a BOC(1,1)
/// replica each chip as its half-chips `+c, -c` ([`subchips`] times as long).
pub fn replica_chips(signal: Signal, code: &[i8]) -> Vec<i8> {
    if signal.replica_boc11() {
        code.iter().flat_map(|&c| [c, -c]).collect()
    } else {
        code.to_vec()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A fixed pseudo-random +-1 code (LCG).
    fn code(n: usize, seed: u32) -> Vec<i8> {
        let mut x = seed;
        (0..n)
            .map(|_| {
                x = x.wrapping_mul(1_103_515_245).wrapping_add(12_345);
                if x >> 31 == 0 { 1 } else { -1 }
            })
            .collect()
    }

    /// The normalised circular autocorrelation of a BOC(1,1) replica, sampled at `per_half`
    /// samples per half-chip, at a lag of `lag` samples.
    fn autocorrelation(replica: &[i8], per_half: usize, lag: usize) -> f64 {
        let sampled: Vec<f64> = replica
            .iter()
            .flat_map(|&c| std::iter::repeat_n(f64::from(c), per_half))
            .collect();
        let n = sampled.len();
        (0..n)
            .map(|i| sampled[i] * sampled[(i + lag) % n])
            .sum::<f64>()
            / n as f64
    }

    /// The BOC(1,1) replica's autocorrelation, computed over a 4092-chip random code:
    /// 1 at zero, zero at +-1/3 chip, -1/2 at +-1/2 chip (the side peaks), zero from one
    /// chip on; in between `1 - 3|x|` then `|x| - 1` (Betz, "Binary Offset Carrier
    /// Modulations for Radionavigation", Navigation 48(4), 2001), within the code's
    /// random cross terms (about 1/sqrt(4092)).
    #[test]
    fn the_b1c_share_is_the_icds() {
        assert!((B1C_PILOT_BOC11_SHARE_DB - 10.0 * (44.0f64 / 29.0).log10()).abs() < 1e-12);
        assert!((BOC61_SHARE_DB - 10.0 * (11.0f64 / 10.0).log10()).abs() < 1e-12);
        assert_eq!(subchips(Signal::BdsB1C), 2);
    }

    #[test]
    fn the_boc11_replica_has_its_autocorrelation() {
        let chips = code(4092, 7);
        let replica = replica_chips(Signal::GalE1, &chips);
        assert_eq!(replica.len(), 8184);
        assert_eq!(&replica[..4], &[chips[0], -chips[0], chips[1], -chips[1]]);
        assert_eq!(replica_chips(Signal::GalE5a, &chips), chips);
        assert_eq!((subchips(Signal::GalE1), subchips(Signal::GpsL1Ca)), (2, 1));
        // 6 samples per half-chip: 12 per chip, so thirds and halves are whole lags.
        let per_half = 6;
        let n = replica.len() * per_half;
        let ideal = |x: f64| {
            let x = x.abs();
            if x <= 0.5 {
                1.0 - 3.0 * x
            } else if x <= 1.0 {
                x - 1.0
            } else {
                0.0
            }
        };
        let tolerance = 3.0 / 4092f64.sqrt();
        for (lag_chips, expected) in [
            (0.0, 1.0),
            (1.0 / 6.0, 0.5),
            (1.0 / 3.0, 0.0),
            (0.5, -0.5),
            (0.75, -0.25),
            (1.0, 0.0),
            (2.0, 0.0),
        ] {
            assert!((ideal(lag_chips) - expected).abs() < 1e-12);
            for sign in [1.0, -1.0] {
                let lag = ((sign * lag_chips * 12.0) as i64).rem_euclid(n as i64) as usize;
                let r = autocorrelation(&replica, per_half, lag);
                assert!(
                    (r - expected).abs() < tolerance,
                    "lag {} chips: {r} vs {expected}",
                    sign * lag_chips
                );
            }
        }
        // Exactly 1 at zero lag.
        assert_eq!(autocorrelation(&replica, 1, 0), 1.0);
    }

    /// The E1 codes of made-up tables, and refusals outside 1-50.
    #[test]
    fn e1_codes_come_from_the_tables() {
        let dir = tempfile::tempdir().unwrap();
        for (name, digit) in [("galileo_e1b.txt", 'a'), ("galileo_e1c.txt", '3')] {
            let text: String = (1..=50)
                .map(|n| format!("{n} {}\n", String::from(digit).repeat(1023)))
                .collect();
            std::fs::write(dir.path().join(name), text).unwrap();
        }
        let tables = E1Codes::from_dir(dir.path(), false).unwrap();
        let codes = SignalCodes::galileo_e1(&tables, 4).unwrap();
        assert_eq!(&codes.data[..4], &[-1, 1, -1, 1]);
        let pilot = codes.pilot.unwrap();
        assert_eq!(&pilot.primary[..4], &[1, 1, -1, -1]);
        assert_eq!(pilot.secondary.len(), 25);
        assert!(SignalCodes::galileo_e1(&tables, 51).is_err());
        assert!(SignalCodes::galileo_e1(&tables, 0).is_err());
    }
}
