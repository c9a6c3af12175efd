#!/usr/bin/env bash
# Issue #14's observation-level study bar (BENCHMARKS.md, "Studies"): `skyforge study run
# scenarios/bench/study-bar.study.toml` (4 runs of 3600 epochs) N times (default 3),
# printing CPU seconds per run of the study. With binaries after N, runs them interleaved:
# scripts/bench-study-bar.sh 3 OLD_BINARY NEW_BINARY.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/bench-cpu.sh
bench_setup 3 "$@"
bench_time " for 4 runs" study run scenarios/bench/study-bar.study.toml
for bin in "${bins[@]}"; do
  printf 'bench: %s mean %.2f CPU-s per run of 3600 epochs\n' "$bin" "$(echo "${total[$bin]} / $runs / 4" | bc -l)"
done
