//! Shared by the single-point and RAIM tests: the embedded nominal constellations on the
//! bundled scenarios' day.

use skyforge_orbits::ephemeris::BeidouSet;
use skyforge_orbits::ephemeris::{EphemerisStore, nominal};
use skyforge_orbits::time::TimeOrigin;

/// Ephemerides and their time origin.
pub struct World {
    pub origin: TimeOrigin,
    pub store: EphemerisStore,
}

/// GPS (and the BDS-3 set when `beidou`) at 2023-03-12 00:00 GPST.
pub fn world(beidou: bool) -> World {
    world_of(beidou, false)
}

/// GPS, the BDS-3 set when `beidou` and Galileo when `galileo`, at 2023-03-12 00:00 GPST.
pub fn world_of(beidou: bool, galileo: bool) -> World {
    let start = hifitime::Epoch::from_gregorian_str("2023-03-12T00:00:00 GPST").unwrap();
    let origin = TimeOrigin::new(start);
    let mut ephs = nominal::gps(start);
    if beidou {
        ephs.extend(nominal::beidou(BeidouSet::Bds3, start));
    }
    if galileo {
        ephs.extend(nominal::galileo(start));
    }
    World {
        store: EphemerisStore::new(ephs, &origin),
        origin,
    }
}
