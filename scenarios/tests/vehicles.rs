//! `[[vehicles]]`: several platforms in one scenario, each with its antennas and
//! oscillator, run one at a time with receiver-side streams of its own.

mod common;

use common::*;

/// A LEO vehicle named `name` with one antenna.
fn vehicle(name: &str, anomaly_deg: f64) -> String {
    format!(
        r#"
[[vehicles]]
name = "{name}"
[vehicles.platform.leo.elements]
semi_major_axis_km = 6878.137
eccentricity = 0.01
inclination_deg = 98.0
raan_deg = 0.0
arg_perigee_deg = 0.0
mean_anomaly_deg = {anomaly_deg:?}
[[vehicles.antennas]]
name = "ant1"
position_body_m = [0.0, 0.0, 0.0]
"#
    )
}

const SITE: &str = "latitude_deg = 30.0\nlongitude_deg = 114.0\nheight_m = 50.0";

const HEAD: &str = r#"
name = "pair"
seed = 5
[time]
start = "2023-03-12T00:00:00 GPST"
duration_s = 60.0
"#;

fn pair() -> String {
    format!(
        "{HEAD}{}{}",
        vehicle("target", 0.0),
        vehicle("chaser", -0.27)
    )
}

#[test]
fn each_vehicle_runs_as_a_single_platform_view_with_its_own_receiver_seed() {
    let s = parse_in(&pair(), std::path::Path::new(".")).expect("two vehicles");
    assert_eq!(s.vehicles.len(), 2);
    // The scenario's own platform is the first vehicle's; it is not built as such.
    assert_eq!(s.platform, s.vehicles[0].platform);
    let err = s.build().expect_err("several vehicles are run per vehicle");
    assert_eq!(err.field, "vehicles");
    let views = s.vehicle_views();
    assert_eq!(views.len(), 2);
    assert_eq!(views[1].vehicle.as_deref(), Some("chaser"));
    assert_eq!(views[1].platform, s.vehicles[1].platform);
    assert!(views[1].vehicles.is_empty());
    // Receiver-side seeds differ between vehicles and from the scenario's; the scenario
    // seed (satellite-side streams) is the same for all.
    let seeds: Vec<u64> = views.iter().map(|v| v.receiver_seed()).collect();
    assert_ne!(seeds[0], seeds[1]);
    assert!(seeds.iter().all(|&r| r != 5));
    assert!(views.iter().all(|v| v.seed == 5));
    for v in &views {
        v.build().expect("a view builds");
    }
    // A single-platform scenario is its own view, with the scenario seed.
    let single = parse_in(&ground(SITE), std::path::Path::new(".")).unwrap();
    assert_eq!(single.vehicle_views(), std::slice::from_ref(&single));
    assert_eq!(single.receiver_seed(), single.seed);
}

#[test]
fn vehicle_tables_are_checked_where_they_are_written() {
    let both = format!("{}{}", ground(SITE), vehicle("target", 0.0));
    assert_eq!(parse_error(&both).field, "vehicles");
    let top_antenna = format!(
        "{}\n[[antennas]]\nname = \"a\"\nposition_body_m = [0.0, 0.0, 0.0]\n",
        pair()
    );
    assert_eq!(parse_error(&top_antenna).field, "antennas");
    let twice = format!("{HEAD}{}{}", vehicle("a", 0.0), vehicle("a", 1.0));
    let err = parse_error(&twice);
    assert_eq!(err.field, "vehicles[1].name");
    assert!(err.allowed.contains("unique"), "{err}");
    let escape = format!("{HEAD}{}", vehicle("../up", 0.0));
    let err = parse_error(&escape);
    assert_eq!(err.field, "vehicles[0].name");
    assert_at(&err, position_of(&escape, "name = \"../up\"", "\"../up\""));
    let bad_orbit = format!(
        "{HEAD}{}",
        vehicle("a", 0.0).replace("eccentricity = 0.01", "eccentricity = 1.5")
    );
    let err = parse_error(&bad_orbit);
    assert!(err.field.starts_with("vehicles[0].platform.leo"), "{err}");
    let no_antenna = format!(
        "{HEAD}{}",
        vehicle("a", 0.0).replace(
            "[[vehicles.antennas]]\nname = \"ant1\"\nposition_body_m = [0.0, 0.0, 0.0]\n",
            ""
        )
    );
    assert_eq!(parse_error(&no_antenna).field, "vehicles[0].antennas");
    let nothing = HEAD.to_string();
    assert_eq!(parse_error(&nothing).field, "platform");
}

/// `[[vehicles.events]]` reach that vehicle's view only, after the scenario's own, and
/// are checked where they are written: an antenna of that vehicle, a span inside the run.
#[test]
fn vehicle_events_reach_their_vehicle_only() {
    let event = "[[vehicles.events]]\nkind = \"outage\"\nantenna = \"ant1\"\n\
                 satellite = \"G05\"\nstart_s = 10.0\nend_s = 12.0\n";
    let text = format!(
        "{HEAD}\n[[errors.events]]\nkind = \"outage\"\nstart_s = 1.0\nend_s = 2.0\n{}{}{event}",
        vehicle("target", 0.0),
        vehicle("chaser", -0.27)
    );
    let s = parse_in(&text, std::path::Path::new(".")).expect("vehicle events");
    let views = s.vehicle_views();
    assert_eq!(
        views[0].errors.events.len(),
        1,
        "the scenario's event alone"
    );
    assert_eq!(views[1].errors.events.len(), 2);
    assert_eq!(views[1].errors.events[1].start_s, 10.0);
    for v in &views {
        v.build().expect("a view builds");
    }
    let late = text.replace(
        "start_s = 10.0\nend_s = 12.0",
        "start_s = 70.0\nend_s = 72.0",
    );
    let err = parse_error(&late);
    assert!(err.field.starts_with("vehicles[1].events[0]"), "{err}");
    let elsewhere = text.replace(
        "antenna = \"ant1\"\nsatellite",
        "antenna = \"ant9\"\nsatellite",
    );
    let err = parse_error(&elsewhere);
    assert_eq!(err.field, "vehicles[1].events[0].antenna");
    assert!(err.allowed.contains("vehicles[1].antennas"), "{err}");
}
