//! Initial state from a TLE through SGP4.
