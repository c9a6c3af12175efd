//! The fuzz targets in the default test suite (seconds each): every committed corpus and
//! regression input replayed, then a short deterministic mutation loop per target over
//! its corpus. `scripts/fuzz.sh` runs the same targets under libFuzzer for minutes or
//! hours (docs/fuzzing.md).

use rand::{Rng, RngCore, SeedableRng};
use rand_chacha::ChaCha8Rng;
use skyforge_fuzz_targets::{TARGETS, target};
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::{Path, PathBuf};

/// Mutated inputs tried per target (a few seconds each in the debug build).
const MUTATIONS_PER_TARGET: usize = 50_000;

/// Numbers a mutation writes over a numeric field: huge, negative, not finite, overflowing.
const NASTY_NUMBERS: &[&str] = &[
    "NaN",
    "nan",
    "inf",
    "-inf",
    "1e308",
    "-1e308",
    "1e999",
    "4.9e-324",
    "-1",
    "-0",
    "0",
    "4294967296",
    "18446744073709551616",
    "-9223372036854775809",
    "99999999999999999999999",
    "2147483647",
    "65535",
    "1D+300",
];

fn fuzz_dir(kind: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../fuzz")
        .join(kind)
}

/// The files of `fuzz/<kind>/<target>/` (none when the folder does not exist).
fn inputs(kind: &str, target: &str) -> Vec<PathBuf> {
    let dir = fuzz_dir(kind).join(target);
    let Ok(entries) = std::fs::read_dir(&dir) else {
        return Vec::new();
    };
    let mut files: Vec<PathBuf> = entries
        .map(|e| {
            e.unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
                .path()
        })
        .filter(|p| p.is_file())
        .collect();
    files.sort();
    files
}

/// Runs `f` on `input`; on a panic, keeps the input in the temporary directory and fails
/// naming it (copy it, minimised, to `fuzz/regressions/<target>/`).
fn run(name: &str, f: fn(&[u8]), input: &[u8], what: &str) {
    if catch_unwind(AssertUnwindSafe(|| f(input))).is_err() {
        let kept = std::env::temp_dir().join(format!(
            "skyforge-fuzz-crash-{name}-{}",
            what.replace(['/', ' '], "_")
        ));
        let saved = std::fs::write(&kept, input).map_or_else(
            |e| format!("(not saved: {e})"),
            |()| kept.display().to_string(),
        );
        panic!("target {name} panicked on {what}; input kept at {saved}");
    }
}

#[test]
fn every_target_has_a_seed_corpus_and_every_folder_a_target() {
    for (name, _) in TARGETS {
        assert!(
            !inputs("corpus", name).is_empty(),
            "fuzz/corpus/{name}/ is empty"
        );
        let fuzz_target = fuzz_dir("fuzz_targets").join(format!("{name}.rs"));
        assert!(fuzz_target.is_file(), "{} missing", fuzz_target.display());
    }
    for kind in ["corpus", "regressions"] {
        let Ok(entries) = std::fs::read_dir(fuzz_dir(kind)) else {
            continue;
        };
        for e in entries {
            let e = e.unwrap_or_else(|e| panic!("{e}"));
            let name = e.file_name().to_string_lossy().into_owned();
            if e.path().is_dir() {
                assert!(
                    target(&name).is_some(),
                    "fuzz/{kind}/{name}: no such target"
                );
            }
        }
    }
}

#[test]
fn corpus_and_regressions_replay_without_a_panic() {
    let mut replayed = 0;
    for &(name, f) in TARGETS {
        for kind in ["corpus", "regressions"] {
            for path in inputs(kind, name) {
                let input = std::fs::read(&path).unwrap_or_else(|e| panic!("{e}"));
                run(name, f, &input, &path.display().to_string());
                replayed += 1;
            }
        }
    }
    assert!(replayed >= TARGETS.len(), "{replayed} inputs replayed");
}

/// Byte ranges of the numeric fields of `input` (digits with signs, points, exponents).
fn numbers(input: &[u8]) -> Vec<(usize, usize)> {
    let mut out = Vec::new();
    let mut i = 0;
    while i < input.len() {
        if input[i].is_ascii_digit() {
            let mut start = i;
            if start > 0 && matches!(input[start - 1], b'-' | b'+' | b'.') {
                start -= 1;
            }
            while i < input.len()
                && (input[i].is_ascii_alphanumeric() && b"0123456789eEdD".contains(&input[i])
                    || matches!(input[i], b'.' | b'-' | b'+'))
            {
                i += 1;
            }
            out.push((start, i));
        } else {
            i += 1;
        }
    }
    out
}

/// Line ranges of `input` (each with its newline).
fn lines(input: &[u8]) -> Vec<(usize, usize)> {
    let mut out = Vec::new();
    let mut start = 0;
    for (i, &b) in input.iter().enumerate() {
        if b == b'\n' {
            out.push((start, i + 1));
            start = i + 1;
        }
    }
    if start < input.len() {
        out.push((start, input.len()));
    }
    out
}

/// One random edit of `input`.
fn mutate(rng: &mut ChaCha8Rng, input: &mut Vec<u8>) {
    let len = input.len();
    match rng.random_range(0..9) {
        // Flip a bit.
        0 if len > 0 => {
            let i = rng.random_range(0..len);
            input[i] ^= 1 << rng.random_range(0..8);
        }
        // Truncate.
        1 => input.truncate(rng.random_range(0..=len)),
        // Insert random bytes.
        2 => {
            let at = rng.random_range(0..=len);
            let mut bytes = vec![0u8; rng.random_range(1..8)];
            rng.fill_bytes(&mut bytes);
            input.splice(at..at, bytes);
        }
        // Delete a run of bytes.
        3 if len > 0 => {
            let at = rng.random_range(0..len);
            let end = (at + rng.random_range(1..16)).min(len);
            input.drain(at..end);
        }
        // Duplicate, delete or move a line.
        4..=5 => {
            let ls = lines(input);
            if ls.is_empty() {
                return;
            }
            let (s, e) = ls[rng.random_range(0..ls.len())];
            let line = input[s..e].to_vec();
            if rng.random_bool(0.5) {
                input.drain(s..e);
            }
            let (at, _) = ls[rng.random_range(0..ls.len())];
            let at = at.min(input.len());
            input.splice(at..at, line);
        }
        // Replace a numeric field by a hostile number.
        6..=7 => {
            let ns = numbers(input);
            if ns.is_empty() {
                return;
            }
            let (s, e) = ns[rng.random_range(0..ns.len())];
            let nasty = NASTY_NUMBERS[rng.random_range(0..NASTY_NUMBERS.len())];
            input.splice(s..e, nasty.bytes());
        }
        // Overwrite a byte with a structural character.
        _ if len > 0 => {
            let i = rng.random_range(0..len);
            input[i] = *b"\n\r \"[]{}=,:>-.0\0"
                .get(rng.random_range(0..16))
                .unwrap_or(&b' ');
        }
        _ => {}
    }
}

#[test]
fn mutated_corpus_inputs_do_not_panic() {
    for &(name, f) in TARGETS {
        let seeds: Vec<Vec<u8>> = inputs("corpus", name)
            .iter()
            .chain(&inputs("regressions", name))
            .map(|p| std::fs::read(p).unwrap_or_else(|e| panic!("{e}")))
            .collect();
        assert!(!seeds.is_empty(), "{name}: no seeds");
        // One fixed stream per target: the same inputs on every run.
        let seed = name.bytes().fold(0x5eed_u64, |h, b| {
            h.wrapping_mul(31).wrapping_add(u64::from(b))
        });
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        for k in 0..MUTATIONS_PER_TARGET {
            let mut input = seeds[rng.random_range(0..seeds.len())].clone();
            for _ in 0..rng.random_range(1..=4) {
                mutate(&mut rng, &mut input);
            }
            run(name, f, &input, &format!("mutation {k}"));
        }
    }
}
