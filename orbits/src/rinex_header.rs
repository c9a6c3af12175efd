//! What every RINEX reader checks first, navigation and observation files alike: the
//! header's first line (format version in columns 1-9, file type in column 21) and the
//! labels of the header lines (columns 61-80); RINEX 2.11, 3.05 and 4.00, section 5 and
//! table A1 of each.

/// The label (columns 61-80, trimmed) of header line `line`; empty where the line is
/// shorter or not ASCII there.
pub fn label(line: &str) -> &str {
    line.get(60..).unwrap_or("").trim()
}

/// The format version (columns 1-9) and file type (column 21, e.g. `O`, `N`) of a RINEX
/// file's first line.
pub fn version_and_type(first: &str) -> Result<(f64, &str), String> {
    let version: f64 = first
        .get(..9)
        .unwrap_or(first)
        .trim()
        .parse()
        .map_err(|_| "no RINEX version in columns 1-9".to_string())?;
    Ok((version, first.get(20..21).unwrap_or("")))
}

/// The major version (2, 3 or 4) of a file of RINEX version `version`, which SkyForge's
/// readers read; any other version is an error that says what is read.
pub fn supported_major(version: f64) -> Result<u8, String> {
    match version {
        v if (2.0..3.0).contains(&v) => Ok(2),
        v if (3.0..4.0).contains(&v) => Ok(3),
        v if (4.0..5.0).contains(&v) => Ok(4),
        v => Err(format!(
            "RINEX version {v} is not read (versions 2.xx, 3.xx and 4.xx are)"
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn versions_and_labels() {
        let line = format!(
            "{:>9}{:11}{:<20}{:<20}RINEX VERSION / TYPE",
            "3.04", "", "O", "M"
        );
        assert_eq!(version_and_type(&line), Ok((3.04, "O")));
        assert_eq!(label(&line), "RINEX VERSION / TYPE");
        assert_eq!(label("short"), "");
        assert_eq!(supported_major(2.11), Ok(2));
        assert_eq!(supported_major(4.02), Ok(4));
        for v in [1.0, 5.0, 9.99, f64::NAN, f64::INFINITY] {
            assert!(
                supported_major(v).unwrap_err().contains("is not read"),
                "{v}"
            );
        }
        assert!(version_and_type("   x").is_err());
    }
}
