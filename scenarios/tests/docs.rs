//! `docs/scenario.md` stays true: its examples parse and build, and every key the schema
//! accepts (as listed by the unknown-key error of each table) is documented there.

use skyforge_scenarios::parse;
use std::path::Path;

const DOC: &str = include_str!("../../docs/scenario.md");

/// The ```toml blocks of the reference that are whole scenarios.
fn scenario_examples() -> Vec<&'static str> {
    DOC.split("```toml\n")
        .skip(1)
        .filter_map(|block| block.split("```").next())
        .filter(|block| block.contains("name = "))
        .collect()
}

#[test]
fn examples_parse_and_build() {
    let examples = scenario_examples();
    assert_eq!(examples.len(), 2, "complete and minimal examples");
    for text in examples {
        let s = parse(text, "docs/scenario.md", Path::new(".")).unwrap_or_else(|e| panic!("{e}"));
        s.build().unwrap_or_else(|e| panic!("{e}"));
    }
}

/// The keys the schema accepts in a table, from the "expected ..." list of the error for
/// an unknown key written into that table of `text`.
fn accepted_keys(text: &str) -> Vec<String> {
    let err = parse(text, "t.toml", Path::new(".")).expect_err("unknown key");
    assert_eq!(err.field.rsplit('.').next(), Some("zzz_unknown"), "{err}");
    let expected = err.allowed.split("expected").nth(1).unwrap_or("");
    expected
        .split('`')
        .skip(1)
        .step_by(2)
        .map(str::to_string)
        .collect()
}

#[test]
fn every_accepted_key_is_documented() {
    let minimal = scenario_examples()[1];
    let unknown = "zzz_unknown = 1\n";
    // Tables of the minimal example get the key inside; the others are added after it.
    let in_minimal = ["time", "platform.ground"];
    let added = [
        "signal",
        "errors",
        "errors.ionosphere",
        "errors.troposphere",
        "errors.receiver_clock",
        "errors.multipath",
        "signal.link_budget",
        "signal.filter",
        "platform.leo",
        "platform.leo.forces",
        "platform.leo.integrator",
        "platform.leo.elements",
        "platform.leo.tle",
        "platform.leo.state",
        "platform.trajectory",
        "platform.segments",
        "platform.attitude",
        "platform.attitude.yaw",
        "gnss",
        "gnss.gps",
        "gnss.beidou",
        "truth",
        "imu",
        "imu.gyro",
        "imu.accel",
        "imu.vibration",
    ];
    let mut texts = vec![
        (String::new(), format!("{unknown}{minimal}")),
        (
            "antennas".to_string(),
            minimal.replacen("[[antennas]]\n", &format!("[[antennas]]\n{unknown}"), 1),
        ),
        (
            "antennas.pcv_m".to_string(),
            format!("{minimal}[antennas.pcv_m]\n{unknown}"),
        ),
    ];
    for table in in_minimal {
        let header = format!("[{table}]\n");
        let text = minimal.replacen(&header, &format!("{header}{unknown}"), 1);
        texts.push((table.to_string(), text));
    }
    for table in added {
        texts.push((
            table.to_string(),
            format!("{minimal}\n[{table}]\n{unknown}"),
        ));
    }
    // Tables with a required key, given first.
    for (table, required) in [
        ("errors.satellite", "model = \"book-sa\"\n"),
        ("errors.satellite.processes", ""),
    ] {
        let parent = if required.is_empty() {
            "[errors.satellite]\nmodel = \"gauss-markov\"\n"
        } else {
            ""
        };
        texts.push((
            table.to_string(),
            format!("{minimal}\n{parent}[{table}]\n{required}{unknown}"),
        ));
    }
    // Arrays of tables: the unknown key is reported before the missing required ones.
    for table in [
        "errors.events",
        "errors.multipath.taps",
        "errors.multipath.surfaces",
    ] {
        texts.push((
            table.to_string(),
            format!("{minimal}\n[[{table}]]\n{unknown}"),
        ));
    }
    for (table, text) in texts {
        let keys = accepted_keys(&text);
        assert!(!keys.is_empty(), "{table}");
        let prefix = if table.is_empty() {
            String::new()
        } else {
            format!("{table}.")
        };
        for key in keys {
            // A key row of a table, or the heading of a sub-table.
            let forms = [
                format!("`{key}` |"),
                format!("`{key}`,"),
                format!("`[{prefix}{key}]`"),
                format!("`[[{prefix}{key}]]`"),
            ];
            assert!(
                forms.iter().any(|form| DOC.contains(form.as_str())),
                "key `{key}` of [{table}] is not in docs/scenario.md"
            );
        }
    }
}
