//! What the receiver knows of the constellation: ephemerides (decoded from the signals or
//! given as assistance), Klobuchar coefficients, and the time origin every time in the
//! receiver refers to (the start of a GPS week, GPST).

use crate::navdecode::NavEvent;
use hifitime::Epoch;
use skyforge_orbits::ephemeris::KlobucharCoeffs;
use skyforge_orbits::ephemeris::{BroadcastEphemeris, EphemerisStore, SatId, System};
use skyforge_orbits::time::{GST_WEEK0_IN_GPS_WEEKS, TimeOrigin, epoch_from_gpst, gpst_week_sow};

/// Seconds per week.
const WEEK_S: f64 = skyforge_orbits::time::SECONDS_PER_WEEK as f64;
/// BDT = GPST - 14 s (BDS-SIS-ICD-B1I 3.0 section 5.1.2: BDT started 2006-01-01 UTC, when
/// GPST - UTC was 14 s).
const BDT_BEHIND_GPST_S: f64 = 14.0;
/// BDT week 0 began at GPS week 1356.
const BDT_WEEK0_IN_GPS_WEEKS: u32 = 1356;

/// Ephemerides, ionosphere and the time origin.
#[derive(Debug, Clone, Default)]
pub(crate) struct NavData {
    origin: Option<TimeOrigin>,
    /// Everything known, unbound (kept to bind once the origin is set).
    known: Vec<BroadcastEphemeris>,
    store: EphemerisStore,
    pub(crate) iono_gps: Option<KlobucharCoeffs>,
    pub(crate) iono_bds: Option<KlobucharCoeffs>,
    /// A time near the data (the first assistance ephemeris' toe), for resolving a time of
    /// week when neither the message nor the recording gives the week.
    reference: Option<Epoch>,
}

impl NavData {
    /// Starts with the assistance ephemerides and coefficients (possibly none) and, when
    /// the approximate time is known, the origin at the start of its GPS week.
    pub(crate) fn new(
        assist: Vec<BroadcastEphemeris>,
        iono_gps: Option<KlobucharCoeffs>,
        iono_bds: Option<KlobucharCoeffs>,
        approx_time: Option<Epoch>,
    ) -> Self {
        let mut nav = Self {
            iono_gps,
            iono_bds,
            reference: assist.first().map(|e| e.toe),
            ..Self::default()
        };
        let week = approx_time
            .map(|t| gpst_week_sow(t).0)
            .or_else(|| assist.first().map(|e| gpst_week_sow(e.toe).0));
        for eph in assist {
            nav.add(eph);
        }
        if let Some(week) = week {
            nav.set_origin_week(week);
        }
        nav
    }

    /// A GPST time (s since the origin) near the data when the assistance gave one.
    pub(crate) fn reference_time(&self) -> Option<f64> {
        Some(self.origin.as_ref()?.seconds_since_start(self.reference?))
    }

    pub(crate) fn origin(&self) -> Option<&TimeOrigin> {
        self.origin.as_ref()
    }

    pub(crate) fn store(&self) -> &EphemerisStore {
        &self.store
    }

    fn set_origin_week(&mut self, gps_week: u32) {
        if self.origin.is_some() {
            return;
        }
        let origin = TimeOrigin::new(epoch_from_gpst(gps_week, 0.0));
        self.store = EphemerisStore::new(self.known.clone(), &origin);
        self.origin = Some(origin);
    }

    fn add(&mut self, eph: BroadcastEphemeris) {
        let same = |k: &BroadcastEphemeris| k.sat == eph.sat && k.toe == eph.toe;
        if let Some(k) = self.known.iter_mut().find(|k| same(k)) {
            *k = eph.clone();
        } else {
            self.known.push(eph.clone());
        }
        if let Some(origin) = &self.origin {
            self.store.extend(EphemerisStore::new(vec![eph], origin));
        }
    }

    /// Take in what a decoder reported.
    pub(crate) fn absorb(&mut self, event: &NavEvent) {
        match event {
            NavEvent::Ephemeris(e) => self.add(e.eph.clone()),
            NavEvent::GpsIonoUtc { iono, .. } => {
                self.iono_gps = Some(KlobucharCoeffs {
                    alpha: iono.alpha,
                    beta: iono.beta,
                });
            }
            NavEvent::BdsIono(k) => {
                self.iono_bds = Some(KlobucharCoeffs {
                    alpha: k.alpha,
                    beta: k.beta,
                });
            }
            _ => {}
        }
    }

    /// The GPST time (s since the origin) of a system time of week `tow_s`, its week
    /// `week` if the message gave it, and the receiver's approximate time `approx_s` (s
    /// since the origin) if it has one. The first week seen sets the origin when no
    /// approximate time did. `None` while neither week nor origin is known.
    pub(crate) fn time_of_week(
        &mut self,
        system: System,
        week: Option<u32>,
        tow_s: f64,
        approx_s: Option<f64>,
    ) -> Option<f64> {
        let (gps_week, gps_tow) = match system {
            System::Gps => (week, tow_s),
            System::Beidou => (
                week.map(|w| w + BDT_WEEK0_IN_GPS_WEEKS),
                tow_s + BDT_BEHIND_GPST_S,
            ),
            System::Galileo => (week.map(|w| w + GST_WEEK0_IN_GPS_WEEKS), tow_s),
        };
        if let Some(w) = gps_week {
            self.set_origin_week(w);
        }
        let origin_week = gpst_week_sow(self.origin.as_ref()?.start()).0;
        match (gps_week, approx_s) {
            (Some(w), _) => Some((f64::from(w) - f64::from(origin_week)) * WEEK_S + gps_tow),
            // The week nearest the approximate time.
            (None, approx) => {
                // Without a clock, the assistance data's epoch (within hours of the
                // recording: half a week is the limit).
                let approx = approx.or_else(|| self.reference_time())?;
                let weeks = ((approx - gps_tow) / WEEK_S).round();
                Some(weeks * WEEK_S + gps_tow)
            }
        }
    }

    /// Whether an ephemeris of `sat` exists for GPST `t_s` (s since the origin).
    pub(crate) fn has_ephemeris(&self, sat: SatId, t_s: f64) -> bool {
        self.store.select(sat, t_s).is_some()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn beidou_time_of_week_lands_on_the_gps_scale() {
        let start = epoch_from_gpst(2300, 100.0);
        let mut nav = NavData::new(Vec::new(), None, None, Some(start));
        // GPST 100 s of week 2300 = BDT 86 s of BDT week 944.
        let t = nav
            .time_of_week(System::Beidou, Some(944), 86.0, None)
            .unwrap();
        assert!((t - 100.0).abs() < 1e-9, "{t}");
        // Without the week: the nearest to the approximate time.
        let t = nav
            .time_of_week(System::Gps, None, 604_790.0, Some(5.0))
            .unwrap();
        assert!((t + 10.0).abs() < 1e-9, "{t}");
        let mut blind = NavData::default();
        assert_eq!(blind.time_of_week(System::Gps, None, 10.0, None), None);
        assert_eq!(
            blind.time_of_week(System::Gps, Some(2301), 10.0, None),
            Some(10.0)
        );
    }
}
