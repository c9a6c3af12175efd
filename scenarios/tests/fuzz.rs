//! Property tests: arbitrary text and mutated valid scenarios never panic; every outcome is
//! a scenario (and then a world or an error) or a clear error naming the source.

mod common;

use proptest::prelude::*;
use skyforge_scenarios::{ScenarioError, bundled, parse};
use std::path::Path;

const SOURCE: &str = "fuzz.toml";

fn assert_clear(err: &ScenarioError) {
    let shown = err.to_string();
    assert!(
        shown.starts_with(SOURCE),
        "error does not name the source: {shown}"
    );
    assert!(!err.allowed.trim().is_empty(), "empty message: {shown}");
    if let (Some(line), Some(column)) = (err.line, err.column) {
        assert!(line >= 1 && column >= 1, "{shown}");
    }
}

/// Parse, and build what parses: never a panic, always Ok or a clear error.
fn outcome(text: &str) {
    match parse(text, SOURCE, Path::new(".")) {
        Ok(scenario) => {
            if let Err(err) = scenario.build() {
                assert_clear(&err);
            }
        }
        Err(err) => assert_clear(&err),
    }
}

/// Byte ranges of the numbers written in `text` (outside strings and comments).
fn numbers(text: &str) -> Vec<std::ops::Range<usize>> {
    let mut found = Vec::new();
    let mut offset = 0;
    for line in text.split_inclusive('\n') {
        let bytes = line.as_bytes();
        let mut in_string = false;
        let mut i = 0;
        while i < bytes.len() {
            let c = bytes[i];
            if c == b'"' {
                in_string = !in_string;
            } else if !in_string && c == b'#' {
                break;
            } else if !in_string
                && (c.is_ascii_digit()
                    || (c == b'-' && bytes.get(i + 1).is_some_and(u8::is_ascii_digit)))
                && (i == 0 || matches!(bytes[i - 1], b' ' | b'[' | b','))
            {
                let end = (i + 1..bytes.len())
                    .find(|&j| {
                        !(bytes[j].is_ascii_digit()
                            || matches!(bytes[j], b'.' | b'e' | b'E' | b'-' | b'+' | b'_'))
                    })
                    .unwrap_or(bytes.len());
                found.push(offset + i..offset + end);
                i = end;
                continue;
            }
            i += 1;
        }
        offset += line.len();
    }
    found
}

#[derive(Debug, Clone)]
enum Mutation {
    /// Replace the n-th number (mod count) by a value.
    Number(usize, String),
    /// Delete the n-th line (mod count).
    Delete(usize),
    /// Duplicate the n-th line (mod count).
    Duplicate(usize),
}

fn value() -> impl Strategy<Value = String> {
    prop_oneof![
        prop::sample::select(vec![
            "nan",
            "+nan",
            "-nan",
            "inf",
            "-inf",
            "0",
            "0.0",
            "-0.0",
            "-1",
            "-1.0",
            "1",
            "1e308",
            "-1e308",
            "1e-320",
            "2",
            "100",
            "1000000",
            "9223372036854775807",
            "-9223372036854775808",
            "18446744073709551616",
            "\"NaN\"",
            "true",
            "\"\"",
            "[]",
            "{}",
            "",
            "0x10",
            "1_000",
        ])
        .prop_map(str::to_string),
        any::<f64>().prop_map(|x| format!("{x:?}")),
        any::<i64>().prop_map(|x| x.to_string()),
        (-1e4..1e4f64).prop_map(|x| format!("{x}")),
    ]
}

fn mutation() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        4 => (any::<usize>(), value()).prop_map(|(n, v)| Mutation::Number(n, v)),
        1 => any::<usize>().prop_map(Mutation::Delete),
        1 => any::<usize>().prop_map(Mutation::Duplicate),
    ]
}

fn apply(text: &str, mutation: &Mutation) -> String {
    match mutation {
        Mutation::Number(n, v) => {
            let spans = numbers(text);
            if spans.is_empty() {
                return text.to_string();
            }
            let span = &spans[n % spans.len()];
            format!("{}{v}{}", &text[..span.start], &text[span.end..])
        }
        Mutation::Delete(n) | Mutation::Duplicate(n) => {
            let lines: Vec<&str> = text.split_inclusive('\n').collect();
            if lines.is_empty() {
                return text.to_string();
            }
            let k = n % lines.len();
            let mut out = String::new();
            for (i, line) in lines.iter().enumerate() {
                if i != k || matches!(mutation, Mutation::Duplicate(_)) {
                    out.push_str(line);
                }
                if i == k && matches!(mutation, Mutation::Duplicate(_)) {
                    out.push_str(line);
                }
            }
            out
        }
    }
}

#[test]
fn number_scanner_finds_values_not_strings_or_comments() {
    let text = "a = 1.5 # 7\nb = \"x 2\"\nc = [0.0, -3e2]\nd = 4\n";
    let found: Vec<&str> = numbers(text).into_iter().map(|r| &text[r]).collect();
    assert_eq!(found, ["1.5", "0.0", "-3e2", "4"]);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn arbitrary_text_never_panics(text in "\\PC{0,400}") {
        outcome(&text);
    }

    #[test]
    fn toml_like_text_never_panics(text in "([a-z_]{1,12} = [-0-9.e\"a-z\\[\\], ]{0,20}\n|\\[[a-z_.]{1,20}\\]\n|\\[\\[antennas\\]\\]\n){0,20}") {
        outcome(&text);
    }

    #[test]
    fn mutated_bundled_scenarios_never_panic(
        which in 0..bundled().len(),
        mutations in prop::collection::vec(mutation(), 1..4),
    ) {
        let mut text = bundled()[which].text.to_string();
        for m in &mutations {
            text = apply(&text, m);
        }
        outcome(&text);
    }

    #[test]
    fn mutated_base_scenario_never_panics(mutations in prop::collection::vec(mutation(), 1..4)) {
        let mut text = common::BASE.to_string();
        for m in &mutations {
            text = apply(&text, m);
        }
        outcome(&text);
    }
}
