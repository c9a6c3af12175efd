#!/usr/bin/env bash
# Fuzz SkyForge's input readers with libFuzzer (cargo-fuzz, nightly): docs/fuzzing.md.
#   scripts/fuzz.sh [TARGET|all] [SECONDS]     default: all, 600 s per target
# Targets: scenario rinex_nav rinex_obs sigmf raw_samples (fuzz-targets/src/lib.rs).
# The corpus grows in $FUZZ_SCRATCH/<target> (default target/fuzz-corpus, not committed),
# seeded from fuzz/corpus/<target>; a crash is written to fuzz/artifacts/<target>/: minimise
# it (cargo +nightly fuzz tmin <target> <file>) and commit it to fuzz/regressions/<target>/.
# Runs one target after another on one core, under nice. The default test suite replays
# the corpus and regressions and runs a short mutation loop (fuzz-targets/tests/replay.rs).
set -euo pipefail
cd "$(dirname "$0")/.."
which="${1:-all}"
seconds="${2:-600}"
all=(scenario rinex_nav rinex_obs sigmf raw_samples)
if [ "$which" = all ]; then targets=("${all[@]}"); else targets=("$which"); fi
for t in "${targets[@]}"; do
  [[ " ${all[*]} " == *" $t "* ]] || { echo "fuzz: unknown target $t (${all[*]})" >&2; exit 2; }
done

if ! rustup toolchain list | grep -q '^nightly'; then
  echo "fuzz: installing the nightly toolchain"
  rustup toolchain install nightly --profile minimal
fi
if ! cargo +nightly fuzz --version >/dev/null 2>&1; then
  echo "fuzz: installing cargo-fuzz"
  cargo +nightly install cargo-fuzz --locked
fi

scratch="${FUZZ_SCRATCH:-$(pwd)/target/fuzz-corpus}"
target_dir="${FUZZ_TARGET_DIR:-$(pwd)/target/fuzz}"
# Largest input per target (bytes): the seeds are a few kB.
max_len() {
  case "$1" in
    sigmf) echo 4096 ;;
    *) echo 16384 ;;
  esac
}

nice cargo +nightly fuzz build --target-dir "$target_dir"
summary=()
for t in "${targets[@]}"; do
  mkdir -p "$scratch/$t"
  log="$scratch/$t.log"
  echo "fuzz: $t for $seconds s (log $log)"
  status=0
  nice cargo +nightly fuzz run --target-dir "$target_dir" "$t" "$scratch/$t" "fuzz/corpus/$t" -- \
    -max_total_time="$seconds" -rss_limit_mb=4096 -timeout=10 -max_len="$(max_len "$t")" \
    -print_final_stats=1 >"$log" 2>&1 || status=$?
  execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  [ -n "$execs" ] || execs=$(grep -o '^#[0-9]*' "$log" | tail -1 | tr -d '#')
  corpus=$(find "$scratch/$t" -type f | wc -l)
  if [ $status -eq 0 ]; then result="no crash"; else result="CRASH (exit $status; see $log, fuzz/artifacts/$t/)"; fi
  line="$t: ${execs:-?} inputs in $seconds s, corpus $corpus files, $result"
  echo "fuzz: $line"
  summary+=("$line")
done
echo "fuzz: summary"
printf '  %s\n' "${summary[@]}"
for line in "${summary[@]}"; do [[ "$line" != *CRASH* ]] || exit 1; done
