//! Navigation-message decoding: GPS LNAV and BeiDou D1/D2 bits to ephemeris, clock, ionosphere and time.
