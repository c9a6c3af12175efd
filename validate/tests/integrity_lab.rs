//! The B-value monitor on paper 002's lab set-up at the observation level.

use skyforge_receiver::integrity::Statistic;
use skyforge_validate::attitude::observation_run;
use skyforge_validate::integrity::lab::{Case, scenario};
use skyforge_validate::integrity::monitor::{calibrate, case_run};

#[test]
#[ignore]
fn timing_probe() {
    let s = scenario(&Case::FaultFree.events(), 3, None).unwrap();
    let t = std::time::Instant::now();
    let _ = observation_run(&s).unwrap();
    eprintln!("observation run: {:?}", t.elapsed());
    let t = std::time::Instant::now();
    let sigma = calibrate(1..=2u64, None).unwrap();
    eprintln!("calibrate 2 seeds: {:?}\n{sigma:#?}", t.elapsed());
    let t = std::time::Instant::now();
    let run = case_run(Case::CycleSlip, 2002, &sigma).unwrap();
    eprintln!("one case run: {:?}", t.elapsed());
    for e in run.epochs.iter().filter(|e| [499.0, 501.0, 600.0, 1000.0].contains(&e.t_s.round())) {
        for s in e.sats.iter().filter(|s| s.sat.to_string() == "C03") {
            eprintln!("{} {} el {:.1} thr {:?}", e.t_s, s.sat, s.elevation_deg, s.threshold);
            for v in s.stations.iter().flatten() {
                eprintln!("   b {:?} alarm {:?}", v.b, v.alarm);
            }
        }
    }
    let _ = Statistic::ALL;
}

#[test]
#[ignore]
fn print_pattern_rows() {
    let t = std::time::Instant::now();
    let rows = skyforge_validate::integrity::patterns::rows(20).unwrap();
    for r in &rows {
        eprintln!("{:50} {:?} {:?} {:?} | {}", r.row, r.thesis, r.ours, r.verdict, r.note);
    }
    eprintln!("{:?}", t.elapsed());
}

#[test]
#[ignore]
fn fault_free_alarm_breakdown() {
    let sigma = calibrate(1..=8u64, None).unwrap();
    eprintln!("{sigma:?}");
    let run = case_run(Case::FaultFree, 2002, &sigma).unwrap();
    let mut counts = std::collections::BTreeMap::new();
    for e in &run.epochs {
        for s in &e.sats {
            for (m, v) in s.stations.iter().enumerate() {
                if let Some(v) = v {
                    for k in 0..4 {
                        if v.alarm[k] {
                            *counts.entry((Statistic::ALL[k].name(), s.sat.to_string(), m, (s.elevation_deg / 5.0).floor() as i32 * 5)).or_insert(0) += 1;
                        }
                    }
                }
            }
        }
    }
    for (k, v) in counts { eprintln!("{k:?} {v}"); }
}

#[test]
#[ignore]
fn divergence_probe() {
    let sigma = calibrate(1..=8u64, None).unwrap();
    let run = case_run(Case::FaultFree, 2002, &sigma).unwrap();
    for e in run.epochs.iter().filter(|e| (e.t_s as i64) % 50 == 0) {
        for s in e.sats.iter().filter(|s| s.sat.to_string() == "C01") {
            let b: Vec<String> = s.stations.iter().flatten().map(|v| format!("{:+.5}{}", v.b[3], if v.alarm[3] {"!"} else {""})).collect();
            let x: Vec<String> = s.stations.iter().flatten().map(|v| format!("{:+.5}", v.statistic[3])).collect();
            eprintln!("{} age {} thr {:.5} B {:?} X {:?}", e.t_s, s.track_age_s, s.threshold[3], b, x);
        }
    }
}
