#!/usr/bin/env bash
# Issue #14's synthesis bar (BENCHMARKS.md): `skyforge synth scenarios/bench/synth-bar.toml`
# N times (default 5), printing CPU seconds (user + system) per run and channel-samples per
# CPU-second (satellites in the first RINEX epoch x samples). With more binaries after N,
# runs them interleaved (this VM's speed drifts within minutes; compare binaries side by
# side): scripts/bench-synth-bar.sh 5 OLD_BINARY NEW_BINARY.
set -euo pipefail
cd "$(dirname "$0")/.."
source scripts/bench-cpu.sh
bench_setup 5 "$@"
bench_time "" synth scenarios/bench/synth-bar.toml
# Satellites in view: the count at the end of the first epoch line of the RINEX file.
sats=$(awk '/^>/ {print $NF; exit}' "$work"/out/ant1.obs.rnx)
rate=2600000; seconds=30
for bin in "${bins[@]}"; do
  mean=$(echo "${total[$bin]} / $runs" | bc -l)
  printf 'bench: %s mean %.3f CPU-s, %s satellites, %.3g channel-samples per CPU-second\n' \
    "$bin" "$mean" "$sats" "$(echo "$sats * $rate * $seconds / $mean" | bc -l)"
done
