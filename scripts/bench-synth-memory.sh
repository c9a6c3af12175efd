#!/usr/bin/env bash
# Synthesis memory against the `--dry-run` bound (docs/limits.md, BENCHMARKS.md "Synthesis
# memory"): the runs of the table, each a bundled or check scenario with its duration,
# sample rate, format and signal-truth rate changed, timed with /usr/bin/time (peak RSS).
#   scripts/bench-synth-memory.sh [all|quick]    quick skips the runs that write > 2 GB
# Needs up to 8 GB in $TMPDIR (each output is removed after its run).
set -euo pipefail
cd "$(dirname "$0")/.."
which="${1:-all}"
cargo build --release -p skyforge-sim
bin=$(pwd)/target/release/skyforge
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$bin" scenarios show interop-gps-static > "$work/gps.toml"
# The three-antenna LEO without its fault events (they fall outside a 3 s span).
sed '/^\[\[errors.events\]\]/,$d' scenarios/check/leo-three-antennas.toml > "$work/leo.toml"

# variant NAME BASE DURATION RATE FORMAT BITS TRUTH_HZ: BASE with those settings.
variant() {
  local name=$1 base=$2 duration=$3 rate=$4 format=$5 bits=$6 truth=$7
  sed -e "s/^duration_s = .*/duration_s = $duration/" \
      -e "s/^sample_rate_hz = .*/sample_rate_hz = $rate/" \
      -e "s/^format = .*/format = \"$format\"/" \
      -e "s/^bits = .*/bits = $bits/" \
      -e "s/^cn0_dbhz = \(.*\)/cn0_dbhz = \1\ntruth_rate_hz = $truth/" \
      "$work/$base.toml" > "$work/$name.toml"
}

# measure NAME: peak RSS of the run and the printed bound.
measure() {
  local s="$work/$1.toml"
  bound=$("$bin" synth "$s" --out "$work/out" --dry-run | sed -n 's/^memory  *at most \([^(]*\).*/\1/p')
  rss=$(/usr/bin/time -f "%M" "$bin" synth "$s" --out "$work/out" 2>&1 >/dev/null | tail -1)
  printf "bench: %-12s peak RSS %5d MB, --dry-run bound %s\n" "$1" $((rss * 1024 / 1000000)) "$bound"
  rm -rf "$work/out"
}

variant gps-4m gps 3.0 4.0e6 ci8 8 1000
variant gps-4m-nt gps 3.0 4.0e6 ci8 8 0
variant gps-100m gps 3.0 1.0e8 ci16 16 1000
variant leo-4m leo 3.0 4.0e6 ci8 4 1000
variant leo-4m-nt leo 3.0 4.0e6 ci8 4 0
variant leo-100m leo 3.0 1.0e8 ci16 16 1000
variant gps-1g gps 2.0 1.0e9 ci16 16 1000
for v in gps-4m gps-4m-nt gps-100m leo-4m leo-4m-nt; do measure "$v"; done
if [ "$which" = all ]; then
  for v in leo-100m gps-1g; do measure "$v"; done
fi
