#!/usr/bin/env bash
# The long acceptance tests that CI skips (scripts/long-tests.txt): each runs on its own,
# with the real-data folder when there is one. About three hours on two cores (the
# signal-level single-epoch attitude runs take most of it; the Galileo one needs the E1
# code tables, SKYFORGE_GALILEO_E1_CODES).
set -euo pipefail
cd "$(dirname "$0")/.."
export SKYFORGE_DATA="${SKYFORGE_DATA:-$(pwd)/../shared/data}"
grep -v '^#' scripts/long-tests.txt | while read -r package target name; do
  [ -n "$name" ] || continue
  echo "acceptance: $package --test $target $name"
  cargo test -p "$package" --test "$target" -- --ignored --exact "$name"
done
