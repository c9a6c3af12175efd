//! The scenarios shipped inside the binary.

/// A bundled scenario: its name (what `resolve` accepts), a one-line summary and its TOML.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Bundled {
    /// Name, e.g. `thesis-leo`, `thesis/v-1.2.1`.
    pub name: &'static str,
    /// One line saying what it simulates.
    pub summary: &'static str,
    /// The scenario file.
    pub text: &'static str,
}

const BUNDLED: &[Bundled] = &[
    Bundled {
        name: "thesis-leo",
        summary: "Thesis LEO (a 6971.593 km, i 34.911 deg), 24 h, GPS + BeiDou, three antennas \
                  with two 1 m baselines, earth-pointing",
        text: include_str!("../bundled/thesis-leo.toml"),
    },
    Bundled {
        name: "thesis/v-1.2.1",
        summary: "Thesis section 1.2.1 visibility: the LEO, 24 h, one antenna with a +/-80 deg \
                  field of view, GPS + BeiDou",
        text: include_str!("../thesis/v-1.2.1.toml"),
    },
    Bundled {
        name: "thesis/t-3.2",
        summary: "Thesis section 3.2 PLL error budget: the LEO, 24 h, GPS only, one antenna \
                  with a +/-80 deg field of view",
        text: include_str!("../thesis/t-3.2.toml"),
    },
    Bundled {
        name: "thesis/t-5.4-2",
        summary: "Thesis table 5.4-2 zero baseline: two front ends on one antenna position and one \
                  oscillator, GPS L1 C/A + BDS-2 B1I, 60 s of I/Q at 45 dB-Hz",
        text: include_str!("../thesis/t-5.4-2.toml"),
    },
    Bundled {
        name: "thesis/t-1.2-2",
        summary: "Thesis table 1.2-2: three GPS antennas on two 1 m baselines on the LEO, \
                  observation level with a constant carrier-phase noise, LS attitude, 600 s",
        text: include_str!("../thesis/t-1.2-2.toml"),
    },
    Bundled {
        name: "thesis/t-1.2-3",
        summary: "Thesis table 1.2-3: as thesis/t-1.2-2 at 1 mm, the true baselines 5 mm off \
                  the nominal geometry on every axis",
        text: include_str!("../thesis/t-1.2-3.toml"),
    },
    Bundled {
        name: "thesis/t-5.4-3",
        summary: "Thesis tables 5.4-3..5: real-time attitude, three GPS L1 antennas on two 1 m \
                  baselines on the LEO, calibrated observation level at 45 dB-Hz, KF, 600 s",
        text: include_str!("../thesis/t-5.4-3.toml"),
    },
    Bundled {
        name: "thesis/t-4.3",
        summary: "Thesis tables 4.3-2..6: geometry offsets on orbit, three GPS L1 antennas \
                  offset from the nominal B0 by the thesis's dB0, calibrated observation \
                  level at 45 dB-Hz, 30247 + 25000 s",
        text: include_str!("../thesis/t-4.3.toml"),
    },
    Bundled {
        name: "thesis/t-5.5",
        summary: "Thesis section 5.5 reverse baseline filtering: three GPS L1 antennas on two 1 m \
                  baselines on the LEO, constant 10 mm phase noise, 6-10 deg attitude swings, 600 s",
        text: include_str!("../thesis/t-5.5.toml"),
    },
    Bundled {
        name: "ground-static",
        summary: "Static ground site at 30 N 114 E, 50 m, 1 h, GPS + BeiDou, one antenna \
                  with a 10 deg elevation mask",
        text: include_str!("../bundled/ground-static.toml"),
    },
    Bundled {
        name: "interop-gps-static",
        summary: "90 s static GPS L1 C/A at 4 Msps ci8 with SigMF and a GNSS-SDR configuration (skyforge synth)",
        text: include_str!("../bundled/interop-gps-static.toml"),
    },
    Bundled {
        name: "interop-bds-static",
        summary: "90 s static BeiDou B1I (GEO/IGSO/MEO) at 4 Msps ci8 with SigMF and a GNSS-SDR configuration (skyforge synth)",
        text: include_str!("../bundled/interop-bds-static.toml"),
    },
    Bundled {
        name: "interop-gal-static",
        summary: "120 s static Galileo E5a (F/NAV data, pilot) at 20.46 Msps ci8 with SigMF and a GNSS-SDR configuration (skyforge synth)",
        text: include_str!("../bundled/interop-gal-static.toml"),
    },
    Bundled {
        name: "interop-e1-static",
        summary: "120 s static Galileo E1 (I/NAV data, pilot, CBOC) at 15 Msps ci8 with SigMF and a GNSS-SDR configuration (skyforge synth)",
        text: include_str!("../bundled/interop-e1-static.toml"),
    },
    Bundled {
        name: "interop-l1-e1-static",
        summary: "120 s static GPS L1 C/A + Galileo E1 in one recording of the 1575.42 MHz band at 15 Msps ci8, with SigMF and a GNSS-SDR configuration for both (skyforge synth)",
        text: include_str!("../bundled/interop-l1-e1-static.toml"),
    },
    Bundled {
        name: "interop-l5-static",
        summary: "120 s static GPS L5 (CNAV data, pilot) at 20.46 Msps ci8 with SigMF and a GNSS-SDR configuration (skyforge synth)",
        text: include_str!("../bundled/interop-l5-static.toml"),
    },
    Bundled {
        name: "interop-leo-gps",
        summary: "90 s GPS L1 C/A on the thesis LEO (one zenith antenna), 4 Msps ci8, for GNSS-SDR with a widened Doppler search",
        text: include_str!("../bundled/interop-leo-gps.toml"),
    },
    Bundled {
        name: "receiver-leo-gps",
        summary: "300 s GPS L1 C/A on the thesis LEO (one zenith antenna), 4 Msps ci8, for the bundled receiver's LEO acceptance",
        text: include_str!("../bundled/receiver-leo-gps.toml"),
    },
    Bundled {
        name: "attitude-leo-gps",
        summary: "60 s GPS L1 C/A on the thesis LEO, three antennas on two 1 m baselines, 4 Msps \
                  ci8, 45 dB-Hz: the attitude chain at the signal level (scripts/demo.sh)",
        text: include_str!("../bundled/attitude-leo-gps.toml"),
    },
    Bundled {
        name: "attitude-leo-l1-l5",
        summary: "60 s GPS L1 C/A on the thesis LEO, three antennas on two 1 m baselines, 4 Msps \
                  ci8, 45 dB-Hz: the attitude chain at the signal level (scripts/demo.sh)",
        text: include_str!("../bundled/attitude-leo-l1-l5.toml"),
    },
    Bundled {
        name: "integrity-lab",
        summary: "Paper 002 lab: two station positions (30 N 104 E, 500 and 600 m), four \
                  receivers on one rubidium clock, 1800 s, BDS-2 + GPS, observation level",
        text: include_str!("../bundled/integrity-lab.toml"),
    },
    Bundled {
        name: "book-od-leo",
        summary: "Book 5.5.4: LEO a = 7271 km, e = 0.001, 2 h, GPS L1 C/A at the observation \
                  level with SA-era satellite errors, for the position filter (B-5.5)",
        text: include_str!("../bundled/book-od-leo.toml"),
    },
    Bundled {
        name: "od-leo",
        summary: "LEO a = 7271 km, e = 0.001, 1 h, GPS L1 C/A at the observation level with \
                  today's satellite errors and Doppler noise, for `skyforge od`",
        text: include_str!("../bundled/od-leo.toml"),
    },
    Bundled {
        name: "od-leo-dual",
        summary: "od-leo with GPS L1 C/A + L2 and carrier phase, a topside ionosphere and \
                  real-time-precise satellite orbits and clocks, for the reduced-dynamic \
                  filter of `skyforge od`",
        text: include_str!("../bundled/od-leo-dual.toml"),
    },
    Bundled {
        name: "book-relnav-leo",
        summary: "Book 5.6.4: two LEOs (target, chaser) at 500 km, e = 0.01, 32 km apart, \
                  600 s, GPS L1 C/A at the observation level with SA-era satellite errors \
                  and Doppler noise, for `skyforge relnav` (B-5.6)",
        text: include_str!("../bundled/book-relnav-leo.toml"),
    },
    Bundled {
        name: "book-relnav-events",
        summary: "Book 5.6.5 figures 5-36/5-38: book-relnav-leo with the book's events, \
                  satellite sets that differ at 39 s and 164 s and chaser pseudoranges \
                  missing at 237 s and 485 s (B-5.6's event rows)",
        text: include_str!("../bundled/book-relnav-events.toml"),
    },
    Bundled {
        name: "grace-relnav",
        summary: "GRACE-like formation: two LEOs at 500 km, i = 89 deg, 200 km apart on one \
                  orbit, 1200 s, GPS L1 C/A + L2 at the observation level, exact satellite \
                  orbits, for `skyforge relnav` in mode double-difference",
        text: include_str!("../bundled/grace-relnav.toml"),
    },
    Bundled {
        name: "paper001-tdcp-static",
        summary: "Paper 001 Fig. 2: a static site near Changsha, 300 s, BeiDou B1I from the \
                  three BDS-3 GEOs, receiver oscillator 1e-7 off frequency, for 10 Hz \
                  carrier-phase time differences (P1-F2)",
        text: include_str!("../bundled/paper001-tdcp-static.toml"),
    },
    Bundled {
        name: "paper001-boat-lake",
        summary: "Paper 001 Fig. 5: a boat on a park lake near Changsha, 600 s moored, then \
                  a closed loop of 4458 s (six squares at 3 m/s) with heave, pitch and roll \
                  waves, a navigation-grade IMU with hull vibration and the three BDS-3 \
                  GEOs at the observation level (P1-D)",
        text: include_str!("../bundled/paper001-boat-lake.toml"),
    },
    Bundled {
        name: "book-gps-ins-flight",
        summary: "The book's GPS/INS flight (3.2): an aircraft at 3000 m, 550 s with a climb, \
                  a 180-deg turn and a descent, the Table 3-1 SINS and a GPS receiver with \
                  Table 3-4's errors at the observation level (B-3.2)",
        text: include_str!("../bundled/book-gps-ins-flight.toml"),
    },
];

/// Every bundled scenario.
pub fn bundled() -> &'static [Bundled] {
    BUNDLED
}
