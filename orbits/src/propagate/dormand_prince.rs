//! Adaptive Dormand-Prince 5(4) integrator with error control and 4th-order dense output.
