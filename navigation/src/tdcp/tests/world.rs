//! The synthetic world: the nominal GPS constellation's broadcast ephemerides, a site at
//! Changsha (28.2 N, 113.0 E), a receiver clock `1e-4 s + drift t`, and noise-free or
//! noisy L1 C/A records: pseudorange `rho + c (dt_r - dt_s)` at the transmit time found by
//! iteration, phase `(P + N lambda + noise) / lambda` with an integer `N` per satellite.

use crate::pvt::{Transmitted, ViewPoint};
use hifitime::{Duration, Epoch, TimeScale};
use skyforge_gnss::observation::{ObsEpoch, ObsFile, ObsRecord};
use skyforge_gnss::signal::Signal;
use skyforge_orbits::constants::C_MPS;
use skyforge_orbits::ephemeris::{BroadcastEphemeris, EphemerisStore, SatId, nominal};
use skyforge_orbits::frames::{Geodetic, c_ecef_ned, geodetic_to_ecef};
use skyforge_orbits::time::TimeOrigin;
use skyforge_orbits::{Mat3, Vec3};

pub(crate) const SIGNAL: Signal = Signal::GpsL1Ca;
/// Satellites above this elevation are recorded (deg): some fall below the 10 deg mask.
const HORIZON_DEG: f64 = 5.0;
const CLOCK_OFFSET_S: f64 = 1e-4;

pub(crate) struct World {
    pub start: Epoch,
    pub origin: TimeOrigin,
    pub ephemerides: Vec<BroadcastEphemeris>,
    pub store: EphemerisStore,
    pub site: Vec3,
    /// ECEF to NED at the site.
    pub c_ecef_ned: Mat3,
    pub drift: f64,
}

impl World {
    /// The world with a receiver clock of frequency offset `drift` (s/s).
    pub fn new(drift: f64) -> Self {
        let start = Epoch::from_gregorian(2023, 3, 12, 0, 0, 0, 0, TimeScale::GPST);
        let origin = TimeOrigin::new(start);
        let ephemerides = nominal::gps(start);
        let store = EphemerisStore::new(ephemerides.clone(), &origin);
        let g = Geodetic::from_degrees(28.2, 113.0, 50.0);
        World {
            start,
            origin,
            ephemerides,
            store,
            site: geodetic_to_ecef(&g),
            c_ecef_ned: c_ecef_ned(g.lat_rad, g.lon_rad),
            drift,
        }
    }

    /// The epoch tagged `tag_s` after the start.
    pub fn time(&self, tag_s: f64) -> Epoch {
        self.start + Duration::from_seconds(tag_s)
    }

    /// A NED vector in ECEF.
    pub fn ned(&self, n: f64, e: f64, d: f64) -> Vec3 {
        self.c_ecef_ned.transpose() * Vec3::new(n, e, d)
    }

    /// The receiver clock at the epoch tagged `tag_s` (s).
    pub fn clock_s(&self, tag_s: f64) -> f64 {
        CLOCK_OFFSET_S + self.drift * tag_s
    }

    /// The epoch tagged `tag_s` for the antenna at `r`, each phase with `noise(el)` (m,
    /// el in rad) added.
    pub fn epoch(&self, tag_s: f64, r: Vec3, noise: &mut dyn FnMut(f64) -> f64) -> ObsEpoch {
        let place = ViewPoint::new(r);
        let dt = self.clock_s(tag_s);
        let lambda = SIGNAL.wavelength_m();
        let sats = (1..=32u8)
            .filter_map(|prn| {
                let sat = SatId::gps(prn);
                let eph = self.store.select(sat, tag_s)?;
                let mut p = 2.2e7;
                for _ in 0..5 {
                    let view = Transmitted::of(eph, tag_s, p).seen_from(&r, None);
                    p = view.range_m + C_MPS * (dt - view.clock_s);
                }
                let (_, el) = place.see(&Transmitted::of(eph, tag_s, p)).az_el_rad?;
                (el > HORIZON_DEG.to_radians()).then(|| {
                    let n = f64::from((u32::from(prn) * 7919) % 4001) - 2000.0;
                    let phase = (p + n * lambda + noise(el)) / lambda;
                    ObsRecord::complete(sat, SIGNAL, p, phase, 0.0, 45.0)
                })
            })
            .collect();
        ObsEpoch {
            time: self.time(tag_s),
            sats,
        }
    }

    /// Noise-free epochs at `tags` of the antenna along `r(tag)`, as a file.
    pub fn file(&self, tags: &[f64], r: impl Fn(f64) -> Vec3) -> ObsFile {
        let epochs = (tags.iter())
            .map(|&t| self.epoch(t, r(t), &mut |_| 0.0))
            .collect();
        ObsFile {
            source: "synthetic".into(),
            approx_ecef_m: Some(self.site),
            codes: Default::default(),
            epochs,
            marker: None,
            dropped: Vec::new(),
        }
    }
}

/// No noise.
pub(crate) fn quiet(_: f64) -> f64 {
    0.0
}
