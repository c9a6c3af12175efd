//! Geometry truth: light time, range and its derivatives, Doppler, azimuth/elevation.
