#!/usr/bin/env bash
# The test suite: formatting, lints, the default tests, the interoperability tier (the
# real GNSS-SDR, RTKLIB, Slurm and Chromium from Debian's gnss-sdr, rtklib, slurm-wlm,
# munge and chromium packages, installed here when missing) and the real-data tier. The long
# signal-level acceptance tests listed in scripts/long-tests.txt run by scripts/acceptance.sh.
#   scripts/test.sh              real-data tier runs when the data folder exists
#   scripts/test.sh --real-data  the real-data tier is required (CI)
# The data folder is $SKYFORGE_DATA, default ../shared/data (relative to the repo root).
set -euo pipefail
cd "$(dirname "$0")/.."
require_data=0
[ "${1:-}" = "--real-data" ] && require_data=1

log=$(mktemp)
trap 'rm -f "$log"' EXIT
# The long acceptance tests run by scripts/acceptance.sh, not here (scripts/long-tests.txt).
skips=()
while read -r _ _ name; do
  if [ -n "$name" ]; then skips+=(--skip "$name"); fi
done < <(grep -v '^#' scripts/long-tests.txt)

scripts/deps.sh gnss-sdr rtklib slurm-wlm munge chromium
echo "test: cargo fmt --check"
cargo fmt --all -- --check
echo "test: cargo clippy"
cargo clippy --workspace --all-targets -- -D warnings
echo "test: default suite"
cargo test --workspace 2>&1 | tee -a "$log"

data="${SKYFORGE_DATA:-$(pwd)/../shared/data}"
if [ -d "$data" ]; then
  echo "test: interoperability and real-data tiers with SKYFORGE_DATA=$data"
  SKYFORGE_DATA="$data" cargo test --workspace -- --ignored "${skips[@]}" 2>&1 | tee -a "$log"
elif [ $require_data -eq 1 ]; then
  echo "test: REAL-DATA FOLDER MISSING: $data (set SKYFORGE_DATA)" >&2
  exit 1
else
  echo "test: interoperability tier (GNSS-SDR, RTKLIB)"
  cargo test -p skyforge-sim --test interop_gnss_sdr --test interop_jamming --test interop_rtklib --test interop_rtklib_receiver --test interop_slurm --test report -- --ignored 2>&1 | tee -a "$log"
  echo "test: ************************************************************"
  echo "test: real-data tier SKIPPED: no data folder at $data (set SKYFORGE_DATA)"
  echo "test: ************************************************************"
fi

# One closing line over every test binary above.
awk '/^test result:/ { for (i = 1; i <= NF; i++) { if ($(i+1) ~ /^passed/) p += $i; if ($(i+1) ~ /^failed/) f += $i } }
     END { printf "tests: %d passed, %d failed\n", p, f }' "$log"
