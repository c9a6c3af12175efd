//! The rule every antenna name keeps: it names output files, HDF5 groups and the RINEX
//! `MARKER NAME`, whether it comes from a scenario, a recording's SigMF metadata
//! (`skyforge:antenna`) or a geometry file.

/// Longest antenna name: the RINEX 3.04 `MARKER NAME` field (A60).
pub const ANTENNA_NAME_MAX: usize = 60;

/// An antenna name names output files (`<name>.obs.rnx`, `<name>.gps-l1ca.sigmf-data`),
/// HDF5 groups and the RINEX `MARKER NAME`: 1 to [`ANTENNA_NAME_MAX`] printable ASCII
/// characters, no `/` or `\`, not `.` or `..`, no leading or trailing space. The rule
/// as written for messages is the error.
pub fn check_antenna_name(name: &str) -> Result<(), &'static str> {
    let printable = name.chars().all(|c| c.is_ascii_graphic() || c == ' ');
    let ok = !name.is_empty()
        && name.len() <= ANTENNA_NAME_MAX
        && printable
        && name.trim() == name
        && !name.contains(['/', '\\'])
        && name != "."
        && name != "..";
    if ok {
        Ok(())
    } else {
        Err(
            "must be 1 to 60 printable ASCII characters (it names files and the RINEX MARKER NAME), without '/' or '\\', not '.' or '..', no leading or trailing space",
        )
    }
}
