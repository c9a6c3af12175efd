#!/usr/bin/env bash
# The long acceptance tests that CI skips (scripts/long-tests.txt): each runs on its own,
# with the real-data folder when there is one. About half an hour on two cores.
set -euo pipefail
cd "$(dirname "$0")/.."
export SKYFORGE_DATA="${SKYFORGE_DATA:-$(pwd)/../shared/data}"
grep -v '^#' scripts/long-tests.txt | while read -r package target name; do
  [ -n "$name" ] || continue
  echo "acceptance: $package --test $target $name"
  cargo test -p "$package" --test "$target" -- --ignored --exact "$name"
done
