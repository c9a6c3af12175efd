//! The multi-frequency baseline models of thesis 2.4.2 (GPS, several frequencies) and 2.4.4
//! (BD/GPS, several frequencies) at the observation level: the observed-only signals GPS
//! L2/L5 and BDS B2I/B3I drawn beside L1 C/A and B1I (`[observation] observed_signals`),
//! through the attitude chain, against the truth.
//!
//! The table is printed (`cargo test -p skyforge-validate --test attitude_multifrequency
//! -- --nocapture`); docs/attitude.md records it.

use skyforge_gnss::observation::ObsRecord;
use skyforge_gnss::signal::Signal;
use skyforge_navigation::relative::Constraint;
use skyforge_runner::observation_run;
use skyforge_signals::obs_model::ObsNoiseConfig;
use skyforge_validate::attitude::{SuccessRate, single_epoch};

// assumed (chosen before the first run): T-1.2-2's middle phase noise, 3 mm, and 0.5 m of
// code, constant and the same on every frequency (Q_f = I, as thesis 2.4.2 writes it when
// the frequencies are alike): a code noisier than the loops' 0.3 m at 45 dB-Hz, so that
// single-frequency GPS leaves the search room to improve. 120 s of the bundled real-time
// attitude scenario (thesis LEO, three antennas on two 1 m baselines) with BeiDou on,
// eight seeds.
const PHASE_M: f64 = 0.003;
const CODE_M: f64 = 0.5;
const DURATION_S: f64 = 120.0;

const OBSERVED: [Signal; 4] = [Signal::GpsL2, Signal::GpsL5, Signal::BdsB2I, Signal::BdsB3I];

fn scenario() -> skyforge_scenarios::Scenario {
    let mut s = skyforge_scenarios::resolve("thesis/t-5.4-3").unwrap();
    s.gnss.beidou.enabled = true;
    s.time.duration_s = DURATION_S;
    s.observation.noise = ObsNoiseConfig::Constant {
        phase_m: PHASE_M,
        code_m: CODE_M,
        doppler_mps: None,
    };
    s.observation.observed_signals = OBSERVED.to_vec();
    s
}

/// `a` above `b` by more than two standard errors of their difference.
fn above(a: &SuccessRate, b: &SuccessRate) -> bool {
    let se = |r: &SuccessRate| r.success.standard_error.unwrap_or(0.0);
    a.success.mean - b.success.mean > 2.0 * (se(a).powi(2) + se(b).powi(2)).sqrt()
}

/// `a` at least `b`, within two standard errors of their difference.
fn at_least(a: &SuccessRate, b: &SuccessRate) -> bool {
    let se = |r: &SuccessRate| r.success.standard_error.unwrap_or(0.0);
    a.success.mean >= b.success.mean - 2.0 * (se(a).powi(2) + se(b).powi(2)).sqrt()
}

/// The truth of each observed-only signal is the synthesised one's with the ionosphere
/// scaled to its carrier: on every satellite the geometry-free code `P_f - P_1` equals the
/// geometry-free phase `lambda_1 phi_1 - lambda_f phi_f` (the truth has no ambiguity; the
/// scenario has no multipath or events), and the L5 and L2 (B3I and B2I) ionospheres stand
/// in the ratio of `(f_1 / f)^2 - 1`, a ratio of carrier frequencies only; the Doppler
/// scales with the carrier.
#[test]
fn observed_signals_follow_the_ionosphere_of_their_carrier() {
    let run = observation_run(&scenario()).unwrap();
    let mut checked = 0;
    let mut largest_m: f64 = 0.0;
    for epoch in run.truth.iter().flat_map(|f| &f.epochs) {
        let of = |sat, signal| {
            epoch
                .sats
                .iter()
                .find(|r: &&ObsRecord| r.sat == sat && r.signal == signal)
        };
        for r in epoch.sats.iter().filter(|r| r.signal.is_default_fix()) {
            let [first, second] = if r.signal == Signal::GpsL1Ca {
                [Signal::GpsL2, Signal::GpsL5]
            } else {
                [Signal::BdsB2I, Signal::BdsB3I]
            };
            let (Some(a), Some(b)) = (of(r.sat, first), of(r.sat, second)) else {
                panic!("{} at {}: no {first} or {second} truth", r.sat, epoch.time);
            };
            let code = |x: &ObsRecord| x.pseudorange_m.unwrap();
            let phase_m = |x: &ObsRecord| x.carrier_phase_cycles.unwrap() * x.signal.wavelength_m();
            let k = |s: Signal| (r.signal.carrier_hz() / s.carrier_hz()).powi(2) - 1.0;
            let (gf_a, gf_b) = (code(a) - code(r), code(b) - code(r));
            for (gf, x) in [(gf_a, a), (gf_b, b)] {
                let gf_phase = phase_m(r) - phase_m(x);
                assert!(
                    (gf - gf_phase).abs() < 1e-4,
                    "{} {}: code {gf} m, phase {gf_phase} m",
                    r.sat,
                    x.signal
                );
            }
            // Doppler at each carrier: the same range rate (the ionosphere's rate is mm/s
            // against km/s).
            for x in [a, b] {
                let (d_x, d_r) = (x.doppler_hz.unwrap(), r.doppler_hz.unwrap());
                if d_r.abs() > 100.0 {
                    let want = x.signal.carrier_hz() / r.signal.carrier_hz();
                    assert!(
                        (d_x / d_r - want).abs() < 1e-4,
                        "{} {}: Doppler {d_x} Hz against {d_r} Hz",
                        r.sat,
                        x.signal
                    );
                }
            }
            if gf_a.abs() > 0.05 {
                let ratio = gf_b / gf_a;
                assert!(
                    (ratio - k(second) / k(first)).abs() < 1e-6,
                    "{}: {ratio} vs {}",
                    r.sat,
                    k(second) / k(first)
                );
            }
            largest_m = largest_m.max(gf_a.abs());
            checked += 1;
        }
    }
    assert!(checked > 1000, "{checked} satellite-epochs");
    // The ionosphere is there to be scaled (the thesis LEO flies under part of it).
    assert!(largest_m > 0.1, "largest L2 - L1 ionosphere {largest_m} m");
}

/// Plain LAMBDA, one epoch at a time, for one, two and three frequencies of each system:
/// the success rates printed; asserted what a second and third frequency must do to a
/// single-frequency search that fails on some epochs, raise it (by more than two standard
/// errors), and never lower one that already succeeds.
#[test]
fn more_frequencies_raise_the_single_epoch_success_rate() {
    let s = scenario();
    let sets: [(&str, Vec<Signal>); 7] = [
        ("GPS L1", vec![Signal::GpsL1Ca]),
        ("GPS L1+L2", vec![Signal::GpsL1Ca, Signal::GpsL2]),
        (
            "GPS L1+L2+L5",
            vec![Signal::GpsL1Ca, Signal::GpsL2, Signal::GpsL5],
        ),
        ("BDS B1I", vec![Signal::BdsB1I]),
        (
            "BDS B1I+B2I+B3I",
            vec![Signal::BdsB1I, Signal::BdsB2I, Signal::BdsB3I],
        ),
        ("GPS+BDS 1f", Signal::DEFAULT_FIX.to_vec()),
        ("GPS+BDS 3f", Signal::ALL.to_vec()),
    ];
    let mut rates = Vec::new();
    for (name, signals) in &sets {
        let r = single_epoch(&s, signals, Constraint::None).unwrap();
        println!("MULTIFREQUENCY {name:16} LAMBDA: {}", r.summary());
        rates.push(r);
    }
    let [l1, l12, l125, b1, b123, both1, both3] = &rates[..] else {
        unreachable!()
    };
    assert!(above(l12, l1), "{l12:?} vs {l1:?}");
    assert!(at_least(l125, l12), "{l125:?} vs {l12:?}");
    assert!(at_least(b123, b1), "{b123:?} vs {b1:?}");
    assert!(at_least(both3, both1), "{both3:?} vs {both1:?}");
}
