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
