#!/usr/bin/env bash
# Wall-clock comparison of two builds on the same machine with Google Benchmark's own compare.py (Debian package
# libbenchmark-tools; its U test needs python3-scipy): runs one benchmark binary of each build with 9 repetitions
# (random interleaving, JSON out) and prints compare.py's table — time change per benchmark and the Mann-Whitney U
# test over the repetitions. Wall clock is noisy on a shared machine: the perf gate (tools/perf-check) counts
# instructions instead; use this to see what a change does to real time.
#   tools/compare-builds.sh OLD_BUILD NEW_BUILD [BINARY] [FILTER]
#   e.g. tools/compare-builds.sh build/before build/release bench/stepper_benchmark 'stepper/.*/enum/prefactored'
# BINARY is relative to each build folder (default bench/backend_benchmark); FILTER is --benchmark_filter.
# Environment: SMCBENCH_COMPARE_REPETITIONS (default 9, at least 9).
set -euo pipefail
(( $# >= 2 )) || { sed -n '2,10p' "$0" | sed 's/^# \{0,1\}//' >&2; exit 2; }
old=$1 new=$2 binary=${3:-bench/backend_benchmark} filter=${4:-.}
repetitions=${SMCBENCH_COMPARE_REPETITIONS:-9}
(( repetitions >= 9 )) || { echo "compare-builds: use at least 9 repetitions (U test)" >&2; exit 2; }
for b in "$old" "$new"; do
  [[ -x "$b/$binary" ]] || { echo "compare-builds: no executable $b/$binary (build it first)" >&2; exit 2; }
done
compare=/usr/share/benchmark/compare.py
if [[ ! -f "$compare" ]] || ! python3 -c 'import scipy' 2>/dev/null; then
  (( EUID == 0 )) || { echo "compare-builds: as root: apt-get install libbenchmark-tools python3-scipy" >&2; exit 2; }
  apt-get update -qq
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends libbenchmark-tools python3-scipy \
    >/dev/null
fi
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT
for side in old new; do
  dir=${!side}
  echo "compare-builds: $dir/$binary ($repetitions repetitions)" >&2
  "$dir/$binary" --benchmark_filter="$filter" --benchmark_repetitions="$repetitions" \
    --benchmark_enable_random_interleaving=true --benchmark_out="$out/$side.json" --benchmark_out_format=json \
    >/dev/null 2>"$out/$side.log" || { cat "$out/$side.log" >&2; exit 2; }
done
color=()
[[ -t 1 ]] || color=(--no-color)
/usr/bin/python3 "$compare" "${color[@]}" -a benchmarks "$out/old.json" "$out/new.json"
