#!/usr/bin/env bash
# End-to-end receiver speed (BENCHMARKS.md, "Receiver end to end"): synthesise the
# three-antenna GPS + BDS-3 recording of scenarios/bench/receiver-speed.toml at 4.092 Msps
# and time `skyforge receive` on it, cold and assisted. Needs about 3 GB in $TMPDIR.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release -p skyforge-sim
bin=$(pwd)/target/release/skyforge
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$bin" synth scenarios/bench/receiver-speed.toml --out "$work/sim"
printf '[pvt]\nelevation_mask_deg = 0.0\n' | cat "$work/sim/receiver.toml" - > "$work/assist.toml"
echo "bench: cold start"
/usr/bin/time -f "bench: %e s wall, %M kB peak RSS" "$bin" receive "$work"/sim/*.sigmf-meta --out "$work/cold"
echo "bench: assisted"
/usr/bin/time -f "bench: %e s wall, %M kB peak RSS" "$bin" receive "$work"/sim/*.sigmf-meta \
    --assist "$work/sim/nav.rnx" --config "$work/assist.toml" --out "$work/assisted"
