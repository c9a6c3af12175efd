//! A static ground site.
//!
//! The reference frame is the site's NED frame; the body frame is NED turned by the
//! attitude profile (zero attitude: body X north, Y east, Z down, so an antenna whose
//! boresight is -Zb looks up).

use super::config::GroundConfig;
use crate::check::Invalid;
use crate::frames::geodetic::{Geodetic, ecef_to_geodetic, geodetic_to_ecef};
use crate::frames::ned::c_ecef_ned;
use crate::{Mat3, Vec3};

/// Largest accepted |height| of a ground site above the ellipsoid (m).
const MAX_ABS_HEIGHT_M: f64 = 1e5;

/// A fixed site on the Earth.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GroundSite {
    /// Site position (ECEF, m).
    pub r_ecef_m: Vec3,
    /// Geodetic coordinates of the site.
    pub geodetic: Geodetic,
    /// NED -> ECEF rotation at the site.
    pub c_ned_ecef: Mat3,
}

impl GroundSite {
    /// A site at an ECEF position.
    pub fn from_ecef(r_ecef_m: Vec3) -> Self {
        let geodetic = ecef_to_geodetic(&r_ecef_m);
        Self::new(r_ecef_m, geodetic)
    }

    /// A site at geodetic coordinates.
    pub fn from_geodetic(geodetic: Geodetic) -> Self {
        Self::new(geodetic_to_ecef(&geodetic), geodetic)
    }

    fn new(r_ecef_m: Vec3, geodetic: Geodetic) -> Self {
        Self {
            r_ecef_m,
            geodetic,
            c_ned_ecef: c_ecef_ned(geodetic.lat_rad, geodetic.lon_rad).transpose(),
        }
    }

    /// `[platform.ground]`: either `ecef_m`, or `latitude_deg` + `longitude_deg` (+
    /// `height_m`, default 0 m above the WGS-84 ellipsoid). Field paths in errors are
    /// relative to `[platform]`.
    pub fn from_config(cfg: &GroundConfig) -> Result<Self, Invalid> {
        let geodetic_given =
            cfg.latitude_deg.is_some() || cfg.longitude_deg.is_some() || cfg.height_m.is_some();
        match (cfg.ecef_m, geodetic_given) {
            (Some(_), true) => Err(Invalid::new(
                "ground.ecef_m",
                "(set)",
                "give either ecef_m or latitude_deg/longitude_deg/height_m, not both",
            )),
            (Some(r), false) => {
                if r.iter().any(|v| !v.is_finite()) {
                    return Err(Invalid::new(
                        "ground.ecef_m",
                        format!("{r:?}"),
                        "must be finite numbers",
                    ));
                }
                let site = Self::from_ecef(Vec3::from(r));
                if !(-MAX_ABS_HEIGHT_M..=MAX_ABS_HEIGHT_M).contains(&site.geodetic.h_m) {
                    return Err(Invalid::new(
                        "ground.ecef_m",
                        format!("{r:?} (height {:.0} m)", site.geodetic.h_m),
                        "must be within 100 km of the WGS-84 ellipsoid",
                    ));
                }
                Ok(site)
            }
            (None, _) => {
                let lat = cfg.latitude_deg.ok_or_else(|| {
                    Invalid::new(
                        "ground.latitude_deg",
                        "(missing)",
                        "required unless ecef_m is given",
                    )
                })?;
                let lon = cfg.longitude_deg.ok_or_else(|| {
                    Invalid::new(
                        "ground.longitude_deg",
                        "(missing)",
                        "required unless ecef_m is given",
                    )
                })?;
                let h = cfg.height_m.unwrap_or(0.0);
                if !(-90.0..=90.0).contains(&lat) {
                    return Err(Invalid::new(
                        "ground.latitude_deg",
                        lat,
                        "must be in [-90, 90]",
                    ));
                }
                if !(-360.0..=360.0).contains(&lon) {
                    return Err(Invalid::new(
                        "ground.longitude_deg",
                        lon,
                        "must be in [-360, 360]",
                    ));
                }
                if !(-MAX_ABS_HEIGHT_M..=MAX_ABS_HEIGHT_M).contains(&h) {
                    return Err(Invalid::new(
                        "ground.height_m",
                        h,
                        "must be in [-100000, 100000] m",
                    ));
                }
                Ok(Self::from_geodetic(Geodetic {
                    lat_rad: lat.to_radians(),
                    lon_rad: lon.to_radians(),
                    h_m: h,
                }))
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cfg(
        lat: Option<f64>,
        lon: Option<f64>,
        h: Option<f64>,
        ecef: Option<[f64; 3]>,
    ) -> GroundConfig {
        GroundConfig {
            latitude_deg: lat,
            longitude_deg: lon,
            height_m: h,
            ecef_m: ecef,
        }
    }

    #[test]
    fn geodetic_site_on_the_equator() {
        let site = GroundSite::from_config(&cfg(Some(0.0), Some(90.0), Some(10.0), None))
            .unwrap_or_else(|e| panic!("{e}"));
        assert!((site.r_ecef_m - Vec3::new(0.0, 6_378_147.0, 0.0)).norm() < 1e-6);
        // Down is -Y, north is +Z, east is -X.
        assert!((site.c_ned_ecef * Vec3::z() - Vec3::new(0.0, -1.0, 0.0)).norm() < 1e-15);
        assert!((site.c_ned_ecef * Vec3::x() - Vec3::z()).norm() < 1e-15);
        assert!((site.c_ned_ecef * Vec3::y() + Vec3::x()).norm() < 1e-15);
    }

    #[test]
    fn ecef_site_matches_geodetic_site() {
        let a = GroundSite::from_config(&cfg(Some(55.7), Some(12.5), Some(50.0), None))
            .unwrap_or_else(|e| panic!("{e}"));
        let r = a.r_ecef_m;
        let b = GroundSite::from_config(&cfg(None, None, None, Some([r.x, r.y, r.z])))
            .unwrap_or_else(|e| panic!("{e}"));
        assert!((b.geodetic.lat_rad - 55.7f64.to_radians()).abs() < 1e-12);
        assert!((b.geodetic.h_m - 50.0).abs() < 1e-6);
        assert!((a.c_ned_ecef - b.c_ned_ecef).norm() < 1e-12);
    }

    #[test]
    fn bad_ground_configs() {
        let field = |c: GroundConfig| GroundSite::from_config(&c).err().map(|e| e.field);
        assert_eq!(
            field(cfg(Some(1.0), None, None, Some([1.0, 2.0, 3.0]))).as_deref(),
            Some("ground.ecef_m")
        );
        assert_eq!(
            field(cfg(None, Some(1.0), None, None)).as_deref(),
            Some("ground.latitude_deg")
        );
        assert_eq!(
            field(cfg(Some(1.0), None, None, None)).as_deref(),
            Some("ground.longitude_deg")
        );
        assert_eq!(
            field(cfg(Some(91.0), Some(0.0), None, None)).as_deref(),
            Some("ground.latitude_deg")
        );
        assert_eq!(
            field(cfg(Some(f64::NAN), Some(0.0), None, None)).as_deref(),
            Some("ground.latitude_deg")
        );
        assert_eq!(
            field(cfg(Some(0.0), Some(0.0), Some(2e5), None)).as_deref(),
            Some("ground.height_m")
        );
        assert_eq!(
            field(cfg(None, None, None, Some([f64::INFINITY, 0.0, 0.0]))).as_deref(),
            Some("ground.ecef_m")
        );
        assert_eq!(
            field(cfg(None, None, None, Some([0.0, 0.0, 0.0]))).as_deref(),
            Some("ground.ecef_m")
        );
    }
}
