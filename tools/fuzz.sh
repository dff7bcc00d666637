#!/usr/bin/env bash
# Builds the libFuzzer targets of tests/fuzz in the `asan` preset (clang, ASan + UBSan, build/asan: the same build as
# the sanitizer tests) and runs each one for N seconds (default 60) from a corpus seeded with the real files, nproc
# targets at a time; exits non-zero if any target finds a crash, hang, leak or sanitizer report.
# Usage: tools/fuzz.sh [seconds-per-target] [target ...]   (see tests/fuzz/README.md)
# Environment: SMCBENCH_FUZZ_JOBS (build parallelism and targets run at once, default nproc),
#              SMCBENCH_FUZZ_ARGS (extra libFuzzer flags).
set -euo pipefail

root=$(cd "$(dirname "$0")/.." && pwd)
seconds=${1:-60}
shift $(( $# > 0 ? 1 : 0 ))
if ! [[ "$seconds" =~ ^[0-9]+$ ]] || (( seconds < 1 )); then
  echo "usage: tools/fuzz.sh [seconds-per-target] [target ...]" >&2
  exit 2
fi
build="$root/build/asan"
jobs=${SMCBENCH_FUZZ_JOBS:-$(nproc)}
# Seeds larger than this are skipped: every mutation of a 3 MB MLCP would re-parse it under ASan (libFuzzer would
# also truncate it to its 1 MB default maximum length).
max_seed_bytes=131072

# clang and its runtime libraries (libFuzzer, ASan, UBSan) from Debian.
clang_rt=$(compgen -G '/usr/lib/llvm-*/lib/clang/*/lib/linux/libclang_rt.fuzzer-x86_64.a' | head -n1 || true)
if ! command -v clang++ >/dev/null || [[ -z "$clang_rt" ]]; then
  echo "fuzz.sh: installing clang and libclang-rt-14-dev" >&2
  sudo=""
  if (( EUID != 0 )); then
    command -v sudo >/dev/null || { echo "fuzz.sh: need root (or sudo) to apt-get install clang libclang-rt-14-dev" >&2; exit 2; }
    sudo=sudo
  fi
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq clang libclang-rt-14-dev >/dev/null
fi

mkdir -p "$root/build"
(cd "$root" && cmake --preset asan >"$root/build/fuzz-configure.log" 2>&1) ||
  { cat "$root/build/fuzz-configure.log" >&2; exit 2; }
manifest="$build/tests/fuzz/fuzz-targets.tsv"

# The targets: all of the manifest (written by tests/fuzz/CMakeLists.txt), or those named on the command line.
declare -A binary dict seeds
all=()
while IFS=$'\t' read -r name bin dictionary globs; do
  [[ -z "$name" ]] && continue
  all+=("$name")
  binary[$name]=$bin
  dict[$name]=$dictionary
  seeds[$name]=$globs
done <"$manifest"
targets=("$@")
(( ${#targets[@]} )) || targets=("${all[@]}")
for t in "${targets[@]}"; do
  [[ -n "${binary[$t]:-}" ]] || { echo "fuzz.sh: unknown target '$t' (known: ${all[*]})" >&2; exit 2; }
done

cmake --build "$build" --target "${targets[@]}" -j "$jobs" || { echo "fuzz.sh: build failed" >&2; exit 2; }

# One target: seeds copied (never linked) so libFuzzer can add to the corpus without touching the originals, then
# libFuzzer for $seconds; its one-line summary goes to $build/logs/<target>.summary, exit status 1 on a finding.
fuzz_one() {
  local t=$1 corpus="$build/corpus/$1" findings="$build/findings/$1" log="$build/logs/$1.log"
  mkdir -p "$corpus" "$findings" "$(dirname "$log")"
  local copied=0 pattern matched f
  IFS='|' read -r -a patterns <<<"${seeds[$t]}"
  for pattern in "${patterns[@]}"; do
    [[ -z "$pattern" ]] && continue
    matched=0
    while IFS= read -r -d '' f; do
      matched=1
      if (( $(stat -c %s "$f") <= max_seed_bytes )); then
        cp -n "$f" "$corpus/seed-$(basename "$f")"
        copied=$((copied + 1))
      fi
    done < <(compgen -G "$pattern" | tr '\n' '\0')
    (( matched )) || echo "fuzz.sh: warning: $t: no seed matches $pattern (starting without it)" >&2
  done
  local args=(-max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1
              -artifact_prefix="$findings/")
  [[ -n "${dict[$t]}" && "${dict[$t]}" != "-" ]] && args+=(-dict="${dict[$t]}")
  # shellcheck disable=SC2206  # SMCBENCH_FUZZ_ARGS is a list of flags on purpose
  local extra=(${SMCBENCH_FUZZ_ARGS:-})
  echo "fuzz.sh: $t for ${seconds}s ($copied seeds, log $log)" >&2
  local rc=0
  "${binary[$t]}" "${args[@]}" "${extra[@]}" "$corpus" >"$log" 2>&1 || rc=$?
  local runs rate size
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -n1)
  rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -n1)
  size=$(find "$corpus" -type f | wc -l)
  if (( rc != 0 )); then
    echo "$t: FINDING (exit $rc), ${runs:-?} runs, ${rate:-?} exec/s; see $log and $findings/" >"$build/logs/$t.summary"
    grep -m4 -E 'ERROR: |runtime error:|FINDING|SUMMARY: |Test unit written to' "$log" >&2 || true
    return 1
  fi
  echo "$t: ok, ${runs:-?} runs, ${rate:-?} exec/s, corpus $size files" >"$build/logs/$t.summary"
}

status=0
running=0
for t in "${targets[@]}"; do
  if (( running >= jobs )); then
    wait -n || status=1
    running=$((running - 1))
  fi
  fuzz_one "$t" &
  running=$((running + 1))
done
while (( running > 0 )); do
  wait -n || status=1
  running=$((running - 1))
done

echo "fuzz.sh: ${seconds}s per target, $jobs at a time" >&2
for t in "${targets[@]}"; do echo "  $(cat "$build/logs/$t.summary" 2>/dev/null || echo "$t: no summary")" >&2; done
exit "$status"
