//! The B value of each station: its statistic against the mean of the others.

/// B values of the statistics `x` of N stations (one satellite, one epoch):
/// `B_m = X_m - 1/(N - 1) sum_{n != m} X_n`. Paper 002 defines B in prose as "the
/// difference between a measurement and the mean of the N measurements after excluding
/// a certain channel" and leaves out the equation; of the candidate formulas only this
/// one gives its reported 100-cycle slip response (100 cycles at the faulty station, a
/// third of it at the other three; papers digest 1.4). Empty with fewer than two
/// stations.
pub fn b_values(x: &[f64]) -> Vec<f64> {
    if x.len() < 2 {
        return Vec::new();
    }
    let others = (x.len() - 1) as f64;
    let sum: f64 = x.iter().sum();
    x.iter().map(|&xm| xm - (sum - xm) / others).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_fault_at_one_of_four_stations_shows_at_a_third_elsewhere() {
        let b = b_values(&[0.0, 0.0, 100.0, 0.0]);
        assert_eq!(b[2], 100.0);
        for m in [0, 1, 3] {
            assert!((b[m] + 100.0 / 3.0).abs() < 1e-12);
        }
    }

    #[test]
    fn a_common_term_cancels() {
        let common = 2.3e7;
        let b = b_values(&[common + 1.0, common - 1.0, common + 0.5]);
        let plain = b_values(&[1.0, -1.0, 0.5]);
        for (x, y) in b.iter().zip(&plain) {
            assert!((x - y).abs() < 1e-8);
        }
        assert!(b_values(&[1.0]).is_empty());
    }
}
