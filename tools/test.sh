#!/usr/bin/env bash
# The README's test command (what .ci/run runs). Installs the dependencies, then runs the gates in order and stops
# at the first that fails:
#   1. release  Release preset (g++ -O3, warnings are errors): build, every test but the `slow` label;
#   2. perf     tools/perf-check: instructions per solve/step under callgrind against results/baseline (> 5 % fails);
#   3. asan     asan preset (clang, ASan + UBSan, -O1): build with the fuzz targets, every test but `slow`/`paper`/`release-only`;
#   4. fuzz     tools/fuzz.sh: every reader's libFuzzer target for SMCBENCH_CI_FUZZ_SECONDS (default 20) each.
# `tools/test.sh STAGE ...` runs only those stages (e.g. `tools/test.sh release`, `tools/test.sh asan fuzz`).
set -euo pipefail
cd "$(dirname "$0")/.."
stages=("$@")
(( ${#stages[@]} )) || stages=(release perf asan fuzz)
for s in "${stages[@]}"; do
  case "$s" in release|perf|asan|fuzz) ;; *) echo "test.sh: unknown stage '$s' (release, perf, asan, fuzz)" >&2; exit 2 ;; esac
done
bash tools/install-deps.sh test

timings=()
run_stage() {
  local start=$SECONDS
  echo "== test.sh: $1" >&2
  case "$1" in
    release|asan)
      cmake --preset "$1" >/dev/null
      cmake --build --preset "$1" -j "$(nproc)"
      ctest --preset "$1" ;;
    perf) bash tools/perf-check ;;
    fuzz) bash tools/fuzz.sh "${SMCBENCH_CI_FUZZ_SECONDS:-20}" ;;
  esac
  timings+=("$1 $((SECONDS - start)) s")
}
for s in "${stages[@]}"; do run_stage "$s"; done
echo "== test.sh: passed (${timings[*]})" >&2
