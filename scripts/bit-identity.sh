#!/usr/bin/env bash
# Bit-identity check for refactorings: the same scenarios and seeds through two skyforge
# binaries (a base revision's and the working tree's) must write byte-identical files:
# I/Q recordings, SigMF metadata, truth.h5, RINEX observation and navigation files, and
# the bundled receiver's outputs (RINEX, receiver.h5, pvt.csv, NMEA) on those recordings.
#
#   scripts/bit-identity.sh --base-rev REV  [--work DIR] [SCENARIO...]
#   scripts/bit-identity.sh --base-bin PATH [--work DIR] [SCENARIO...]
#   ... [--new-bin PATH]   compare against an already built binary instead of building
#                          the working tree (while the tree is being edited)
#
# --base-rev builds REV in a temporary git worktree (its own target directory);
# --base-bin uses an already built binary. SCENARIO is a bundled name or a file; the
# default list is the one issue #10 names: interop-gps-static, interop-bds-static,
# thesis/t-5.4-2 and scenarios/check/leo-three-antennas.toml (multi-antenna LEO), plus
# `run` of thesis-leo (24 h geometry truth), then (unless BIT_IDENTITY_MORE=0) issue #31's
# attitude-leo-gps through synth, receive --geometry and attitude, the integrity-lab
# monitor and a small study. BIT_IDENTITY_RECEIVER=0 compares the synthesis alone (for a
# change meant to alter the receiver's numbers); BIT_IDENTITY_NEW_FILES names outputs the
# change adds (below). Exits 1 on the first difference, naming
# the files that differ. Needs about 10 GB of disk under --work (default: a temporary
# directory, removed at the end).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
base_rev="" base_bin="" new_built="" work=""
scenarios=()
while [ $# -gt 0 ]; do
  case "$1" in
    --base-rev) base_rev=$2; shift 2 ;;
    --base-bin) base_bin=$2; shift 2 ;;
    --work) work=$2; shift 2 ;;
    --new-bin) new_built=$2; shift 2 ;;
    *) scenarios+=("$1"); shift ;;
  esac
done
if [ -z "$base_rev" ] && [ -z "$base_bin" ]; then
  echo "usage: $0 --base-rev REV | --base-bin PATH [--work DIR] [SCENARIO...]" >&2
  exit 2
fi
[ ${#scenarios[@]} -gt 0 ] || scenarios=(interop-gps-static interop-bds-static thesis/t-5.4-2 \
  "$root/scenarios/check/leo-three-antennas.toml")
if [ -z "$work" ]; then
  work=$(mktemp -d)
  trap 'rm -rf "$work"' EXIT
fi
mkdir -p "$work"

if [ -n "$base_rev" ]; then
  src="$work/base-src"
  git -C "$root" worktree add --detach "$src" "$base_rev" >/dev/null
  trap 'git -C "$root" worktree remove --force "$src"; rm -rf "$work"' EXIT
  echo "bit-identity: building $base_rev"
  CARGO_TARGET_DIR="$root/target/bit-identity-base" cargo build --quiet --manifest-path "$src/Cargo.toml" -p skyforge-sim
  base_bin="$root/target/bit-identity-base/debug/skyforge"
fi
if [ -z "$new_built" ]; then
  echo "bit-identity: building the working tree"
  cargo build --quiet --manifest-path "$root/Cargo.toml" -p skyforge-sim
  new_built="$root/target/debug/skyforge"
fi
# A copy, so that a rebuild during the check does not change the binary under test.
new_bin="$work/skyforge-new"
cp "$new_built" "$new_bin"

# Every file below $1 with its SHA-256, paths relative to $1 (the --force manifest,
# .skyforge-manifest, is left out: binaries before it did not write one).
# A study journal (*.runs.jsonl) holds one line per finished run in the order the runs
# finished, which parallel runs do not fix: its lines are compared sorted.
digest() {
  (cd "$1" && find . -type f ! -name .skyforge-manifest ! -name '*.runs.jsonl' -print0 | sort -z | xargs -0 sha256sum
   find . -type f -name '*.runs.jsonl' | sort | while read -r f; do echo "$(sort "$f" | sha256sum | cut -d' ' -f1)  $f (lines sorted)"; done)
}

# Files the working tree writes that the base did not (an output added by the change,
# e.g. BIT_IDENTITY_NEW_FILES='truth\.sp3'): an extended regular expression of paths
# (relative, without ./) left out of the new side only; every file both write must
# still be identical.
new_files=${BIT_IDENTITY_NEW_FILES:-}
digest_new() {
  if [ -n "$new_files" ]; then
    digest "$1" | grep -v -E "  \./($new_files)\$" || true
  else
    digest "$1"
  fi
}

# Compare directories $1/base/$2 and $1/new/$2.
same() {
  if ! diff <(digest "$1/base/$2") <(digest_new "$1/new/$2") >"$1/diff.txt"; then
    echo "bit-identity: DIFFERENT in $2:" >&2
    cat "$1/diff.txt" >&2
    exit 1
  fi
  echo "bit-identity: identical: $2 ($(digest "$1/new/$2" | wc -l) files)"
}

# `run` of thesis-leo: geometry truth only.
for which in base new; do
  bin=$base_bin; [ $which = new ] && bin=$new_bin
  "$bin" run thesis-leo --out "$work/$which/run-thesis-leo" >/dev/null
done
same "$work" run-thesis-leo
rm -rf "$work"/{base,new}/run-thesis-leo

for s in "${scenarios[@]}"; do
  tag=$(basename "$s" .toml | tr '/' '-')
  for which in base new; do
    bin=$base_bin; [ $which = new ] && bin=$new_bin
    out="$work/$which/$tag"
    "$bin" synth "$s" --out "$out/synth" >/dev/null
    # The bundled receiver takes the recordings of the signals it tracks; a scenario of
    # other signals (gps-l5, gal-e5a) is compared on its synthesis alone.
    tracked=("$out"/synth/*.gps-l1ca.sigmf-meta "$out"/synth/*.bds-b1i.sigmf-meta)
    metas=()
    for m in "${tracked[@]}"; do if [ -f "$m" ]; then metas+=("$m"); fi; done
    if [ ${#metas[@]} -eq 0 ] || [ "${BIT_IDENTITY_RECEIVER:-1}" = 0 ]; then continue; fi
    args=("${metas[@]}" --assist "$out/synth/nav.rnx" --out "$out/receive")
    [ -f "$out/synth/receiver.toml" ] && args+=(--config "$out/synth/receiver.toml")
    "$bin" receive "${args[@]}" >/dev/null
  done
  same "$work" "$tag/synth"
  if [ -d "$work/base/$tag/receive" ]; then same "$work" "$tag/receive"; fi
  rm -rf "$work"/{base,new}/"$tag"
done
# Issue #31's further runs: the attitude chain through `receive --geometry` and `attitude`
# (attitude-leo-gps), the integrity monitor on the lab's observation-level run, and a
# small study (two C/N0 points x two seeds of attitude-cn0).
if [ "${BIT_IDENTITY_MORE:-1}" = 1 ]; then
  study="$work/small-study.toml"
  sed -e "s|^scenario = \"../|scenario = \"$root/|" -e 's/^seeds = .*/seeds = 2/' \
    -e 's/^values = .*/values = [40.0, 45.0]/' "$root/studies/attitude-cn0.toml" >"$study"
  for which in base new; do
    bin=$base_bin; [ $which = new ] && bin=$new_bin
    out="$work/$which"
    "$bin" synth attitude-leo-gps --out "$out/att/synth" >/dev/null
    s="$out/att/synth"
    "$bin" receive "$s"/*.sigmf-meta --assist "$s/nav.rnx" --config "$s/receiver.toml" \
      --geometry "$s/geometry.toml" --out "$out/att/receive" >/dev/null
    "$bin" attitude "$out"/att/receive/*.obs.rnx --nav "$s/nav.rnx" \
      --geometry "$s/geometry.toml" --out "$out/att/attitude" >/dev/null
    "$bin" run integrity-lab --out "$out/lab/run" >/dev/null
    "$bin" monitor run "$out"/lab/run/observations/{A,B,C,D}.obs.rnx --nav "$out/lab/run/nav.rnx" \
      --out "$out/lab/monitor" >/dev/null
    "$bin" study run "$study" --out "$out/study" >/dev/null
  done
  for d in att/synth att/receive att/attitude lab/run lab/monitor study; do same "$work" "$d"; done
fi
echo "bit-identity: all outputs identical"
