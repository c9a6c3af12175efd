//! A trajectory read from CSV, interpolated smoothly (e.g. cubic Hermite or spline).
