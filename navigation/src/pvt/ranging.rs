//! One ranging per satellite from the signals it was measured on: the single signal the
//! broadcast ionosphere model corrects, or the ionosphere-free combination of two signals
//! on different carriers (the dual-frequency user's).

use super::Measurement;
use skyforge_gnss::signal::Signal;
use skyforge_orbits::ephemeris::SatId;

/// How the solver removes the ionospheric delay.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum IonosphereCorrection {
    /// One signal per satellite (its system's default signal where measured, otherwise the
    /// first given) with the broadcast Klobuchar model.
    #[default]
    Broadcast,
    /// The ionosphere-free combination of the two signals of each satellite whose carriers
    /// lie farthest apart (GPS L1 C/A + L5, Galileo E1 + E5a); a satellite measured on one
    /// carrier only is left out, as a dual-frequency receiver leaves it.
    DualFrequency,
}

/// The pseudorange the solver ranges to one satellite with.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Ranging {
    pub sat: SatId,
    /// Pseudorange (m): of `signal`, or the ionosphere-free combination of `signal` and
    /// `second`.
    pub pseudorange_m: f64,
    /// The signal measured (the higher carrier of a combination).
    pub signal: Signal,
    /// The second signal of an ionosphere-free combination.
    pub second: Option<Signal>,
}

impl Ranging {
    fn single(m: &Measurement) -> Self {
        Self {
            sat: m.sat,
            pseudorange_m: m.pseudorange_m,
            signal: m.signal,
            second: None,
        }
    }

    /// The coefficients (a, b) of the ionosphere-free combination `a P_hi - b P_lo` of two
    /// signals, carriers `f_hi > f_lo`: a = f_hi^2 / (f_hi^2 - f_lo^2), b = a - 1, so that
    /// the 1/f^2 delay cancels and the geometry keeps unit weight: IS-GPS-200 20.3.3.3.3.3's
    /// `PR = (PR_L2 - gamma PR_L1) / (1 - gamma)`, gamma = (f_L1 / f_L2)^2, for any pair.
    pub fn iono_free_coefficients(hi: Signal, lo: Signal) -> (f64, f64) {
        let (f1, f2) = (hi.carrier_hz().powi(2), lo.carrier_hz().powi(2));
        let a = f1 / (f1 - f2);
        (a, a - 1.0)
    }

    /// How much larger the pseudorange's noise is than one signal's, for equal noise on
    /// both signals of a combination: sqrt(a^2 + b^2); 1 for a single signal.
    pub fn noise_factor(&self) -> f64 {
        match self.second {
            Some(lo) => {
                let (a, b) = Self::iono_free_coefficients(self.signal, lo);
                a.hypot(b)
            }
            None => 1.0,
        }
    }

    /// The clock offset (s) by which this ranging's signal runs later than its first
    /// signal's, given each signal's offset `of(signal)` (group delays combine as the
    /// pseudoranges do).
    pub fn combined(&self, of: impl Fn(Signal) -> f64) -> f64 {
        match self.second {
            Some(lo) => {
                let (a, b) = Self::iono_free_coefficients(self.signal, lo);
                a * of(self.signal) - b * of(lo)
            }
            None => of(self.signal),
        }
    }
}

/// One ranging per satellite of `meas`, in the order each satellite first appears.
pub(crate) fn per_satellite(
    meas: &[Measurement],
    correction: IonosphereCorrection,
) -> Vec<Ranging> {
    let mut sats: Vec<SatId> = Vec::new();
    for m in meas {
        if !sats.contains(&m.sat) {
            sats.push(m.sat);
        }
    }
    sats.iter()
        .filter_map(|&sat| {
            let of_sat: Vec<&Measurement> = meas.iter().filter(|m| m.sat == sat).collect();
            match correction {
                IonosphereCorrection::Broadcast => Some(Ranging::single(preferred(&of_sat))),
                IonosphereCorrection::DualFrequency => iono_free(&of_sat),
            }
        })
        .collect()
}

/// The system's default signal where measured, otherwise the first.
fn preferred<'m>(of_sat: &[&'m Measurement]) -> &'m Measurement {
    of_sat
        .iter()
        .find(|m| m.signal.is_default_fix())
        .unwrap_or(&of_sat[0])
}

/// The ionosphere-free combination of the two measurements whose carriers lie farthest
/// apart, or `None` when every measurement is on one carrier.
fn iono_free(of_sat: &[&Measurement]) -> Option<Ranging> {
    let mut best: Option<(f64, &Measurement, &Measurement)> = None;
    for (i, hi) in of_sat.iter().enumerate() {
        for lo in &of_sat[i + 1..] {
            let (hi, lo) = if hi.signal.carrier_hz() >= lo.signal.carrier_hz() {
                (*hi, *lo)
            } else {
                (*lo, *hi)
            };
            let gap = hi.signal.carrier_hz() - lo.signal.carrier_hz();
            if gap > 0.0 && best.is_none_or(|(g, _, _)| gap > g) {
                best = Some((gap, hi, lo));
            }
        }
    }
    let (_, hi, lo) = best?;
    let (a, b) = Ranging::iono_free_coefficients(hi.signal, lo.signal);
    Some(Ranging {
        sat: hi.sat,
        pseudorange_m: a * hi.pseudorange_m - b * lo.pseudorange_m,
        signal: hi.signal,
        second: Some(lo.signal),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn m(prn: u8, signal: Signal, pseudorange_m: f64) -> Measurement {
        Measurement {
            sat: SatId::gps(prn),
            pseudorange_m,
            doppler_hz: None,
            signal,
        }
    }

    /// A delay of 1/f^2 cancels in the combination and a common range passes unchanged.
    #[test]
    fn the_combination_cancels_a_delay_in_inverse_square_of_frequency() {
        let (rho, i1) = (2.2e7, 7.3);
        let f1 = Signal::GpsL1Ca.carrier_hz();
        let delay = |s: Signal| i1 * (f1 / s.carrier_hz()).powi(2);
        let meas = [
            m(3, Signal::GpsL5, rho + delay(Signal::GpsL5)),
            m(3, Signal::GpsL1Ca, rho + delay(Signal::GpsL1Ca)),
            m(3, Signal::GpsL2, rho + delay(Signal::GpsL2)),
            m(8, Signal::GpsL1Ca, rho),
        ];
        let r = per_satellite(&meas, IonosphereCorrection::DualFrequency);
        assert_eq!(r.len(), 1, "G08 has one carrier: left out");
        assert_eq!(
            (r[0].signal, r[0].second),
            (Signal::GpsL1Ca, Some(Signal::GpsL5)),
            "the carriers farthest apart"
        );
        assert!(
            (r[0].pseudorange_m - rho).abs() < 1e-6,
            "{}",
            r[0].pseudorange_m - rho
        );
        // L1/L5: a = 2.2606, b = 1.2606 (f = 154 and 115 times 10.23 MHz).
        let g = (154.0f64 / 115.0).powi(2);
        let (a, b) = Ranging::iono_free_coefficients(Signal::GpsL1Ca, Signal::GpsL5);
        assert!((a - g / (g - 1.0)).abs() < 1e-12 && (b - 1.0 / (g - 1.0)).abs() < 1e-12);
        assert!((r[0].noise_factor() - a.hypot(b)).abs() < 1e-15);
        // The group delays combine as the pseudoranges: a delay on L1 alone scales by a.
        let d = r[0].combined(|s| if s == Signal::GpsL1Ca { 1e-9 } else { 0.0 });
        assert!((d - a * 1e-9).abs() < 1e-21);
    }

    /// The broadcast model takes one signal per satellite, the default one where measured,
    /// in the order the satellites first appear.
    #[test]
    fn one_signal_per_satellite_prefers_the_default() {
        let meas = [
            m(5, Signal::GpsL5, 1.0),
            m(2, Signal::GpsL5, 2.0),
            m(5, Signal::GpsL1Ca, 3.0),
        ];
        let r = per_satellite(&meas, IonosphereCorrection::Broadcast);
        let got: Vec<(u8, Signal, Option<Signal>)> =
            r.iter().map(|r| (r.sat.prn, r.signal, r.second)).collect();
        assert_eq!(got, [(5, Signal::GpsL1Ca, None), (2, Signal::GpsL5, None)]);
        assert_eq!(r[0].pseudorange_m, 3.0);
    }
}
