//! Ranging codes: GPS L1 C/A, BeiDou B1I, and the Neumann-Hoffman secondary code.
