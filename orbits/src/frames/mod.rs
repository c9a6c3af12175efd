//! Reference frames: ECI <-> ECEF (Earth rotation), WGS-84 geodetic <-> ECEF, NED, the
//! orbital frame of thesis section 2.5.1, and yaw/pitch/roll (3-2-1) with quaternions.

pub mod earth_rotation;
pub(crate) mod euler;
pub(crate) mod geodetic;
pub(crate) mod ned;
pub(crate) mod orbital;

pub use geodetic::{Geodetic, ecef_to_geodetic, geodetic_to_ecef, radii_of_curvature_m};
pub use ned::{az_el, c_ecef_ned};
pub use orbital::{c_orbital_eci, c_rac_eci, relative_in_frame_of, relative_in_target_frame};

pub use euler::YawPitchRoll;
