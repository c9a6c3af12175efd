#!/usr/bin/env bash
# Issue #14's observation-level study bar (BENCHMARKS.md, "Studies"): `skyforge study run
# scenarios/bench/study-bar.study.toml` (4 runs of 3600 epochs) N times (default 3),
# printing CPU seconds per run of the study. With binaries after N, runs them interleaved:
# scripts/bench-study-bar.sh 3 OLD_BINARY NEW_BINARY.
set -euo pipefail
cd "$(dirname "$0")/.."
runs=${1:-3}
shift || true
if [ $# -eq 0 ]; then
  cargo build --release -p skyforge-sim
  set -- "$(pwd)/target/release/skyforge"
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
declare -A total
for _ in $(seq 1 "$runs"); do
  for bin in "$@"; do
    rm -rf "$work/out"
    cpu=$(/usr/bin/time -f "%U %S" "$bin" study run scenarios/bench/study-bar.study.toml --out "$work/out" 2>&1 >/dev/null | tail -1 | awk '{print $1 + $2}')
    total[$bin]=$(echo "${total[$bin]:-0} + $cpu" | bc -l)
    echo "bench: $bin $cpu CPU-s for 4 runs"
  done
done
for bin in "$@"; do
  printf 'bench: %s mean %.2f CPU-s per run of 3600 epochs\n' "$bin" "$(echo "${total[$bin]} / $runs / 4" | bc -l)"
done
