//! Reading sample files: SkyForge SigMF recordings and raw files of other sources, several antennas on one sample clock.
