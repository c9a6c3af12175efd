#!/usr/bin/env bash
# End-to-end receiver speed (BENCHMARKS.md, "Receiver end to end"): synthesise a scenario's
# recordings and time `skyforge receive` on them, cold and assisted.
#   scripts/bench-receive.sh            three-antenna GPS + BDS-3 at 4.092 Msps
#                                       (scenarios/bench/receiver-speed.toml; about 3 GB)
#   scripts/bench-receive.sh SCENARIO   another, e.g. scenarios/bench/receiver-speed-l1-l5.toml
#                                       (issue #34's bar; about 4.7 GB)
# The recordings go to $TMPDIR.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release -p skyforge-sim
bin=$(pwd)/target/release/skyforge
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
scenario=${1:-scenarios/bench/receiver-speed.toml}
"$bin" synth "$scenario" --out "$work/sim"
printf '[pvt]\nelevation_mask_deg = 0.0\n' | cat "$work/sim/receiver.toml" - > "$work/assist.toml"
echo "bench: cold start"
/usr/bin/time -f "bench: %e s wall, %U s user, %S s system, %M kB peak RSS" "$bin" receive "$work"/sim/*.sigmf-meta --out "$work/cold"
echo "bench: assisted"
/usr/bin/time -f "bench: %e s wall, %U s user, %S s system, %M kB peak RSS" "$bin" receive "$work"/sim/*.sigmf-meta \
    --assist "$work/sim/nav.rnx" --config "$work/assist.toml" --out "$work/assisted"
