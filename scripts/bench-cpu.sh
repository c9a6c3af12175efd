# CPU timing of skyforge binaries, interleaved, for the bench-*-bar.sh scripts (sourced
# from the repository root; defines functions only).

# bench_setup DEFAULT_RUNS [RUNS [BINARY...]]: `runs` (RUNS, else DEFAULT_RUNS), `bins`
# (the BINARYs, else a fresh release build), a scratch directory `work` removed on exit
# and `total`, each binary's CPU seconds over all runs.
bench_setup() {
  local default=$1
  shift
  runs=${1:-$default}
  shift || true
  bins=("$@")
  if [ ${#bins[@]} -eq 0 ]; then
    cargo build --release -p skyforge-sim
    bins=("$(pwd)/target/release/skyforge")
  fi
  work=$(mktemp -d)
  trap 'rm -rf "$work"' EXIT
  declare -gA total
}

# bench_time NOTE ARG...: `runs` times, each binary in turn runs `ARG... --out $work/out`
# (removed first); prints its CPU seconds (user + system) followed by NOTE and adds them
# to `total`.
bench_time() {
  local note=$1 bin cpu
  shift
  for _ in $(seq 1 "$runs"); do
    for bin in "${bins[@]}"; do
      rm -rf "$work/out"
      cpu=$(/usr/bin/time -f "%U %S" "$bin" "$@" --out "$work/out" 2>&1 >/dev/null | tail -1 | awk '{print $1 + $2}')
      total[$bin]=$(echo "${total[$bin]:-0} + $cpu" | bc -l)
      echo "bench: $bin $cpu CPU-s$note"
    done
  done
}
