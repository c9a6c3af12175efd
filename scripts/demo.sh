#!/usr/bin/env bash
# The README's first command (embedded constellations, no data files needed): installs
# missing system packages, builds skyforge in release mode, then
#  1. runs the bundled thesis LEO scenario -> out/thesis-leo/truth.h5;
#  2. runs the attitude chain at the signal level on the bundled attitude-leo-gps (the
#     thesis LEO, three antennas on two 1 m baselines, 60 s of GPS L1 C/A I/Q at 45 dB-Hz):
#     synth -> receive -> attitude -> validate attitude, which prints the baseline and
#     attitude errors against the truth beside the thesis's tables 5.4-4 and 5.4-5.
#     Writes out/attitude-leo-gps/{sim,rx,att} (the I/Q in sim/ is about 1.4 GB).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/deps.sh
echo "demo: building skyforge (release)"
cargo build --release -p skyforge-sim
skyforge="${CARGO_TARGET_DIR:-target}/release/skyforge"
echo "demo: skyforge run thesis-leo --out out/thesis-leo --force"
"$skyforge" run thesis-leo --out out/thesis-leo --force

demo=out/attitude-leo-gps
mkdir -p "$demo"
start=$SECONDS
echo
echo "demo: the attitude chain at the signal level, bundled attitude-leo-gps -> $demo"
echo "demo: skyforge synth attitude-leo-gps --out $demo/sim --force"
"$skyforge" synth attitude-leo-gps --out "$demo/sim" --force
echo "demo: skyforge receive (three antennas) --out $demo/rx"
"$skyforge" receive "$demo"/sim/ant1.gps-l1ca.sigmf-meta "$demo"/sim/ant2.gps-l1ca.sigmf-meta \
    "$demo"/sim/ant3.gps-l1ca.sigmf-meta --assist "$demo/sim/nav.rnx" \
    --config "$demo/sim/receiver.toml" --out "$demo/rx" --force
# The chain with the real-time KF attitude, as the thesis's tables 5.4-3..5.
printf '[relative]\nattitude = { method = "kf" }\n' >"$demo/chain.toml"
echo "demo: skyforge attitude --config $demo/chain.toml --out $demo/att"
"$skyforge" attitude "$demo"/rx/ant1.obs.rnx "$demo"/rx/ant2.obs.rnx "$demo"/rx/ant3.obs.rnx \
    --nav "$demo/sim/nav.rnx" --geometry "$demo/sim/geometry.toml" \
    --config "$demo/chain.toml" --out "$demo/att" --force
echo "demo: skyforge validate attitude --truth $demo/sim --observations $demo/rx --attitude $demo/att"
"$skyforge" validate attitude --truth "$demo/sim" --observations "$demo/rx" \
    --attitude "$demo/att" --json "$demo/validate-attitude.json"
echo "demo: the attitude chain took $((SECONDS - start)) s (synth, receive, attitude, validate)"
