use super::*;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rand_distr::StandardNormal;
use skyforge_gnss::observation::ObsRecord;

/// An epoch at `t_s` of eight GPS satellites whose C/N0 is 45 dB-Hz plus `change(prn)`
/// plus white noise of 0.5 dB; satellites with a NaN change are not tracked.
fn epoch(t_s: f64, rng: &mut ChaCha8Rng, change: impl Fn(u8) -> f64) -> ObsEpoch {
    let sats = (1..=8u8)
        .filter(|p| !change(*p).is_nan())
        .map(|prn| {
            let noise: f64 = rng.sample(StandardNormal);
            ObsRecord::complete(
                SatId::gps(prn),
                Signal::GpsL1Ca,
                2e7,
                1e8,
                0.0,
                45.0 + change(prn) + 0.5 * noise,
            )
        })
        .collect();
    ObsEpoch {
        time: Epoch::from_gpst_seconds(1e9 + t_s),
        sats,
    }
}

/// A day of clean epochs raises no alarm (the per-epoch rate 1e-6 allows 0.09).
#[test]
fn a_clean_day_raises_no_alarm() {
    let mut rng = ChaCha8Rng::seed_from_u64(1);
    let mut monitor = Cn0Monitor::new(Cn0MonitorConfig::default()).unwrap();
    let alarms = (0..86_400)
        .map(|t| monitor.epoch(&epoch(f64::from(t), &mut rng, |_| 0.0)))
        .filter(|v| v.alarm)
        .count();
    assert_eq!(alarms, 0);
}

/// A common drop of 2 dB (a jammer at J/S 20 dB against 45 dB-Hz at 4 Msps makes 2.5)
/// raises the alarm at its first epoch and holds it while it lasts; one satellite's fade
/// of 15 dB does not; losing most satellites at once does.
#[test]
fn a_common_drop_or_a_mass_loss_raises_it_and_a_fade_does_not() {
    let mut rng = ChaCha8Rng::seed_from_u64(2);
    let mut monitor = Cn0Monitor::new(Cn0MonitorConfig::default()).unwrap();
    for t in 0..600 {
        assert!(!monitor.epoch(&epoch(f64::from(t), &mut rng, |_| 0.0)).alarm);
    }
    for t in 600..660 {
        let fade = monitor.epoch(&epoch(f64::from(t), &mut rng, |p| {
            if p == 3 { -15.0 } else { 0.0 }
        }));
        assert!(!fade.alarm, "{fade:?}");
    }
    for t in 660..700 {
        let jammed = monitor.epoch(&epoch(f64::from(t), &mut rng, |_| -2.0));
        assert!(jammed.alarm && jammed.change_db < -1.0, "{jammed:?}");
    }
    for t in 700..760 {
        assert!(!monitor.epoch(&epoch(f64::from(t), &mut rng, |_| 0.0)).alarm);
    }
    let lost = monitor.epoch(&epoch(
        760.0,
        &mut rng,
        |p| if p <= 3 { 0.0 } else { f64::NAN },
    ));
    assert!(lost.alarm && lost.tracked == 3, "{lost:?}");
}

/// Settings out of range are refused, naming them.
#[test]
fn bad_settings_are_refused() {
    let bad = Cn0MonitorConfig {
        false_alarm: 0.7,
        ..Cn0MonitorConfig::default()
    };
    assert!(Cn0Monitor::new(bad).unwrap_err().contains("false_alarm"));
}
