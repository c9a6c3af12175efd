#!/usr/bin/env bash
# Run the bundled thesis LEO scenario (embedded constellations, no data files needed):
# installs missing system packages, builds skyforge in release mode, writes out/thesis-leo/truth.h5.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/deps.sh
echo "demo: building skyforge (release)"
cargo build --release -p skyforge-sim
echo "demo: skyforge run thesis-leo --out out/thesis-leo --force"
target/release/skyforge run thesis-leo --out out/thesis-leo --force
