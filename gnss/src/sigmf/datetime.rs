//! SigMF `core:datetime`: ISO-8601 UTC `YYYY-MM-DDTHH:MM:SS[.fraction]Z` (SigMF 1.0
//! "Captures Array": the time MUST be UTC, ending in `Z`), written to the nanosecond
//! ([`format_utc`]) and read with a fraction of any length ([`parse_utc`]).

use hifitime::Epoch;

/// The `core:datetime` of `at`: ISO-8601 UTC with nanoseconds and a trailing Z.
pub fn format_utc(at: Epoch) -> String {
    let (y, mo, d, h, mi, sec, ns) = at.to_gregorian_utc();
    format!("{y:04}-{mo:02}-{d:02}T{h:02}:{mi:02}:{sec:02}.{ns:09}Z")
}

/// The UTC epoch of an ISO-8601 `YYYY-MM-DDTHH:MM:SS[.fraction]Z` string (fraction kept
/// to the nanosecond, further digits truncated), or `None` when it is not one.
pub fn parse_utc(s: &str) -> Option<Epoch> {
    let s = s.trim();
    let body = s.strip_suffix('Z')?;
    let b = body.as_bytes();
    if b.len() < 19
        || b[4] != b'-'
        || b[7] != b'-'
        || !matches!(b[10], b'T' | b't')
        || b[13] != b':'
        || b[16] != b':'
    {
        return None;
    }
    let digits = |range: std::ops::Range<usize>| -> Option<u32> {
        let part = body.get(range)?;
        (!part.is_empty() && part.bytes().all(|c| c.is_ascii_digit()))
            .then(|| part.parse().ok())
            .flatten()
    };
    let year = i32::try_from(digits(0..4)?).ok()?;
    let month = u8::try_from(digits(5..7)?).ok()?;
    let day = u8::try_from(digits(8..10)?).ok()?;
    let hour = u8::try_from(digits(11..13)?).ok()?;
    let minute = u8::try_from(digits(14..16)?).ok()?;
    let second = u8::try_from(digits(17..19)?).ok()?;
    let nanos = match body.get(19..)? {
        "" => 0,
        frac => {
            let f = frac.strip_prefix('.')?;
            if f.is_empty() || !f.bytes().all(|c| c.is_ascii_digit()) {
                return None;
            }
            // Nine digits: nanoseconds; pad shorter fractions, truncate longer ones.
            f.bytes()
                .chain(std::iter::repeat(b'0'))
                .take(9)
                .fold(0u32, |acc, c| acc * 10 + u32::from(c - b'0'))
        }
    };
    Epoch::maybe_from_gregorian_utc(year, month, day, hour, minute, second, nanos).ok()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_what_skyforge_and_other_recorders_write() {
        let e = parse_utc("2023-03-12T00:00:00.000000000Z").unwrap();
        assert_eq!(e, Epoch::from_gregorian_utc_at_midnight(2023, 3, 12));
        let e = parse_utc("2020-06-25T13:15:30.5Z").unwrap();
        assert_eq!(
            e,
            Epoch::from_gregorian_utc(2020, 6, 25, 13, 15, 30, 500_000_000)
        );
        // Twelve fraction digits: truncated to the nanosecond.
        let e = parse_utc("2020-06-25T13:15:30.123456789999Z").unwrap();
        assert_eq!(
            e,
            Epoch::from_gregorian_utc(2020, 6, 25, 13, 15, 30, 123_456_789)
        );
        assert_eq!(
            parse_utc("2020-06-25T13:15:30Z").unwrap(),
            Epoch::from_gregorian_utc_hms(2020, 6, 25, 13, 15, 30)
        );
    }

    #[test]
    fn reads_back_what_it_writes() {
        let at = Epoch::from_gregorian_utc(2024, 2, 29, 23, 59, 59, 123_456_789);
        assert_eq!(format_utc(at), "2024-02-29T23:59:59.123456789Z");
        assert_eq!(parse_utc(&format_utc(at)), Some(at));
    }

    #[test]
    fn rejects_what_is_not_utc_iso_8601() {
        for bad in [
            "",
            "2020-06-25T13:15:30",
            "2020-06-25 13:15:30Z",
            "2020-13-25T13:15:30Z",
            "2020-06-25T25:15:30Z",
            "2020-06-25T13:15:30.Z",
            "2020-06-25T13:15:30+01:00",
            "20-06-25T13:15:30Z",
            "2020-06-25T13:1x:30Z",
            "2020-06-25T13:15:30.12aZ",
            "２020-06-25T13:15:30Z",
        ] {
            assert_eq!(parse_utc(bad), None, "{bad}");
        }
    }
}
