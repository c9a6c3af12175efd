//! The book's steady state (5.6.5) needs the satellites in use unchanged and no epoch
//! missed: how long that has held, as every mode reports it
//! (`RelativeEstimate::same_satellites_s`).

/// Since when the satellites in use (any comparable description of them) have been the
/// same, and how many epochs were missed.
#[derive(Debug)]
pub(crate) struct SameSatellites<S> {
    last: Option<(S, f64)>,
    missed: usize,
}

impl<S: PartialEq> SameSatellites<S> {
    pub(crate) fn new() -> Self {
        Self {
            last: None,
            missed: 0,
        }
    }

    /// How long `used` has been in use at `t_s` (s; 0 where it has just changed).
    pub(crate) fn at(&mut self, used: S, t_s: f64) -> f64 {
        let since = match &self.last {
            Some((s, since)) if *s == used => *since,
            _ => t_s,
        };
        self.last = Some((used, since));
        t_s - since
    }

    /// An epoch missed (no estimate): counted, and the next set counts afresh.
    pub(crate) fn miss<T>(&mut self) -> Option<T> {
        self.missed += 1;
        self.last = None;
        None
    }

    /// The epochs missed so far.
    pub(crate) fn missed(&self) -> usize {
        self.missed
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_from_the_last_change_or_miss() {
        let mut s = SameSatellites::new();
        assert_eq!(s.at([1, 2], 10.0), 0.0);
        assert_eq!(s.at([1, 2], 11.0), 1.0);
        assert_eq!(s.at([1, 3], 12.0), 0.0);
        assert_eq!(s.at([1, 3], 14.0), 2.0);
        assert_eq!(s.miss::<()>(), None);
        assert_eq!(s.at([1, 3], 16.0), 0.0);
        assert_eq!(s.missed(), 1);
    }
}
