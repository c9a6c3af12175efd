#!/usr/bin/env bash
# Issue 15's signal-level reference run: paper 002's lab (the bundled integrity-lab,
# BeiDou B1I as the paper) for its full 1800 s, synthesised and received as the samples
# are rendered (`synth --receive`: the 58 GB of I/Q never touch the disk), monitored with
# the bundled thresholds and the surveyed station positions, and scored against the
# injected faults. Prints the time of each step and the score; writes everything to DIR.
#   scripts/reference/integrity-1800.sh DIR [SKYFORGE [SECONDS]]
# (SKYFORGE: a release binary, default target/release/skyforge; SECONDS: a shorter span
# to try the script, default the paper's 1800)
# Faults at station C (assumed, chosen before the first run): the paper's 30 m multipath
# on C03 (600-605 s), a quarter-cycle carrier jump on C01 from 900 s (whole cycles are
# invisible to a PLL), a 2 s outage of C02 at 1000 s (a real slip); at every station the
# paper's 0.1 m/s ionospheric ramp on C04 (1200-1373 s; the common reading: no alarm).
set -euo pipefail
dir=${1:?output directory}
sky=$(realpath "${2:-target/release/skyforge}")
span=${3:-1800}
mkdir -p "$dir"
"$sky" scenarios show integrity-lab | SPAN="$span" python3 -c '
import os, sys
s = sys.stdin.read()
s = s.replace("duration_s = 1800.0", "duration_s = %s.0" % os.environ["SPAN"])
s = s.replace("[gnss.gps]\nsource", "[gnss.gps]\nenabled = false\nsource")
s = s.replace("level = \"observation\"", "level = \"signal\"")
s += """
[[errors.events]]
kind = "code-step"
antenna = "C"
satellite = "C03"
start_s = 600.0
end_s = 605.0
value = 30.0

[[errors.events]]
kind = "phase-jump"
antenna = "C"
satellite = "C01"
start_s = 900.0
end_s = 1800.0
value = 0.25

[[errors.events]]
kind = "outage"
antenna = "C"
satellite = "C02"
start_s = 1000.0
end_s = 1002.0

[[errors.events]]
kind = "iono-ramp"
satellite = "C04"
start_s = 1200.0
end_s = 1373.0
value = 0.1
"""
print(s, end="")' > "$dir/lab.toml"
repo=$(cd "$(dirname "$0")/../.." && pwd)
cd "$dir"
t0=$(date +%s)
"$sky" synth lab.toml --out sim --receive --force
t1=$(date +%s)
# The bundled thresholds with the surveyed station positions (the truth RINEX headers'
# APPROX POSITION XYZ), as reference stations are surveyed.
python3 - "$repo/scenarios/calibration/monitor-lab.toml" > monitor.toml <<'PY'
import sys
stations = ""
for s in "ABCD":
    line = next(l for l in open(f"sim/{s}.obs.rnx") if "APPROX POSITION XYZ" in l)
    x, y, z = (float(line[14 * k:14 * k + 14]) for k in range(3))
    stations += f'[[stations]]\nname = "{s}"\nposition_ecef_m = [{x!r}, {y!r}, {z!r}]\n'
bundled = open(sys.argv[1]).read().replace("stations = []\n", "")
at = bundled.index("[thresholds]")
print(bundled[:at] + stations + "\n" + bundled[at:], end="")
PY
"$sky" monitor run sim/receive/{A,B,C,D}.obs.rnx --nav sim/nav.rnx --config monitor.toml --out mon --force
"$sky" validate monitor --truth sim --monitor mon --json score.json
t2=$(date +%s)
echo "reference: synth --receive $((t1 - t0)) s, end to end $((t2 - t0)) s"
