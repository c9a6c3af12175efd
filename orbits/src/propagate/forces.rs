//! Accelerations: central body, zonal harmonics J2..J6, atmospheric drag.
