#!/usr/bin/env bash
# Issue #14's synthesis bar (BENCHMARKS.md): `skyforge synth scenarios/bench/synth-bar.toml`
# N times (default 5), printing CPU seconds (user + system) per run and channel-samples per
# CPU-second (satellites in the first RINEX epoch x samples). With more binaries after N,
# runs them interleaved (this VM's speed drifts within minutes; compare binaries side by
# side): scripts/bench-synth-bar.sh 5 OLD_BINARY NEW_BINARY.
set -euo pipefail
cd "$(dirname "$0")/.."
runs=${1:-5}
shift || true
if [ $# -eq 0 ]; then
  cargo build --release -p skyforge-sim
  set -- "$(pwd)/target/release/skyforge"
fi
scenario=scenarios/bench/synth-bar.toml
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
declare -A total
for _ in $(seq 1 "$runs"); do
  for bin in "$@"; do
    rm -rf "$work/out"
    cpu=$(/usr/bin/time -f "%U %S" "$bin" synth "$scenario" --out "$work/out" 2>&1 >/dev/null | tail -1 | awk '{print $1 + $2}')
    total[$bin]=$(echo "${total[$bin]:-0} + $cpu" | bc -l)
    echo "bench: $bin $cpu CPU-s"
  done
done
# Satellites in view: the count at the end of the first epoch line of the RINEX file.
sats=$(awk '/^>/ {print $NF; exit}' "$work"/out/ant1.obs.rnx)
rate=2600000; seconds=30
for bin in "$@"; do
  mean=$(echo "${total[$bin]} / $runs" | bc -l)
  printf 'bench: %s mean %.3f CPU-s, %s satellites, %.3g channel-samples per CPU-second\n' \
    "$bin" "$mean" "$sats" "$(echo "$sats * $rate * $seconds / $mean" | bc -l)"
done
